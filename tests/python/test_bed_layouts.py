"""`tfdem stats`'s reading of a run (tfdem.bed, tfdem.bedstats) on every layout a user may
bring, on hand-made output files in the solver's formats (no simulation): one layer (one cell
deep), pseudo-2-D (3 cells deep), 3-D (4 cells deep); one, two and nine sizes; the LIGGGHTS
and the hard-sphere engine; a run resumed once (two segments, the first one's rows past the
resume superseded), which is also what a run on N ranks writes (its probes and particles.dat
are written once, by the first rank, under the case's postProcessing).

Every case is a 4 x 16 cm column of 1 cm gas cells written by `tfdem new` (cells x = 5, 15,
25, 35 mm; y = 5 ... 155 mm; z at the centres of the depth's cells). The hand-made values and
the answers by hand:

- the maps: void fraction eps(x, y, z) = 0.4 + 0.5 y / 0.16 m + 0.1 (z / D - 1/2) at every
  cell centre, D the depth. The z term averages to zero over the depth's cell centres
  (symmetric about D / 2), so the depth-averaged solids fraction of row j is
  0.6 - 0.5 y_j / 0.16: 0.584375 at y = 5 mm, 0.115625 at 155 mm, whatever the depth. The
  front cells alone would give 0.1 (1/2 - 1/(2 n_z)) less: 0.0333 less at n_z = 3.
- Delta p: the bed's floor is y = 10 mm (above the empty windbox row tfdem new puts below a
  bed fed through its whole bottom), its first rows of cell centres 15 and 25 mm, the
  column's highest 155 mm (20 cm do not fit: the upper level is that row, 14.5 cm above the
  floor). p on the first row 101625 + 40 z / D + 10 sin(2 pi 5 t) Pa, on the second 20 Pa
  less, on the top row 101327 + 6 x / 0.04 m Pa. The cross-section means: 101645 + sine at
  15 mm, 20 less at 25 mm, so 101655 + sine extrapolated linearly to the floor (half a cell
  below the first row); 101330 at 155 mm: Delta p = 325 Pa, the sine averaging out over the
  window 0.2-1 s (four whole periods); the front cells alone would give 305 + 20 / n_z.
  Its dominant frequency 5 Hz (resolution 1 / 0.8 s).
- the weight per area: ten spheres of each size, sum 2498.8 (9.81) pi d^3 / 6 / (0.04 D);
  for one size of 2 mm one layer deep (D = 2 mm): 10 (2498.8) (9.81) (4.18879e-9)
  / (0.04 (0.002)) = 12.835 Pa.
- the mean particle height 2 cm (particles.dat).
"""
import math
import os
import re
import sys
import tempfile

import numpy

from handmade_run import (bed_yaml, buoyant_weight_per_area, make_case, write_data_file, write_particles_dat,
                          write_probes)
from tfdem.bed import FIELDS, PRESSURE, default_dp_height, write_bed_probes
from tfdem.bedstats import describe, plot, statistics

failures = []
WIDTH, HEIGHT, CELL = 0.04, 0.16, 0.01
# m: the bed's floor (above a windbox row of 1 cm), its first two rows of cell centres and the
# column's highest row, Delta p's upper level (the column is shorter than 20 cm)
FLOOR, BOTTOM, SECOND, TOP = 0.010, 0.015, 0.025, 0.155
START, END, BATCH, BAND = 0.2, 1.0, 0.2, 0.05
NINE_SIZES = [0.0012 + 0.0001 * k for k in range(9)]
LAYOUTS = {  # name: (depth, diameters, engine, cells across the depth, resumed)
    "one layer, one size": ("one_layer", [0.002], "liggghts", 1, False),
    "pseudo-2-D, two sizes": (0.03, [0.0015, 0.002], "liggghts", 3, False),
    "3-D, nine sizes": (0.04, NINE_SIZES, "liggghts", 4, False),
    "3-D, hard spheres": (0.04, [0.002], "hard_sphere", 4, False),
    "3-D, resumed (as N ranks write)": (0.04, [0.002], "liggghts", 4, True),
}


