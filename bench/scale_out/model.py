#!/usr/bin/env python3
"""A scaling model of TFDEM's time per simulated second, from costs and counts measured here.

`measure`: seed 000's jet and bubbling beds and seed 001's segregation bed (Goldschmidt) run a
few gas steps from their packings on 1, 2, 3, 4 and 8 ranks (oversubscribed: the counts do not
care, the times are taken on 1 rank only), the gas whole, LIGGGHTS splitting as the template
says (`processors * 1 1`) and the segregation bed also `* * 1`. From each run's report: the
DEM and coupling time per particle-step (1 rank), LIGGGHTS' ghost particles per rank and the
cell exchange's bytes and messages per coupling step (`TFDEM communication:`). Writes
`communication.csv`.

`predict`: for P ranks, the time per simulated second of the fullest rank,
  T = n_dem [c_p (N_P + G_P) + 2 a_P (alpha + 72 G_P / a_P / beta)]
    + n_gas [gas step (tfdem-gas-layout's measured costs, the layout it picks)
             + c_c N_P + whole: 2 log2(P) (alpha + 48 C / beta), split: m alpha + b / beta]
with N_P and G_P the fullest rank's own and ghost particles, counted from the bed's own
positions (its packing) on LIGGGHTS' processor grid (equal parts of the box; free axes chosen
as LIGGGHTS' procs2box does, by the least subdomain surface) with the ghost cut-off d_max +
skin; a_P the split axes (two neighbours each, one message a DEM step: positions, velocities
and spins, 9 doubles a ghost); c_p, c_c the bed's measured costs on one rank (a ghost counted
as a particle: with `newton off` its pairs are computed on both sides); alpha = 1.5 us and
beta = 12.5 GB/s an InfiniBand network's latency and bandwidth (assumed, not measured here);
m, b the cell exchange's messages and bytes per rank at 4 ranks (measured). The model's
ghost counts are checked against the measured ones (1-8 ranks), its 1- and 2-rank times
against the measured ones. Predicted: each bed, and a 3-D lattice bed of 10^6 spheres, at 16,
64 and 256 ranks; weak scaling at 15,625 spheres a rank (a 3-D lattice) to 256 ranks; and
Goldschmidt's 60 s per law on 64 ranks against the goal of 2 h. Writes `model.csv`.

Usage: . scripts/tfdem-env.sh; "$TFDEM_PYTHON" bench/scale_out/model.py measure|predict
"""
import argparse
import csv
import itertools
import math
import os
import re
import shutil
import subprocess
import sys
import tempfile

import numpy as np

from tfdem import STUDIES, TUTORIALS, outputs
from tfdem.case import Case
from tfdem.liggghts import read_data_box, read_data_file
from tfdem.run import run

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
import memory  # noqa: E402  (the lattice bed of memory.py)

# The bubbling bed's Allrun copies its packing from bubbling_bed_packing; the others keep theirs
SEGREGATION = os.path.join(STUDIES, "bidisperse_segregation")
PACKINGS = {os.path.join(TUTORIALS, "bubbling_bed"): os.path.join(TUTORIALS, "bubbling_bed_packing", "bed.data")}
BEDS = {  # name: (case folder, DEM processors grid)
    "jet": (os.path.join(TUTORIALS, "jet_bed"), "* 1 1"),
    "bubbling": (os.path.join(TUTORIALS, "bubbling_bed"), "* 1 1"),
    "segregation": (SEGREGATION, "* 1 1"),
    "segregation_2d_grid": (SEGREGATION, "* * 1"),
}
RANKS = (1, 2, 3, 4, 8)
GAS_STEPS = 20
ALPHA, BETA = 1.5e-6, 12.5e9           # s, bytes/s: an InfiniBand network (assumed)
GHOST_BYTES, CELL_BYTES = 72.0, 48.0   # 9 doubles a ghost per DEM step; 6 doubles a cell summed
WEAK_PER_RANK = 15625
PREDICT_RANKS = (1, 2, 4, 8, 16, 64, 256)
COMMUNICATION_CSV = os.path.join(HERE, "communication.csv")
MODEL_CSV = os.path.join(HERE, "model.csv")


# Geometry: LIGGGHTS' processor grid and the ghosts it makes --------------------------------
def processor_grid(spec, ranks, extent):
    """(Px, Py, Pz) for a `processors` spec ('*' free) on `ranks` ranks: the given counts, the
    free ones as LIGGGHTS' procs2box picks them (the least subdomain surface)."""
    given = [None if w == "*" else int(w) for w in spec.split()]
    best, best_surface = None, math.inf
    for grid in itertools.product(range(1, ranks + 1), repeat=3):
        if math.prod(grid) != ranks or any(g is not None and g != n for g, n in zip(given, grid)):
            continue
        a, b, c = (extent[k] / grid[k] for k in range(3))
        surface = a * b + b * c + a * c
        if surface < best_surface - 1e-15:
            best, best_surface = grid, surface
    return best


