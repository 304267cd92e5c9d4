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
3. Bubbling: seed 000's uniform-inflow bed (tutorials/bubbling_bed, 4000 spheres at 1.5 U_mf,
   the LIGGGHTS contacts' e_n, beta_0 and mu by tfdem.engines.hard_sphere_laws) from a poured
   packing, 1 s: fluidized, the pressure drop over the 20 cm probes carries the bed, from 0.5 s
   on its mean between 0.90 and 1.00 of the bed weight per cross-section (by hand from the data
   file: the inlet probe sits half a cell above the inlet and bubbles lift particles above
   20 cm; the tutorial's LIGGGHTS bed measures 0.954, bench/engines' hard spheres 0.952 over
   5-20 s), and it fluctuates (standard deviation above 50 Pa: bubbles; 140-150 Pa measured
   with either engine); the mean particle height rises above the packing's; every particle and
   its mass kept; no inelastic collapse (the run ends).
4. Outlet: 200 spheres blown out of a column (tests/cases/blowout, its top the outlet) for
   0.1 s: they leave (all of them by 0.05 s: the emptied bed goes on to the end), the spheres
   at the start = those in the column + those that left, and their mass to 1e-12
   (test_blowout's counts for LIGGGHTS).
5. Restart: 200 spheres blown about in a column (tests/cases/blowout's mesh) run 0.1 s
   straight, and 0.05 s then resumed to 0.1 s: the fields and the engine's restart file at
   0.1 s byte for byte the same; particles and mass accounted for. Stopped by SIGTERM at
   0.073 s (between the write times 0.05 and 0.1 s) and resumed: exit status 75, the straight
   run's write times and the stop's, and the same bytes at 0.1 s (the checkpoint keeps the
   neighbour lists, which decide the events' order).
6. Beds poured at rest by tfdem pack (3-D, 1500 spheres of 2.5 mm in 4 x 1.5 cm; bidisperse,
   1.5 and 2.5 mm at 30/70 by mass, 1 cm deep), their gas below U_mf: 0.01 s runs to its end.
   Their soft pour's overlapping pairs and wall contacts taken as touching exactly where they
   are collide at one instant without end once gravity moves the bed (the 3-D bed: 15 million
   collisions at t = 0, stopped as a cascade at one instant); taken a millionth of their
   distance closer (EventFlight's rule) they collide at distinct times and run their course.
"""
import math
import os
import re
import shutil
import signal
import time

from tfdem import SOURCE_DIR, TUTORIALS
from tfdem.case import Case
from tfdem.engines import convert_to_hard_sphere, use_hard_sphere
from tfdem.fixed_bed import VELOCITIES, FixedBed
from tfdem.liggghts import read_data_file, write_data_file
from tfdem.newcase import derive, load_bed, write_case
from tfdem.outputs import joined_series, particle_statistics, probes, vtk_particles
from tfdem.packing import pack_case
from tfdem.physics import SettlingSphere
from tfdem.run import start
from tfdem_testlib import Checks, copy_case, run, scratch

SETTLING = os.path.join(TUTORIALS, "settling_particle")
PACKED = os.path.join(TUTORIALS, "packed_bed_ergun")
BLOWOUT = os.path.join(SOURCE_DIR, "tests", "cases", "blowout")
BUBBLING = os.path.join(TUTORIALS, "bubbling_bed")
PACKING = os.path.join(TUTORIALS, "bubbling_bed_packing", "in.pack")
BUBBLING_FROM = 0.5  # s: the first bubbles have formed
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


def bubbling(checks):
    packing = scratch("hard_sphere_bubbling_packing")
    run(["tfdem-liggghts", "-in", PACKING, "-var", "steps", "20000", "-var", "out", "bed.data", "-log", "log.liggghts"],
        packing, "log.screen")
    case = Case(copy_case(BUBBLING, "hard_sphere_bubbling"))
    data = os.path.basename(case.dem().read_data())
    shutil.copy(os.path.join(packing, "bed.data"), case.file(data))
    convert_to_hard_sphere(case)
    case.set_control(endTime=1.0, writeInterval=1.0)
    case.set_coupling("output.statistics_interval", 0.05)
    run(["blockMesh"], case.path, "log.blockMesh")
    _, output = run(["tfdemFoam"], case.path, "log.tfdemFoam")
    atoms = read_data_file(case.file(data))
    mass = sum(rho * math.pi * d ** 3 / 6 for d, rho in zip(atoms["diameter"], atoms["density"]))
    lower, upper = case.mesh_bounds()
    weight = mass * case.gravity_magnitude() / ((upper[0] - lower[0]) * (upper[2] - lower[2]))
    dp = [p[0] - p[1] for t, p in probes(case.path, "pressure", "p") if t >= BUBBLING_FROM]
    mean = sum(dp) / len(dp)
    std = math.sqrt(sum((x - mean) ** 2 for x in dp) / len(dp))
    checks.within("hard spheres, bubbling: mean p(inlet) - p(20 cm) over 0.5-1 s / bed weight per area",
                  mean / weight, 0.95, 0.05)
    checks.true("hard spheres, bubbling: p(inlet) - p(20 cm) fluctuates (std > 50 Pa)", std > 50, f"({std:.0f} Pa)")
    stats = particle_statistics(case.path)
    heights = [h for t, h in zip(stats["t"], stats["mean_height"]) if t >= BUBBLING_FROM]
    g = case.gravity()
    up = "xyz"[max(range(3), key=lambda a: abs(g[a]))]
    packed = sum(atoms[up]) / len(atoms[up])
    checks.true("hard spheres, bubbling: mean particle height over 0.5-1 s above the packing's",
                min(heights) > packed, f"({min(heights):.4f} m, packed {packed:.4f} m)")
    checks.true(f"hard spheres, bubbling: {len(atoms['id'])} particles at the end",
                stats["particles"][-1] == len(atoms["id"]), f"({stats['particles'][-1]:g})")
    checks.close("hard spheres, bubbling: mass kept", stats["mass"][-1], mass, 1e-12)
    collisions = re.search(r"TFDEM hard spheres: (\d+) pair and (\d+) wall", output)
    checks.true("hard spheres, bubbling: the spheres collide", collisions and int(collisions.group(1)) > 1e5,
                f"({collisions.group(0) if collisions else 'no report'})")


def blowout_bed(name, outlets=False):
    """tests/cases/blowout's column with 200 spheres of 2.5 mm at 50 kg/m^3 in 5 m/s of gas;
    its top an outlet (coupling.yaml dem.outlets) or a wall."""
    case = Case(copy_case(BLOWOUT, name))
    positions = [(0.003 + 0.0034 * (k % 10), 0.003 + 0.0034 * (k // 10), 0.00125) for k in range(200)]
    write_data_file(case.file("bed.data"), (0, 0, 0), (0.04, 0.1, 0.0025), [0.0025] * 200, [50] * 200, positions)
    use_hard_sphere(case, "bed.data", **GLASS)
    if not outlets:
        case.set_coupling("dem.outlets", [])
    case.set_control(endTime=0.1, writeInterval=0.05, writePrecision=17, writeControl="runTime")
    run(["blockMesh"], case.path, "log.blockMesh")
    return case


def outlet(checks):
    case = blowout_bed("hard_sphere_outlet", outlets=True)
    _, output = run(["tfdemFoam"], case.path, "log.tfdemFoam")
    left = joined_series(case.path, "tfdemOutlets", "outlets.dat")
    left_count = sum(int(values[1]) for _, values in left)
    left_mass = sum(values[2] for _, values in left)
    stats = particle_statistics(case.path)
    in_bed = int(stats["particles"][-1])
    checks.true("hard spheres, outlet: spheres left", left_count > 0, f"({left_count} left, {in_bed} in the column)")
    checks.true("hard spheres, outlet: the run went on to 0.1 s (all may have left: an emptied bed goes on)",
                os.path.isdir(case.file("0.1")))
    checks.true("hard spheres, outlet: 200 at the start = in the column + left", in_bed + left_count == 200,
                f"({in_bed} + {left_count})")
    checks.close("hard spheres, outlet: mass at the start = in the column + left", stats["mass"][-1] + left_mass,
                 200 * 50 * math.pi * 0.0025 ** 3 / 6, 1e-12)
    checks.true("hard spheres, outlet: no particle lost", "were lost" not in output)


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
    stopped = blowout_bed("hard_sphere_restart_stopped")
    proc = start(["tfdemFoam"], stopped.path, "log.stopped")
    while proc.poll() is None and "\nTime = 0.073\n" not in open(stopped.file("log.stopped"), errors="replace").read():
        time.sleep(0.02)
    proc.send_signal(signal.SIGTERM)
    code = proc.wait()
    stop = re.search(r"stopped at t = (\S+) s", open(stopped.file("log.stopped"), errors="replace").read())
    checks.true("hard spheres, SIGTERM between writes: exit 75 at a checkpoint", code == 75 and stop is not None,
                f"(exit {code})")
    stopped.set_control(startFrom="latestTime")
    run(["tfdemFoam"], stopped.path, "log.tfdemFoam")
    times = sorted(float(t) for t in os.listdir(stopped.path) if re.fullmatch(r"0\.[0-9]+", t))
    checks.true("hard spheres, SIGTERM: the straight run's write times and the stop's",
                stop is not None and times == sorted([0.05, 0.1, float(stop.group(1))]), f"({times})")
    for name in ("p", "U", "voidFraction", "dem.restart"):
        a, b = straight.file("0.1", name), stopped.file("0.1", name)
        checks.true(f"hard spheres, SIGTERM: 0.1/{name} bit for bit", open(a, "rb").read() == open(b, "rb").read())
    stats = particle_statistics(resumed.path)
    checks.true("hard spheres, restart: 200 particles at the end", stats["particles"][-1] == 200,
                f"({stats['particles'][-1]:g})")
    checks.close("hard spheres, restart: mass kept", stats["mass"][-1], 200 * 50 * math.pi * 0.0025 ** 3 / 6, 1e-12)


POURED = {
    "3-D": """box: {width: 0.04, height: 0.12, depth: 0.015}
particles: {density: 2500, sizes: [{diameter: 0.0025, number: 1500}], restitution: 0.9, friction: 0.1}
""",
    "bidisperse": """box: {width: 0.04, height: 0.12, depth: 0.01}
particles:
  density: 2500
  count: 1500
  sizes: [{diameter: 0.0015, mass_fraction: 0.3}, {diameter: 0.0025, mass_fraction: 0.7}]
  restitution: 0.9
  friction: 0.1
""",
}


def poured_at_rest(checks):
    for name, particles in POURED.items():
        root = scratch(f"hard_sphere_poured_{name}")
        source = os.path.join(root, "bed.yaml")
        with open(source, "w") as f:
            f.write(particles + "dem: {engine: hard_sphere}\ngas: {density: 1.2, viscosity: 1.8e-5}\n"
                    "inflow: {velocity: 0.3}\nrun: {end_time: 0.01, write_interval: 0.01}\n")
        bed = load_bed(source)
        case = os.path.join(root, "case")
        write_case(case, bed, derive(bed, source), source)
        print(pack_case(case, runner=lambda *a, **k: run(*a[:3])))
        run(["blockMesh"], case, "log.blockMesh")
        code, output = run(["tfdemFoam"], case, "log.tfdemFoam", expect_success=False)
        collisions = re.search(r"TFDEM hard spheres: (\d+) pair and (\d+) wall collisions", output)
        checks.true(f"hard spheres, {name} bed poured at rest: 0.01 s run to its end", code == 0 and collisions,
                    output[-1500:] if code else "")


def main():
    checks = Checks()
    settling(checks)
    packed_bed(checks)
    bubbling(checks)
    outlet(checks)
    restart(checks)
    poured_at_rest(checks)
    checks.finish()


if __name__ == "__main__":
    main()
