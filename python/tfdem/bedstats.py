"""The bubbling statistics of any bed case (`tfdem stats CASE --end-time T`): the case is run
under CASE/statistics/ (a copy, its own outputs untouched) with the bed probes of tfdem.bed,
resumable like a study's runs, and reported over a window with honest errors:

    tfdem stats CASE --end-time T [--window START END] [--batch S] [--band S] [--dp-height H]
                     [--ranks R] [--gas whole|split] [--root DIR]

Reported, each over the window with its standard error from batch means (tfdem.accuracy):
Delta p between the bed's floor (the inlet, or the top of a distributor plate) and the height
`--dp-height` above it (default seed 000's 20 cm, or the column's highest row of cells when it
is shorter), each p the linear interpolation of the rows of cell centres either side (at the
floor, extrapolated from the first two rows above it), so the same heights on every grid; the
fluctuation of its `--band` means and the faster rest (the gas-step jitter),
the mean particle height, the dominant frequency of Delta p (error: the spectral resolution
1 / window), and Delta p as a share of the bed's weight per area (a fluidized bed's gas
carries the weight of the particles above the floor). The batch-means error holds when
a batch is much longer than Delta p's integrated autocorrelation time tau (tfdem.stats);
tau and the error it implies, std sqrt(tau / N), are reported beside it, and a batch shorter
than 5 tau is named. Writes ROOT/bed_statistics.json and ROOT/bed_statistics.png (Delta p and
the mean height against time, the time-averaged solids-fraction map). Any layout: a bed more
than one cell deep has its map averaged over the depth and the rows of its Delta p averaged over
the cross-section (width and depth), which the report says.
"""
import argparse
import json
import math
import os

import numpy

from tfdem.accuracy import scalar_metrics
from tfdem.batch import STATUS, BatchError, CaseRun, run_batch
from tfdem.bed import BedOutputs, default_dp_height, pressure_levels, write_bed_probes
from tfdem.case import Case, CaseError
from tfdem.frontdoor import add_debug_option, doing, run_command, save_figure_atomic, write_text_atomic
from tfdem.inputs import non_negative_number, positive_count, positive_number
from tfdem.packing import STAMP, verify_stamp
from tfdem.run import DEFAULT_GAS_LAYOUT, GAS_LAYOUTS, command, prepare_gas, run
from tfdem.stats import integrated_autocorrelation_time

FIELD_INTERVAL = 0.05       # s: solids-fraction map samples
STATISTICS_INTERVAL = 0.01  # s: Delta p and particle statistics samples
BATCH = 0.5                 # s: about one bubble period of seed 000's beds
BAND = 0.05                 # s: the bed's motion below 20 Hz (tfdem.accuracy)
FEWEST_BATCHES = 4
TAU_BATCHES = 5.0           # a batch-means error wants batches at least this many tau long


