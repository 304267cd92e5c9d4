"""The tfdem package's readers and editors on hand-made files (no simulation): series joined
over a resume, stale files of an earlier run refused, fix-print and dump files rewound when a
resumed run appends, coupling.yaml edited in place with its comments, the batch-means error
of a hand-made signal, the solid fraction of a slab cutting spheres, a packing.yaml read, a
bubble found in a hand-made gas-fraction map, the mixing fraction of a coloured layer."""
import math
import os
import shutil
import sys
import tempfile

import numpy

from tfdem.batch import CaseRun, eta_seconds, run_batch, variants_command_line
from tfdem.bubble import coloured_above, find_bubble
from tfdem.case import Case, CaseError, Grid, set_yaml_value
from tfdem.engines import hard_sphere_laws, restitution_of_damping
from tfdem.liggghts import DemScript, ScriptError
from tfdem.outputs import OutputError, dump_frames, fix_print, joined_series
from tfdem.packing import POUR_SCRIPT, at_rest, jiggle, largest_overlap, packing_settings, script_stiffness, set_atom_types, to_mid_plane
from tfdem.physics import jenkins_zhang_effective_restitution, slab_solid_fraction
from tfdem.run import RunError, command, decompose, mesh_cells
from tfdem.stats import batch_means

failures = []


def check(name, condition, detail=""):
    print(("PASS " if condition else "FAIL ") + name + (f" {detail}" if detail else ""))
    if not condition:
        failures.append(name)


def write(path, text):
    os.makedirs(os.path.dirname(path), exist_ok=True)
    with open(path, "w") as f:
        f.write(text)


def check_hard_sphere_laws(root):
    """A LIGGGHTS script's linear spring-dashpot as hard-sphere coefficients: damping written
    with seed 001's eq. 27 (normal) and eq. 30 (tangential, 2/7 m_ab) for e_n = 0.9, beta_0 =
    0.5 through variables (PI, sqrt, ln, ^, v_, ${}) comes back as 0.9 and 0.5; seed 000's
    uniform bed (SPEC: eta_n 0.00177 N s/m, k_n 800 N/m, 2.5 mm glass) gives e_n ~ 0.97."""
    m = 2526 * math.pi * 0.0025 ** 3 / 6
    path = os.path.join(root, "in.laws")
    write(path, f"""variable m equal 2526*PI*0.0025^3/6
variable kn equal 800
variable kt equal 2.0/7.0*v_kn
variable en equal 0.9
variable bt equal 0.5
variable etan equal -2*ln(v_en)*sqrt(v_m/2*v_kn)/sqrt(PI^2+ln(v_en)^2)
variable etat equal -2*ln(v_bt)*sqrt(2/7*v_m/2*v_kt)/sqrt(PI^2+ln(v_bt)^2)
fix m1 all property/global kn peratomtypepair 2 ${{kn}} 1200 1200 1200
fix m2 all property/global kt peratomtypepair 2 ${{kt}} ${{kt}} ${{kt}} ${{kt}}
fix m3 all property/global gamman_abs peratomtypepair 2 ${{etan}} 0.00393 0.00393 0.00393
fix m4 all property/global gammat_abs peratomtypepair 2 ${{etat}} 0 0 0
fix m5 all property/global coefficientFriction peratomtypepair 2 0.1 0.3 0.3 0.3
""")
    laws = hard_sphere_laws(DemScript(path), [m])
    check("hard-sphere laws: e_n and beta_0 of eq. 27 and 30 recovered",
          abs(laws["restitution"] - 0.9) < 1e-12 and abs(laws["tangential_restitution"] - 0.5) < 1e-12, str(laws))
    wall = laws["wall"]
    # the wall (infinite mass, m_ab = m): e = exp(-pi eta / sqrt(4 m k - eta^2)) by hand
    by_hand = math.exp(-math.pi * 0.00393 / math.sqrt(4 * m * 1200 - 0.00393 ** 2))
    check("hard-sphere laws: the walls' own, undamped tangential elastic",
          abs(wall["restitution"] - by_hand) < 1e-12 and wall["tangential_restitution"] == 1.0
          and wall["friction"] == 0.3, str(wall))
    # tables of 3 types, the particles all type 1, the walls type 3 (fix wall/gran ... type 3, as
    # the single bubble's script): the walls' law is the 1-3 entry, type 2 is not used
    write(path, """fix m1 all property/global kn peratomtypepair 3 800 800 1200 800 800 800 1200 800 1200
fix m2 all property/global kt peratomtypepair 3 200 200 200 200 200 200 200 200 200
fix m3 all property/global gamman_abs peratomtypepair 3 0.00177 0.05 0.00393 0.05 0.05 0.05 0.00393 0.05 0.00393
fix m4 all property/global gammat_abs peratomtypepair 3 0 0 0 0 0 0 0 0 0
fix m5 all property/global coefficientFriction peratomtypepair 3 0.1 0.9 0.3 0.9 0.9 0.9 0.3 0.9 0.3
fix floor all wall/gran model hooke/stiffness tangential history primitive type 3 yplane 0 absolute_damping on
""")
    three = hard_sphere_laws(DemScript(path), [m])
    check("hard-sphere laws: the walls' type from fix wall/gran (type 3 of 3, type 2 unused)",
          abs(three["wall"]["restitution"] - by_hand) < 1e-12 and three["wall"]["friction"] == 0.3
          and abs(three["restitution"] - math.exp(-math.pi * 0.00177 / math.sqrt(4 * m / 2 * 800 - 0.00177 ** 2))) < 1e-12,
          str(three))
    seed000 = restitution_of_damping(800, 0.00177, m / 2)
    check("seed 000's uniform bed: e_n ~ 0.97 (SPEC)", abs(seed000 - 0.97) < 0.005, f"{seed000:.4f}")
    check("critical damping: e = 0", restitution_of_damping(800, 2 * math.sqrt(m * 800), m) == 0.0)
    write(path, "fix m1 all property/global kn peratomtypepair 1 800\n")
    try:
        hard_sphere_laws(DemScript(path), [m])
        message = ""
    except ScriptError as e:
        message = str(e)
    check("a script without the spring-dashpot tables is refused by name", "gamman_abs" in message, message)
    write(path, "variable a equal v_b+1\nvariable b equal v_a\nfix g all gravity ${a} vector 0 -1 0\n")
    try:
        DemScript(path).value("${a}")
        message = ""
    except CaseError as e:
        message = str(e)
    check("a circular variable is named", "circular variable 'a'" in message, message)


