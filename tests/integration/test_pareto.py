"""The speed-against-error tool (bench/pareto/pareto.py) and its errors (tfdem.accuracy).

1. Its error computation on hand-made series with known answers: Delta p = c + 10 sin(2 pi 2 t)
   + 3 (-1)^n sampled every 0.01 s (n the sample; a jitter at 50 Hz), c = 100 Pa (point) and
   90 Pa (reference), window 0.5-3.49 s (300 samples), 0.5 s batches of whole periods: mean
   error 10 Pa with zero batch-means error (not within noise); the dominant frequency 2 Hz;
   in the bed band (5-sample running means, 50 ms, none reaching past the window's end, so
   over 0.5-3.51 s their centres fill the six batches) the sine keeps
   G = (1 + 2 cos w + 2 cos 2w) / 5 of its amplitude (w = 0.04 pi per sample) and the jitter
   3/5, so the band's fluctuation is sqrt((10 G)^2 / 2 + 0.6^2) and the jitter's
   sqrt((10 (1 - G))^2 / 2 + 2.4^2); over 0.5-3.49 s the series cut at 3.49 s scores as
   the whole one (a run that ran on past the window as one that stopped at its end); solids
   maps of 0.5 and 0.4 everywhere: L1 0.1 on the coarse grid, also when the point's map is on
   a twice finer grid; the Pareto front of three (cost, error) pairs.
2. A tiny sweep (the bubbling bed, 2 points, 0.05 s) runs and writes its CSV, plots and table;
   a misspelt point key and a negative DEM step are refused with a message naming them.
"""
import csv
import math
import os
import subprocess

import numpy
import yaml

from tfdem import SOURCE_DIR, accuracy
from tfdem.run import environment
from tfdem_testlib import Checks, scratch

PARETO = os.path.join(SOURCE_DIR, "bench", "pareto", "pareto.py")


class HandMap:
    """A map series as BedOutputs holds one: two samples of a uniform solids fraction."""

    def __init__(self, value, shape):
        self.shape = shape
        self.field_t = numpy.array([1.0, 3.0])
        self.solids = numpy.full((2, shape[0] * shape[1]), value)

    def field_average(self, values, start, end):
        pick = (self.field_t >= start) & (self.field_t <= end)
        return values[pick].mean(axis=0).reshape(self.shape)


def check_errors(checks):
    t = numpy.arange(0, 400) * 0.01
    wave = 10 * numpy.sin(2 * math.pi * 2 * t) + 3 * (-1.0) ** numpy.arange(0, 400)
    height = numpy.full_like(t, 0.1)
    point = accuracy.scalar_metrics(t, 100 + wave, t, height, 0.5, 3.49, 0.5, 0.05)
    reference = accuracy.scalar_metrics(t, 90 + wave, t, height, 0.5, 3.49, 0.5, 0.05)
    mean_error = accuracy.scalar_error(point["dp20_mean"], reference["dp20_mean"])
    checks.within("mean error of Delta p", mean_error["error"], 10.0, 1e-9)
    checks.within("... its sigma", mean_error["sigma"], 0.0, 1e-9)
    checks.true("... not within noise", not mean_error["within_noise"])
    w = 0.04 * math.pi
    gain = (1 + 2 * math.cos(w) + 2 * math.cos(2 * w)) / 5
    banded = accuracy.scalar_metrics(t, 100 + wave, t, height, 0.5, 3.51, 0.5, 0.05)
    checks.within("fluctuation in the bed band (batch std)", banded["dp20_std"]["value"],
                  math.sqrt((10 * gain) ** 2 / 2 + 0.6 ** 2), 1e-9)
    checks.within("jitter above the band (batch std)", banded["dp20_jitter"]["value"],
                  math.sqrt((10 * (1 - gain)) ** 2 / 2 + 2.4 ** 2), 1e-9)
    cut = t <= 3.49 + 1e-9
    stopped = accuracy.scalar_metrics(t[cut], 100 + wave[cut], t[cut], height[cut], 0.5, 3.49, 0.5, 0.05)
    for key in ("dp20_mean", "dp20_std", "dp20_jitter"):
        checks.within(f"{key}: the run cut at the window's end scores the same", stopped[key]["value"],
                      point[key]["value"], 1e-9)
    checks.within("frequency", point["dp20_frequency"]["value"], 2.0, 1e-12)
    checks.within("frequency error between the two", accuracy.scalar_error(point["dp20_frequency"],
                                                                         reference["dp20_frequency"])["error"], 0.0, 1e-12)
    same = accuracy.map_error(HandMap(0.5, (4, 3)), HandMap(0.4, (4, 3)), 0.0, 4.0)
    checks.within("map L1", same["error"], 0.1, 1e-12)
    checks.within("map noise floor (steady maps)", same["sigma"], 0.0, 1e-12)
    refined = accuracy.map_error(HandMap(0.5, (8, 6)), HandMap(0.4, (4, 3)), 0.0, 4.0)
    checks.within("map L1, point on a twice finer grid", refined["error"], 0.1, 1e-12)
    checks.true("Pareto front of (1, 3), (2, 1), (3, 2)", accuracy.pareto_front([1, 2, 3], [3, 1, 2]) == [0, 1])


