"""The bed drivers on a case `tfdem new` wrote, with nothing edited by hand: a one-layer bed of
800 1 mm beads on a distributor plate (the your_own_bed tutorial's) bubbling at 1.3 m/s
(2.4 U_mf), poured by `tfdem pack`.

1. `tfdem stats` (1.2 s, window START-END = 0.2-1.2 s, 0.1 s batches):
   - the Delta p levels are where the case puts them, by hand: the bed's floor is the top of
     the plate's cell row (y = 4 mm); the column of 12 cm has no room for 20 cm, so the upper
     level is its highest row of cell centres (cells 4 mm: y = 118 mm);
   - the bed's weight per area by hand, N rho_rel pi d^3 / 6 g / (width depth) = 256.7 Pa;
   - the momentum balance of the fluidized bed: the time-averaged Delta p between the levels
     equals the buoyant weight per area of the solids above the floor (the spheres' caps
     above y = 4 mm, from the particle files of the window), within three of the driver's
     own standard errors, and that error below 5 % of Delta p (it cannot pass by being
     vague); measured 2026-12-07: 252.9 +- 5.4 Pa against 256.7 Pa (between the bed's first
     row and the top, before: 229.4 +- 6.0 Pa against the 236.7 Pa above that row);
   - the same bed with `dem: {engine: hard_sphere}` (seed 001's event-driven engine), the same
     checks: measured 255.2 +- 6.4 Pa against 256.7 Pa.
2. `pareto.py` on a two-point sweep of the same case (its template a path relative to the
   sweep file, no `packing`: the case's own bed; 0.2 s): both points run and are reported,
   and, with the sweep's dp_height of 10 cm, the points' Delta p probes are on the rows either
   side of its levels (6 and 10 mm for the plate's top at 4 mm, 102 and 106 mm for 104 mm) and
   the report reads them; a template that is not a case is
   refused with a message naming it.
"""
import csv
import glob
import math
import os
import subprocess

import yaml

import tfdem.packing
from tfdem import SOURCE_DIR
from tfdem.newcase import derive, load_bed, write_case
from tfdem.outputs import probe_locations, vtk_particles
from tfdem.run import environment
from tfdem_testlib import Checks, run, scratch

PARETO = os.path.join(SOURCE_DIR, "bench", "pareto", "pareto.py")
BED = """
box: {width: 0.04, height: 0.12, depth: one_layer}
particles:
  density: 2500
  sizes: [{diameter: 0.001, number: 800}]
  restitution: 0.9
  friction: 0.1
gas: {density: 1.2, viscosity: 1.8e-5}
inflow: {velocity: 1.3, plate: {pressure_drop_fraction: 0.3}}
run: {end_time: 1.0, write_interval: 0.05}
"""
N, RHO, RHO_GAS, D, G, WIDTH = 800, 2500.0, 1.2, 0.001, 9.81, 0.04
FLOOR, TOP_ROW = 0.004, 0.118  # m: the plate's top; 12 cm - half a 4 mm cell
# the sweep's own dp_height 0.1 m: its upper level 0.104 m lies midway between the rows at 0.102 and 0.106
PARETO_DP_HEIGHT, PARETO_PRESSURE_ROWS = 0.1, [0.006, 0.010, 0.102, 0.106]
START, END = 0.2, 1.2  # s: the statistics' window, after the bed's start


def python(args, root):
    proc = subprocess.run(["/usr/bin/python3"] + args, cwd=root, env=environment(), stdout=subprocess.PIPE,
                          stderr=subprocess.STDOUT, text=True)
    print(proc.stdout[-2500:])
    return proc


def cap_volume_above(y_centre, d, level):
    """Volume of a sphere (centre height y_centre, diameter d) above the plane y = level."""
    r = d / 2
    h = min(max(y_centre + r - level, 0.0), 2 * r)
    return math.pi * h * h * (3 * r - h) / 3