def check(name, condition, detail=""):
    print(("PASS " if condition else "FAIL ") + name + (f" {detail}" if detail else ""))
    if not condition:
        failures.append(name)


def close(name, value, expected, tolerance=1e-9):
    check(name, abs(value - expected) <= tolerance * max(1.0, abs(expected)), f"({value:.10g} vs {expected:.10g})")


def centres(n, spacing):
    return [(k + 0.5) * spacing for k in range(n)]


def probe_points(text, name):
    """The probeLocations of function `name` in a controlDict's text, as rounded tuples."""
    body = re.search(rf"{name}\s*\{{.*?probeLocations\s*\((.*?)\);", text, re.S).group(1)
    return sorted(tuple(round(float(v), 9) for v in point.split()) for point in re.findall(r"\(([^()]*)\)", body))


def hand_outputs(case, depth, nz, diameters, resumed):
    """The run's files: maps every 0.05 s, p and particles.dat every 0.01 s, to 1 s."""
    dz = depth / nz
    cells = [(x, y, z) for z in centres(nz, dz) for y in centres(16, CELL) for x in centres(4, CELL)]
    bottom = [(x, BOTTOM, z) for z in centres(nz, dz) for x in centres(4, CELL)]
    second = [(x, SECOND, z) for z in centres(nz, dz) for x in centres(4, CELL)]
    top = [(x, TOP, z) for z in centres(nz, dz) for x in centres(4, CELL)]

    def eps(x, y, z):
        return 0.4 + 0.5 * y / HEIGHT + 0.1 * (z / depth - 0.5)

    def pressure(t, wrong=0.0):
        return ([101625 + 40 * z / depth + 10 * math.sin(2 * math.pi * 5 * t) + wrong for _, _, z in bottom]
                + [101605 + 40 * z / depth + 10 * math.sin(2 * math.pi * 5 * t) + wrong for _, _, z in second]
                + [101327 + 6 * x / WIDTH for x, _, _ in top])

    field_t = [round(0.05 * k, 10) for k in range(1, 21)]
    p_t = [round(0.01 * k, 10) for k in range(1, 101)]
    bidisperse = len(diameters) == 2
    particle_row = lambda t: [t, 10 * len(diameters), 0.01, 0.02, 4.5, 0.95] + ([0.1] if bidisperse else [])
    # a resumed run: the first segment ran on to 0.6 s (rows past 0.5 s superseded; their
    # Delta p is 1000 Pa off), the second started at 0.5 s
    segments = [("0", 0.6 if resumed else 1.0, 1000.0 if resumed else 0.0)] + ([("0.5", 1.0, 0.0)] if resumed else [])
    for start, end, wrong in segments:
        after = float(start)
        pick = lambda times: [t for t in times if after < t <= end + 1e-9]
        for field in ("voidFraction", "contactForceByWeight", "dragForceByWeight", "granularTemperature"):
            value = {"voidFraction": eps}.get(field, lambda x, y, z: 1.0)
            write_probes(case, FIELDS, field, cells, [(t, [value(*c) for c in cells]) for t in pick(field_t)], start)
        write_probes(case, PRESSURE, "p", bottom + second + top,
                     [(t, pressure(t, wrong if t > 0.5 + 1e-9 else 0.0)) for t in pick(p_t)], start)
        write_particles_dat(case, [particle_row(t) for t in pick(p_t)], bidisperse, start)
    atoms = [(k + 1, d, 0.02, 0.01 + 0.003 * n, depth / 2) for k, d in enumerate(diameters) for n in range(10)]
    write_data_file(case.file("bed.data"), atoms, ((0, 0, 0), (WIDTH, HEIGHT, depth)))
    return cells, bottom + second + top


