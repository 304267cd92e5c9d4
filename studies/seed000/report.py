"""The study's report: seed 000's figures from the runs' outputs, and the table of every
number beside the paper's (report/README.md, report/numbers.json, copied to
results/numbers.json and results/README.md, which are kept in the repository).

Every number comes from a run's record (record.py: its series and window-averaged maps,
results/<run>/), written from the run folder when the run finished and read back; a run
without a folder but with a record (a clone without runs/) still gives its numbers and the
figures of series and time-averaged maps; only the figures of particles or of an instant
(Figs. 6, 7, 8, 10, 12) need the run folders. A configuration with realizations is drawn from
its first one (its maps in Fig. 13: their mean). Every time average comes with its standard
error from batch means (study.yaml `batch`); averages cover seed 000's window (5-10 s) and
5-20 s. The maps
are time averages of the fields the runs sampled at every cell centre (study.yaml
`field_interval`). The realizations of study.yaml add ensemble errors, blocking curves,
autocorrelation times and noise floors (replicates.py).
"""
import json
import math
import os
import re
import shutil

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy  # noqa: E402

from record import DP_HEADERS, Record  # noqa: E402
from headline import HEADLINE, PAIRS, REPLICATES, Headline, pair_lines, replace_block  # noqa: E402
from replicates import Replicates  # noqa: E402
from tfdem.bed import BedOutputs  # noqa: E402
from tfdem.outputs import vtk_particles  # noqa: E402
from tfdem.stats import batch_means, dominant_frequency, window  # noqa: E402

# Seed 000's results (text of the paper; its figures give no more digits)
PAPER = {
    "bulk_coordination_jet": "~1.2 (Fig. 5)",
    "bulk_coordination_jet_value": 1.2,  # "varies around 1.2" (text beside Fig. 5)
    "bulk_coordination_uniform": "~0.5 (Fig. 5)",
    "bulk_coordination_uniform_value": 0.5,
    "multicontact_jet": "> 0.6 most of the time (Fig. 11)",
    "multicontact_uniform": "~0.3 (Fig. 11)",
    "multicontact_uniform_value": 0.3,
    "mean_height_m1": 8.9,   # cm, 5-10 s, averaged-velocity method (method 1)
    "mean_height_m2": 9.1,   # cm, per-particle method (method 2)
    "mean_height_tfm": 9.16,  # cm, TFM
    "mean_height_experiment": 11.4,  # cm, Goldschmidt et al.
    "force_ratio_jet": "2-10 in most of the bed, up to 100 in the corners beside the jet (Fig. 7)",
    "force_ratio_uniform": "never above 15 (Fig. 12)",
    "cost_tfdem_jet": 6780.0,  # s for 20 s, one 2.0 GHz Opteron 270 core
    "cost_tfm_jet": 5350.0,
}


BED_SOLIDS = 0.05  # the cells whose time-averaged solids fraction is above this are the bed's
CORNER = (0.04, 0.06)  # m: the bottom corners, x within this of a wall and y below this (Fig. 7, 8)


class RunData(BedOutputs):
    """What a finished run wrote, as arrays, with its cost: the figures' input (a Record, the
    numbers')."""

    def __init__(self, run):
        super().__init__(run.case, run.tfm, dp_from=run.dp_from)
        self.run, self.name = run, run.name
        self.wall = run.wall_seconds()
        self.cpu = run.cpu_seconds()
        self.timing = None if run.tfm else run.timing_seconds()


def averaged(t, y, start, end, batch):
    m, err, n = batch_means(list(t), list(y), start, end, batch)
    return {"mean": m, "error": err, "batches": n, "std": float(numpy.std(window(list(t), list(y), start, end)))}


def fmt(stat, scale=1.0, digits=3):
    if stat is None:
        return "-"
    err = stat["error"] * scale
    text = f"{stat['mean'] * scale:.{digits}g}"
    return text + (f" ± {err:.2g}" if err == err else "")


