"""Where a 3-D bed's weight goes, on a case `tfdem new` wrote and `tfdem pack` poured, with
nothing edited: 2000 glass beads of 2 mm (2500 kg/m^3, friction 0.3) in a 2.4 x 12 x 2.4 cm
column of 8 mm cells (3 x 15 x 3), uniform inflow through the whole bottom (so the bed's floor
is at y = 8 mm, above an empty windbox row).

By hand: W = 2000 (2500) pi (0.002)^3 / 6 (9.81) = 0.205460 N; the cross-section 0.024^2 =
5.76e-4 m^2; the buoyant weight per area (2498.8 / 2500) W / 5.76e-4 = 356.53 Pa; U_mf (Wen-Yu)
1.063 m/s.

1. At rest on its floor at 0.5 m/s (0.47 U_mf), 0.2 s, averaged over 0.1-0.2 s: the gas's
   pressure drop times the area, (p(inlet, area average) - p(top row at y = 116 mm,
   cross-section average) - rho_g g y) A, equals the gas's force on the particles (the DEM's
   own record, forces.txt) within 1 % of W (measured 0.2429 W against 0.2432 W), and the gas,
   the floor, the four walls and the lid carry the whole weight within 1 % of W (measured
   1.0000: gas 0.243, floor 0.777, walls -0.021). Before the windbox row the beads sat in the
   inlet's cells, whose face pressure leaves their half cell's drop out: Delta p A was
   0.197 W against the gas's 0.2365 W. `tfdem summary` on the run writes its table (the same
   balance per row) and picture.
2. Bubbling (slugging, in a column 12 d wide) at 2 U_mf (2.126 m/s), 1.6 s, over 0.2-1.6 s in
   batches of 0.2 s: Delta p A (as above) and the gas's force agree within three standard
   errors of their batch-mean difference, that error below 1 % of W; the gas, the floor, the
   walls and the lid carry the weight within three standard errors (the floor and the walls
   carry about 5 % and 1 %: Delta p between the bed's bottom row and the top is short of the
   weight above that row by as much, so that balance is not the one checked here). Measured:
   the gas 0.9464 +- 0.0157 W, Delta p A - the gas's force +0.0004 +- 0.0008 W, the floor
   0.046, the walls 0.011, the sum 1.0034 +- 0.0134.

About 1.5 min on one core (2 min beside a build).
3. `tfdem stats` on the bubbling case (0.4 s, window 0.1-0.4 s): it runs on a 3-D bed (the
   crash this replaces: "cannot reshape array of size 135 into shape (15, 3)"), its map is
   averaged over the depth's 3 cells and says so, its Delta p is taken between the bed's floor
   (y = 8 mm, extrapolated from the rows of cross-section averages at 12 and 20 mm) and the top
   row (116 mm), and that Delta p is a share of the weight per area (356.53 Pa), not more (the
   window holds one slug: measured 2026-12-07 275.7 Pa, 0.77, from the floor; 223.6 Pa, 0.63,
   from the bed's first row before; checked between 0.3 and 1.05).
"""
import math
import os
import subprocess

import numpy
import yaml

import tfdem.packing
from tfdem.case import Case
from tfdem.fluidization import side_columns
from tfdem.newcase import derive, load_bed, write_case
from tfdem.outputs import fix_print, pressure_series
from tfdem.run import environment
from tfdem_testlib import Checks, run, scratch

BED = """
box: {width: 0.024, height: 0.12, depth: 0.024}
particles:
  density: 2500
  sizes: [{diameter: 0.002, number: 2000}]
  restitution: 0.9
  friction: 0.3
gas: {density: 1.2, viscosity: 1.8e-5}
inflow: {velocity: %(velocity)s}
run: {end_time: %(end)s, write_interval: 0.05}
"""
N, RHO, RHO_GAS, D, G, SIDE = 2000, 2500.0, 1.2, 0.002, 9.81, 0.024
WEIGHT = N * RHO * math.pi * D ** 3 / 6 * G          # N
AREA = SIDE * SIDE
FLOOR, TOP_ROW = 0.008, 0.116                        # m: above the windbox row; 12 cm - half a cell
AT_REST, BUBBLING = 0.5, 2.126                       # m/s: 0.47 and 2 U_mf
START, END, BATCH = 0.2, 1.6, 0.2                   # s: the bubbling run's window and batches
STATS_END = 0.4
WEIGHT_PER_AREA = (RHO - RHO_GAS) / RHO * WEIGHT / AREA   # Pa


def generate(root, name, velocity, end):
    source = os.path.join(root, f"{name}.yaml")
    with open(source, "w") as f:
        f.write(BED % {"velocity": velocity, "end": end})
    bed = load_bed(source)
    path = os.path.join(root, name)
    write_case(path, bed, derive(bed, source), source)
    print(tfdem.packing.pack_case(path, runner=lambda *a, **k: run(*a[:3])))
    return Case(path)


def window_mean(rows, start, end):
    return numpy.mean([v for t, v in rows if start - 1e-9 <= t <= end + 1e-9], axis=0)


