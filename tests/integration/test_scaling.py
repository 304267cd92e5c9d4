"""The cost-against-size benchmark (bench/scaling/scaling.py).

1. Tiling a hand-made data file of two atoms (with velocities) 3 times, 0.1 m wide: 6 atoms,
   ids 1-6, copy k at x + 0.1 k, velocities copied, box x 0-0.3 m.
2. The bubbling bed widened 4 times: mesh x 0-0.6 m with 60 x 45 cells, the DEM's right wall
   at x = 0.6 m (0.15 x 4 by hand).
3. A tiny run (the bed twice as wide, 1 and 2 ranks, 0.001 s): 8000 particles and 1350 cells
   (2 x 4000, 2 x 15 x 45), positive finite costs, its CSV, plot and table written.
"""
import csv
import importlib.util
import math
import os
import subprocess

from tfdem import SOURCE_DIR, TUTORIALS
from tfdem.case import Case
from tfdem.liggghts import read_data_box, read_data_file
from tfdem.run import environment
from tfdem_testlib import Checks, scratch

SCALING = os.path.join(SOURCE_DIR, "bench", "scaling", "scaling.py")

TWO_ATOMS = """LAMMPS data file, hand-made

2 atoms
2 atom types

0.0 0.1 xlo xhi
0.0 0.2 ylo yhi
0.0 0.0025 zlo zhi

Atoms

1 1 0.0025 2526 0.01 0.05 0.00125 0 0 0
2 1 0.0025 2526 0.09 0.03 0.00125 0 0 0

Velocities

1 0.5 0 0 0 0 0
2 0 -0.25 0 0 0 0
"""


def load_scaling():
    spec = importlib.util.spec_from_file_location("scaling", SCALING)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def check_tiling(checks, scaling):
    root = scratch("scaling_tiling")
    source, dest = os.path.join(root, "two.data"), os.path.join(root, "six.data")
    open(source, "w").write(TWO_ATOMS)
    checks.true("tile returns 6 atoms", scaling.tile_data_file(source, dest, 3, 0.1) == 6)
    atoms = read_data_file(dest)
    checks.true("ids 1-6", atoms["id"] == [1, 2, 3, 4, 5, 6])
    for got, expected in zip(atoms["x"], [0.01, 0.09, 0.11, 0.19, 0.21, 0.29]):
        checks.within("x of a copy", got, expected, 1e-12)
    checks.true("y copied", atoms["y"] == [0.05, 0.03] * 3)
    checks.within("box x upper", read_data_box(dest)[1][0], 0.3, 1e-12)
    velocities = open(dest).read().split("Velocities", 1)[1].split()
    checks.true("velocities of copy 3 (ids 5, 6)", velocities[28:35] == ["5", "0.5", "0", "0", "0", "0", "0"]
                and velocities[35:37] == ["6", "0"])


def check_widen(checks, scaling):
    case = Case(os.path.join(TUTORIALS, "bubbling_bed")).copy_to(os.path.join(scratch("scaling_widen"), "case"))
    scaling.widen(case, 4)
    lower, upper = case.mesh_bounds()
    checks.within("mesh x lower", lower[0], 0.0, 1e-12)
    checks.within("mesh x upper", upper[0], 0.6, 1e-12)
    checks.true("60 x 45 cells", tuple(case.grid().counts[:2]) == (60, 45))
    checks.true("right wall at 0.6 m", case.dem().command("fix", "wall_x1")[-4:-2] == ["xplane", "0.6"])


def check_tiny_run(checks):
    root = scratch("scaling_run")
    proc = subprocess.run(["/usr/bin/python3", SCALING, "run", "--factors", "2", "--ranks", "1", "2",
                           "--end-time", "0.001", "--root", root], env=environment(),
                          stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    print(proc.stdout[-3000:])
    checks.true("scaling.py run", proc.returncode == 0, f"(exit code {proc.returncode})")
    report = os.path.join(root, "report")
    for name in ("scaling.csv", "scaling.png", "README.md"):
        checks.true(f"report/{name} written", os.path.isfile(os.path.join(report, name)))
    if not os.path.isfile(os.path.join(report, "scaling.csv")):
        return
    rows = list(csv.DictReader(open(os.path.join(report, "scaling.csv"))))
    checks.true("two runs", sorted(float(r["ranks"]) for r in rows) == [1.0, 2.0])
    for r in rows:
        checks.true(f"{r['ranks']} rank(s): 8000 particles, 1350 cells",
                    float(r["particles"]) == 8000 and float(r["cells"]) == 1350)
        costs = [float(r[k]) for k in ("dem_per_particle_step", "coupling_per_particle_step", "gas_per_cell_step",
                                       "efficiency")]
        checks.true(f"{r['ranks']} rank(s): costs and efficiency positive and finite",
                    all(math.isfinite(c) and c > 0 for c in costs), f"{costs}")


def main():
    checks = Checks()
    scaling = load_scaling()
    check_tiling(checks, scaling)
    check_widen(checks, scaling)
    check_tiny_run(checks)
    checks.finish()


if __name__ == "__main__":
    main()