def check_contact_definitions(root):
    """tfdem.contacts on hand-made configurations: three touching spheres in a line (N_c 1, 2, 1)
    beside an isolated touching pair; a pair at a surface gap of 0.7 % of d (a contact at 1 %,
    not at 0.5 % or 0); a sphere overlapping a wall (a neighbour only with walls) and one 0.7 %
    of d from a wall; the walls of a LIGGGHTS input (the top open); a static cell left out; the
    numpy binning agreeing with the k-d tree."""
    from tfdem import contacts
    d, r = 0.004, 0.002
    # a line of three, 0.999 d apart (overlapping), and an overlapping pair 10 d away
    p = numpy.array([[0.1, 0.1, r], [0.1 + 0.999 * d, 0.1, r], [0.1 + 1.998 * d, 0.1, r],
                     [0.3, 0.1, r], [0.3 + 0.999 * d, 0.1, r]])
    radii = numpy.full(len(p), r)
    pairs = contacts.contact_pairs(p, radii, 0.0)
    nc = contacts.coordination(len(p), pairs)
    check("contacts: a line of three and a pair give N_c 1 2 1 1 1",
          pairs.tolist() == [[0, 1], [1, 2], [3, 4]] and nc.tolist() == [1, 2, 1, 1, 1], f"{pairs.tolist()} {nc.tolist()}")
    line = numpy.array([True, True, True, False, False])
    check("contacts: the line alone: bulk 4/3, multicontact (caption) 1/3, N_c >= 2 among all 1/3",
          abs(contacts.bulk_coordination(nc, line) - 4 / 3) < 1e-12
          and abs(contacts.multicontact_ratio(nc, line) - 1 / 3) < 1e-12
          and abs(contacts.multicontact_fraction(nc, line) - 1 / 3) < 1e-12)
    check("contacts: all five: bulk 6/5, caption ratio 1/5, N_c >= 2 among all 1/5, collisions 2/3",
          abs(contacts.bulk_coordination(nc) - 6 / 5) < 1e-12 and abs(contacts.multicontact_ratio(nc) - 1 / 5) < 1e-12
          and abs(contacts.multicontact_fraction(nc) - 1 / 5) < 1e-12
          and abs(contacts.multicontact_collision_ratio(nc, pairs) - 2 / 3) < 1e-12)
    # a pair whose surfaces are 0.7 % of d apart
    q = numpy.array([[0.05, 0.2, r], [0.05 + 1.007 * d, 0.2, r]])
    counts = [len(contacts.contact_pairs(q, numpy.full(2, r), g)) for g in (0.0, 0.005, 0.01)]
    check("contacts: a gap of 0.7 % of d is a contact at 1 %, not at 0.5 % or 0", counts == [0, 0, 1], str(counts))
    # walls: x = 0 and x = 0.15, y = 0; no top wall. Particle 0 overlaps x = 0, particle 1 is
    # 0.7 % of d from y = 0, particle 2 is free
    script = os.path.join(root, "in.walls")
    write(script, """read_data bed.data
fix wall_x0 all wall/gran model hooke/stiffness tangential history primitive type 2 xplane 0 absolute_damping on
fix wall_x1 all wall/gran model hooke/stiffness tangential history primitive type 2 xplane 0.15 absolute_damping on
fix wall_y0 all wall/gran model hooke/stiffness tangential history primitive type 2 yplane 0 absolute_damping on
# fix wall_y1 all wall/gran model hooke/stiffness tangential history primitive type 2 yplane 0.9
""")
    walls = contacts.walls_of_script(script)
    check("contacts: the walls of an input (a commented-out top is not a wall)",
          walls == [(0, 0.0), (0, 0.15), (1, 0.0)] and contacts.data_file_of_script(script) == "bed.data", str(walls))
    w = numpy.array([[0.999 * r, 0.3, r], [0.07, r + 0.007 * d, r], [0.07, 0.3, r]])
    wr = numpy.full(3, r)
    at = {g: contacts.wall_contacts(w, wr, walls, g).tolist() for g in (0.0, 0.005, 0.01)}
    none = contacts.coordination(3, contacts.contact_pairs(w, wr, 0.0))
    with_walls = contacts.coordination(3, contacts.contact_pairs(w, wr, 0.0), contacts.wall_contacts(w, wr, walls, 0.0))
    check("contacts: a sphere overlapping a wall counts it only with walls; 0.7 % of d from a wall only at 1 %",
          none.tolist() == [0, 0, 0] and with_walls.tolist() == [1, 0, 0]
          and at == {0.0: [[0, 0]], 0.005: [[0, 0]], 0.01: [[0, 0], [1, 2]]}, f"{with_walls.tolist()} {at}")
    check("contacts: a wall contact is a binary collision when the particle has no other neighbour",
          contacts.multicontact_collision_ratio(with_walls, numpy.zeros((0, 2), dtype=int),
                                                contacts.wall_contacts(w, wr, walls, 0.0)) == 0.0)
    # two 1 cm cells: the left one's particles creep at 1 mm/s (static below 4 mm/s), the right's move
    s = numpy.array([[0.002, 0.002, r], [0.006, 0.002, r], [0.012, 0.002, r], [0.016, 0.002, r]])
    v = numpy.array([[0.001, 0, 0], [0, -0.001, 0], [0.05, 0, 0], [0, 0.001, 0]])
    static = contacts.static_mask(s, v, (0, 0, 0), (0.01, 0.01, 0.004), (2, 1, 1), 0.004)
    nc = numpy.array([2, 2, 0, 1])
    check("contacts: a static cell is masked out (bulk N_c of the rest 0.5, caption ratio 0)",
          static.tolist() == [True, True, False, False] and contacts.bulk_coordination(nc, ~static) == 0.5
          and contacts.multicontact_ratio(nc, ~static) == 0.0, str(static.tolist()))
    # the numpy binning (no scipy) finds the k-d tree's pairs in a random cloud
    cloud = numpy.random.default_rng(3).uniform(0, 0.05, (600, 3)) * [1, 1, 0.1]
    cr = numpy.full(600, r)
    tree = contacts.contact_pairs(cloud, cr, 0.01)
    saved = contacts.cKDTree
    contacts.cKDTree = None
    try:
        binned = contacts.contact_pairs(cloud, cr, 0.01)
    finally:
        contacts.cKDTree = saved
    brute = [[i, j] for i in range(600) for j in range(i + 1, 600)
             if numpy.sum((cloud[i] - cloud[j]) ** 2) < (2 * r * 1.01) ** 2]
    check("contacts: numpy binning and the k-d tree find the brute-force pairs",
          binned.tolist() == brute and (saved is None or tree.tolist() == brute), f"{len(binned)} {len(tree)} {len(brute)}")


