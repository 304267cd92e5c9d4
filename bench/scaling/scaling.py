#!/usr/bin/env python3
"""How cost grows with the bed: seed 000's uniform-inflow bubbling bed (tutorials/bubbling_bed,
4000 particles, 15 x 45 cells) widened `factor` times side by side (factor x 4000 particles,
15 factor x 45 cells, the same packing tiled in x, the same inflow), run on 1 and 2 ranks,
the gas mesh split between the ranks (GAS).

    scaling.py run [--factors 1 4 16] [--ranks 1 2] [--end-time 0.05] [--root DIR]
    scaling.py report [--root DIR]

Each run starts from the packed bed (the first 0.05 s: the bed still packed, its densest
contacts). Per run it records the wall time and the solver's own split (rank 0's
DEM / locate+map / forces / gas seconds) and derives processor-seconds per particle-step
(DEM), per particle per coupling step (locate, map, forces and their exchange) and per
cell-step (gas), the parallel efficiency of the time loop (the split's sum, start-up left
out) loop(1 rank) / (ranks x loop), and how many cell records crossed ranks per coupling
step. `report` writes root/report/: scaling.csv, scaling.png (log-log cost against
particles) and README.md (the table). Runs already done are skipped; a benchmark, on demand,
not a test.
"""
import argparse
import csv
import os
import re
import sys
import time

from tfdem import TUTORIALS
from tfdem.case import Case, CaseError
from tfdem.outputs import OutputError, log_numbers, solver_timing
from tfdem.run import RunError, prepare_gas, run

HERE = os.path.dirname(os.path.abspath(__file__))
TEMPLATE = os.path.join(TUTORIALS, "bubbling_bed")
PACKING = os.path.join(TUTORIALS, "bubbling_bed_packing")
# The gas split over the ranks (decomposePar): the layout whose exchange and per-rank gas cost
# extrapolate to many nodes (the whole layout solves every cell on every rank).
GAS = "split"
FIELDS = ("factor", "ranks", "particles", "cells", "end_time", "dem_steps", "gas_steps", "wall", "loop",
          "DEM", "locate+map", "forces", "gas", "dem_per_particle_step", "coupling_per_particle_step",
          "gas_per_cell_step", "efficiency", "remote_records_per_step")


def tile_data_file(source, dest, factor, width):
    """A LIGGGHTS data file with `factor` copies of source's atoms side by side in x (copy k
    shifted by k x width, ids renumbered, velocities copied), box widened to factor x width."""
    lines = open(source).read().splitlines()
    section, header, atoms, velocities = None, [], [], []
    for line in lines:
        words = line.split()
        if words[:1] in (["Atoms"], ["Velocities"]):
            section = words[0]
            continue
        if section is None:
            header.append(line)
        elif words:
            (atoms if section == "Atoms" else velocities).append(words)
    count = len(atoms)
    out = []
    for line in header:
        words = line.split()
        if words[-1:] == ["atoms"]:
            line = f"{count * factor} atoms"
        elif words[-2:] == ["xlo", "xhi"]:
            line = f"{float(words[0]):.16e} {float(words[0]) + factor * width:.16e} xlo xhi"
        out.append(line)
    out += ["Atoms", ""]
    for k in range(factor):
        for words in atoms:
            x = float(words[4]) + k * width
            out.append(" ".join([str(int(words[0]) + k * count)] + words[1:4] + [f"{x:.16e}"] + words[5:]))
    if velocities:
        out += ["", "Velocities", ""]
        for k in range(factor):
            for words in velocities:
                out.append(" ".join([str(int(words[0]) + k * count)] + words[1:]))
    with open(dest, "w") as f:
        f.write("\n".join(out) + "\n")
    return count * factor


