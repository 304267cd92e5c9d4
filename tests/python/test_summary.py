"""`tfdem summary CASE` (tfdem.summary) on hand-made outputs in the solver's and LIGGGHTS'
formats (no simulation): a bed one layer deep and a 3-D bed, one size and two, both engines,
a run resumed once and a run stopped before its first particle file.

Every case is a 4 x 16 cm column of 1 cm cells written by `tfdem new` (uniform inflow: the
bed's floor above an empty windbox row), run to 0.1 s. The hand-made values and the answers
by hand:

- p: the inlet's area average 101625 + 5 sin(2 pi 100 t) Pa every 1 ms, the top row's
  101327 Pa. A row of summary.csv (every 0.01 s, the particle statistics) carries Delta p's
  mean over the ten samples since the previous row, a whole period of the sine: 298 Pa.
- particles.dat: the mean particle height 0.02 + 0.1 t m, bulk coordination 4.5, multicontact
  0.95, and for two sizes the segregation degree 0.1: copied into the row of that time.
- forces.txt (LIGGGHTS): per 1 ms the gas 0.9 W +- 0.01 W (alternating, so that the ten
  samples of a row average to 0.9 W), the floor 0.05 W, the side walls 0.01 W and 0.005 W,
  the lid 0, and in 3-D the front and back walls 0.02 W and 0.015 W: rows of gas 0.9, floor
  0.05, walls 0.015 (one layer) or 0.05 (3-D), lid 0; W = the data file's sum of rho pi d^3 / 6
  g (ten spheres of 2 mm: 10 (2500) pi 8e-9 / 6 (9.81) = 1.02730e-3 N).
- a resumed run (restarted from 0.05 s after running on to 0.06 s): 10 rows, the first run's
  rows past 0.05 s superseded (their Delta p 1000 Pa off, their gas force 1 W off).
- the snapshot: the last particle file (0.1 s; 0.05 s written too), or before any, the bed
  the run started from; a 3-D bed drawn as a mid-depth slice 2 d thick.
- the lid warning: none when the lid carries nothing; the lid's share over the run's second
  half, or the particles at the lid for hard spheres, by hand in check_lid_warnings.
"""
import contextlib
import io
import math
import os
import re
import sys
import tempfile

from handmade_run import (G, RHO, bed_yaml, make_case, write, write_data_file, write_forces, write_particles_dat,
                          write_surface_average, write_vtk_particles)
from tfdem import summary

failures = []
CASES = {  # name: (depth, diameters, engine, resumed, particle files written)
    "one layer, one size": ("one_layer", [0.002], "liggghts", False, True),
    "one layer, two sizes, hard spheres": ("one_layer", [0.0015, 0.002], "hard_sphere", False, True),
    "3-D, one size, resumed": (0.04, [0.002], "liggghts", True, True),
    "3-D, two sizes, stopped before a particle file": (0.04, [0.0015, 0.002], "liggghts", False, False),
}
END = 0.1


def check(name, condition, detail=""):
    print(("PASS " if condition else "FAIL ") + name + (f" {detail}" if detail else ""))
    if not condition:
        failures.append(name)


def close(a, b, tolerance=1e-9):
    return abs(a - b) <= tolerance * max(1.0, abs(b))


def hand_outputs(case, depth, diameters, resumed, particle_files):
    """The run's files; a resumed run's first segment runs on to 0.06 s with wrong values."""
    atoms = [(k + 1, d, 0.002 + 0.0035 * n, 0.012 + 0.002 * k, depth / 2) for k, d in enumerate(diameters)
             for n in range(10)]
    write_data_file(case.file("bed.data"), atoms, ((0, 0.01, 0), (0.04, 0.16, depth)))
    weight = sum(RHO * math.pi * d ** 3 / 6 for _, d, *_ in atoms) * G
    two_sizes, three_d = len(diameters) == 2, case.grid().counts[2] > 1
    segments = [("0", 0.06, True), ("0.05", END, False)] if resumed else [("0", END, False)]
    for start, end, wrong in segments:
        after = float(start)
        millis = [round(0.001 * k, 10) for k in range(1, 101) if after + 1e-9 < 0.001 * k <= end + 1e-9]
        off = lambda t: 1000.0 if wrong and t > 0.05 + 1e-9 else 0.0
        write_surface_average(case, "inletPressure", "inlet", 4, 0.0016,
                              [(t, 101625 + 5 * math.sin(2 * math.pi * 100 * t) + off(t)) for t in millis], start)
        write_surface_average(case, "abovePressure", "abovePressurePlane", 4, 0.0016,
                              [(t, 101327.0) for t in millis], start)
        hundredths = [t for t in millis if abs(round(t, 2) - t) < 1e-12]
        write_particles_dat(case, [[t, 10 * len(diameters), 0.01, 0.02 + 0.1 * t, 4.5, 0.95] + ([0.1] if two_sizes else [])
                                   for t in hundredths], two_sizes, start)
        if not case.hard_sphere():
            write_forces_segment(case, millis, weight, three_d, wrong, append=start != "0")
    if particle_files:
        for t in (0.05, END):
            write_vtk_particles(case.file("VTK", f"particles_{t:g}.vtk"), t,
                                [(k, d, (x, y + t, z)) for k, (_, d, x, y, z) in enumerate(atoms)])
    return weight