def check_jiggle(root):
    """Random velocities of a given spread on a data file of 4000 atoms at rest: each component's
    sample standard deviation within 4 sigma of the asked 1e-6 m/s (a normal sample's standard
    deviation has a standard error of sigma / sqrt(2 n), 1.1 % at n = 4000), means near zero
    (standard error sigma / sqrt(n)), spins and positions untouched; the same seed gives the
    same velocities, another seed others."""
    n, speed = 4000, 1e-6
    atoms = "".join(f"{i} 1 0.0025 2500 {0.001 * (i % 100)!r} {0.001 * (i // 100)!r} 0.0015 0 0 0\n"
                    for i in range(1, n + 1))
    text = (f"LIGGGHTS data file\n\n{n} atoms\n1 atom types\n\n0 0.1 xlo xhi\n0 0.05 ylo yhi\n0 0.003 zlo zhi\n\n"
            f"Atoms\n\n{atoms}\nVelocities\n\n" + "".join(f"{i} 0 0 0 0 0 0\n" for i in range(1, n + 1)))

    def velocities(seed):
        path = os.path.join(root, f"jiggled_{seed}.data")
        write(path, text)
        jiggle(path, speed, seed)
        lines = open(path).read().split("\n")
        start = lines.index("Velocities") + 2
        rows = [line.split() for line in lines[start:start + n]]
        check("jiggled: atoms kept", lines[:lines.index("Velocities")] == text.split("\n")[:lines.index("Velocities")])
        check("jiggled: ids in order, spins zero", [int(r[0]) for r in rows] == list(range(1, n + 1))
              and all(r[4:7] == ["0", "0", "0"] for r in rows))
        return numpy.array([[float(v) for v in r[1:4]] for r in rows])

    v = velocities(7)
    for axis in range(3):
        spread = v[:, axis].std(ddof=1)
        check(f"jiggled: component {axis}'s spread {speed:g} m/s within 4 sigma",
              abs(spread / speed - 1) < 4 / math.sqrt(2 * n), f"{spread:.4g}")
        check(f"jiggled: component {axis}'s mean zero within 4 sigma",
              abs(v[:, axis].mean()) < 4 * speed / math.sqrt(n), f"{v[:, axis].mean():.3g}")
    check("jiggled: the same seed, the same velocities", numpy.array_equal(v, velocities(7)))
    check("jiggled: another seed, other velocities", not numpy.allclose(v, velocities(8)))