def widen(case, factor):
    """The case `factor` times as wide in x: mesh vertices and cells, the DEM's right wall."""
    (x0, _, _), (x1, _, _) = case.mesh_bounds()
    width = x1 - x0
    mesh = case.file("system", "blockMeshDict")
    text = open(mesh).read()
    text, n = re.subn(rf"\(\s*{re.escape(f'{x1:g}')}\s", f"({x0 + factor * width:.12g} ", text)
    if n == 0:
        raise CaseError(f"{mesh}: no vertex at x = {x1:g}")
    open(mesh, "w").write(text)
    case.scale_cells(0, factor)
    script = case.dem_script()
    text = open(script).read()
    text, n = re.subn(rf"(?m)^(fix\s+\S+\s+all\s+wall/gran\b.*\bxplane\s+){re.escape(f'{x1:g}')}\b",
                      rf"\g<1>{x0 + factor * width:.12g}", text)
    if n != 1:
        raise CaseError(f"{script}: expected one wall/gran at xplane {x1:g}, found {n}")
    open(script, "w").write(text)
    return width


def packing():
    path = os.path.join(PACKING, "bed.data")
    if not os.path.isfile(path):
        run([os.path.join(PACKING, "Allrun")], PACKING, "log.scaling_packing")
    return path


def prepare(path, factor, ranks, end_time):
    case = Case(TEMPLATE).copy_to(path)
    case.set_control(endTime=end_time, writeInterval=end_time)
    width = widen(case, factor)
    data = case.file(os.path.basename(case.dem().read_data()))
    particles = tile_data_file(packing(), data, factor, width)
    run(["blockMesh"], path, "log.blockMesh")
    prepare_gas(path, ranks, GAS)
    return case, particles


def measure(root, factor, ranks, end_time):
    """One run, its row of FIELDS in its folder's scaling.csv (skipped when that exists)."""
    path = os.path.join(root, f"x{factor}_ranks{ranks}")
    result = os.path.join(path, "scaling.csv")
    if os.path.isfile(result):
        return
    case, particles = prepare(path, factor, ranks, end_time)
    cells = case.grid().cell_count
    print(f"x{factor}, {ranks} rank(s): {particles} particles, {cells} cells, {end_time} s ...", flush=True)
    start = time.monotonic()
    run(["tfdemFoam"], path, "log.tfdemFoam", ranks, gas=GAS)
    wall = time.monotonic() - start
    log = os.path.join(path, "log.tfdemFoam")
    split = solver_timing(log)
    gas_steps = round(end_time / case.delta_t())
    dem_steps = round(end_time / case.dem_time_step())
    remote = log_numbers(log, r"TFDEM parallel: (\S+) cell records received")
    row = {"factor": factor, "ranks": ranks, "particles": particles, "cells": cells,
           "end_time": end_time, "dem_steps": dem_steps, "gas_steps": gas_steps, "wall": wall,
           "loop": sum(split.values()),
           **{k: split[k] for k in ("DEM", "locate+map", "forces", "gas")},
           "dem_per_particle_step": ranks * split["DEM"] / (particles * dem_steps),
           "coupling_per_particle_step": ranks * (split["locate+map"] + split["forces"]) / (particles * gas_steps),
           "gas_per_cell_step": ranks * split["gas"] / (cells * gas_steps),
           "efficiency": float("nan"),
           "remote_records_per_step": remote[0] / gas_steps if remote else 0.0}
    with open(result, "w") as f:
        writer = csv.DictWriter(f, FIELDS)
        writer.writeheader()
        writer.writerow(row)
    print(f"  wall {wall:.1f} s; DEM {split['DEM']:.1f} s, gas {split['gas']:.1f} s", flush=True)


def rows_of(root):
    rows = []
    for name in sorted(os.listdir(root)) if os.path.isdir(root) else []:
        if not re.fullmatch(r"x\d+_ranks\d+", name):
            continue
        result = os.path.join(root, name, "scaling.csv")
        if os.path.isfile(result):
            with open(result) as f:
                rows.append({k: float(v) for k, v in next(csv.DictReader(f)).items()})
    serial = {r["factor"]: r["loop"] for r in rows if r["ranks"] == 1}
    for r in rows:
        if r["factor"] in serial:
            r["efficiency"] = serial[r["factor"]] / (r["ranks"] * r["loop"])
    return sorted(rows, key=lambda r: (r["particles"], r["ranks"]))


