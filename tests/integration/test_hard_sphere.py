"""The hard-sphere engine behind the coupling (dem.engine: hard_sphere), on the cases the
LIGGGHTS runs are verified on, with the same expected values and tolerances:

1. One sphere settling in air (tutorials/settling_particle, its one particle in a data file):
   terminal velocity within 1 % of tfdem.physics.SettlingSphere's ODE (its u_t equals the
   force balance by hand, 0.553186076 m/s) and the curve within 1 % of u_t, from the particle
   files written every 0.01 s.
2. The fixed bed of tutorials/packed_bed_ergun (its lattice written as a data file, the
   particles held, move: false): Delta p within 0.5 % of Ergun at 0.3, 0.6 and 1.0 m/s, and
   the particles' summed fluid force within 0.5 % of Ergun's Delta p times the cross-section
   plus the gas buoyancy (tfdem.fixed_bed.FixedBed, as coupled.packed_bed).
3. Restart: 200 spheres blown about in a column (tests/cases/blowout's mesh) run 0.1 s
   straight, and 0.05 s then resumed to 0.1 s: the fields and the engine's restart file at
   0.1 s byte for byte the same; particles and mass accounted for.
"""
import math
import os
import re
import shutil

from tfdem import SOURCE_DIR, TUTORIALS
from tfdem.case import Case
from tfdem.engines import use_hard_sphere, write_data_file
from tfdem.fixed_bed import VELOCITIES, FixedBed
from tfdem.outputs import particle_statistics, vtk_particles
from tfdem.physics import SettlingSphere
from tfdem_testlib import Checks, copy_case, run

SETTLING = os.path.join(TUTORIALS, "settling_particle")
PACKED = os.path.join(TUTORIALS, "packed_bed_ergun")
BLOWOUT = os.path.join(SOURCE_DIR, "tests", "cases", "blowout")
# glass on glass (Hoomans et al. 1996): the collisions do not matter in cases 1 and 2
GLASS = {"restitution": 0.9, "tangential_restitution": 0.33, "friction": 0.1}


def particle_files(case):
    """(t, particle file) of the case's VTK/particles_<t>.vtk, in time order."""
    found = []
    for name in os.listdir(Case(case).file("VTK")):
        m = re.fullmatch(r"particles_(.+)\.vtk", name)
        if m:
            found.append((float(m.group(1)), Case(case).file("VTK", name)))
    return sorted(found)


def settling(checks):
    case = copy_case(SETTLING, "hard_sphere_settling")
    write_data_file(Case(case).file("bed.data"), (0, 0, 0), (0.06, 0.4, 0.02), [1e-4], [2500], [(0.03, 0.35, 0.01)])
    use_hard_sphere(case, "bed.data", **GLASS)
    Case(case).set_control(writeInterval=0.01)
    run(["blockMesh"], case, "log.blockMesh")
    run(["tfdemFoam"], case, "log.tfdemFoam")
    # the start is the data file's state, at rest: a particle file at every write time after it
    track = [(t, vtk_particles(path)["velocity"][0][1]) for t, path in particle_files(case)]
    checks.true("hard spheres, settling: 50 particle files over 0.5 s", len(track) == 50, f"(got {len(track)})")
    sphere = SettlingSphere.from_case(Case(case))
    u_t = sphere.terminal_velocity()
    expected = sphere.velocity([t for t, _ in track])
    checks.close("hard spheres, settling: terminal velocity (m/s) at 0.5 s", -track[-1][1], u_t, 0.01)
    worst = max(abs(v - e) for (_, v), e in zip(track, expected)) / u_t
    checks.within("hard spheres, settling: max |v - v_ODE| / u_t over 0-0.5 s", worst, 0.0, 0.01)


def packed_bed(checks):
    bed = FixedBed(PACKED)
    dem = Case(PACKED).dem()
    (x0, y0, z0), (x1, y1, z1) = dem.region("box")
    sites = dem.lattice_sites("bed")
    d, rho = Case(PACKED).particle_properties()
    for u in VELOCITIES:
        case = Case(copy_case(PACKED, f"hard_sphere_packed_U{u}"))
        write_data_file(case.file("bed.data"), (x0, y0, z0), (x1, y1, z1), [d] * len(sites), [rho] * len(sites), sites)
        use_hard_sphere(case, "bed.data", move=False, **GLASS)
        case.set_patch_value("U", "inlet", (0, u, 0))
        run(["blockMesh"], case.path, "log.blockMesh")
        run(["tfdemFoam"], case.path, "log.tfdemFoam")
        checks.close(f"hard spheres, fixed bed: pressure drop at U = {u} m/s (Pa)",
                     bed.measured_pressure_drop(case.path), bed.expected_pressure_drop(u), 0.005)
        last = vtk_particles(particle_files(case.path)[-1][1])
        force = sum(f[1] for f in last["fluidForce"])
        checks.close(f"hard spheres, fixed bed: sum of particle fluid forces at U = {u} m/s (N)", force,
                     bed.expected_particle_force(u), 0.005)


def blowout_bed(name):
    """tests/cases/blowout's column with 200 spheres of 2.5 mm at 50 kg/m^3 in 5 m/s of gas."""
    case = Case(copy_case(BLOWOUT, name))
    positions = [(0.003 + 0.0034 * (k % 10), 0.003 + 0.0034 * (k // 10), 0.00125) for k in range(200)]
    write_data_file(case.file("bed.data"), (0, 0, 0), (0.04, 0.1, 0.0025), [0.0025] * 200, [50] * 200, positions)
    use_hard_sphere(case, "bed.data", **GLASS)
    case.set_coupling("dem.outlets", [])
    case.set_control(endTime=0.1, writeInterval=0.05, writePrecision=17, writeControl="runTime")
    run(["blockMesh"], case.path, "log.blockMesh")
    return case


def restart(checks):
    straight = blowout_bed("hard_sphere_restart_straight")
    run(["tfdemFoam"], straight.path, "log.tfdemFoam")
    resumed = blowout_bed("hard_sphere_restart_resumed")
    resumed.set_control(endTime=0.05)
    run(["tfdemFoam"], resumed.path, "log.first")
    resumed.set_control(endTime=0.1, startFrom="latestTime")
    _, output = run(["tfdemFoam"], resumed.path, "log.tfdemFoam")
    checks.true("hard spheres, restart: resumed from 0.05 s", "resuming gas and particles from t = 0.05 s" in output)
    collisions = re.search(r"TFDEM hard spheres: (\d+) pair and (\d+) wall", output)
    checks.true("hard spheres, restart: the resumed run's spheres collide", collisions and int(collisions.group(1)) > 100,
                f"({collisions.group(0) if collisions else 'no report'})")
    for name in ("p", "U", "voidFraction", "dem.restart"):
        a, b = straight.file("0.1", name), resumed.file("0.1", name)
        checks.true(f"hard spheres, restart: 0.1/{name} bit for bit", open(a, "rb").read() == open(b, "rb").read())
    stats = particle_statistics(resumed.path)
    checks.true("hard spheres, restart: 200 particles at the end", stats["particles"][-1] == 200,
                f"({stats['particles'][-1]:g})")
    checks.close("hard spheres, restart: mass kept", stats["mass"][-1], 200 * 50 * math.pi * 0.0025 ** 3 / 6, 1e-12)


def main():
    checks = Checks()
    settling(checks)
    packed_bed(checks)
    restart(checks)
    checks.finish()


if __name__ == "__main__":
    main()