class FlakyPreparation(CaseRun):
    """A run whose preparation fails part-way the first time (as a pour can), after its
    folder and status file exist; its 'solver' ends only when the preparation finished."""
    attempts = 0

    def prepare(self, end_time):
        FlakyPreparation.attempts += 1
        if os.path.isdir(self.case.path):
            shutil.rmtree(self.case.path)
        write(self.case.file("system", "controlDict"), "endTime 1;\nstartFrom startTime;\n")
        self.set_status(state="preparing", end_time=end_time)
        if FlakyPreparation.attempts == 1:
            raise RuntimeError("the pour failed")
        write(self.case.file("packed_bed.data"), "atoms\n")

    def command(self):
        return ["sh", "-c", "test -f packed_bed.data && echo End"]


def check_failed_preparation(root):
    """A batch run again after a preparation that failed part-way prepares the run anew (it
    was taken as prepared, and the solver then found no packed bed)."""
    flaky = FlakyPreparation("flaky", os.path.join(root, "flaky"))
    try:
        run_batch([flaky], 1.0, 1, poll=0.05)
        first = "no error"
    except RuntimeError as e:
        first = str(e)
    check("a preparation that fails part-way stops the batch", first == "the pour failed", first)
    finished = run_batch([flaky], 1.0, 1, poll=0.05)
    check("run again, the run is prepared anew and finishes", finished and FlakyPreparation.attempts == 2
          and flaky.done(), f"({finished}, {FlakyPreparation.attempts} preparations, {flaky.status()})")


