#!/usr/bin/env python3
"""Speed against error: a sweep of a bed tutorial's settings, each point's wall time and its
error against a reference point, a Pareto plot per metric, a CSV and a README table.

    pareto.py run SWEEP.yaml [--end-time T] [--jobs N] [--root DIR] [--points a,b]
    pareto.py report SWEEP.yaml [--end-time T] [--root DIR] [--cost wall|cpu]

A sweep (bench/pareto/<case>.yaml, or a user's own file) names its template, the simulated
time, the averaging window and its points: each point changes only what it lists (see
POINT_KEYS). The template is a tutorial's name or the path of any bed case (one `tfdem new`
wrote, say; relative to the sweep file); `packing` (optional) names the packed bed to start
from and the script that makes it, relative to tutorials/, else the template's own data file
(`tfdem pack` pours it); `dp_height` (optional) the height of Delta p's upper row above the
bed's bottom row (default 20 cm, or the column when shorter: tfdem.bed). Points are runs of
tfdem.batch (tfdem.bedstats.BedRun): resumable, skipped when done, `--jobs` side by side
(default 1: wall times are only comparable when nothing else runs; with 2 the processor time
is the fairer cost). Runs and the report go beside the sweep file, in a folder of its name.

Metrics over the window, each with its standard error from batch means: mean of Delta p at
20 cm, its standard deviation in the bed's band (50 ms means) and above it (the gas-step
jitter; tfdem.accuracy), mean particle height, the dominant frequency of Delta p (error:
its spectral resolution 1/window), and the time-averaged solids-fraction map (error: L1 against
the reference on the coarser grid; noise: the same L1 between the two halves of each run's
window). A point's error in a metric is |value - reference|; it is within noise when below
twice the combined standard error sqrt(e^2 + e_ref^2).
"""
import argparse
import csv
import difflib
import os
import sys

import yaml

from tfdem import TUTORIALS
from tfdem.batch import BatchError, run_batch
from tfdem.accuracy import METRICS, map_error, pareto_front, scalar_error, scalar_metrics
from tfdem.bed import BedOutputs
from tfdem.bedstats import BedRun
from tfdem.case import CaseError, set_sub_dict_entry
from tfdem.run import DEFAULT_GAS_LAYOUT, RunError, check_gas_layout, run

SWEEP_KEYS = ("template", "packing", "dp_height", "end_time", "window", "batch", "band", "field_interval",
              "statistics_interval", "reference", "points")
OPTIONAL_SWEEP_KEYS = ("packing", "dp_height")
POINT_KEYS = ("dem_time_step", "gas_time_step", "refine", "coupling", "fv_solution", "ranks", "gas")


class SweepError(Exception):
    """A sweep definition problem, named with the file, the key and the fix."""


def _unknown(path, where, key, valid):
    near = difflib.get_close_matches(key, valid, 1)
    return SweepError(f"{path}: {where}unknown key '{key}'" + (f" (did you mean '{near[0]}'?)" if near else "")
                      + f"; valid: {', '.join(valid)}")


def load_sweep(path):
    try:
        with open(path) as f:
            sweep = yaml.safe_load(f)
    except OSError as e:
        raise SweepError(f"{path}: cannot read the sweep ({e.strerror})") from None
    for key in sweep:
        if key not in SWEEP_KEYS:
            raise _unknown(path, "", key, SWEEP_KEYS)
    for key in SWEEP_KEYS:
        if key not in sweep and key not in OPTIONAL_SWEEP_KEYS:
            raise SweepError(f"{path}: missing '{key}'")
    for name, spec in sweep["points"].items():
        for key in spec or {}:
            if key not in POINT_KEYS:
                raise _unknown(path, f"point {name}: ", key, POINT_KEYS)
        _check_point(path, name, spec or {})
    if sweep["reference"] not in sweep["points"]:
        raise SweepError(f"{path}: reference '{sweep['reference']}' is not one of the points "
                         f"({', '.join(sweep['points'])})")
    sweep["path"] = os.path.abspath(path)
    sweep["template_path"] = template_path(sweep)
    return sweep


def template_path(sweep):
    """The template case's folder: a tutorial's name, or a path (absolute, or relative to the
    sweep file)."""
    name = sweep["template"]
    if os.sep in name or name.startswith("."):
        folder = os.path.join(os.path.dirname(sweep["path"]), name)
    else:
        folder = os.path.join(TUTORIALS, name)
    if not os.path.isfile(os.path.join(folder, "coupling.yaml")):
        raise SweepError(f"{sweep['path']}: template '{name}': {folder} is not a case (no coupling.yaml); give a "
                         f"tutorial's name or the path of a case")
    return os.path.abspath(folder)