class BedRun(CaseRun):
    """A bed case run under `path` with the bed probes: the template copied with the packed
    bed its DEM script reads (packed_bed()), the run's end time, `modify(case)` (a
    subclass's changes), the mesh, the probes, the gas layout."""

    def __init__(self, name, path, template, ranks=1, gas=DEFAULT_GAS_LAYOUT, dp_height=None,
                 field_interval=FIELD_INTERVAL, statistics_interval=STATISTICS_INTERVAL):
        super().__init__(name, path)
        self.template, self.ranks, self.gas = os.path.abspath(template), int(ranks), gas
        self.dp_height = dp_height
        self.field_interval, self.statistics_interval = field_interval, statistics_interval

    def command(self):
        return command([self.solver], self.ranks, self.gas)

    def complete_fields(self):
        # a split run restarts from its beginning (its checkpoints are per processor)
        return ("no-resume",) if self.ranks > 1 and self.gas == "split" else ("tfdem.checkpoint",)

    def packed_bed(self):
        """The data file the run starts from: the template's own (its DEM script's read_data)."""
        template = Case(self.template)
        packed = template.file(template.particles_file())
        if not os.path.isfile(packed):
            raise CaseError(f"{packed}: no packed bed to start from; pour it first: tfdem pack {template.path}")
        if os.path.exists(packed + STAMP):  # a bed tfdem pack poured: the one it finished
            verify_stamp(template)
        return packed

    def prepare(self, end_time):
        packed = self.packed_bed()
        refuse_foreign_folder(self.case.path)
        case = Case(self.template).copy_to(self.case.path)
        data = case.particles_file()
        self.set_status(state="preparing", end_time=end_time)  # "prepared" once all of it is done (run_batch)
        case.set_control(endTime=end_time, writeInterval=self.write_interval(end_time), startFrom="startTime",
                         writePrecision=17)
        self.modify(case)
        case.set_coupling("output.statistics_interval", self.statistics_interval)
        os.makedirs(os.path.dirname(case.file(data)), exist_ok=True)
        with open(packed, "rb") as src, open(case.file(data), "wb") as dst:
            dst.write(src.read())
        run(["blockMesh"], case.path, "log.blockMesh")
        write_bed_probes(case, self.field_interval, self.statistics_interval,
                         dp_height=self.dp_height or default_dp_height(case))
        prepare_gas(case.path, self.ranks, self.gas)

    def modify(self, case):
        """Changes to the copied case before its mesh is made (none here)."""

    def write_interval(self, end_time):
        """The template's checkpoint interval, or end_time when shorter."""
        return min(float(Case(self.template).control("writeInterval")), end_time)


def refuse_foreign_folder(path):
    """A run's folder is made afresh (the old one removed): refuse one that holds files and is
    not a run's (no status file), so that nothing of a user's is removed."""
    if os.path.isfile(path) or os.path.islink(path):
        raise BatchError(f"{path}: a file where the run's folder belongs: give another --root, or move the file")
    if os.path.isdir(path) and os.listdir(path) and not os.path.isfile(os.path.join(path, STATUS)):
        raise BatchError(f"{path}: a folder with files that is not a run's (no {STATUS}): the run would replace "
                         "it; give a new or empty folder (--root), or remove it yourself")


def bed_weight_per_area(case):
    """The packed bed's buoyant weight per area of the column's cross-section (Pa), from the
    data file the run read (masses from the per-atom density and diameter)."""
    atoms = case.particles()
    rho_gas, _ = case.gas()
    g = math.sqrt(sum(c * c for c in case.gravity()))
    lo, hi = case.mesh_bounds()
    volume = sum(math.pi * d ** 3 / 6 for d in atoms["diameter"])
    mass = sum(rho * math.pi * d ** 3 / 6 for rho, d in zip(atoms["density"], atoms["diameter"]))
    return (mass - rho_gas * volume) * g / ((hi[0] - lo[0]) * (hi[2] - lo[2]))


def correlation_check(t, y, start, end, batch):
    """Delta p's integrated autocorrelation time over the window (s), the standard error it
    implies (std sqrt(tau / N)) and whether the batches are at least TAU_BATCHES tau long."""
    t, y = numpy.asarray(t), numpy.asarray(y)
    pick = (t >= start - 1e-9) & (t <= end + 1e-9)
    values = y[pick]
    step = float(numpy.median(numpy.diff(t[pick])))
    try:
        tau, _ = integrated_autocorrelation_time(values)
    except ValueError as e:
        return {"tau_seconds": None, "error_from_tau": None, "batches_long_enough": False, "note": str(e)}
    tau_seconds = tau * step
    return {"tau_seconds": tau_seconds, "error_from_tau": float(values.std(ddof=1) * math.sqrt(tau / values.size)),
            "batches_long_enough": bool(batch >= TAU_BATCHES * tau_seconds)}


