#!/usr/bin/env python3
"""Peak memory per rank against the particle and cell counts, to a million particles.

For each particle count N a 3-D bed is generated with `tfdem new` (spheres of 2.5 mm, 2500
kg/m^3, a square column, gas cells of 4 d, and for some counts also of 3 d, the smallest `tfdem new` allows with the
centroid mapping: (4/3)^3 = 2.4 times the cells; uniform inflow of 1 m/s) and its bed is written as
a simple cubic lattice of spacing 1.05 d (a pour of a million would take hours; the memory
does not care how the spheres got there), filled row by row from the floor. The run is a
few coupling steps (`--steps`, each the generated gas step) on each rank count with the gas
whole on every rank; the solver's own report gives the peak resident set (VmHWM) of the
largest rank and over all, the cells and the time split.

Writes bench/scale_out/memory.csv (one row per N and rank count) and prints it. One run per
point on a shared machine: the memory is what it is, the times are a figure, not a
comparison.

Usage: . scripts/tfdem-env.sh; "$TFDEM_PYTHON" bench/scale_out/memory.py [--counts 4000 45000 ...] [--ranks 1 2]
"""
import argparse
import csv
import math
import os
import subprocess
import tempfile
import time

import numpy as np
import yaml

from tfdem import SOURCE_DIR, outputs
from tfdem.case import Case
from tfdem.run import run

HERE = os.path.dirname(os.path.abspath(__file__))
DIAMETER, DENSITY, SPACING = 0.0025, 2500.0, 1.05   # m, kg/m^3, lattice spacing / d
COLUMN_OVER_BED = 2.5                              # the column's height over the lattice's
FIELDS = ("particles", "cell_diameters", "cells", "ranks", "peak_rank_mb", "smallest_rank_mb", "total_mb", "mb_per_1000_particles_over_base",
          "dem_s_per_step", "gas_s_per_step", "coupling_s_per_step", "wall_s")


def lattice_shape(count):
    """(n across x and z, rows up y) of the square lattice that holds `count` spheres."""
    across = math.ceil(count ** (1.0 / 3.0))
    return across, math.ceil(count / across ** 2)


def bed_yaml(count, cell_diameters):
    across, rows = lattice_shape(count)
    spacing = SPACING * DIAMETER
    width = across * spacing
    return {"mesh": {"cell_size": cell_diameters * DIAMETER},"box": {"width": width, "height": COLUMN_OVER_BED * rows * spacing, "depth": width},
            "particles": {"density": DENSITY, "sizes": [{"diameter": DIAMETER, "number": count}],
                          "restitution": 0.9, "friction": 0.1},
            "inflow": {"velocity": 1.0},
            "run": {"end_time": 1.0, "write_interval": 1.0}}


def lattice_positions(count):
    """(count, 3) centres of the cubic lattice filled row by row from the floor: `across` spheres
    along x and z, rows up y."""
    across, _ = lattice_shape(count)
    k = np.arange(count)
    sites = np.column_stack([k % across, k // across ** 2, (k // across) % across])
    return (sites + 0.5) * (SPACING * DIAMETER)


def write_lattice(path, count, box):
    """A LIGGGHTS data file (atom_style granular, 2 atom types: spheres and walls) of `count`
    spheres at rest on a cubic lattice in the box from the floor up."""
    with open(path, "w") as f:
        f.write(f"TFDEM lattice bed of {count} spheres\n\n{count} atoms\n2 atom types\n\n")
        for axis, extent in zip("xyz", box):
            f.write(f"0 {extent!r} {axis}lo {axis}hi\n")
        f.write("\nAtoms\n\n")
        for k, (x, y, z) in enumerate(lattice_positions(count).tolist()):
            f.write(f"{k + 1} 1 {DIAMETER!r} {DENSITY!r} {x!r} {y!r} {z!r} 0 0 0\n")


def measure(count, cell_diameters, ranks, steps, where):
    case_dir = os.path.join(where, f"bed_{count}_{cell_diameters}_{ranks}")
    spec = os.path.join(where, f"bed_{count}_{cell_diameters}.yaml")
    with open(spec, "w") as f:
        yaml.safe_dump(bed_yaml(count, cell_diameters), f)
    subprocess.run([os.path.join(SOURCE_DIR, "tfdem"), "new", case_dir, "--from", spec], check=True,
                   stdout=subprocess.DEVNULL)
    case = Case(case_dir)
    gas_step = float(case.control("deltaT"))
    case.set_control(endTime=steps * gas_step, writeInterval=1.0)
    spec_box = bed_yaml(count, cell_diameters)["box"]
    write_lattice(case.file("bed.data"), count, (spec_box["width"], spec_box["height"], spec_box["depth"]))
    run(["blockMesh"], case_dir, "log.blockMesh")
    started = time.monotonic()
    run(["tfdemFoam"], case_dir, "log.tfdemFoam", ranks, gas="whole")
    wall = time.monotonic() - started
    log = case.file("log.tfdemFoam")
    peak, smallest, total = outputs.log_numbers(
        log, r"TFDEM memory: peak resident set (\S+) MB on the largest of \d+ rank\(s\) \(rank \d+\), (\S+) MB on the"
        r" smallest \(rank \d+\), (\S+) MB over all")
    cells = outputs.log_numbers(log, r"TFDEM coupling: Cartesian grid (\d+) x (\d+) x (\d+) cells")
    timing = outputs.solver_timing(log)
    return {"particles": count, "cell_diameters": cell_diameters, "cells": int(cells[0] * cells[1] * cells[2]), "ranks": ranks,
            "peak_rank_mb": round(peak, 1), "smallest_rank_mb": round(smallest, 1), "total_mb": round(total, 1),
            "dem_s_per_step": round(timing["DEM"] / steps, 3), "gas_s_per_step": round(timing["gas"] / steps, 3),
            "coupling_s_per_step": round((timing["locate+map"] + timing["forces"]) / steps, 3),
            "wall_s": round(wall, 1)}


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--counts", type=int, nargs="+", default=[4000, 45000, 300000, 1000000])
    parser.add_argument("--fine", type=int, nargs="*", default=[45000, 300000],
                        help="counts also run on cells of 3 d")
    parser.add_argument("--ranks", type=int, nargs="+", default=[1, 2])
    parser.add_argument("--steps", type=int, default=3, help="coupling steps per run")
    parser.add_argument("--out", default=os.path.join(HERE, "memory.csv"))
    args = parser.parse_args()
    rows = []
    with tempfile.TemporaryDirectory(prefix="tfdem_memory_") as where:
        points = [(n, 4) for n in args.counts] + [(n, 3) for n in args.fine]
        for count, cell_diameters in points:
            for ranks in args.ranks:
                rows.append(measure(count, cell_diameters, ranks, args.steps, where))
                print(rows[-1], flush=True)
    base = {r["ranks"]: r for r in rows if r["particles"] == min(args.counts) and r["cell_diameters"] == 4}
    for r in rows:
        b = base[r["ranks"]]
        if r["cell_diameters"] != 4:
            continue
        extra = r["particles"] - b["particles"]
        r["mb_per_1000_particles_over_base"] = round(1000 * (r["total_mb"] - b["total_mb"]) / extra, 3) if extra else ""
    with open(args.out, "w", newline="") as f:
        writer = csv.DictWriter(f, fieldnames=FIELDS)
        writer.writeheader()
        writer.writerows(rows)
    print(open(args.out).read())


if __name__ == "__main__":
    main()