def report(root):
    rows = rows_of(root)
    if not rows:
        sys.exit(f"{root}: no finished runs; run `scaling.py run` first")
    out = os.path.join(root, "report")
    os.makedirs(out, exist_ok=True)
    with open(os.path.join(out, "scaling.csv"), "w") as f:
        writer = csv.DictWriter(f, FIELDS)
        writer.writeheader()
        writer.writerows(rows)
    lines = ["| particles | cells | ranks | wall (s) | DEM (s) | gas (s) | DEM us/particle-step | "
             "coupling us/particle-step | gas us/cell-step | efficiency | cross-rank records/step |",
             "|---|---|---|---|---|---|---|---|---|---|---|"]
    for r in rows:
        lines.append(f"| {r['particles']:.0f} | {r['cells']:.0f} | {r['ranks']:.0f} | {r['wall']:.1f} | "
                     f"{r['DEM']:.1f} | {r['gas']:.1f} | {1e6 * r['dem_per_particle_step']:.3f} | "
                     f"{1e6 * r['coupling_per_particle_step']:.3f} | {1e6 * r['gas_per_cell_step']:.2f} | "
                     f"{r['efficiency']:.2f} | {r['remote_records_per_step']:.0f} |")
    with open(os.path.join(out, "README.md"), "w") as f:
        f.write("# Cost against bed size (bench/scaling/scaling.py)\n\n"
                f"{rows[0]['end_time']:g} s simulated from the packed bed; processor-microseconds per "
                "particle-step (DEM), per particle and coupling step (locate, map, forces), per "
                "cell and gas step (gas); efficiency = loop(1 rank) / (ranks x loop), loop the "
                "time loop (the solver's timed parts, start-up left out).\n\n"
                + "\n".join(lines) + "\n")
    plot(rows, os.path.join(out, "scaling.png"))
    print("\n".join(lines))
    print(f"report: {out}")


def plot(rows, path):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(figsize=(6, 4.5))
    for ranks, marker in ((1, "o"), (2, "s")):
        sel = [r for r in rows if r["ranks"] == ranks]
        if not sel:
            continue
        n = [r["particles"] for r in sel]
        for key, label, colour in (("dem_per_particle_step", "DEM per particle-step", "C0"),
                                   ("coupling_per_particle_step", "coupling per particle-step", "C1"),
                                   ("gas_per_cell_step", "gas per cell-step", "C2")):
            ax.loglog(n, [1e6 * r[key] for r in sel], marker=marker, color=colour,
                      linestyle="-" if ranks == 1 else "--", label=f"{label}, {ranks} rank(s)")
    ax.set_xlabel("particles")
    ax.set_ylabel("processor microseconds")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(path, dpi=120)


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("action", choices=("run", "report"))
    parser.add_argument("--factors", type=int, nargs="+", default=[1, 4, 16])
    parser.add_argument("--ranks", type=int, nargs="+", default=[1, 2])
    parser.add_argument("--end-time", type=float, default=0.05)
    parser.add_argument("--root", default=os.path.join(HERE, "runs"))
    args = parser.parse_args(argv)
    if any(f < 1 for f in args.factors) or any(r < 1 for r in args.ranks) or args.end_time <= 0:
        parser.error("factors and ranks must be whole numbers >= 1 and --end-time positive")
    try:
        if args.action == "run":
            for factor in args.factors:
                for ranks in args.ranks:
                    measure(args.root, factor, ranks, args.end_time)
        report(args.root)
    except (CaseError, RunError, OutputError) as e:
        sys.exit(f"scaling.py: {e}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