def check_at_rest(checks, root):
    case = generate(root, "at_rest", AT_REST, 0.2)
    run(["blockMesh"], case.path, "log.blockMesh")
    run(["tfdemFoam"], case.path, "log.tfdemFoam")
    step = case.dem().time_step()
    forces = [(n * step, values) for n, values in fix_print(case.file("forces.txt"))]
    mean = window_mean(forces, 0.1, 0.2)
    gas, floor, lid = mean[0] / WEIGHT, mean[1] / WEIGHT, mean[4] / WEIGHT
    walls = sum(mean[k - 1] for k in side_columns(forces)) / WEIGHT
    checks.true("forces.txt records all four walls of a 3-D bed", side_columns(forces) == (3, 4, 6, 7))
    y_top = case.pressure_height("abovePressure")
    checks.within("the top row's cross-section average at 116 mm", y_top, TOP_ROW, 1e-12)
    inlet = dict(pressure_series(case.path, "inletPressure"))
    above = pressure_series(case.path, "abovePressure")
    dp = window_mean([(t, inlet[t] - p - RHO_GAS * G * y_top) for t, p in above if t in inlet], 0.1, 0.2)
    checks.within(f"at rest: Delta p A against the gas's force on the particles (gas {gas:.4f} W), in W",
                  dp * AREA / WEIGHT, gas, 0.01)
    checks.within(f"at rest: gas {gas:.4f} + floor {floor:.4f} + walls {walls:+.4f} + lid {lid:.4f} = the weight",
                  gas + floor + walls + lid, 1.0, 0.01)
    proc = subprocess.run(["/usr/bin/python3", "-m", "tfdem.summary", case.path], env=environment(),
                          capture_output=True, text=True)
    checks.true("tfdem summary on the run: its table and picture", proc.returncode == 0
                and proc.stdout.splitlines()[-2:] == [case.file("summary.csv"), case.file("summary.png")],
                f"({proc.returncode}: {proc.stdout[-300:]} {proc.stderr[-300:]})")


def batch_means(rows, start, end, batch):
    """Means of (t, value) rows over consecutive batches of `batch` s in [start, end]."""
    count = int(round((end - start) / batch))
    edges = [start + k * batch for k in range(count + 1)]
    return numpy.array([numpy.mean([v for t, v in rows if lo + 1e-9 < t <= hi + 1e-9], axis=0)
                        for lo, hi in zip(edges, edges[1:])])


def mean_and_error(values):
    return float(numpy.mean(values)), float(numpy.std(values, ddof=1) / math.sqrt(len(values)))


def check_bubbling(checks, root):
    case = generate(root, "bubbling", BUBBLING, END)
    run(["blockMesh"], case.path, "log.blockMesh")
    run(["tfdemFoam"], case.path, "log.tfdemFoam")
    step = case.dem().time_step()
    forces = [(n * step, values) for n, values in fix_print(case.file("forces.txt"))]
    shares = [(t, [v[0] / WEIGHT, v[1] / WEIGHT, sum(v[k - 1] for k in side_columns(forces)) / WEIGHT, v[4] / WEIGHT])
              for t, v in forces]
    inlet = dict(pressure_series(case.path, "inletPressure"))
    y_top = case.pressure_height("abovePressure")
    dp = [(t, (inlet[t] - p - RHO_GAS * G * y_top) * AREA / WEIGHT)
          for t, p in pressure_series(case.path, "abovePressure") if t in inlet]
    carried = batch_means(shares, START, END, BATCH)
    pressure = batch_means(dp, START, END, BATCH)
    gas, gas_error = mean_and_error(carried[:, 0])
    difference, error = mean_and_error(pressure - carried[:, 0])
    checks.true(f"bubbling: Delta p A against the gas's force {gas:.4f} +- {gas_error:.4f} W, within 3 standard errors "
                "of their batch-mean difference", abs(difference) <= 3 * error,
                f"({difference:+.4f} +- {error:.4f} W)")
    checks.true("... and that error below 1 % of W", error < 0.01, f"({error:.4f} W)")
    total, total_error = mean_and_error(carried.sum(axis=1))
    floor, walls = carried[:, 1].mean(), carried[:, 2].mean()
    checks.true(f"bubbling: gas + floor ({floor:.4f}) + walls ({walls:+.4f}) + lid carry the weight, within 3 standard "
                "errors", abs(total - 1) <= 3 * total_error + 1e-3, f"({total:.4f} +- {total_error:.4f})")


def check_stats(checks, root):
    """tfdem stats on a copy of the bubbling case (under bubbling/statistics)."""
    case = os.path.join(root, "bubbling")
    proc = subprocess.run(["/usr/bin/python3", "-m", "tfdem.bedstats", case, "--end-time", str(STATS_END),
                           "--window", "0.1", str(STATS_END), "--batch", "0.075"], env=environment(),
                          stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    print(proc.stdout[-2500:])
    checks.true("tfdem stats on a 3-D bed", proc.returncode == 0, f"(exit code {proc.returncode})")
    path = os.path.join(case, "statistics", "bed_statistics.json")
    if not os.path.isfile(path):
        checks.true("bed_statistics.json written", False)
        return
    s = yaml.safe_load(open(path))
    checks.true("the map averaged over the depth's 3 cells, and said so", "averaged over the depth (3 cells)" in s["map"]
                and s["map"] in proc.stdout, f"({s['map']})")
    checks.true("the Delta p levels at 8 and 116 mm", numpy.allclose(s["dp_levels"], [FLOOR, TOP_ROW], atol=1e-12),
                f"({s['dp_levels']})")
    checks.true("Delta p between them a share of the weight, not more",
                0.3 * WEIGHT_PER_AREA < s["dp_mean"]["value"] < 1.05 * WEIGHT_PER_AREA,
                f"({s['dp_mean']['value']:.1f} Pa against {WEIGHT_PER_AREA:.1f} Pa)")
    checks.true("the picture written", os.path.isfile(os.path.join(case, "statistics", "bed_statistics.png")))


def main():
    checks = Checks()
    root = scratch("pressure_balance_3d")
    check_at_rest(checks, root)
    check_bubbling(checks, root)
    check_stats(checks, root)
    checks.finish()


if __name__ == "__main__":
    main()