def cuts(positions, lower, upper, grid, balanced):
    """Each axis's subdomain boundaries: even parts of the box (LIGGGHTS' default), or, balanced,
    at the particles' quantiles along it (what LIGGGHTS' `balance ... shift` aims at)."""
    out = []
    for axis in range(3):
        if balanced and grid[axis] > 1:
            inner = np.quantile(positions[:, axis], np.arange(1, grid[axis]) / grid[axis])
            out.append(np.concatenate([[lower[axis]], inner, [upper[axis]]]))
        else:
            out.append(np.linspace(lower[axis], upper[axis], grid[axis] + 1))
    return out


def rank_counts(positions, lower, upper, grid, cutoff, balanced=False):
    """(own, ghost) particles of each subdomain of the box split by `grid` (cuts()): own = centre
    inside, ghost = centre outside but within `cutoff` of it (LIGGGHTS' borders: the box grown
    by the ghost cut-off, corners included)."""
    edges = cuts(positions, lower, upper, grid, balanced)
    index = np.column_stack([np.clip(np.searchsorted(edges[a], positions[:, a], side="right") - 1, 0, grid[a] - 1)
                             for a in range(3)])
    own, ghost = [], []
    for cell in itertools.product(*(range(g) for g in grid)):
        lo = np.array([edges[a][cell[a]] for a in range(3)])
        hi = np.array([edges[a][cell[a] + 1] for a in range(3)])
        mine = np.all(index == np.asarray(cell), axis=1)
        near = np.all((positions >= lo - cutoff) & (positions < hi + cutoff), axis=1)
        own.append(int(mine.sum()))
        ghost.append(int((near & ~mine).sum()))
    return own, ghost


def bed_geometry(case):
    data = PACKINGS.get(os.path.basename(case.path), case.file(os.path.basename(case.dem().read_data())))
    atoms = read_data_file(data)
    positions = np.column_stack([atoms["x"], atoms["y"], atoms["z"]])
    lower, upper = read_data_box(data)
    skin = float(re.search(r"(?m)^neighbor\s+(\S+)", open(case.dem_script()).read()).group(1))
    return positions, lower, upper, max(atoms["diameter"]) + skin


# Measure ------------------------------------------------------------------------------------
def set_processors(case, spec):
    path = case.dem_script()
    text = re.sub(r"(?m)^processors[ \t]+.*$", f"processors      {spec}", open(path).read())
    open(path, "w").write(text)


def measure_run(name, tutorial, spec, ranks, where):
    source = Case(tutorial)
    data = os.path.basename(source.dem().read_data())
    packing = PACKINGS.get(tutorial, source.file(data))
    if not os.path.isfile(packing):
        sys.exit(f"model.py: {packing} is missing: run {tutorial}'s Allrun (or Allpack) once to make it")
    case = source.copy_to(os.path.join(where, f"{name}_{ranks}"))
    shutil.copy(packing, case.file(data))
    set_processors(case, spec)
    step = float(case.control("deltaT"))
    case.set_control(endTime=GAS_STEPS * step, writeInterval=1e3)
    run(["blockMesh"], case.path, "log.blockMesh")
    run(["tfdemFoam"], case.path, "log.tfdemFoam", ranks, gas="whole")
    log = case.file("log.tfdemFoam")
    timing = outputs.solver_timing(log)
    interval = outputs.log_numbers(log, r"(\d+) DEM steps per gas step")[0]
    count = outputs.log_numbers(log, r"TFDEM coupling: (\d+) particles")[0]
    cells = math.prod(outputs.log_numbers(log, r"TFDEM coupling: Cartesian grid (\d+) x (\d+) x (\d+) cells"))
    row = {"bed": name, "ranks": ranks, "particles": int(count), "cells": int(cells),
           "dem_steps_per_gas_step": int(interval),
           "gas_steps": GAS_STEPS, "dem_s": timing["DEM"], "coupling_s": timing["locate+map"] + timing["forces"],
           "gas_s": timing["gas"], "ghosts_per_rank": 0.0, "ghosts_fullest": 0.0, "exchange_bytes": 0.0,
           "exchange_messages": 0.0}
    found = outputs.log_numbers(log, r"TFDEM communication: per coupling step the cell exchange sent (\S+) bytes in"
                                     r" (\S+) messages .*?ghost particles (\S+) per rank on average .*?, (\S+) on the"
                                     r" fullest rank")
    if found:
        row.update(exchange_bytes=found[0], exchange_messages=found[1], ghosts_per_rank=found[2],
                   ghosts_fullest=found[3])
    positions, lower, upper, cutoff = bed_geometry(case)
    grid = processor_grid(spec, ranks, np.asarray(upper) - np.asarray(lower))
    own, ghost = rank_counts(positions, lower, upper, grid, cutoff)
    row.update(grid="x".join(map(str, grid)), model_ghosts_per_rank=sum(ghost) / ranks,
               model_ghosts_fullest=max(ghost))
    return row


