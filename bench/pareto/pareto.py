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
(`tfdem pack` pours it); `dp_height` (optional) the height of Delta p's upper level above the
bed's floor (default 20 cm, or the column when shorter: tfdem.bed). Points are runs of
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
import io
import os
import re
import sys

from tfdem import TUTORIALS
from tfdem.batch import run_batch
from tfdem.accuracy import METRICS, map_error, pareto_front, scalar_error, scalar_metrics
from tfdem.bed import BedOutputs
from tfdem.bedstats import BedRun, refuse_foreign_folder
from tfdem.case import CaseError, set_sub_dict_entry
from tfdem.frontdoor import add_debug_option, doing, run_command, save_figure_atomic, write_text_atomic
from tfdem.inputs import InputError, Source, load_yaml, positive_count, positive_number, shown, suggestion
from tfdem.run import DEFAULT_GAS_LAYOUT, GAS_LAYOUTS, run

SWEEP_KEYS = ("template", "packing", "dp_height", "end_time", "window", "batch", "band", "field_interval",
              "statistics_interval", "reference", "points")
OPTIONAL_SWEEP_KEYS = ("packing", "dp_height")
POINT_KEYS = ("dem_time_step", "gas_time_step", "refine", "coupling", "fv_solution", "ranks", "gas")


class SweepError(InputError):
    """A sweep definition problem, named with the file, the key and the fix."""


def load_sweep(path):
    """The sweep file read and checked (every key, every point); adds `path` and
    `template_path`."""
    source = Source(path, SweepError)
    sweep = source.mapping("", load_yaml(path, SweepError), SWEEP_KEYS)
    for key in SWEEP_KEYS:
        if key not in OPTIONAL_SWEEP_KEYS:
            source.required("", sweep, key, "it (bench/pareto/bubbling_bed.yaml shows every key)")
    seconds = "a time in s above 0"
    sweep["template"] = source.text("template", sweep["template"], "a tutorial's name or the path of a case")
    sweep["end_time"] = source.number("end_time", sweep["end_time"], 0.0, low_open=True, what=seconds)
    start, end = source.sequence("window", sweep["window"], 2, 2, "[start, end] in s")
    start = source.number("window[0]", start, 0.0, what="the window's start in s, 0 or more")
    end = source.number("window[1]", end, start, sweep["end_time"], low_open=True,
                        what=f"the window's end in s, after its start and at most end_time ({sweep['end_time']:g})")
    sweep["window"] = [start, end]
    for key in ("batch", "band", "field_interval", "statistics_interval"):
        sweep[key] = source.number(key, sweep[key], 0.0, low_open=True, what=seconds)
    if sweep["band"] >= end - start:
        source.fail("band", f"{shown(sweep['band'])} s is not shorter than the window ({end - start:g} s): give a "
                    "shorter band")
    if "dp_height" in sweep:
        sweep["dp_height"] = source.number("dp_height", sweep["dp_height"], 0.0, low_open=True,
                                           what="a height in m above 0")
    if "packing" in sweep:
        packing = source.mapping("packing", sweep["packing"], ("file", "make"))
        for key in ("file", "make"):
            source.text(f"packing.{key}", source.required("packing", packing, key, "a path relative to tutorials/"),
                        "a path relative to tutorials/")
    points = source.mapping("points", sweep["points"], what="a mapping of point names to their changes")
    if not points:
        source.fail("points", "no point: give at least the reference point")
    for name, spec in points.items():
        _check_point(source, name, spec)
        points[name] = spec or {}
    reference = source.text("reference", sweep["reference"], "the name of one of the points")
    if reference not in points:
        source.fail("reference", f"{shown(reference)} is not one of the points{suggestion(reference, list(points))}")
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