def statistics(run_case, start, end, batch, band, dp_height=None):
    """The report's numbers (a dict) of a finished run's case, Delta p over dp_height (default
    tfdem.bed.default_dp_height) from the bed's floor."""
    outputs = BedOutputs(run_case, dp_height=dp_height)
    t, height = outputs.mean_height()
    metrics = scalar_metrics(outputs.p_t, outputs.dp, t, height, start, end, batch, band)
    weight = bed_weight_per_area(run_case)
    names = {"dp20_mean": "dp_mean", "dp20_std": "dp_fluctuation", "dp20_jitter": "dp_jitter",
             "mean_height": "mean_height", "dp20_frequency": "dp_frequency"}
    out = {"window": [start, end], "batch": batch, "band": band, "dp_levels": list(outputs.levels),
           "dp_height": outputs.levels[1] - outputs.levels[0], "weight_per_area": weight, "map": map_description(outputs)}
    out.update({names[k]: v for k, v in metrics.items()})
    out["dp_over_weight"] = {"value": metrics["dp20_mean"]["value"] / weight,
                             "error": metrics["dp20_mean"]["error"] / weight}
    out["correlation"] = correlation_check(outputs.p_t, outputs.dp, start, end, batch)
    return out, outputs


def map_description(outputs):
    """What a map cell of the report stands for: the cell, or the x, y column of cells averaged
    over the depth (a bed more than one cell deep)."""
    if outputs.depth_cells == 1:
        return "the solids fraction of each gas cell (the bed is one cell deep)"
    return f"the solids fraction of each x, y column of gas cells averaged over the depth ({outputs.depth_cells} cells)"


def describe(s):
    """The report's lines."""
    def pm(key, scale=1.0, unit=""):
        v = s[key]
        return f"{v['value'] * scale:.4g} ± {v['error'] * scale:.2g}{unit}"
    c = s["correlation"]
    lines = [f"window {s['window'][0]:g}-{s['window'][1]:g} s, batches of {s['batch']:g} s (± one standard error)",
             f"  Delta p (y = {s['dp_levels'][0]:.4g} to {s['dp_levels'][1]:.4g} m, {s['dp_height'] * 100:.3g} cm): "
             f"{pm('dp_mean', unit=' Pa')}, {pm('dp_over_weight')} of the bed's weight per area "
             f"({s['weight_per_area']:.4g} Pa)",
             f"  its fluctuation ({1000 * s['band']:g} ms means): {pm('dp_fluctuation', unit=' Pa')}; "
             f"faster jitter {pm('dp_jitter', unit=' Pa')}",
             f"  dominant frequency {pm('dp_frequency', unit=' Hz')}",
             f"  mean particle height {pm('mean_height', 100, ' cm')}",
             f"  time-averaged map: {s['map']}; Delta p between p at the two heights, each from its rows' means over the cross-section"]
    if c["tau_seconds"] is None:
        lines.append(f"  Delta p's correlation time: not measurable in this window ({c['note']}); the batch-means "
                     "errors are unchecked: run longer")
    else:
        lines.append(f"  Delta p's integrated autocorrelation time {c['tau_seconds'] * 1000:.3g} ms: error from it "
                     f"{c['error_from_tau']:.2g} Pa against {s['dp_mean']['error']:.2g} Pa from batch means"
                     + ("" if c["batches_long_enough"] else
                        f"; batches of {s['batch']:g} s are shorter than {TAU_BATCHES:g} tau, so the batch-means "
                        "errors are too small: give --batch longer, or run longer"))
    return lines


def plot(outputs, s, path):
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, axes = plt.subplots(1, 3, figsize=(11, 3.6), gridspec_kw={"width_ratios": [2, 2, 1]})
    start, end = s["window"]
    axes[0].plot(outputs.p_t, outputs.dp, lw=0.5)
    axes[0].axhline(s["weight_per_area"], color="k", ls="--", lw=0.8, label="bed weight per area")
    axes[0].axvspan(start, end, color="0.9", zorder=0)
    axes[0].set_xlabel("t (s)")
    axes[0].set_ylabel(f"Δp over {s['dp_height'] * 100:.3g} cm (Pa)")
    axes[0].legend(fontsize=7)
    t, h = outputs.mean_height()
    axes[1].plot(t, numpy.asarray(h) * 100)
    axes[1].axvspan(start, end, color="0.9", zorder=0)
    axes[1].set_xlabel("t (s)")
    axes[1].set_ylabel("mean particle height (cm)")
    grid = outputs.grid
    extent = [grid.origin[0], grid.origin[0] + grid.counts[0] * grid.spacing[0],
              grid.origin[1], grid.origin[1] + grid.counts[1] * grid.spacing[1]]
    image = axes[2].imshow(outputs.field_average(outputs.solids, start, end), origin="lower", extent=extent,
                           vmin=0, vmax=0.65, cmap="viridis")
    across = "" if outputs.depth_cells == 1 else f"\naveraged over the depth ({outputs.depth_cells} cells)"
    axes[2].set_title(f"solids fraction{across}", fontsize=8)
    fig.colorbar(image, ax=axes[2], fraction=0.08)
    fig.tight_layout()
    save_figure_atomic(fig, path, dpi=110)
    plt.close(fig)