def measure(args):
    rows = []
    with tempfile.TemporaryDirectory(prefix="tfdem_model_") as where:
        for name in args.beds:
            tutorial, spec = BEDS[name]
            for ranks in args.ranks:
                rows.append(measure_run(name, tutorial, spec, ranks, where))
                print({k: (round(v, 4) if isinstance(v, float) else v) for k, v in rows[-1].items()}, flush=True)
    with open(COMMUNICATION_CSV, "w", newline="") as f:
        writer = csv.DictWriter(f, fieldnames=list(rows[0]))
        writer.writeheader()
        writer.writerows(rows)


# Predict ------------------------------------------------------------------------------------
def gas_step(cells, ranks):
    """(layout, seconds) of tfdem-gas-layout's rule and its measured step cost."""
    done = subprocess.run(["tfdem-gas-layout", str(int(cells)), str(ranks)], capture_output=True, text=True,
                          check=True)
    whole, split = (float(v) * 1e-3 for v in
                    re.search(r"gas step (\S+) ms whole, (\S+) ms split", done.stderr).groups())
    layout = done.stdout.strip()
    return layout, whole if layout == "whole" else split


def step_time(own, ghost, grid, ranks, costs, cells, dem_per_gas, exchange):
    """Seconds of the fullest rank per gas step."""
    split_axes = sum(g > 1 for g in grid)
    dem = costs["c_p"] * (own + ghost) + 2 * split_axes * ALPHA + GHOST_BYTES * ghost / BETA
    layout, gas = gas_step(cells, ranks)
    if ranks == 1:
        link = 0.0
    elif layout == "whole":
        link = 2 * math.ceil(math.log2(ranks)) * (ALPHA + CELL_BYTES * cells / BETA)
    else:
        link = exchange["messages"] * ALPHA + exchange["bytes"] / BETA
    return dem_per_gas * dem + gas + costs["c_c"] * own + link, layout


def predict_bed(label, positions, lower, upper, cutoff, spec, costs, cells, dem_per_gas, gas_dt, exchange, ranks,
                balanced=False):
    grid = processor_grid(spec, ranks, np.asarray(upper) - np.asarray(lower))
    own, ghost = rank_counts(positions, lower, upper, grid, cutoff, balanced)
    fullest = int(np.argmax(np.asarray(own) + np.asarray(ghost)))
    seconds, layout = step_time(own[fullest], ghost[fullest], grid, ranks, costs, cells, dem_per_gas, exchange)
    return {"bed": label, "ranks": ranks, "grid": "x".join(map(str, grid)), "gas_layout": layout,
            "own_fullest": own[fullest], "ghosts_fullest": ghost[fullest],
            "s_per_simulated_s": seconds / gas_dt}


def costs_of(rows, bed):
    one = next(r for r in rows if r["bed"] == bed and int(r["ranks"]) == 1)
    n, gas_steps, interval = float(one["particles"]), float(one["gas_steps"]), float(one["dem_steps_per_gas_step"])
    return {"c_p": float(one["dem_s"]) / (n * gas_steps * interval), "c_c": float(one["coupling_s"]) / (n * gas_steps),
            "gas": float(one["gas_s"]) / gas_steps}