def _check_point(source, name, spec):
    """The point's name (a folder's: runs/<name>) and changes: steps positive seconds, ranks and
    refinement whole numbers of 1 or more, the gas layout's name, the dictionaries' entries."""
    key = f"points.{name}"
    if not re.fullmatch(r"[A-Za-z0-9_.+-]+", name) or name in (".", ".."):
        source.fail(key, f"{shown(name)} is not a plain folder name (its runs go to runs/<name>): use letters, "
                    "digits, '_', '.', '+' and '-'")
    spec = source.mapping(key, spec or {}, POINT_KEYS)
    for step in ("dem_time_step", "gas_time_step"):
        if step in spec:
            spec[step] = source.number(f"{key}.{step}", spec[step], 0.0, low_open=True,
                                       what="a positive number of seconds")
    if "ranks" in spec:
        spec["ranks"] = source.count(f"{key}.ranks", spec["ranks"], what="a whole number of MPI ranks, 1 or more")
    if "gas" in spec:
        source.choice(f"{key}.gas", spec["gas"], list(GAS_LAYOUTS))
    if "refine" in spec:
        factors = source.sequence(f"{key}.refine", spec["refine"], 2, 2, "[x, y], two whole numbers >= 1")
        spec["refine"] = [source.count(f"{key}.refine[{axis}]", f, what="a whole number >= 1")
                          for axis, f in enumerate(factors)]
    for section in ("coupling", "fv_solution"):
        entries = source.mapping(f"{key}.{section}", spec.get(section, {}), what="a mapping of dotted keys to values")
        for entry, value in entries.items():
            if isinstance(value, (list, dict)) or value is None:
                source.fail(f"{key}.{section}.{entry}", f"{shown(value)}: give one value")


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
        near = suggestion(unknown[0], list(sweep["points"]))
        raise SweepError(f"--points: unknown point(s) {', '.join(unknown)}{near}; {sweep['path']} has: "
                         f"{', '.join(sweep['points'])}")
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
    outputs = {p.name: BedOutputs(p.case, dp_height=p.dp_height) for p in finished}
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
    table = io.StringIO(newline="")
    writer = csv.DictWriter(table, fieldnames=list(rows[0]))
    writer.writeheader()
    writer.writerows(rows)
    write_text_atomic(os.path.join(out, "pareto.csv"), table.getvalue())
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
        save_figure_atomic(fig, os.path.join(out, f"pareto_{metric}.png"), dpi=110)
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
    write_text_atomic(os.path.join(out, "README.md"), "\n".join(lines))


def main(argv=None):
    return run_command("pareto.py", _pareto, argv)


def _pareto(argv):
    parser = argparse.ArgumentParser(prog="pareto.py", description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("command", choices=("run", "report"))
    parser.add_argument("sweep", help="sweep definition (bench/pareto/<case>.yaml)")
    parser.add_argument("--end-time", type=positive_number("the simulated time of each point in s"), default=None,
                        help="simulated seconds per point (default: the sweep's; the window and batches scale with it)")
    parser.add_argument("--jobs", type=positive_count("the points side by side"), default=1,
                        help="points side by side (default 1)")
    parser.add_argument("--root", default=None, help="folder for runs/ and report/ (default: beside the sweep file, "
                        "a folder of its name)")
    parser.add_argument("--points", default="", help="comma-separated point names to run (default: all); the "
                        "report covers every finished point")
    parser.add_argument("--cost", choices=("wall", "cpu"), default="wall",
                        help="the plots' cost axis: wall time, or the solver's processor time (fairer when other "
                             "work shared the cores)")
    add_debug_option(parser)
    args = parser.parse_args(argv)
    with doing("reading the sweep", args.sweep):
        sweep = load_sweep(args.sweep)
    end_time = sweep["end_time"] if args.end_time is None else args.end_time
    root = os.path.abspath(args.root or os.path.splitext(os.path.abspath(args.sweep))[0])
    if os.path.exists(root) and not os.path.isdir(root):
        raise SweepError(f"--root {root}: a file where the sweep's folder belongs: give a folder")
    if args.command == "run":
        names = [n.strip() for n in args.points.split(",") if n.strip()]
        if args.points.strip() and not names:
            raise SweepError(f"--points {args.points!r}: no point name: give names from {sweep['path']}")
        points = points_of(sweep, root, names)
        for point in points:
            refuse_foreign_folder(point.case.path)
        return 0 if run_batch(points, end_time, args.jobs) else 1
    with doing("reporting the sweep", args.sweep):
        report(sweep, points_of(sweep, root), end_time, os.path.join(root, "report"), args.cost)
    return 0


if __name__ == "__main__":
    sys.exit(main())