def _check_point(path, name, spec):
    """The point's numbers: steps positive seconds, ranks and refinement positive whole numbers."""
    def bad(key, expected):
        return SweepError(f"{path}: point {name}: {key} must be {expected}, got {spec[key]!r}")

    for key in ("dem_time_step", "gas_time_step"):
        if key in spec and not (isinstance(spec[key], (int, float)) and spec[key] > 0):
            raise bad(key, "a positive number of seconds")
    if "ranks" in spec and not (isinstance(spec["ranks"], int) and spec["ranks"] >= 1):
        raise bad("ranks", "a whole number >= 1")
    if "gas" in spec:
        try:
            check_gas_layout(spec["gas"])
        except ValueError as e:
            raise SweepError(f"{path}: point {name}: gas: {e}") from None
    refine = spec.get("refine")
    if refine is not None and not (isinstance(refine, list) and len(refine) == 2
                                   and all(isinstance(f, int) and f >= 1 for f in refine)):
        raise bad("refine", "[x, y], two whole numbers >= 1")


class Point(BedRun):
    """One point of the sweep: the template with the point's changes, under root/runs/<name>."""

    def __init__(self, name, spec, sweep, root):
        spec = spec or {}
        super().__init__(name, os.path.join(root, "runs", name), sweep["template_path"], int(spec.get("ranks", 1)),
                         spec.get("gas", DEFAULT_GAS_LAYOUT), sweep.get("dp_height"), sweep["field_interval"],
                         sweep["statistics_interval"])
        self.spec, self.sweep = spec, sweep

    def packed_bed(self):
        return _packing(self.sweep) or super().packed_bed()

    def modify(self, case):
        self._time_steps(case)
        for axis, factor in enumerate(self.spec.get("refine", [1, 1])):
            if factor != 1:
                case.scale_cells(axis, factor)
        for key, value in self.spec.get("coupling", {}).items():
            case.set_coupling(key, value)
        for key, value in self.spec.get("fv_solution", {}).items():
            set_sub_dict_entry(case.file("system", "fvSolution"), key, value)

    def write_interval(self, end_time):
        return min(1.0, end_time)

    def _time_steps(self, case):
        """DEM step and gas step of the point (tfdem.case.Case.set_time_steps)."""
        try:
            case.set_time_steps(self.spec.get("dem_time_step"), self.spec.get("gas_time_step"))
        except CaseError as e:
            raise SweepError(f"point {self.name}: {e}") from None


def _packing(sweep):
    """The packed bed a sweep starts from (its `packing`: the file and the script that makes
    it, both relative to tutorials/, made once), or None: the template's own data file."""
    packing = sweep.get("packing")
    if not packing:
        return None
    path = os.path.join(TUTORIALS, packing["file"])
    if not os.path.isfile(path):
        maker = os.path.join(TUTORIALS, packing["make"])
        run([maker], os.path.dirname(maker), "log.pareto_packing")
    return path


def points_of(sweep, root, names=()):
    unknown = [n for n in names if n not in sweep["points"]]
    if unknown:
        raise SweepError(f"unknown point(s) {', '.join(unknown)}; {sweep['path']} has: {', '.join(sweep['points'])}")
    return [Point(n, s, sweep, root) for n, s in sweep["points"].items() if not names or n in names]


# Report ------------------------------------------------------------------------------------
def report(sweep, points, end_time, out, cost="wall"):
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    scale = end_time / sweep["end_time"]
    start, end = (w * scale for w in sweep["window"])
    batch = sweep["batch"] * scale
    finished = [p for p in points if p.done()]
    by_name = {p.name: p for p in finished}
    if sweep["reference"] not in by_name:
        raise SweepError(f"the reference point '{sweep['reference']}' has not finished: run it first")
    outputs = {p.name: BedOutputs(p.case) for p in finished}
    metrics = {}
    for name, d in outputs.items():
        t, h = d.mean_height()
        metrics[name] = scalar_metrics(d.p_t, d.dp, t, h, start, end, batch, sweep["band"])
    ref = sweep["reference"]
    rows = []
    for p in finished:
        row = {"point": p.name, "wall_seconds": p.wall_seconds(), "cpu_seconds": p.cpu_seconds(), "ranks": p.ranks}
        for metric in (m for m in METRICS if m != "solids_map"):
            row[metric] = metrics[p.name][metric]["value"]
            row[f"{metric}_stderr"] = metrics[p.name][metric]["error"]
            for k, v in scalar_error(metrics[p.name][metric], metrics[ref][metric]).items():
                row[f"{metric}_{k}"] = v
        for k, v in map_error(outputs[p.name], outputs[ref], start, end).items():
            row[f"solids_map_{k}"] = v
        rows.append(row)
    os.makedirs(out, exist_ok=True)
    with open(os.path.join(out, "pareto.csv"), "w", newline="") as f:
        writer = csv.DictWriter(f, fieldnames=list(rows[0]))
        writer.writeheader()
        writer.writerows(rows)
    others = [r for r in rows if r["point"] != ref]
    for metric in METRICS:
        fig, ax = plt.subplots(figsize=(6, 4))
        costs = [r[f"{cost}_seconds"] for r in others]
        errors = [r[f"{metric}_error"] for r in others]
        ax.errorbar(costs, errors, yerr=[2 * r[f"{metric}_sigma"] for r in others], fmt="o", capsize=3)
        for r in others:
            ax.annotate(r["point"], (r[f"{cost}_seconds"], r[f"{metric}_error"]), fontsize=7,
                        xytext=(3, 3), textcoords="offset points")
        front = sorted(pareto_front(costs, errors), key=lambda i: costs[i])
        ax.plot([costs[i] for i in front], [errors[i] for i in front], "r-", lw=1, label="Pareto front")
        ax.set_xlabel("wall time (s)" if cost == "wall" else "processor time (s)")
        ax.set_ylabel(f"|{metric} - reference| (bars: 2 sigma)")
        ax.set_title(f"{os.path.basename(sweep['path'])}: {metric}, {start:g}-{end:g} s", fontsize=9)
        ax.legend(fontsize=7)
        fig.tight_layout()
        fig.savefig(os.path.join(out, f"pareto_{metric}.png"), dpi=110)
        plt.close(fig)
    write_table(sweep, rows, ref, start, end, out)
    print(f"report: {len(rows)} points -> {out}")
    return rows


