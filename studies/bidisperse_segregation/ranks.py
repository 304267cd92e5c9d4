"""Goldschmidt's bed on N ranks against one rank (issue 29): are its statistics those of one
rank, within the noise of independent realizations?

    ranks.py run [--ranks 4] [--realizations 3] [--many-realizations 3] [--end-time 1] [--jobs 2]
    ranks.py report [--ranks 4] [--realizations 3] [--many-realizations 3] [--window 0.6 1] [--name ranks]

A bed this chaotic cannot match one rank to round-off on N ranks (the sums of contact forces
come in another order), so the test is statistical. `run` pours the bed once (bed.data, as
segregation.py) and runs it with the polydisperse drag from realizations of one initial
state: r1 the poured bed at rest, r2, r3, ... its particles given random velocities of
JIGGLE m/s (tfdem.packing.jiggle, one seed a realization), far below the bed's own motion;
the bed's chaos makes them independent realizations within a few tenths of a second. The
realizations run on 1 rank (runs/rank1_r<k>) and on N ranks (runs/ranks<N>_r<k>; as many, or
fewer: --many-realizations, down to one, whose error is then the 1-rank realizations' spread,
the scatter a single run has), the gas whole on every rank, with the bed probes of tfdem.bed
(Delta p at 20 cm, solids-fraction maps) and the particle statistics every 0.01 s; resumable
as the other batches.

`report` takes each run's means over the window (default: from WINDOW_START, the bubbling
bed after its first eruption, to the end): Delta p at 20 cm and its fluctuation, the mean
particle height, the degree of segregation s (seed 001 eq. 49), the bulk coordination
number; the ensemble means of the two rank counts with their standard errors across
realizations and their difference; and the time-averaged solids-fraction maps' L1 across the
rank counts against the L1 within one (tfdem.bed.l1_permutation_test). Written to
results/<name>.json and results/<name>.md (--name, default ranks), and each run's Delta p
series over the span all runs reached to results/ranks_dp.csv.
"""
import argparse
import json
import os
import sys

import numpy

from tfdem.batch import BatchError, run_batch
from tfdem.bed import BedOutputs, l1_noise_floor, l1_permutation_test, cross_l1
from tfdem.bedstats import BAND, BedRun
from tfdem.accuracy import scalar_metrics
from tfdem.case import Case, CaseError
from tfdem.packing import jiggle, pour_case
from tfdem.run import RunError
from tfdem.stats import difference, ensemble, interval_mean

HERE = os.path.dirname(os.path.abspath(__file__))
JIGGLE = 1e-6  # m/s: the realizations' random velocities, a millionth of the bubbles' speeds
WINDOW_START = 0.6  # s: Delta p falls in the first eruption over 0.41-0.5 s; bubbling after it
SEEDS = (104729, 224737, 350377, 479909, 611953, 746773)  # the 10,000th ... 60,000th primes
LAW = {"coupling.drag_law": "beetstra", "coupling.polydisperse_drag": "beetstra_2007"}
METRICS = {  # name: (label, unit, scale)
    "dp_mean": ("Delta p at 20 cm", "Pa", 1.0),
    "dp_fluctuation": ("its fluctuation (50 ms means)", "Pa", 1.0),
    "mean_height": ("mean particle height", "cm", 100.0),
    "segregation": ("degree of segregation s", "", 1.0),
    "bulk_coordination": ("bulk coordination number", "", 1.0),
}


class RealizationRun(BedRun):
    """Realization k (1, 2, ...) of the poured bed on `ranks` ranks: the tutorial with the
    polydisperse drag, its bed at rest (k = 1) or jiggled with SEEDS[k - 2]."""

    def __init__(self, ranks, k, root=HERE):
        name = f"rank1_r{k}" if ranks == 1 else f"ranks{ranks}_r{k}"
        super().__init__(name, os.path.join(root, "runs", name), root, ranks)
        self.realization = k

    def modify(self, case):
        for key, value in LAW.items():
            case.set_coupling(key, value)

    def prepare(self, end_time):
        super().prepare(end_time)
        if self.realization > 1:
            jiggle(self.case.file(self.case.particles_file()), JIGGLE, SEEDS[self.realization - 2])