def predict(args):
    rows = list(csv.DictReader(open(COMMUNICATION_CSV)))
    print("ghosts per rank, measured (run's mean) against the model (the packing's):")
    for r in rows:
        if int(r["ranks"]) > 1:
            print(f"  {r['bed']:<20} {r['ranks']} ranks {r['grid']:<6} measured {float(r['ghosts_per_rank']):8.1f}"
                  f"  model {float(r['model_ghosts_per_rank']):8.1f}  fullest {float(r['ghosts_fullest']):6.0f}"
                  f" / {float(r['model_ghosts_fullest']):6.0f}")
    out = []
    exchange_at_4 = {}
    for name in BEDS:
        at4 = [r for r in rows if r["bed"] == name and int(r["ranks"]) == 4]
        exchange_at_4[name] = {"bytes": float(at4[0]["exchange_bytes"]), "messages": float(at4[0]["exchange_messages"])} \
            if at4 else {"bytes": 0.0, "messages": 0.0}
    for name, (tutorial, spec) in BEDS.items():
        if not any(r["bed"] == name for r in rows):
            continue
        case = Case(tutorial)
        positions, lower, upper, cutoff = bed_geometry(case)
        costs = costs_of(rows, name)
        one = next(r for r in rows if r["bed"] == name and int(r["ranks"]) == 1)
        cells = float(one["cells"])
        dem_per_gas, gas_dt = float(one["dem_steps_per_gas_step"]), float(case.control("deltaT"))
        for ranks in PREDICT_RANKS:
            out.append(predict_bed(name, positions, lower, upper, cutoff, spec, costs, cells, dem_per_gas, gas_dt,
                                   exchange_at_4[name], ranks))
        if spec == "* * 1":  # the same grid with its cuts at the particles' quantiles
            for ranks in PREDICT_RANKS:
                out.append(predict_bed(name + "_balanced", positions, lower, upper, cutoff, spec, costs, cells,
                                       dem_per_gas, gas_dt, exchange_at_4[name], ranks, balanced=True))
    # A 3-D lattice of 10^6 spheres (memory.py's bed) with the segregation bed's costs, and
    # weak scaling at WEAK_PER_RANK spheres a rank
    costs = costs_of(rows, "segregation")
    one = next(r for r in rows if r["bed"] == "segregation" and int(r["ranks"]) == 1)
    dem_per_gas = float(one["dem_steps_per_gas_step"])
    gas_dt = float(Case(SEGREGATION).control("deltaT"))
    variants = (("", "* * *", False), ("_columns", "* 1 *", False), ("_balanced", "* * *", True))
    for label, per_rank in (("lattice_1e6", None), ("weak_15625_per_rank", WEAK_PER_RANK)):
        for suffix, spec, balanced in variants:
            for ranks in PREDICT_RANKS:
                count = per_rank * ranks if per_rank else 1000000
                positions, lower, upper = lattice(count)
                cells = _lattice_cells(count)
                out.append(predict_bed(label + suffix, positions, lower, upper, memory.DIAMETER + 0.0005, spec, costs,
                                       cells, dem_per_gas, gas_dt, {"bytes": 0.0, "messages": 0.0}, ranks, balanced))
    for r in out:
        base = next(b for b in out if b["bed"] == r["bed"] and b["ranks"] == 1)
        r["efficiency"] = base["s_per_simulated_s"] / r["s_per_simulated_s"] / (1 if r["bed"].startswith("weak") else r["ranks"])
    with open(MODEL_CSV, "w", newline="") as f:
        writer = csv.DictWriter(f, fieldnames=list(out[0]))
        writer.writeheader()
        writer.writerows(out)
    print(f"\n{'bed':<22}{'ranks':>6}{'grid':>9}{'gas':>7}{'own':>9}{'ghosts':>8}{'s per sim s':>13}{'efficiency':>11}")
    for r in out:
        print(f"{r['bed']:<22}{r['ranks']:>6}{r['grid']:>9}{r['gas_layout']:>7}{r['own_fullest']:>9}"
              f"{r['ghosts_fullest']:>8}{r['s_per_simulated_s']:>13.1f}{r['efficiency']:>11.2f}")
    print("\n2 ranks against 1, loop time (DEM + coupling + gas of rank 0), measured here against the model:")
    for name in BEDS:
        measured = {int(r["ranks"]): sum(float(r[k]) for k in ("dem_s", "coupling_s", "gas_s"))
                    for r in rows if r["bed"] == name}
        model = {r["ranks"]: r["s_per_simulated_s"] for r in out if r["bed"] == name}
        if 1 in measured and 2 in measured:
            print(f"  {name:<20} measured {measured[2] / measured[1]:.2f}, model {model[2] / model[1]:.2f}")
    for name in ("segregation", "segregation_2d_grid", "segregation_2d_grid_balanced"):
        at64 = next((r for r in out if r["bed"] == name and r["ranks"] == 64), None)
        if at64:
            hours = 60 * at64["s_per_simulated_s"] / 3600
            print(f"Goldschmidt's 60 s on 64 ranks ({name}, grid {at64['grid']}): {hours:.2f} h per law "
                  f"({'meets' if hours <= 2 else 'misses'} the 2 h goal)")


def lattice(count):
    """memory.py's lattice bed: its centres and its box."""
    box = memory.bed_yaml(count, 4)["box"]
    return memory.lattice_positions(count), (0.0, 0.0, 0.0), (box["width"], box["height"], box["depth"])


def _lattice_cells(count):
    box = memory.bed_yaml(count, 4)["box"]
    cell = 4 * memory.DIAMETER
    return math.prod(max(1, round(box[k] / cell)) for k in ("width", "height", "depth"))


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("what", choices=("measure", "predict"))
    parser.add_argument("--beds", nargs="+", default=list(BEDS), choices=list(BEDS))
    parser.add_argument("--ranks", type=int, nargs="+", default=list(RANKS))
    args = parser.parse_args()
    measure(args) if args.what == "measure" else predict(args)


if __name__ == "__main__":
    main()
