#!/usr/bin/env python3
"""The diffusion smoothing's bandwidth against its error and cost (coupling.void_fraction.
diffusion_bandwidth, particle_field_filter.h): speed against error for choosing b.

For each bandwidth b (and unspread, b = 0):
- the fixed bed of tutorials/packed_bed_ergun (d = 2.5 mm) on gas cells of 2.04 mm (its 10.2
  mm cells split 5 x 5, smaller than a particle), per_particle_conservative, at 0.3 m/s: the
  pressure gradient inside the bed, farther than 2.5 b from both edges (two probes), against
  Ergun's (seed 000 eq. 30 via tfdem.fixed_bed) and the 1-D model of the spread bed's over the
  same window; the whole bed's drop against Ergun and against the 1-D model
  (FixedBed.spread_pressure_drop); the solver's locate+map and
  forces time per coupling step;
- one 100 um sphere settling from rest (tutorials/settling_particle) on cells of 4 mm (its 2 cm
  cells split 5 x 5; b in the same metres), per_particle_conservative: the terminal velocity at
  0.5 s and the largest |v - v_ODE| / u_t over 0-0.5 s against tfdem.physics.SettlingSphere
  (the sphere's ODE with the same drag law, independent of the solver).

Writes bench/bandwidth/sweep.csv (one row per bed and bandwidth) and prints it. One run per
point: the beds are steady (the fixed bed) or deterministic (one sphere); the times are one
run's, on a machine that may be busy: a figure of the cost, not a comparison.

Usage: . scripts/tfdem-env.sh; "$TFDEM_PYTHON" bench/bandwidth/sweep.py [--bandwidths 0 0.0025 ...]
"""
import argparse
import csv
import os
import tempfile

from tfdem import TUTORIALS, outputs
from tfdem.case import Case
from tfdem.fixed_bed import FixedBed
from tfdem.outputs import dump_track
from tfdem.physics import SettlingSphere
from tfdem.run import run

HERE = os.path.dirname(os.path.abspath(__file__))
BANDWIDTHS = (0.0, 0.0025, 0.005, 0.0075, 0.01, 0.015)  # m: 0-6 d of the fixed bed's spheres
REFINE = 5
PACKED_U = 0.3  # m/s


def filtered_copy(source, dest, bandwidth):
    case = source.copy_to(dest)
    case.scale_cells(0, REFINE)
    case.scale_cells(1, REFINE)
    case.set_coupling("coupling.transfer", "per_particle_conservative")
    if bandwidth > 0:
        case.set_coupling("coupling.void_fraction.diffusion_bandwidth", bandwidth)
    return case


def per_step_ms(dest, case):
    """(locate+map + forces, gas) of the solver's timing line, ms per coupling step."""
    timing = outputs.solver_timing(os.path.join(dest, "log.tfdemFoam"))
    steps = round(case.end_time() / case.delta_t())
    return 1e3 * (timing["locate+map"] + timing["forces"]) / steps, 1e3 * timing["gas"] / steps


def packed_bed(root, b):
    bed = FixedBed(os.path.join(TUTORIALS, "packed_bed_ergun"))
    dest = os.path.join(root, f"packed_b{b:g}")
    case = filtered_copy(bed.case, dest, b)
    case.set_patch_value("U", "inlet", (0, PACKED_U, 0))
    margin = 2.5 * max(b, case.grid().spacing[1])
    below, above = case.probe_locations("pressure")[:2]
    interior = [case.grid().centre_of_cell_at(1, y) for y in (bed.bottom + margin, bed.bottom + bed.height - margin)]
    case.set_probe_locations("pressure", [below, above] + [(below[0], y, below[2]) for y in interior])
    run(["blockMesh"], dest, "log.blockMesh")
    run(["tfdemFoam"], dest, "log.tfdemFoam")
    measured = FixedBed(dest).measured_pressure_drop(dest)
    _, p = outputs.probes(dest, "pressure", "p")[-1]
    span = interior[1] - interior[0]
    ergun_interior = (bed.ergun_gradient(PACKED_U) + bed.rho_g * bed.g) * span
    ergun = bed.expected_pressure_drop(PACKED_U)
    model = bed.spread_pressure_drop(PACKED_U, b) if b > 0 else float("nan")
    model_interior = (bed.spread_pressure_drop(PACKED_U, b, heights=tuple(interior))
                      if b > 0 else float("nan"))
    coupling_ms, gas_ms = per_step_ms(dest, case)
    return {"bed": "packed", "bandwidth_m": b, "bandwidth_d": b / bed.d, "cell_m": case.grid().spacing[1],
            "interior_error": (p[2] - p[3]) / ergun_interior - 1, "whole_bed_error": measured / ergun - 1,
            "model_error": measured / model - 1 if b > 0 else float("nan"),
            "model_interior_error": model_interior / ergun_interior - 1 if b > 0 else float("nan"),
            "floored": "floored" in open(os.path.join(dest, "log.tfdemFoam")).read().lower(),
            "map_forces_ms_per_step": coupling_ms, "gas_ms_per_step": gas_ms}


def settling(root, b):
    dest = os.path.join(root, f"settling_b{b:g}")
    case = filtered_copy(Case(os.path.join(TUTORIALS, "settling_particle")), dest, b)
    run(["blockMesh"], dest, "log.blockMesh")
    run(["tfdemFoam"], dest, "log.tfdemFoam")
    sphere = SettlingSphere.from_case(Case(dest))
    track = dump_track(dest, "vy")
    u_t = sphere.terminal_velocity()
    expected = sphere.velocity([t for t, _ in track])
    coupling_ms, gas_ms = per_step_ms(dest, case)
    return {"bed": "settling", "bandwidth_m": b, "bandwidth_d": b / case.particle_diameters()[0],
            "cell_m": case.grid().spacing[1], "terminal_error": -track[-1][1] / u_t - 1,
            "curve_error": max(abs(v - e) for (_, v), e in zip(track, expected)) / u_t,
            "map_forces_ms_per_step": coupling_ms, "gas_ms_per_step": gas_ms}


COLUMNS = ("bed", "bandwidth_m", "bandwidth_d", "cell_m", "interior_error", "model_interior_error", "whole_bed_error",
           "model_error",
           "terminal_error", "curve_error", "floored", "map_forces_ms_per_step", "gas_ms_per_step")


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--bandwidths", type=float, nargs="+", default=BANDWIDTHS)
    parser.add_argument("--out", default=os.path.join(HERE, "sweep.csv"))
    args = parser.parse_args()
    root = tempfile.mkdtemp(prefix="tfdem_bandwidth_")
    rows = []
    for b in args.bandwidths:
        for bench in (packed_bed, settling):
            row = bench(root, b)
            rows.append(row)
            print(", ".join(f"{k} {row[k]:.4g}" if isinstance(row[k], float) else f"{k} {row[k]}"
                            for k in COLUMNS if k in row), flush=True)
    with open(args.out, "w", newline="") as f:
        w = csv.DictWriter(f, COLUMNS, restval="")
        w.writeheader()
        for row in rows:
            w.writerow({k: (f"{v:.6g}" if isinstance(v, float) else v) for k, v in row.items()})
    print(f"written {args.out}")


if __name__ == "__main__":
    main()