def check_layout(root, name, depth, diameters, engine, nz, resumed):
    case, _, dv = make_case(root, re.sub(r"\W+", "_", name), bed_yaml(depth, diameters, engine))
    depth = dv["depth"]
    check(f"{name}: tfdem new's grid 4 x 16 x {nz}", (dv["nx"], dv["ny"], dv["nz"]) == (4, 16, nz))
    cells, rows = hand_outputs(case, depth, nz, diameters, resumed)
    write_bed_probes(case, 0.05, 0.01, dp_height=default_dp_height(case))  # as tfdem stats does
    text = open(case.file("system", "controlDict")).read()
    rounded = lambda points: sorted(tuple(round(v, 9) for v in p) for p in points)
    check(f"{name}: the map probes at every cell centre, every depth's", probe_points(text, FIELDS) == rounded(cells))
    check(f"{name}: the Delta p probes at every cell of the three rows (the floor's two, the top's), across the "
          "width and depth",
          probe_points(text, PRESSURE) == rounded(rows))
    s, outputs = statistics(case, START, END, BATCH, BAND)
    expected_map = numpy.array([0.6 - 0.5 * y / HEIGHT for y in centres(16, CELL)])
    average = outputs.field_average(outputs.solids, START, END)
    check(f"{name}: the map is (rows, columns) = (16, 4)", average.shape == (16, 4), str(average.shape))
    check(f"{name}: the map averaged over the depth (0.584375 at 5 mm ... 0.115625 at 155 mm)",
          numpy.allclose(average, expected_map[:, None], atol=1e-12), f"({average[0, 0]:.6f} ... {average[-1, 0]:.6f})")
    # cross-section means: 101645 Pa at 15 mm, 101625 at 25 mm, so 101655 extrapolated to the
    # floor at 10 mm (half a cell below the first row: + 20 / 2); 101330 at 155 mm
    close(f"{name}: Delta p from the floor (extrapolated) to the top row, 325 Pa", s["dp_mean"]["value"], 325.0, 1e-6)
    check(f"{name}: Delta p levels at 10 and 155 mm", numpy.allclose(s["dp_levels"], [FLOOR, TOP]),
          str(s["dp_levels"]))
    check(f"{name}: dominant frequency 5 Hz within the spectral resolution", abs(s["dp_frequency"]["value"] - 5.0)
          <= s["dp_frequency"]["error"], f"({s['dp_frequency']['value']:.4g} +- {s['dp_frequency']['error']:.3g} Hz)")
    close(f"{name}: mean particle height 2 cm", s["mean_height"]["value"], 0.02)
    close(f"{name}: weight per area by hand", s["weight_per_area"],
          buoyant_weight_per_area([d for d in diameters for _ in range(10)], WIDTH, depth), 1e-9)
    if name == "one layer, one size":
        close(f"{name}: weight per area 12.835 Pa (the docstring's numbers)", s["weight_per_area"], 12.835, 1e-4)
    said = "averaged over the depth" in s["map"] if nz > 1 else "one cell deep" in s["map"]
    check(f"{name}: the report says what a map cell stands for", said and any(s["map"] in line for line in describe(s)),
          f"({s['map']})")
    figure = os.path.join(root, re.sub(r"\W+", "_", name) + ".png")
    plot(outputs, s, figure)
    check(f"{name}: the figure written", os.path.getsize(figure) > 1000)
    return outputs


def main():
    with tempfile.TemporaryDirectory() as root:
        for name, (depth, diameters, engine, nz, resumed) in LAYOUTS.items():
            outputs = check_layout(root, name, depth, diameters, engine, nz, resumed)
            check(f"{name}: BedOutputs says how many cells it averaged", outputs.depth_cells == nz)
    if failures:
        print(f"{len(failures)} check(s) failed: {', '.join(failures)}")
        sys.exit(1)
    print("all passed")


if __name__ == "__main__":
    main()