def write_table(sweep, rows, ref, start, end, out):
    lines = [f"# Speed against error: {os.path.basename(sweep['path'])}", "",
             f"Template `{sweep['template']}`, averages over {start:g}-{end:g} s, reference point `{ref}`. "
             "Error = |point - reference|; `~` = within noise (below 2 sigma of batch means; for the map, "
             "below the L1 between the two halves of the window).", "",
             f"Δp std: the fluctuation of Δp's {1000 * sweep['band']:g} ms means (the bed's motion); Δp jitter: "
             "the rest (numerical, grows as the gas step shrinks: bench/README.md).", "",
             "| point | wall (s) | processor (s) | Δp mean (Pa) | Δp std (Pa) | Δp jitter (Pa) | mean height (cm) "
             "| frequency (Hz) | solids map L1 |",
             "|---|---|---|---|---|---|---|---|---|"]
    for r in rows:
        cells = []
        for metric, scale in (("dp20_mean", 1), ("dp20_std", 1), ("dp20_jitter", 1), ("mean_height", 100),
                              ("dp20_frequency", 1), ("solids_map", 1)):
            if metric == "solids_map":
                text = f"{r['solids_map_error']:.3g}"
            else:
                text = f"{r[metric] * scale:.4g} ± {r[f'{metric}_stderr'] * scale:.2g}"
                if r["point"] != ref:
                    text += f" (Δ {r[f'{metric}_error'] * scale:.2g})"
            if r["point"] != ref and r[f"{metric}_within_noise"]:
                text += " ~"
            cells.append(text)
        lines.append(f"| {r['point']} | {r['wall_seconds']:.0f} | {r['cpu_seconds']:.0f} | " + " | ".join(cells) + " |")
    lines += ["", *(f"![{m}](pareto_{m}.png)" for m in METRICS), ""]
    with open(os.path.join(out, "README.md"), "w") as f:
        f.write("\n".join(lines))


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("command", choices=("run", "report"))
    parser.add_argument("sweep", help="sweep definition (bench/pareto/<case>.yaml)")
    parser.add_argument("--end-time", type=float, default=None, help="simulated seconds per point (default: the sweep's; "
                        "the window and batches scale with it)")
    parser.add_argument("--jobs", type=int, default=1, help="points side by side (default 1)")
    parser.add_argument("--root", default=None, help="folder for runs/ and report/ (default: beside the sweep file, "
                        "a folder of its name)")
    parser.add_argument("--points", default="", help="comma-separated point names to run (default: all); the "
                        "report covers every finished point")
    parser.add_argument("--cost", choices=("wall", "cpu"), default="wall",
                        help="the plots' cost axis: wall time, or the solver's processor time (fairer when other "
                             "work shared the cores)")
    args = parser.parse_args(argv)
    try:
        sweep = load_sweep(args.sweep)
        end_time = args.end_time or sweep["end_time"]
        root = args.root or os.path.splitext(os.path.abspath(args.sweep))[0]
        if args.command == "run":
            points = points_of(sweep, root, [n for n in args.points.split(",") if n])
            return 0 if run_batch(points, end_time, args.jobs) else 1
        report(sweep, points_of(sweep, root), end_time, os.path.join(root, "report"), args.cost)
        return 0
    except (SweepError, BatchError, CaseError, RunError) as e:
        print(f"pareto.py: {e}", file=sys.stderr)
        return 2
    except KeyboardInterrupt:
        return 130


if __name__ == "__main__":
    sys.exit(main())