def default_window(end_time):
    """The last four fifths of the run: the first fifth is the start-up."""
    return 0.2 * end_time, end_time


def main(argv=None):
    return run_command("tfdem stats", _stats, argv, known=(ValueError,))


def _arguments(argv):
    parser = argparse.ArgumentParser(prog="tfdem stats", description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    seconds = positive_number("a time in s above 0")
    parser.add_argument("case")
    parser.add_argument("--end-time", type=seconds, required=True, help="simulated seconds")
    parser.add_argument("--window", type=non_negative_number("a time in s (0 or more)"), nargs=2,
                        metavar=("START", "END"), help="the averaging window, s (default: the last four fifths of "
                        "the run)")
    parser.add_argument("--batch", type=seconds, default=BATCH, help=f"batch-means batches, s (default {BATCH:g})")
    parser.add_argument("--band", type=seconds, default=BAND, help=f"Delta p's band, s (default {BAND:g})")
    parser.add_argument("--dp-height", type=positive_number("a height in m above 0"), default=None,
                        help="m from the bed's floor to Delta p's upper level (default 0.2, or the column when shorter)")
    parser.add_argument("--ranks", type=positive_count("the run's MPI ranks"), default=1)
    parser.add_argument("--gas", default=DEFAULT_GAS_LAYOUT, choices=sorted(GAS_LAYOUTS),
                        help="whole (on every rank) or split")
    parser.add_argument("--root", default=None, help="the run's folder (default CASE/statistics)")
    add_debug_option(parser)
    return parser.parse_args(argv)


def _stats(argv):
    args = _arguments(argv)
    template = os.path.abspath(args.case)
    if not os.path.isfile(os.path.join(template, "coupling.yaml")):
        raise CaseError(f"{args.case}: not a case folder (no coupling.yaml): give the folder of a bed case "
                        "(tfdem new writes one)")
    root = os.path.abspath(args.root or os.path.join(template, "statistics"))
    refuse_foreign_folder(root)
    start, end = args.window or default_window(args.end_time)
    if not start < end <= args.end_time + 1e-12:
        raise CaseError(f"--window {start:g} {end:g}: give 0 <= START < END <= the end time {args.end_time:g}")
    if args.band >= end - start:
        raise CaseError(f"--band {args.band:g}: Delta p's band must be shorter than the window ({end - start:g} s): "
                        "give a shorter band or a longer window")
    batch = args.batch
    if (end - start) / batch < FEWEST_BATCHES:
        batch = (end - start) / FEWEST_BATCHES
        print(f"tfdem stats: batches of {batch:g} s (the window holds fewer than {FEWEST_BATCHES} of "
              f"{args.batch:g} s)")
    if args.dp_height is not None:
        pressure_levels(Case(template), args.dp_height)
    bed = BedRun("statistics", root, template, args.ranks, args.gas, args.dp_height)
    if not run_batch([bed], args.end_time, jobs=1):
        return 1
    with doing("reading the run's outputs in", root):
        s, outputs = statistics(bed.case, start, end, batch, args.band, args.dp_height)
    report = os.path.join(root, "bed_statistics.json")
    with doing("writing", report):
        write_text_atomic(report, json.dumps(s, indent=1))
    figure = os.path.join(root, "bed_statistics.png")
    with doing("plotting", figure):
        plot(outputs, s, figure)
    print("\n".join(describe(s)))
    print(f"written: {report}, {figure}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