class Report:
    def __init__(self, study, runs, end_time, out, results, study_readme=None):
        self.study, self.end_time, self.out, self.results = study, end_time, out, results
        self.study_readme = study_readme
        self.windows = [(a * end_time, b * end_time) for a, b in study["windows"]]
        self.batch = study["batch"] * end_time / study["end_time"]
        self.snapshot = study["snapshot_time"] * end_time
        self.data, self.records = {}, {}
        self.missing = []
        for r in runs:
            folder = os.path.join(results, r.name)
            if r.done():
                self.data[r.name] = RunData(r)
                Record.from_outputs(self.data[r.name], self.windows).write(folder)
            if r.done() or os.path.isfile(os.path.join(folder, "run.json")):
                self.records[r.name] = Record.read(folder, r.name)
            else:
                self.missing.append(r.name)
        self.numbers = {"windows": self.windows, "batch": self.batch, "snapshot": self.snapshot, "runs": {},
                        "from_records_only": sorted(set(self.records) - set(self.data))}
        os.makedirs(out, exist_ok=True)

    # Numbers -----------------------------------------------------------------------------
    def run_numbers(self, d):
        out = {"wall_seconds": d.wall, "cpu_seconds": d.cpu}
        if d.meta.get("timing"):
            out["timing"] = d.meta["timing"]
        for (start, end) in self.windows:
            key = f"{start:g}-{end:g}"
            w = {"dp20": averaged(d.p_t, d.dp, start, end, self.batch)}
            t, h = d.mean_height()
            w["mean_height"] = averaged(t, h, start, end, self.batch)
            if not d.tfm:
                p = d.particles
                w["bulk_coordination"] = averaged(p["t"], p["bulk_coordination"], start, end, self.batch)
                w["multicontact"] = averaged(p["t"], p["multicontact"], start, end, self.batch)
                w["force_ratio"] = self.ratio_numbers(d, start, end)
            pick = (d.p_t >= start - 1e-9) & (d.p_t <= end + 1e-9)
            w["dp20_frequency"] = dominant_frequency(d.p_t[pick], d.dp[pick])
            out[key] = w
        return out

    def ratio_numbers(self, d, start, end):
        """Contact/drag ratio of the time-averaged maps over the bed's cells (time-averaged
        solids fraction above 0.1): share of cells between 2 and 10, median, largest, and the
        largest in the bottom corners (CORNER)."""
        contact, drag = d.window_map("contact", start, end), d.window_map("drag", start, end)
        solids = d.window_map("solids", start, end)
        bed = (solids > 0.1) & (drag > 0)
        ratio = numpy.where(drag > 0, contact / numpy.where(drag > 0, drag, 1), numpy.nan)
        width, height = CORNER
        corner = bed & (d.y < height) & ((d.x < width) | (d.x > d.width - width))
        values = ratio[bed]
        return {"share_2_to_10": float(((values >= 2) & (values <= 10)).mean()) if values.size else float("nan"),
                "median": float(numpy.median(values)) if values.size else float("nan"),
                "largest": float(values.max()) if values.size else float("nan"),
                "largest_in_corners": float(ratio[corner].max()) if corner.any() else float("nan")}

    def theta_numbers(self):
        """The granular temperature (seed 000 eq. 6) of TF-DEM (method 1) against the TFM's
        transported Theta, per bed, over the first window: the solids-weighted mean over the bed's
        cells (time-averaged solids fraction above BED_SOLIDS), sum alpha_s Theta / sum alpha_s,
        and the same per row of cells; for the runs whose records keep a theta map."""
        start, end = self.windows[0]
        out = {}
        for bed in ("jet", "uniform"):
            names = [n for n in (f"{bed}_m1", f"{bed}_tfm") if n in self.records
                     and "theta" in self.records[n].maps.get(f"{start:g}-{end:g}", {})]
            if len(names) < 2:
                continue
            values = {}
            for n in names:
                r = self.records[n]
                solids, theta = r.window_map("solids", start, end), r.window_map("theta", start, end)
                weight = numpy.where(solids > BED_SOLIDS, solids, 0.0)
                rows = numpy.where(weight.sum(axis=1) > 0,
                                   (weight * theta).sum(axis=1) / numpy.maximum(weight.sum(axis=1), 1e-300), numpy.nan)
                values[n] = {"bed_mean": float((weight * theta).sum() / weight.sum()),
                             "row_y": [float(y) for y in r.y[:, 0]], "rows": [float(v) for v in rows]}
            dem, tfm = values[f"{bed}_m1"]["bed_mean"], values[f"{bed}_tfm"]["bed_mean"]
            out[bed] = {"runs": values, "tfm_over_tfdem": tfm / dem, "window": [start, end]}
        return out

    def theta_figure(self):
        """Granular temperature per row and per cell, TF-DEM (method 1) and TFM, each bed."""
        theta = self.numbers.get("granular_temperature", {})
        beds = [b for b in ("jet", "uniform") if b in theta]
        if not beds:
            return
        start, end = self.windows[0]
        fig, axes = plt.subplots(len(beds), 3, figsize=(9, 4.5 * len(beds)), squeeze=False)
        for k, bed in enumerate(beds):
            runs = theta[bed]["runs"]
            for n, values in runs.items():
                axes[k, 0].semilogx(values["rows"], 100 * numpy.array(values["row_y"]), label=f"{n}: bed mean "
                                    f"{values['bed_mean']:.2e}")
            axes[k, 0].set_xlabel("Θ (m²/s²), solids-weighted row mean", fontsize=8)
            axes[k, 0].set_ylabel("height (cm)", fontsize=8)
            axes[k, 0].set_ylim(0, 45)
            axes[k, 0].legend(fontsize=6)
            for j, n in enumerate(runs):
                r = self.records[n]
                t = numpy.log10(numpy.maximum(r.window_map("theta", start, end), 1e-6))
                image = self.map_axes(axes[k, 1 + j], r, t, f"{n}: log10 Θ, {start:g}-{end:g} s",
                                      vmin=-5, vmax=-1, cmap="magma")
            fig.colorbar(image, ax=list(axes[k, 1:]), shrink=0.8, label="log10 Θ (m²/s²)")
        fig.suptitle("Granular temperature: TF-DEM's particles (seed 000 eq. 6) and the TFM's Theta", fontsize=9)
        fig.savefig(os.path.join(self.out, "fig_granular_temperature.png"), dpi=110)
        plt.close(fig)
        self.figures.append("fig_granular_temperature.png")

    # Figures -------------------------------------------------------------------------------
    def save(self, fig, name):
        fig.tight_layout()
        fig.savefig(os.path.join(self.out, name), dpi=110)
        plt.close(fig)
        self.figures.append(name)

    def save_series(self, fig, ax, ylabel, title, filename):
        """A time-series figure's axes, legend and title, saved."""
        ax.set_xlabel("t (s)")
        ax.set_ylabel(ylabel)
        ax.legend(fontsize=7)
        ax.set_title(title, fontsize=9)
        self.save(fig, filename)

    def map_axes(self, ax, r, values, title, vmin=0, vmax=0.65, cmap="viridis", top=0.45):
        """A map of `values` on record r's cells, the bottom `top` metres."""
        extent = r.extent
        image = ax.imshow(values, origin="lower", extent=extent, vmin=vmin, vmax=vmax, cmap=cmap,
                          interpolation="nearest", aspect="equal")
        ax.set_ylim(extent[2], min(top, extent[3]))
        ax.set_title(title, fontsize=8)
        ax.set_xticks([0, 0.05, 0.1, 0.15])
        ax.tick_params(labelsize=7)
        return image

    def realizations(self, config):
        """The records of a configuration's realizations (<config>_r1, _r2, ...), in order."""
        pattern = re.compile(re.escape(config) + r"_r(\d+)$")
        found = [(int(m.group(1)), n) for n in self.records for m in [pattern.match(n)] if m]
        return [n for _, n in sorted(found)]

    def shown(self, *configs):
        """The runs a figure draws for these configurations, as far as they have records: a
        configuration's first realization when it has realizations, else its single run."""
        names = [(self.realizations(c) or [c])[0] for c in configs]
        return [n for n in names if n in self.records]

    def fig3(self):
        names = self.shown("jet_m1", "jet_m2", "jet_tfm", "jet_tfm_phase_pressure", "jet_tfm_peer")
        if not names:
            return
        start, end = self.windows[0]
        fig, ax = plt.subplots(figsize=(8, 3.5))
        for n in names:
            r = self.records[n]
            s = averaged(r.p_t, r.dp, start, end, self.batch)
            ax.plot(r.p_t, r.dp, lw=0.6, label=f"{n}: {s['mean']:.0f} ± {s['std']:.0f} Pa (mean ± std, {start:g}-{end:g} s)")
        levels = {DP_HEADERS[self.records[n].dp_from].split(": ", 1)[1] for n in names}
        between = levels.pop() if len(levels) == 1 else "at 20 cm (levels differ: see each record)"
        self.save_series(fig, ax, "Δp at 20 cm (Pa)", f"Fig. 3: pressure drop {between}, central-jet bed",
                         "fig3_jet_pressure_drop.png")

    def series_figure(self, key, ylabel, title, filename, paper_lines):
        names = self.shown("jet_m1", "jet_m2", "uniform_m1", "uniform_m2")
        if not names:
            return
        fig, ax = plt.subplots(figsize=(8, 3.5))
        for n in names:
            p = self.records[n].particles
            ax.plot(p["t"], p[key], lw=0.6, label=n)
        for value, label in paper_lines:
            ax.axhline(value, ls="--", lw=0.8, color="k")
            ax.text(0.01, value, label, fontsize=7, va="bottom", transform=ax.get_yaxis_transform())
        self.save_series(fig, ax, ylabel, title, filename)

    def particle_snapshot(self, name, filename, title):
        if name not in self.data:
            return
        d = self.data[name]
        folder = d.run.case.file("VTK")
        files = sorted(os.listdir(folder), key=lambda f: abs(float(f[len("particles_"):-len(".vtk")]) - self.snapshot))
        p = vtk_particles(os.path.join(folder, files[0]))
        t = float(files[0][len("particles_"):-len(".vtk")])
        x = numpy.array(p["position"])
        v = numpy.array(p["velocity"])
        nc = numpy.array(p["coordination"])
        fig, ax = plt.subplots(figsize=(5, 7.5))
        sc = ax.scatter(x[:, 0], x[:, 1], c=nc, s=6, cmap="jet", vmin=0, vmax=6)
        # arrows in metres per (m/s): 1 m/s is drawn 1 cm long
        arrows = ax.quiver(x[:, 0], x[:, 1], v[:, 0], v[:, 1], angles="xy", scale_units="xy", scale=100,
                           width=0.003, color="black")
        ax.quiverkey(arrows, 0.6, 0.95, 1.0, "1 m/s", labelpos="E", coordinates="axes")
        ax.set_xlim(0, d.grid.upper(0))
        ax.set_ylim(0, 0.45)
        ax.set_aspect("equal")
        fig.colorbar(sc, ax=ax, label="N_c")
        ax.set_title(f"{title}\n{name}, t = {t:g} s", fontsize=9)
        self.save(fig, filename)

    def force_figure(self, name, filename, title):
        if name not in self.data:
            return
        d = self.data[name]
        start, end = self.windows[0]
        fig, axes = plt.subplots(2, 3, figsize=(8, 8))
        rows = (("at %g s" % self.snapshot, lambda v: d.field_at(v, self.snapshot)),
                ("averaged %g-%g s" % (start, end), lambda v: d.field_average(v, start, end)))
        for i, (label, pick) in enumerate(rows):
            contact, drag = pick(d.contact), pick(d.drag)
            ratio = numpy.where(drag > 0, contact / numpy.where(drag > 0, drag, 1), -1)
            for j, (values, what, vmax) in enumerate(((contact, "contact |Σ f_c|/(m g)", None),
                                                      (drag, "drag |Σ f_d|/(m g)", None),
                                                      (ratio, "contact / drag (-1: no drag)", 20))):
                top = vmax or max(float(numpy.percentile(values, 99)), 1e-9)
                image = self.map_axes(axes[i, j], self.records[name], values, f"{what}\n{label}", vmin=-1 if vmax else 0,
                                      vmax=top, cmap="jet")
                fig.colorbar(image, ax=axes[i, j], shrink=0.7)
        fig.suptitle(title, fontsize=9)
        self.save(fig, filename)

    def fig8(self):
        peer = (self.realizations("jet_tfm_peer") or ["jet_tfm_peer"])[0]
        names = [n for n in ("jet_m1", "jet_tfm", "jet_tfm_phase_pressure", peer) if n in self.data]
        if "jet_m1" not in names or len(names) < 2:
            return
        start, end = self.windows[0]
        fig, axes = plt.subplots(1, 2 * len(names), figsize=(2.5 * 2 * len(names), 5))
        for k, (label, pick) in enumerate((("at %g s" % self.snapshot, lambda d: d.field_at(d.solids, self.snapshot)),
                                           ("%g-%g s" % (start, end), lambda d: d.field_average(d.solids, start, end)))):
            for j, n in enumerate(names):
                d = self.data[n]
                image = self.map_axes(axes[len(names) * k + j], self.records[n], pick(d), f"{n}, {label}")
        fig.colorbar(image, ax=list(axes), shrink=0.8, label="solids fraction")
        fig.suptitle("Fig. 8: solids fraction, central-jet bed, TF-DEM (method 1) and TFM", fontsize=9)
        fig.savefig(os.path.join(self.out, "fig8_jet_dem_vs_tfm.png"), dpi=110)
        plt.close(fig)
        self.figures.append("fig8_jet_dem_vs_tfm.png")

    def fig9(self):
        names = self.shown("uniform_m1", "uniform_m2", "uniform_m2_interpolated", "uniform_tfm",
                           "uniform_tfm_phase_pressure", "uniform_tfm_peer")
        if not names:
            return
        fig, ax = plt.subplots(figsize=(8, 3.5))
        for n in names:
            t, h = self.records[n].mean_height()
            ax.plot(t, 100 * h, lw=0.6, label=n)
        for key, label in (("mean_height_m1", "paper, method 1"), ("mean_height_m2", "paper, method 2"),
                           ("mean_height_tfm", "paper, TFM"), ("mean_height_experiment", "experiment")):
            ax.axhline(PAPER[key], ls="--", lw=0.7, color="k")
            ax.text(1.0, PAPER[key], f" {label} {PAPER[key]} cm", fontsize=6, va="center",
                    transform=ax.get_yaxis_transform())
        self.save_series(fig, ax, "mean particle height (cm)", "Fig. 9: mean particle height, uniform-inflow bed",
                         "fig9_uniform_mean_height.png")

    def fig13(self):
        """The uniform bed's time-averaged solids fraction per configuration: the mean of its
        realizations' maps (or its one run's)."""
        configs = [c for c in ("uniform_m1", "uniform_m2", "uniform_m2_interpolated", "uniform_tfm",
                               "uniform_tfm_phase_pressure", "uniform_tfm_peer") if self.realizations(c) or c in self.records]
        if len(configs) < 2:
            return
        start, end = self.windows[0]
        fig, axes = plt.subplots(1, len(configs), figsize=(2.6 * len(configs), 5))
        for ax, c in zip(axes, configs):
            names = self.realizations(c) or [c]
            mean = numpy.mean([self.records[n].window_map("solids", start, end) for n in names], axis=0)
            image = self.map_axes(ax, self.records[names[0]], mean, f"{c}\n(n = {len(names)})", top=0.3)
        fig.colorbar(image, ax=list(axes), shrink=0.8, label=f"solids fraction, {start:g}-{end:g} s")
        fig.suptitle("Fig. 13: time-averaged solids fraction, uniform-inflow bed, method 1 and method 2", fontsize=9)
        fig.savefig(os.path.join(self.out, "fig13_uniform_methods.png"), dpi=110)
        plt.close(fig)
        self.figures.append("fig13_uniform_methods.png")

    # Assembly ------------------------------------------------------------------------------
    def build(self):
        self.figures = []
        for name, d in self.records.items():
            self.numbers["runs"][name] = self.run_numbers(d)
        self.numbers["granular_temperature"] = self.theta_numbers()
        self.fig3()
        self.series_figure("bulk_coordination", "bulk coordination number",
                           "Fig. 5: bulk coordination number (mean N_c)", "fig5_coordination.png",
                           [(1.2, "paper: jet ~1.2"), (0.5, "paper: uniform ~0.5")])
        self.particle_snapshot("jet_m1", "fig6_jet_particles.png", "Fig. 6: particles, velocities and N_c")
        self.force_figure("jet_m1", "fig7_jet_forces.png", "Fig. 7: contact and drag force per cell, central-jet bed")
        self.fig8()
        self.fig9()
        self.particle_snapshot("uniform_m1", "fig10_uniform_particles.png", "Fig. 10: particles, velocities and N_c")
        self.series_figure("multicontact", "multicontact ratio", "Fig. 11: particles with N_c > 1 over those with N_c >= 1",
                           "fig11_multicontact.png", [(0.6, "paper: jet > 0.6"), (0.3, "paper: uniform ~0.3")])
        self.force_figure("uniform_m1", "fig12_uniform_forces.png",
                          "Fig. 12: contact and drag force per cell, uniform-inflow bed")
        self.fig13()
        self.theta_figure()
        replicates = Replicates(self, PAPER)
        self.numbers["replicates"] = replicates.numbers()
        replicates.figure(self)
        replicates.grid_figure(self)
        headline = Headline(self, replicates, PAPER, CORNER)
        self.numbers["fig8"] = headline.fig8_numbers() if replicates.groups else {}
        headline_lines = headline.markdown() if replicates.groups else []
        self.numbers["figures"] = self.figures
        self.numbers["missing_runs"] = self.missing
        with open(os.path.join(self.out, "numbers.json"), "w") as f:
            json.dump(self.numbers, f, indent=1, default=float)
        replicate_lines = replicates.markdown()
        self.write_readme(headline_lines, replicate_lines)
        for name in ("numbers.json", "README.md"):
            shutil.copy(os.path.join(self.out, name), os.path.join(self.results, name))
        if headline_lines and self.study_readme:
            with open(self.study_readme) as f:
                text = f.read()
            with open(self.study_readme, "w") as f:
                text = replace_block(text, HEADLINE, headline_lines)
                text = replace_block(text, PAIRS, pair_lines(replicates.result, replicates.windows[-1]))
                f.write(replace_block(text, REPLICATES, replicate_lines[2:]))

    def write_readme(self, headline_lines, replicate_lines):
        w0 = f"{self.windows[0][0]:g}-{self.windows[0][1]:g}"
        w1 = f"{self.windows[1][0]:g}-{self.windows[1][1]:g}"
        runs = self.numbers["runs"]

        def stat(run, key, scale=1.0):
            return fmt(runs[run][w0].get(key), scale), fmt(runs[run][w1].get(key), scale)

        lines = [f"# Seed 000 study: report ({self.end_time:g} s runs)", "",
                 f"Averages over {w0} s (seed 000's window) and {w1} s, ± the standard error of batch means "
                 f"({self.batch:g} s batches). Made by `study.py report` from the runs' records "
                 "(`results/<run>/`, written from `runs/`).", ""]
        if self.missing:
            lines += [f"Runs not finished (left out): {', '.join(self.missing)}", ""]
        if self.numbers["from_records_only"]:
            lines += ["From their records only (no run folder, so in none of the figures of particles or of an "
                      "instant: Figs. 6, 7, 8, 10, 12): "
                      f"{', '.join(self.numbers['from_records_only'])}", ""]
        lines += ["## Seed 000's results beside ours", ""] + headline_lines
        lines += ["", "## The single runs", "", "The runs made once (the lattice-packed and TFM runs); the realizations' "
                  "ensembles are under Replicates.", ""]
        lines += ["| quantity | run | paper | ours " + w0 + " s | ours " + w1 + " s |", "|---|---|---|---|---|"]
        rows = [("Δp at 20 cm (Pa), jet", r, "figure only (Fig. 3)", "dp20", 1.0)
                for r in ("jet_m1", "jet_m2", "jet_fine_m1", "jet_tfm", "jet_tfm_phase_pressure")]
        rows += [("bulk coordination number, jet", r, PAPER["bulk_coordination_jet"], "bulk_coordination", 1.0)
                 for r in ("jet_m1", "jet_m2")]
        rows += [("bulk coordination number, uniform", r, PAPER["bulk_coordination_uniform"], "bulk_coordination", 1.0)
                 for r in ("uniform_m1", "uniform_m2")]
        rows += [("multicontact ratio, jet", r, PAPER["multicontact_jet"], "multicontact", 1.0) for r in ("jet_m1", "jet_m2")]
        rows += [("multicontact ratio, uniform", r, PAPER["multicontact_uniform"], "multicontact", 1.0)
                 for r in ("uniform_m1", "uniform_m2")]
        for r, key in (("uniform_m1", "mean_height_m1"), ("uniform_m2", "mean_height_m2"),
                       ("uniform_m2_interpolated", "mean_height_m2"), ("uniform_tfm", "mean_height_tfm"),
                       ("uniform_tfm_phase_pressure", "mean_height_tfm")):
            rows.append(("mean particle height (cm), uniform", r,
                         f"{PAPER[key]} (experiment {PAPER['mean_height_experiment']})", "mean_height", 100.0))
        for label, run, paper, key, scale in [row for row in rows if row[1] in runs]:
            a, b = stat(run, key, scale)
            lines.append(f"| {label} | {run} | {paper} | {a} | {b} |")
        lines += ["", "Contact / drag force ratio of the time-averaged maps over bed cells (solids fraction > 0.1):", "",
                  "| run | paper | share of cells 2-10 | median | largest | largest in the bottom corners |",
                  "|---|---|---|---|---|---|"]
        for run, paper in (("jet_m1", PAPER["force_ratio_jet"]), ("uniform_m1", PAPER["force_ratio_uniform"])):
            if run in runs:
                r = runs[run][w0]["force_ratio"]
                lines.append(f"| {run} | {paper} | {r['share_2_to_10']:.2f} | {r['median']:.3g} | {r['largest']:.3g} | "
                             f"{r['largest_in_corners']:.3g} |")
        if self.numbers["granular_temperature"]:
            lines += ["", "Granular temperature Θ (m²/s²; seed 000 eq. 6 from the particles, the TFM's transported "
                          f"Theta) over {w0} s, solids-weighted over the bed's cells (time-averaged solids fraction "
                          f"above {BED_SOLIDS}):", "", "| bed | TF-DEM (method 1) | TFM | TFM / TF-DEM |", "|---|---|---|---|"]
            for bed, v in self.numbers["granular_temperature"].items():
                lines.append(f"| {bed} | {v['runs'][bed + '_m1']['bed_mean']:.3g} | {v['runs'][bed + '_tfm']['bed_mean']:.3g} | "
                             f"{v['tfm_over_tfdem']:.3g} |")
        lines += ["", "Cost on this machine (two runs side by side on its 2 cores; processor time is the "
                      "solver's own, OpenFOAM's ExecutionTime):", "",
                  "| run | wall time | processor time | processor time per simulated second |", "|---|---|---|---|"]
        for name, values in runs.items():
            lines.append(f"| {name} | {values['wall_seconds']:.0f} s | {values['cpu_seconds']:.0f} s | "
                         f"{values['cpu_seconds'] / self.end_time:.1f} s |")
        lines += ["", f"Paper (one 2.0 GHz Opteron 270 core, 20 s of the jet bed): TF-DEM "
                       f"{PAPER['cost_tfdem_jet']:.0f} s, TFM {PAPER['cost_tfm_jet']:.0f} s.", ""]
        lines += replicate_lines + ["", "## Figures", ""]
        lines += [f"![{f}]({f})" for f in self.figures]
        with open(os.path.join(self.out, "README.md"), "w") as f:
            f.write("\n".join(lines) + "\n")


def write_report(study, runs, end_time, out, results, study_readme=None):
    """The report of `runs` into `out`, its numbers and README copied to `results`; with
    study_readme (the study's README.md, for a report of the study's own length) the headline
    table written into it between headline.py's markers."""
    report = Report(study, runs, end_time, out, results, study_readme)
    if not report.records:
        raise SystemExit(f"report: no finished run in runs/ and no record in {results} (study.py run first)")
    report.build()
    bad = [f"{run}.{w}.{k}" for run, values in report.numbers["runs"].items() for w, v in values.items()
           if isinstance(v, dict) for k, s in v.items()
           if isinstance(s, dict) and "mean" in s and not math.isfinite(s["mean"])]
    print(f"report: {len(report.figures)} figures, {len(report.data)} runs -> {out}"
          + (f"; NOT FINITE: {', '.join(bad)}" if bad else ""))
    if bad:
        raise SystemExit(1)
