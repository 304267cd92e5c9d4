"""A third particle engine registered the way the two are (tests/engines/free_fall_engine.cpp:
its own file and one TFDEM_ENGINE line, linked into the solver as tfdemFoam_test_engine): one
100 um glass sphere settling in air (tutorials/settling_particle, its sphere in a data file,
dem.engine: free_fall) reaches the terminal velocity of tfdem.physics.SettlingSphere's ODE
(its u_t equals the force balance by hand, 0.553186076 m/s) within 1 %, and its velocity follows
the ODE's curve within 1 % of u_t: the solver drives the engine through ParticleEngine alone.
The engine's keys are in the configuration the solver prints, and a misspelt one is named."""
import os
import re
import shutil

from tfdem import BUILD_DIR, TUTORIALS
from tfdem.case import Case
from tfdem.liggghts import write_data_file
from tfdem.outputs import vtk_particles
from tfdem.physics import SettlingSphere
from tfdem_testlib import Checks, copy_case, run

SOLVER = os.path.join(BUILD_DIR, "tests", "tfdemFoam_test_engine")
COUPLING = """gas: {density: 1.2, viscosity: 1.8e-5}
particles: {diameter: 1.0e-4, density: 2500}
dem:
  engine: free_fall
  particles: bed.data
coupling: {transfer: per_particle, drag_law: ergun_wen_yu, void_fraction: {method: centroid}}
"""


def main():
    checks = Checks()
    case = copy_case(os.path.join(TUTORIALS, "settling_particle"), "test_engine_settling")
    write_data_file(Case(case).file("bed.data"), (0, 0, 0), (0.06, 0.4, 0.02), [1e-4], [2500], [(0.03, 0.35, 0.01)])
    os.remove(Case(case).file("in.settling"))
    with open(Case(case).file("coupling.yaml"), "w") as f:
        f.write(COUPLING)
    Case(case).set_control(writeInterval=0.01)
    run(["blockMesh"], case, "log.blockMesh")
    _, output = run([SOLVER], case, "log.tfdemFoam")
    checks.true("the solver names the test engine's key in its effective configuration",
                "engine: free_fall" in output and "particles: bed.data" in output)
    frames = sorted((float(m.group(1)), os.path.join(case, "VTK", name)) for name in os.listdir(os.path.join(case, "VTK"))
                    for m in [re.fullmatch(r"particles_(.+)\.vtk", name)] if m)
    track = [(t, vtk_particles(path)["velocity"][0][1]) for t, path in frames]
    sphere = SettlingSphere.from_case(Case(case))
    u_t = sphere.terminal_velocity()
    checks.close("free-fall engine, settling: terminal velocity (m/s) at 0.5 s", -track[-1][1], u_t, 0.01)
    worst = max(abs(v - e) for (_, v), e in zip(track, sphere.velocity([t for t, _ in track]))) / u_t
    checks.within("free-fall engine, settling: max |v - v_ODE| / u_t over 0-0.5 s", worst, 0.0, 0.01)

    for name in os.listdir(case):  # a fresh start again: the first run's checkpoints go
        if re.fullmatch(r"0\.[0-9]+", name):
            shutil.rmtree(os.path.join(case, name))
    with open(Case(case).file("coupling.yaml"), "w") as f:
        f.write(COUPLING.replace("particles: bed.data", "particle: bed.data"))
    code, output = run([SOLVER], case, "log.misspelt", expect_success=False)
    checks.true("a misspelt key of the test engine is named with its nearest name",
                code != 0 and "dem.particle: unknown key (did you mean 'particles'?)" in output, output[-800:])
    checks.finish()


if __name__ == "__main__":
    main()