def runs(ranks, realizations, many_realizations=None, root=HERE):
    """Realizations 1 .. `realizations` on one rank, then 1 .. `many_realizations` (default as
    many) on `ranks` ranks."""
    many = realizations if many_realizations is None else many_realizations
    return ([RealizationRun(1, k, root) for k in range(1, realizations + 1)]
            + [RealizationRun(ranks, k, root) for k in range(1, many + 1)])


def run_metrics(out, start, end):
    """A run's means over [start, end] (METRICS) and its time-averaged solids-fraction map, from
    its BedOutputs; a window past the run's last probe is refused."""
    if out.p_t[-1] < end - 1e-9:
        raise ValueError(f"{out.case.path}: probed to {out.p_t[-1]:g} s, short of the window's end {end:g} s: "
                         f"give a --window inside the runs, or run them on (ranks.py run --end-time {end:g})")
    t, height = out.mean_height()
    scalars = scalar_metrics(out.p_t, out.dp, t, height, start, end, end - start, BAND)
    values = {"dp_mean": scalars["dp20_mean"]["value"], "dp_fluctuation": scalars["dp20_std"]["value"],
              "mean_height": scalars["mean_height"]["value"]}
    for key in ("segregation", "bulk_coordination"):
        values[key] = interval_mean(out.particles["t"], out.particles[key], start, end)
    return values, out.field_average(out.solids, start, end)


def single_realization(value, spread):
    """One realization as an estimate of its configuration's mean: its error is the spread of
    the realizations (the scatter one run has), taken from the other rank count's."""
    return {"mean": float(value), "error": float(spread), "spread": float(spread), "n": 1, "values": [float(value)]}


def compare(one_rank, many_ranks):
    """The two rank counts' ensembles of each metric ({metric: [values, one a realization]};
    at least two on one rank, one or more on many) and their difference (many - one) with its
    standard error and size in standard errors."""
    out = {}
    for key in METRICS:
        a = ensemble(one_rank[key])
        b = (ensemble(many_ranks[key]) if len(many_ranks[key]) > 1
             else single_realization(many_ranks[key][0], a["spread"]))
        d = difference(b, a)
        out[key] = {"one_rank": a, "many_ranks": b, "difference": d,
                    "in_errors": d["mean"] / d["error"] if d["error"] > 0 else float("inf")}
    return out


def maps_comparison(maps_one, maps_many):
    """The solids-fraction maps: mean L1 across the rank counts, the floor within each, and
    the exact permutation test's p (None, as the floor within many, with one map on many)."""
    two = len(maps_many) > 1
    return {"cross": float(numpy.mean(cross_l1(maps_one, maps_many))),
            "floor_one_rank": l1_noise_floor(maps_one)["mean"],
            "floor_many_ranks": l1_noise_floor(maps_many)["mean"] if two else None,
            "p": l1_permutation_test(maps_one, maps_many)["p"] if two else None}


def table(result):
    """The report's Markdown table."""
    n = result["ranks"]
    lines = [f"| over {result['window'][0]:g}-{result['window'][1]:g} s | 1 rank | {n} ranks | "
             f"{n} ranks - 1 rank | in standard errors |", "|---|---|---|---|---|"]
    for key, (label, unit, scale) in METRICS.items():
        c = result["metrics"][key]

        def pm(e):
            return f"{e['mean'] * scale:.4g} ± {e['error'] * scale:.2g}"
        lines.append(f"| {label}{f' ({unit})' if unit else ''} | {pm(c['one_rank'])} | {pm(c['many_ranks'])} | "
                     f"{pm(c['difference'])} | {c['in_errors']:+.1f} |")
    m = result["maps"]
    lines.append("")
    many = result["many_realizations"]
    within_many = (f", within {n} ranks {m['floor_many_ranks']:.4f}; permutation test p = {m['p']:.2f}"
                   if m["p"] is not None else " (one map on many ranks: no floor within it, no permutation test)")
    lines.append(f"Solids-fraction maps (time-averaged over the window): L1 across the rank counts {m['cross']:.4f}, "
                 f"within 1 rank {m['floor_one_rank']:.4f}{within_many}. Realizations: {result['realizations']} on "
                 f"1 rank, {many} on {n} (mean ± the standard error across them"
                 f"{'; one realization: ± the 1-rank spread' if many == 1 else ''}).")
    return "\n".join(lines)