def check_tiny_sweep(checks):
    root = scratch("pareto_tiny")
    sweep = yaml.safe_load(open(os.path.join(SOURCE_DIR, "bench", "pareto", "bubbling_bed.yaml")))
    sweep.update(end_time=0.05, window=[0.01, 0.05], batch=0.01, band=0.005, field_interval=0.005,
                 statistics_interval=0.001,
                 points={"reference": sweep["points"]["reference"], "default": {}})
    path = os.path.join(root, "tiny.yaml")
    yaml.safe_dump(sweep, open(path, "w"))
    for command in ("run", "report"):
        proc = subprocess.run(["/usr/bin/python3", PARETO, command, path, "--root", root], env=environment(),
                              stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
        print(proc.stdout[-3000:])
        checks.true(f"pareto.py {command}", proc.returncode == 0, f"(exit code {proc.returncode})")
    report = os.path.join(root, "report")
    for name in ["pareto.csv", "README.md"] + [f"pareto_{m}.png" for m in accuracy.METRICS]:
        checks.true(f"report/{name} written", os.path.isfile(os.path.join(report, name)))
    if os.path.isfile(os.path.join(report, "pareto.csv")):
        rows = list(csv.DictReader(open(os.path.join(report, "pareto.csv"))))
        checks.true("two points in the CSV", sorted(r["point"] for r in rows) == ["default", "reference"])
        for r in rows:
            finite = all(math.isfinite(float(r[f"{m}_error"])) for m in accuracy.METRICS)
            checks.true(f"{r['point']}: every error finite", finite)
        own = [r for r in rows if r["point"] == "reference"]
        checks.true("the reference's own errors are zero",
                    bool(own) and all(float(own[0][f"{m}_error"]) == 0.0 for m in accuracy.METRICS))
    bad = dict(sweep, points={"reference": {}, "coarse": {"refine_y": 2}})
    yaml.safe_dump(bad, open(path, "w"))
    proc = subprocess.run(["/usr/bin/python3", PARETO, "run", path, "--root", root], env=environment(),
                          stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    checks.true("a misspelt point key is named with the nearest one",
                proc.returncode == 2 and "points.coarse.refine_y: unknown key (did you mean 'refine'?)" in proc.stdout)
    yaml.safe_dump(dict(sweep, points={"reference": {}, "coarse": {"dem_time_step": -1}}), open(path, "w"))
    proc = subprocess.run(["/usr/bin/python3", PARETO, "run", path, "--root", root], env=environment(),
                          stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    checks.true("a negative DEM step is named with what is expected",
                proc.returncode == 2 and "points.coarse.dem_time_step: -1 is not above 0: give a positive number of "
                "seconds" in proc.stdout)


def main():
    checks = Checks()
    check_errors(checks)
    check_tiny_sweep(checks)
    checks.finish()


if __name__ == "__main__":
    main()