def check_stats(checks, root, case, label):
    proc = python(["-m", "tfdem.bedstats", case, "--end-time", str(END), "--window", str(START), str(END), "--batch", "0.1"], root)
    checks.true(f"{label}: tfdem stats on a generated case", proc.returncode == 0, f"(exit code {proc.returncode})")
    path = os.path.join(case, "statistics", "bed_statistics.json")
    if not os.path.isfile(path):
        checks.true("bed_statistics.json written", False)
        return
    s = yaml.safe_load(open(path))
    checks.within(f"{label}: Delta p's lower level, the plate's top (m)", s["dp_levels"][0], FLOOR, 1e-12)
    checks.within(f"{label}: upper level: the column's highest row (m)", s["dp_levels"][1], TOP_ROW, 1e-12)
    weight = N * (RHO - RHO_GAS) * math.pi * D ** 3 / 6 * G / (WIDTH * D)
    checks.close(f"{label}: bed weight per area (Pa) by hand", s["weight_per_area"], weight, 1e-9)
    above = []
    for frame in glob.glob(os.path.join(case, "statistics", "VTK", "particles_*.vtk")):
        t = float(os.path.basename(frame)[len("particles_"):-len(".vtk")])
        if START - 1e-9 <= t <= END + 1e-9:
            particles = vtk_particles(frame)
            volume = sum(cap_volume_above(p[1], d, FLOOR) for p, d in zip(particles["position"], particles["diameter"]))
            above.append(volume * (RHO - RHO_GAS) * G / (WIDTH * D))
    frames = round((END - START) / 0.05) + 1  # write_interval 0.05 s
    checks.true(f"{label}: {frames} particle files in the window", len(above) == frames, f"({len(above)})")
    dp, error = s["dp_mean"]["value"], s["dp_mean"]["error"]
    carried = sum(above) / max(1, len(above))
    checks.true(f"{label}: Delta p = the weight above the floor, within 3 standard errors",
                abs(dp - carried) <= 3 * error, f"({dp:.1f} +- {error:.1f} Pa against {carried:.1f} Pa)")
    checks.true(f"{label}: ... and that error below 5 % of Delta p", error < 0.05 * dp, f"({error:.1f} Pa)")


def check_pareto(checks, root):
    sweep = {"template": "./case", "dp_height": PARETO_DP_HEIGHT, "end_time": 0.2, "window": [0.05, 0.2], "batch": 0.05, "band": 0.01,
             "field_interval": 0.01, "statistics_interval": 0.002, "reference": "reference",
             "points": {"reference": {"gas_time_step": 2.5e-4}, "default": {}}}
    path = os.path.join(root, "sweep.yaml")
    yaml.safe_dump(sweep, open(path, "w"))
    for command in ("run", "report"):
        proc = python([PARETO, command, path], root)
        checks.true(f"pareto.py {command} on a generated case", proc.returncode == 0, f"(exit code {proc.returncode})")
    table = os.path.join(root, "sweep", "report", "pareto.csv")
    rows = list(csv.DictReader(open(table))) if os.path.isfile(table) else []
    checks.true("both points reported beside the sweep file", sorted(r["point"] for r in rows) == ["default", "reference"])
    for point in ("reference", "default"):
        heights = sorted({round(p[1], 12) for p in probe_locations(os.path.join(root, "sweep", "runs", point),
                                                                    "studyPressure")})
        checks.true(f"{point}: Delta p probes on the rows at {PARETO_PRESSURE_ROWS} m", heights == PARETO_PRESSURE_ROWS,
                    f"({heights})")
    yaml.safe_dump(dict(sweep, template="./nowhere"), open(path, "w"))
    proc = python([PARETO, "run", path], root)
    checks.true("a template that is not a case is named", proc.returncode == 2 and "template './nowhere'" in proc.stdout
                and "is not a case" in proc.stdout)


def generate(root, name, text):
    """tfdem new and tfdem pack of the bed `text`: the case's path."""
    source = os.path.join(root, f"{name}.yaml")
    with open(source, "w") as f:
        f.write(text)
    case = os.path.join(root, name)
    bed = load_bed(source)
    write_case(case, bed, derive(bed, source), source)
    print(tfdem.packing.pack_case(case, runner=lambda *a, **k: run(*a[:3])))
    return case


def main():
    checks = Checks()
    root = scratch("drivers_on_new_case")
    check_stats(checks, root, generate(root, "case", BED), "soft spheres")
    check_pareto(checks, root)
    check_stats(checks, root, generate(root, "hard_sphere_case", BED + "dem: {engine: hard_sphere}\n"), "hard spheres")
    checks.finish()


if __name__ == "__main__":
    main()
