"""tfdem-liggghts applies a per-atom fluid force stored in fix tfdem/coupling.

With a stored force -f m g and gravity g, a sphere starting at rest at z0 falls as
  z(t) = z0 - (1 - f) g t^2 / 2,  v(t) = -(1 - f) g t.
Velocity Verlet is exact for a constant acceleration, so the tolerance is 1e-6 relative
(on the displacement and velocity; for f = 1 against g t, the speed it would have had).
On 2 ranks the box is split at z = 0.5 m; the spheres start at 0.9 m and end below 0.5 m,
so they cross ranks and their stored force must travel with them.
"""
import os

from tfdem import SOURCE_DIR
from tfdem.liggghts import DemScript
from tfdem.outputs import dump_frames
from tfdem_testlib import Checks, run, scratch

STEPS = 5000
SCRIPT = os.path.join(SOURCE_DIR, "tests", "cases", "dem_free_fall", "in.free_fall")


class Scene:
    """g, the start height, the DEM step and the z the box is split at on 2 ranks (its middle:
    `processors 1 1 *`), from the script."""

    def __init__(self, path):
        dem = DemScript(path)
        self.g = -dem.gravity()[2]
        self.z0 = dem.value(dem.command("create_atoms")[5])  # create_atoms 1 single x y z
        self.dt = dem.time_step()
        lo, hi = dem.region("box")
        self.rank_boundary_z = 0.5 * (lo[2] + hi[2])


def last_snapshot(path):
    frames = dump_frames(path)
    columns, rows = frames[max(frames)]
    return [dict(zip(columns, row)) for row in rows]


def check_case(checks, fraction, ranks):
    scene = Scene(SCRIPT)
    G, Z0, DT = scene.g, scene.z0, scene.dt
    case = scratch(f"dem_free_fall_f{fraction}_np{ranks}")
    run(["tfdem-liggghts", "-in", SCRIPT, "-var", "weight_fraction", str(fraction),
         "-var", "steps", str(STEPS), "-var", "dumpfile", "dump.final", "-log", "log.liggghts"],
        case, "screen.txt", ranks=ranks)
    atoms = last_snapshot(os.path.join(case, "dump.final"))
    checks.true(f"f={fraction} np={ranks}: 8 atoms in final snapshot", len(atoms) == 8)
    t = STEPS * DT
    drop_exact = 0.5 * (1 - fraction) * G * t * t
    v_exact = -(1 - fraction) * G * t
    worst_z = max(abs((Z0 - a["z"]) - drop_exact) for a in atoms)
    worst_v = max(abs(a["vz"] - v_exact) for a in atoms)
    scale_z = drop_exact if fraction < 1 else 0.5 * G * t * t
    scale_v = abs(v_exact) if fraction < 1 else G * t
    checks.within(f"f={fraction} np={ranks}: max |drop - (1-f) g t^2/2| / scale", worst_z / scale_z, 0.0, 1e-6)
    checks.within(f"f={fraction} np={ranks}: max |v - v_exact| / scale", worst_v / scale_v, 0.0, 1e-6)
    if ranks > 1 and fraction < 1:
        checks.true(f"f={fraction} np={ranks}: atoms crossed the rank boundary z = {scene.rank_boundary_z:g} m",
                    all(a["z"] < scene.rank_boundary_z < Z0 for a in atoms))


def main():
    checks = Checks()
    for ranks in (1, 2):
        for fraction in (1.0, 0.5):
            check_case(checks, fraction, ranks)
    checks.finish()


if __name__ == "__main__":
    main()