def write_dp_series(series, path):
    """Delta p at 20 cm of each run ({name: (t, Delta p)}, probed every 0.01 s), from 0 to the end
    all runs reached, one column a run: the series behind the README's account of the bed, small
    enough to keep."""
    times = min((t for t, _ in series.values()), key=lambda t: t[-1])
    with open(path, "w") as f:
        f.write("t (s)," + ",".join(f"{name} (Pa)" for name in series) + "\n")
        for ti in times:
            f.write(f"{ti:.4g}," + ",".join(f"{numpy.interp(ti, t, dp):.1f}" for t, dp in series.values()) + "\n")


def report(ranks, realizations, many_realizations, window, name="ranks", root=HERE):
    one, many = {k: [] for k in METRICS}, {k: [] for k in METRICS}
    maps = {1: [], ranks: []}
    series = {}
    for r in runs(ranks, realizations, many_realizations, root):
        if not r.done():
            raise BatchError(f"{r.name} has not finished: run it first (ranks.py run)")
        out = BedOutputs(r.case)
        series[r.name] = (numpy.asarray(out.p_t), numpy.asarray(out.dp))
        values, solids = run_metrics(out, *window)
        for key in METRICS:
            (one if r.ranks == 1 else many)[key].append(values[key])
        maps[r.ranks].append(solids)
    result = {"ranks": ranks, "realizations": realizations, "many_realizations": many_realizations,
              "window": list(window),
              "per_run": {"one_rank": one, "many_ranks": many},
              "metrics": compare(one, many), "maps": maps_comparison(maps[1], maps[ranks])}
    os.makedirs(os.path.join(root, "results"), exist_ok=True)
    with open(os.path.join(root, "results", f"{name}.json"), "w") as f:
        json.dump(result, f, indent=1)
    write_dp_series(series, os.path.join(root, "results", "ranks_dp.csv"))
    text = table(result)
    with open(os.path.join(root, "results", f"{name}.md"), "w") as f:
        f.write(text + "\n")
    print(text)


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("action", choices=("run", "report"))
    parser.add_argument("--ranks", type=int, default=4, help="the rank count to compare with one (default 4)")
    parser.add_argument("--realizations", type=int, default=3, help=f"per rank count, 2 to {len(SEEDS) + 1} (default 3)")
    parser.add_argument("--many-realizations", type=int, default=None,
                        help="on the N ranks, 1 to --realizations (default as many)")
    parser.add_argument("--end-time", type=float, default=1.0, help="simulated seconds per run (default 1)")
    parser.add_argument("--window", type=float, nargs=2, default=None, metavar=("START", "END"),
                        help=f"the report's averaging window, s (default {WINDOW_START:g} to the end time)")
    parser.add_argument("--name", default="ranks", help="the report's files: results/NAME.json, .md (default ranks)")
    parser.add_argument("--jobs", type=int, default=2)
    args = parser.parse_args(argv)
    if args.ranks < 2 or not 2 <= args.realizations <= len(SEEDS) + 1:
        parser.error(f"--ranks must be 2 or more and --realizations 2 to {len(SEEDS) + 1}")
    many = args.realizations if args.many_realizations is None else args.many_realizations
    if not 1 <= many <= args.realizations:
        parser.error(f"--many-realizations must be 1 to --realizations ({args.realizations}), got {many}")
    window = args.window or (WINDOW_START, args.end_time)
    if not args.name or os.path.basename(args.name) != args.name or args.name.startswith("."):
        parser.error(f"--name {args.name!r} must be a plain file name (results/NAME.json), e.g. ranks_first_eruption")
    if not window[0] < window[1]:
        parser.error(f"the window {window[0]:g}-{window[1]:g} s is empty: give --window START END, "
                     f"or an --end-time past {WINDOW_START:g} s")
    try:
        if args.action == "run":
            if not os.path.exists(os.path.join(HERE, "bed.data")):
                print("pouring the bed (tfdem.packing, packing.yaml)", flush=True)
                print(pour_case(HERE, ranks=2), flush=True)
            if not run_batch(runs(args.ranks, args.realizations, many), args.end_time, args.jobs):
                return 1
        report(args.ranks, args.realizations, many, window, args.name)
    except (BatchError, CaseError, RunError, ValueError) as e:
        print(f"ranks.py: {e}", file=sys.stderr)
        return 2
    return 0


if __name__ == "__main__":
    sys.exit(main())