def write_forces_segment(case, millis, weight, three_d, wrong, append):
    """forces.txt rows at each 1 ms (a DEM step of t / dt); a resumed run appends."""
    dt = case.dem().time_step()
    rows = []
    for t in millis:
        k = int(round(t * 1000))
        gas = 0.9 * weight + 0.01 * weight * (-1) ** k + (1.0 if wrong and t > 0.05 + 1e-9 else 0.0)
        row = [int(round(t / dt)), gas, 0.05 * weight, 0.01 * weight, 0.005 * weight, 0.0]
        rows.append(row + ([0.02 * weight, 0.015 * weight] if three_d else []))
    path = case.file("forces.txt")
    before = open(path).read() if append else ""
    write_forces(case, rows)
    if append:
        write(path, before + open(path).read())


def run_summary(case_path):
    out, err = io.StringIO(), io.StringIO()
    with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
        code = summary.main([case_path])
    return code, out.getvalue(), err.getvalue()


def check_case(root, name, depth, diameters, engine, resumed, particle_files):
    case, _, dv = make_case(root, re.sub(r"\W+", "_", name), bed_yaml(depth, diameters, engine))
    weight = hand_outputs(case, dv["depth"], diameters, resumed, particle_files)
    code, out, err = run_summary(case.path)
    csv, png = case.file("summary.csv"), case.file("summary.png")
    check(f"{name}: exit 0, the two paths printed as the last lines", code == 0 and out.splitlines()[-2:] == [csv, png],
          f"({code}: {out.splitlines()[-2:]} {err})")
    lines = open(csv).read().splitlines()
    header = lines[0]
    rows = [[float(v) for v in line.split(",")] for line in lines[1:]]
    check(f"{name}: the header names the units", all(u in header for u in ("t (s)", "dp (Pa)", "mean particle height (m)",
                                                                          "mass (kg)")), header)
    check(f"{name}: the segregation degree for two sizes only", ("segregation degree" in header) == (len(diameters) == 2))
    liggghts = engine == "liggghts"
    check(f"{name}: the forces for LIGGGHTS only", ("gas force / weight" in header) == liggghts)
    times = [round(0.01 * k, 10) for k in range(1, 11)]
    check(f"{name}: a row every 0.01 s to 0.1 s, superseded rows dropped", [r[0] for r in rows] == times,
          f"({[r[0] for r in rows]})")
    check(f"{name}: Delta p 298 Pa in every row", all(close(r[1], 298.0, 1e-9) for r in rows),
          f"({[round(r[1], 6) for r in rows]})")
    check(f"{name}: mean particle height 0.02 + 0.1 t", all(close(r[2], 0.02 + 0.1 * r[0]) for r in rows))
    if liggghts:
        walls = 0.05 if case.grid().counts[2] > 1 else 0.015
        first = len(rows[0]) - 4
        shares = [r[first:] for r in rows]
        check(f"{name}: gas 0.9, floor 0.05, walls {walls}, lid 0 of the weight ({weight:.6g} N)",
              all(close(a, b, 1e-7) for s in shares for a, b in zip(s, (0.9, 0.05, walls, 0.0))), f"({shares[-1]})")
    check(f"{name}: no lid warning (the lid carries nothing)", "warning" not in out, out)
    check(f"{name}: the picture written", os.path.getsize(png) > 1000)
    snapshot, particles = summary.last_particles(case)
    check(f"{name}: the snapshot is the last particle file, else the starting bed",
          snapshot == (END if particle_files else None) and len(particles["diameter"]) == 10 * len(diameters),
          f"({snapshot})")