def main():
    root = tempfile.mkdtemp()
    # A run to t = 0.3 killed and resumed from its checkpoint at 0.2: the first segment's rows
    # after 0.2 are superseded by the resumed segment's.
    write(os.path.join(root, "postProcessing", "s", "0", "v.dat"), "# t v\n0.1 1\n0.2 2\n0.3 99\n")
    write(os.path.join(root, "postProcessing", "s", "0.2", "v.dat"), "0.3 3\n0.4 4\n")
    rows = joined_series(root, "s", "v.dat")
    check("series joined over a resume", rows == [(0.1, [1.0]), (0.2, [2.0]), (0.3, [3.0]), (0.4, [4.0])], str(rows))
    write(os.path.join(root, "postProcessing", "s", "0", "v_0.dat"), "0.1 5\n")
    try:
        joined_series(root, "s", "v.dat")
        check("a file of an earlier run beside it is refused", False)
    except OutputError as e:
        check("a file of an earlier run beside it is refused", "mixes two runs" in str(e), str(e))

    # fix print appended by a resumed run from t = 0.2
    path = os.path.join(root, "height.txt")
    write(path, "# t h\n0.1 1\n0.2 2\n0.3 98\n0.3 3\n0.4 4\n")
    check("fix print rewound at a repeated time", fix_print(path) == [(0.1, [1.0]), (0.2, [2.0]), (0.3, [3.0]), (0.4, [4.0])])
    frame = "ITEM: TIMESTEP\n{}\nITEM: NUMBER OF ATOMS\n1\nITEM: BOX BOUNDS\n0 1\n0 1\n0 1\nITEM: ATOMS id x\n1 {}\n"
    path = os.path.join(root, "p.dump")
    write(path, frame.format(100, 1.0) + frame.format(200, 9.0) + frame.format(200, 2.0) + frame.format(300, 3.0))
    frames = dump_frames(path)
    check("dump rewound at a repeated step", sorted(frames) == [100, 200, 300] and frames[200][1][0][1] == 2.0)

    # The solver's time split summed over the segments that printed it (a killed segment did not)
    timed = os.path.join(root, "timed")
    line = ("TFDEM timing: DEM {} s, locate+map 0.5 s, forces 0.25 s, gas 3 s, statistics {} s, checkpoints 0.125 s; "
            "(DEM + coupling + gas) / DEM = 3.2 on 1 rank(s)\n")
    write(os.path.join(timed, "log.solver.1"), "ExecutionTime = 5 s\n" + line.format(1.5, 0.0625))
    write(os.path.join(timed, "log.solver.2"), "ExecutionTime = 2 s\n")
    write(os.path.join(timed, "log.solver.3"), line.format(2.5, 0.0625))
    t = CaseRun("timed", timed).timing_seconds()
    check("timing summed over the timed segments", t is not None and t["DEM"] == 4.0 and t["statistics"] == 0.125
          and t["gas"] == 6.0 and t["segments"] == 3 and t["segments_timed"] == 2, str(t))
    check("no timing line: None", CaseRun("none", os.path.join(root, "none")).timing_seconds() is None)
    check_failed_preparation(root)

    # coupling.yaml edited in place: a value, a new key in a section, a new section
    case_dir = os.path.join(root, "case")
    write(os.path.join(case_dir, "coupling.yaml"),
          "# a case\ndem:\n  script: in.bed   # the DEM\n  coupling_interval: 10\ncoupling:\n  transfer: averaged\n")
    case = Case(case_dir)
    set_yaml_value(case.file("coupling.yaml"), "coupling.transfer", "per_particle")
    set_yaml_value(case.file("coupling.yaml"), "dem.outlets", ["top"])
    set_yaml_value(case.file("coupling.yaml"), "output.statistics_interval", 0.01)
    text = open(case.file("coupling.yaml")).read()
    check("yaml edited: values", case.coupling_value("coupling.transfer") == "per_particle"
          and case.coupling_value("dem.outlets") == ["top"] and case.coupling_value("output.statistics_interval") == 0.01
          and case.coupling_value("dem.coupling_interval") == 10, text)
    check("yaml edited: comments kept", "# a case" in text and "# the DEM" in text)
    # a key whose old value is a block list (as yaml.safe_dump writes one) takes the new value alone
    listed = Case(os.path.join(root, "listed"))
    write(listed.file("coupling.yaml"), "dem:\n  outlets:\n  - outlet\n  - side\n  engine: hard_sphere\n")
    set_yaml_value(listed.file("coupling.yaml"), "dem.outlets", [])
    check("yaml edited: a block list replaced whole", listed.coupling_value("dem.outlets") == []
          and listed.coupling_value("dem.engine") == "hard_sphere", open(listed.file("coupling.yaml")).read())

    # Time steps: DEM 2e-5 s and gas 5e-4 s give 25 DEM steps per gas step; 3e-5 s is 1.5 steps
    write(case.file("in.bed"), "units si\ntimestep        1e-5\nrun 0\n")
    write(case.file("system", "controlDict"), "FoamFile { version 2.0; }\ndeltaT          1e-4;\nendTime 1;\n")
    case.set_time_steps(dem=2e-5, gas=5e-4)
    check("time steps set: DEM step, gas step, interval 25",
          case.dem_time_step() == 2e-5 and case.delta_t() == 5e-4 and case.coupling_value("dem.coupling_interval") == 25,
          f"{case.dem_time_step()} {case.delta_t()} {case.coupling_value('dem.coupling_interval')}")
    case.set_time_steps(gas=1e-3)
    check("gas step alone: DEM step kept, interval 50",
          case.dem_time_step() == 2e-5 and case.coupling_value("dem.coupling_interval") == 50)
    try:
        case.set_time_steps(gas=3e-5)
        check("a gas step that is not a whole number of DEM steps is refused", False)
    except CaseError as e:
        check("a gas step that is not a whole number of DEM steps is refused", "(1.5)" in str(e), str(e))
    try:
        case.set_time_steps(dem=0)
        check("a DEM step of 0 is refused", False)
    except CaseError as e:
        check("a DEM step of 0 is refused", "must both be positive" in str(e), str(e))

    # More ranks than gas cells are refused before decomposePar runs: a mesh whose owner file
    # says 120 cells, split over 121 ranks
    with tempfile.TemporaryDirectory() as where:
        os.makedirs(os.path.join(where, "constant", "polyMesh"))
        with open(os.path.join(where, "constant", "polyMesh", "owner"), "w") as f:
            f.write('FoamFile\n{\n    note        "nPoints:294  nCells:120  nFaces:506  nInternalFaces:214";\n}\n')
        check("the mesh's cell count from its owner header", mesh_cells(where) == 120, mesh_cells(where))
        try:
            decompose(where, 121)
            check("121 ranks for 120 cells refused", False)
        except RunError as e:
            check("121 ranks for 120 cells refused, the fix named", "121 ranks for a mesh of 120 cells" in str(e)
                  and "at most 120 ranks" in str(e), str(e))

    # A run resumed at 1 s of 20 s that reached 1.5 s in 60 s of wall: 18.5 s left at 0.5 s per
    # minute is 37 min (the rate since the start of the whole run, 1.5 s per minute, said 12 min)
    eta = eta_seconds(60.0, 1.5, 1.0, 20.0)
    check("ETA of a resumed run at its rate since the resume", abs(eta - 37 * 60.0) < 1e-9, eta)
    check("no ETA before 2 % of the span is done", eta_seconds(60.0, 1.2, 1.0, 20.0) != eta_seconds(60.0, 1.2, 1.0, 20.0))

    # Batch means of a square wave of period 1 s sampled at 0.01 s: batches of 1 s hold one
    # period each, so every batch mean is the wave's mean 0.5 and the error is 0.
    t = [k * 0.01 for k in range(1000)]
    y = [1.0 if (k % 100) < 50 else 0.0 for k in range(1000)]
    m, err, n = batch_means(t, y, 0.0, 10.0, 1.0)
    check("batch means of a whole-period square wave", abs(m - 0.5) < 1e-12 and err < 1e-12 and n == 10, f"{m} {err} {n}")
    # Two-level batches: means 0 and 1 alternate: mean 0.5, error std/sqrt(n-1) = 0.5/sqrt(9)
    y = [float(int(ti) % 2) for ti in t]
    m, err, n = batch_means(t, y, 0.0, 10.0, 1.0)
    check("batch-means error by hand", abs(m - 0.5) < 1e-12 and abs(err - 0.5 / math.sqrt(9)) < 1e-12, f"{m} {err}")

    # Slab 0 < y < 1 cm of area 1 cm^2 with three spheres of d = 4 mm: one inside (y = 5 mm),
    # one cut in half by y = 0, one whose cap of height 1 mm pokes in from above (centre at
    # y = 1.1 cm, r = 2 mm: cap pi h^2 (3r - h)/3 = pi (1 mm)^2 (5 mm)/3).
    v = math.pi * 4e-3 ** 3 / 6
    cap = math.pi * 1e-3 ** 2 * 5e-3 / 3
    fraction = slab_solid_fraction({"diameter": [4e-3] * 3, "y": [5e-3, 0.0, 1.1e-2]}, 0.0, 1e-2, 1e-4)
    check("slab solid fraction by hand", abs(fraction - (v + v / 2 + cap) / 1e-6) < 1e-12, f"{fraction}")

    # packing.yaml: its settings, an unknown key named, a missing count refused
    write(os.path.join(case_dir, "packing.yaml"), "count: 100\nmass_fraction_small: 0.25\n")
    check("packing.yaml read", packing_settings(case) == {"count": 100, "mass_fraction_small": 0.25})
    for text, expected in (("count: 100\nmas_fraction_small: 0.2\n",
                            "mas_fraction_small: unknown key (did you mean 'mass_fraction_small'?)"),
                           ("seed: 15485863\n", "count: missing")):
        write(os.path.join(case_dir, "packing.yaml"), text)
        try:
            packing_settings(case)
            check(f"packing.yaml refused: {expected}", False)
        except CaseError as e:
            check(f"packing.yaml refused: {expected}", expected in str(e), str(e))

    # A 10 x 8 map (cells 1 cm x 2 cm): freeboard in the top two rows, a 3-wide x 2-high bubble
    # (rows 3-4, columns 2-4) and a lone dilute cell (row 1, column 7), eps 0.9 in them, 0.45
    # elsewhere. Bubble: 6 cells = 12 cm^2, D = sqrt(4 * 12e-4 / pi), aspect 4 cm / 3 cm,
    # centroid x = 3.5 cm, y = 8 cm (rows 3-4 span 6-10 cm).
    eps = numpy.full((10, 8), 0.45)
    eps[8:, :] = 1.0
    eps[3:5, 2:5] = 0.9
    eps[1, 7] = 0.9
    bubble = find_bubble(eps, 0.01, 0.02)
    check("bubble by hand", bubble is not None and abs(bubble["area"] - 12e-4) < 1e-15
          and abs(bubble["diameter"] - math.sqrt(4 * 12e-4 / math.pi)) < 1e-12
          and abs(bubble["aspect"] - 4 / 3) < 1e-12 and abs(bubble["x"] - 0.035) < 1e-12
          and abs(bubble["y"] - 0.08) < 1e-12, str(bubble))
    eps[3:5, 2:5] = 0.45
    eps[1, 7] = 0.45
    check("no bubble once it has erupted", find_bubble(eps, 0.01, 0.02) is None)
    # Coloured layer: ids 1-4 start below 0.1 m, two of them now above it: 1/2.
    start = {1: 0.02, 2: 0.05, 3: 0.08, 4: 0.09, 5: 0.15}
    check("coloured fraction above the interface", coloured_above(start, [1, 2, 3, 4, 5], [0.2, 0.05, 0.12, 0.01, 0.3], 0.1) == 0.5)
    # The bed lifted by 0.05 m: two of the four coloured ones are above the old interface,
    # one above the new middle 0.15 m: 1/4.
    check("coloured fraction above a moved middle",
          coloured_above(start, [1, 2, 3, 4, 5], [0.07, 0.10, 0.13, 0.16, 0.3], 0.1, 0.15) == 0.25)

    # A one-layer bed poured in a slab, moved onto the mid-plane of a 4 mm deep box (its motion
    # untouched), written at rest, declared with the template's 2 atom types; a type beyond
    # them refused
    data = os.path.join(case_dir, "poured.data")
    write(data, "LIGGGHTS data file\n\n2 atoms\n3 atom types\n\n0 0.15 xlo xhi\n0 0.9 ylo yhi\n"
                "0 0.0042 zlo zhi\n\nAtoms\n\n1 1 0.004 2700 0.01 0.02 0.0019 0 0 0\n"
                "2 1 0.004 2700 0.05 0.02 0.0023 0 0 0\n\nVelocities\n\n1 0.1 0.2 0.3 0.4 0.5 0.6\n"
                "2 0 0 -0.01 0.02 0 1\n")
    to_mid_plane(data, 0.004)
    set_atom_types(data, 2)
    lines = open(data).read().split("\n")
    check("moved onto the mid-plane", lines[10].split()[6] == "0.002" and lines[11].split()[6] == "0.002", lines[10])
    check("box 4 mm deep", "0 0.004 zlo zhi" in lines, str(lines[:9]))
    check("motion untouched by the move", lines[15].split() == ["1", "0.1", "0.2", "0.3", "0.4", "0.5", "0.6"], lines[15])
    at_rest(data)
    lines = open(data).read().split("\n")
    check("written at rest: every velocity and spin zero",
          lines[15].split() == ["1"] + ["0"] * 6 and lines[16].split() == ["2"] + ["0"] * 6, str(lines[15:17]))
    check("centres kept at rest", lines[10].split()[4:7] == ["0.01", "0.02", "0.002"], lines[10])
    check_jiggle(case_dir)
    check("no overlap in the bed above: 0", largest_overlap(data) == 0.0, str(largest_overlap(data)))
    # By hand: a 4 mm and a 2 mm sphere 2.9 mm apart overlap by 0.1 mm, 5 % of the smaller
    # diameter; a third sphere 1 mm clear of both adds nothing
    pair = os.path.join(case_dir, "overlapping.data")
    write(pair, "LIGGGHTS data file\n\n3 atoms\n2 atom types\n\n0 0.15 xlo xhi\n0 0.9 ylo yhi\n"
                "0 0.004 zlo zhi\n\nAtoms\n\n1 1 0.004 2700 0.01 0.02 0.002 0 0 0\n"
                "2 2 0.002 2700 0.0129 0.02 0.002 0 0 0\n3 2 0.002 2700 0.0169 0.02 0.002 0 0 0\n")
    check("largest overlap by hand: 5 % of the smaller diameter", abs(largest_overlap(pair) - 0.05) < 1e-9,
          str(largest_overlap(pair)))
    check("2 atom types declared", "2 atom types" in lines, str(lines[:5]))
    try:
        set_atom_types(data, 0)
        message = ""
    except CaseError as e:
        message = str(e)
    check("a type beyond the declared count refused", "atoms of type 1, more than the 0 types" in message, message)

    # The gas layouts' commands: whole runs without -parallel, split with it; serial as is
    check("gas whole on 2 ranks: mpirun, no -parallel",
          command(["tfdemFoam"], 2, "whole") == ["mpirun", "-np", "2", "tfdemFoam"])
    check("gas split on 2 ranks: -parallel",
          command(["tfdemFoam"], 2, "split") == ["mpirun", "-np", "2", "tfdemFoam", "-parallel"])
    check("1 rank: the program alone", command(["tfdemFoam"], 1, "split") == ["tfdemFoam"])
    try:
        command(["tfdemFoam"], 2, "hole")
        message = ""
    except ValueError as e:
        message = str(e)
    check("a gas layout that does not exist is named with the valid ones",
          "'hole'" in message and "'whole'" in message and "'split'" in message, message)

    # A batch driver refuses an end time that is not positive (argparse's exit code 2)
    try:
        variants_command_line("doc", case_dir, {"a": {}}, None, None, 1.0, ["run", "--end-time", "0"])
        code = None
    except SystemExit as stop:
        code = stop.code
    check("batch driver refuses --end-time 0", code == 2, str(code))

    # Probes rewritten in place, comments and the other entries kept; a probe's cell centre
    write(case.file("system", "controlDict"), "FoamFile { version 2.0; }\nfunctions\n{\n  pressure\n  {\n"
          "    type probes; // p\n    probeLocations  ((0 0.0255 0) (0 0.1785 0));\n  }\n}\n")
    case.set_probe_locations("pressure", [(0, 0.0255, 0), (0, 0.1785, 0), (0.001, 0.07, 0.5)])
    check("probe locations rewritten", case.probe_locations("pressure") ==
          [(0, 0.0255, 0), (0, 0.1785, 0), (0.001, 0.07, 0.5)] and "// p" in open(case.file("system", "controlDict")).read())
    grid = Grid((0, 0.01, 0), (1, 0.002, 1), (1, 100, 1))
    check("the centre of the cell holding y = 0.0735 is 0.073 (cells of 2 mm from 0.01 m)",
          abs(grid.centre_of_cell_at(1, 0.0735) - 0.073) < 1e-15, str(grid.centre_of_cell_at(1, 0.0735)))
    check("a point past the grid takes its last cell's centre", abs(grid.centre_of_cell_at(1, 0.5) - 0.209) < 1e-15)

    # The run's softest contact (the pour's overlap bound is waived when the run is no stiffer)
    stiff = Case(os.path.join(root, "stiff"))
    write(stiff.file("coupling.yaml"), "dem:\n  script: in.bed\n")
    write(stiff.file("in.bed"), "variable kw equal 2*600\nfix m1 all property/global kn peratomtypepair 2 900 ${kw} "
          "${kw} 1500\n")
    check("the script's softest k_n by hand: 900 N/m", script_stiffness(stiff) == 900.0, str(script_stiffness(stiff)))
    write(stiff.file("in.bed"), "units si\n")
    check("a script without k_n: none", script_stiffness(stiff) is None)
    # the pour's own k_n, which a pour above 2 % overlap is weighed against (in.pour's default)
    try:
        pour_kn = DemScript(POUR_SCRIPT).value("${kn}")
    except ScriptError as e:
        pour_kn = str(e)
    check("in.pour reads as a script, its k_n 800 N/m (it is weighed against a run's)", pour_kn == 800.0, str(pour_kn))

    check_hard_sphere_laws(root)
    check_contact_definitions(root)

    # Jenkins & Zhang's effective restitution by hand: 0.97 - 0.15 exp(-0.3) = 0.97 - 0.15 x 0.7408182
    e = jenkins_zhang_effective_restitution(0.97, 0.1)
    check("Jenkins & Zhang's effective e of e 0.97, mu 0.1 is 0.8588773", abs(e - 0.8588773) < 1e-7, f"{e:.8f}")
    check("a frictionless sphere keeps its e", jenkins_zhang_effective_restitution(0.9, 0.0) == 0.9)

    print(f"{'FAILED: ' + ', '.join(failures) if failures else 'all passed'}")
    sys.exit(1 if failures else 0)


if __name__ == "__main__":
    main()