def check_refusals(root):
    code, _, err = run_summary(os.path.join(root, "nowhere"))
    check("not a case: exit 2, named", code == 2 and "not a case folder" in err, err.strip())
    case, _, _ = make_case(root, "not_run", bed_yaml("one_layer", [0.002]))
    code, _, err = run_summary(case.path)
    check("a case that has not run: exit 2, the missing output named", code == 2 and "tfdemParticles" in err,
          err.strip())
    check("... and nothing written", not os.path.exists(case.file("summary.csv")))


def check_mid_depth_slab():
    """2 mm spheres: a box 40 mm deep is drawn as the slice 4 mm thick about z = 20 mm (centres
    within 2 mm of it), a box 6 mm deep (3 d, under 2 x 2 d) whole."""
    z = [0.005, 0.0185, 0.0199, 0.0215, 0.0205, 0.0225, 0.035]
    particles = {"position": [(0.01, 0.02, v) for v in z], "diameter": [0.002] * len(z)}
    position, d, slab = summary.mid_depth_slab(particles, 0.0, 0.04)
    check("3-D: the mid-depth slice 4 mm thick holds the centres within 2 mm of z = 20 mm",
          slab == (0.02, 0.004) and sorted(position[:, 2]) == [0.0185, 0.0199, 0.0205, 0.0215] and len(d) == 4,
          f"({slab}, {sorted(position[:, 2])})")
    position, d, slab = summary.mid_depth_slab(particles, 0.0, 0.006)
    check("a bed 3 d deep: every particle, no slice", slab is None and len(d) == len(z), f"({slab})")


def check_lid_warnings(root):
    """The lid's share over the run's second half: rows at 0.01 ... 0.1 s with the lid carrying
    -0.04 of the weight to 0.05 s and -0.2 after: the half from 0.05 s holds 0.05 s (-0.04)
    and 0.06 ... 0.1 s (-0.2), a mean |share| of (0.04 + 5 x 0.2) / 6 = 0.17333; with -0.06
    after 0.05 s, (0.04 + 5 x 0.06) / 6 = 0.0567 > 0.05, and -0.05 gives 0.04833: none.
    Hard spheres (no lid column): 3 of 40 particles of 2 mm with their centres 1 mm under the
    lid at y = 0.16 m warn (7.5 %), 2 of 40 (5 %) do not."""
    case, _, _ = make_case(root, "lid", bed_yaml(0.04, [0.002]))
    header = ["t (s)", "dp", "mean particle height (m)", summary.FORCES[3] + " (mean since the previous row)"]
    for late, expected in ((0.2, 0.17333), (0.06, 0.0567), (0.05, None)):
        rows = [[0.01 * k, 0.0, 0.0, -0.04 if k <= 5 else -late] for k in range(1, 11)]
        warnings = summary.lid_warnings(case, header, rows)
        if expected is None:
            check(f"the lid carrying 0.048 of the weight: no warning", warnings == [], str(warnings))
        else:
            check(f"the lid carrying {expected:.3g} of the weight over 0.05-0.1 s: a warning with the share and the fix",
                  len(warnings) == 1 and f"carries {expected:.2f} of the bed's weight" in warnings[0]
                  and "t = 0.05 to 0.1 s" in warnings[0] and "box.height" in warnings[0], str(warnings))
    hard, _, _ = make_case(root, "lid_hard_spheres", bed_yaml(0.04, [0.002], "hard_sphere"))
    for at_lid, warned in ((3, True), (2, False)):
        particles = [(k, 0.002, (0.002 + 0.0009 * k, 0.159 if k < at_lid else 0.02, 0.02)) for k in range(40)]
        write_vtk_particles(hard.file("VTK", "particles_0.1.vtk"), 0.1, particles)
        warnings = summary.lid_warnings(hard, ["t (s)", "dp", "mean particle height (m)"], [[0.1, 0.0, 0.0]])
        check(f"hard spheres, {at_lid} of 40 at the lid: {'a warning' if warned else 'none'}",
              (len(warnings) == 1 and f"{at_lid} of the 40 particles" in warnings[0]) if warned else warnings == [],
              str(warnings))


def main():
    check_mid_depth_slab()
    with tempfile.TemporaryDirectory() as root:
        for name, settings in CASES.items():
            check_case(root, name, *settings)
        check_refusals(root)
        check_lid_warnings(root)
    if failures:
        print(f"{len(failures)} check(s) failed: {', '.join(failures)}")
        sys.exit(1)
    print("all passed")


if __name__ == "__main__":
    main()
