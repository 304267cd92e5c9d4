"""The study's headline table: each of seed 000's results beside ours, over the paper's
window (5-10 s), from the report's numbers alone. A configuration with realizations gives its
ensemble mean ± the standard error across realizations (replicates.py); a single run (the
TFM peers, the lattice-packed jet_m1) its mean ± the batch-means error, which the
realizations show to be too small for the jet bed (the factor is printed under the table).

study.py report writes the table into report/README.md and between the markers of the
study's README.md (markers(), replace_block), so the README's table is the report's; the
replicates' tables go into it the same way.
"""
import math
import numpy

from replicates import MAP_DEPTH, pm, signed
from tfdem.bed import l1_difference
from tfdem.outputs import TIMING_PARTS
from tfdem.stats import ensemble

HEADLINE, PAIRS, REPLICATES = "the headline table", "the pairs table", "the replicates' tables"
AXIS_HEIGHTS = (0.01, 0.07, 0.13)  # m: the jet axis' solids fraction at these heights (Fig. 8)


def axis_profile(field, record, heights=AXIS_HEIGHTS):
    """The map's value on the vertical mid-plane (the jet's axis) at each height: the column
    whose centre is on it, or the mean of the two beside it, in the row whose centre is nearest."""
    columns = numpy.flatnonzero(numpy.isclose(record.x[0], 0.5 * record.width))
    if columns.size == 0:
        middle = record.shape[1] // 2
        columns = numpy.array([middle - 1, middle])
    column = field[:, columns].mean(axis=1)
    return [float(column[int(numpy.argmin(numpy.abs(record.y[:, 0] - h)))]) for h in heights]


def corner_mean(field, record, width, height):
    """The map's mean over the bottom corners (x < width or x > W - width, y < height)."""
    x, y = record.x, record.y
    corner = (y < height) & ((x < width) | (x > record.width - width))
    return float(field[corner].mean())


def mirror_l1(field, record):
    """Mean |map - its mirror image| over the bottom MAP_DEPTH: 0 for a left-right symmetric bed."""
    rows = int((record.y[:, 0] < MAP_DEPTH).sum())
    return l1_difference(field, field[:, ::-1], rows)


class Headline:
    """The rows of the headline table from a built Report (numbers, records) and its
    Replicates result."""

    def __init__(self, report, replicates, paper, corner):
        self.report, self.paper, self.corner = report, paper, corner
        self.r = replicates.result
        self.groups, self.tfm_groups = replicates.groups, replicates.tfm_groups
        self.w = f"{report.windows[0][0]:g}-{report.windows[0][1]:g}"
        self.runs = report.numbers["runs"]

    # Sources --------------------------------------------------------------------------------
    def ens(self, config, key, part="mean"):
        return self.r["ensembles"][config][self.w][key][part] if config in self.groups else None

    def single(self, run, key):
        return self.runs[run][self.w][key] if run in self.runs else None

    def diff(self, kind, pair, quantity):
        return self.r["differences"].get(kind, {}).get(pair, {}).get(self.w, {}).get(quantity)

    def realized(self, config, key, scale=1.0, unit=""):
        e = self.ens(config, key)
        u = f" {unit}" if unit else ""
        return f"{pm(e['mean'], e['error'], scale)}{u} (`{config}`, n = {e['n']})" if e else f"- (`{config}` not run)"

    def one_run(self, run, key, scale=1.0, unit=""):
        s = self.single(run, key)
        u = f" {unit}" if unit else ""
        return f"{pm(s['mean'], s['error'], scale)}{u} (`{run}`, one run)" if s else f"- (`{run}` not run)"

    def dp(self, config):
        """Δp's mean, std and dominant frequency of an ensemble."""
        e = self.r["ensembles"].get(config, {}).get(self.w)
        if not e:
            return f"- (`{config}` not run)"
        return (f"{pm(e['dp20']['mean']['mean'], e['dp20']['mean']['error'])} Pa, std "
                f"{pm(e['dp20']['std']['mean'], e['dp20']['std']['error'])} Pa, "
                f"{pm(e['dp20_frequency']['mean'], e['dp20_frequency']['error'])} Hz (`{config}`, n = {e['dp20']['mean']['n']})")

    def dp_single(self, run):
        s = self.single(run, "dp20")
        if not s:
            return f"- (`{run}` not run)"
        return (f"{pm(s['mean'], s['error'])} Pa, std {s['std']:.3g} Pa, "
                f"{self.runs[run][self.w]['dp20_frequency']:.2g} Hz (`{run}`, one run)")

    def peer(self, bed, key, part="mean"):
        """The kinetic-theory TFM peer's ensemble against TF-DEM's (replicates' "tfm"): {tfm,
        tfdem, difference}, or None before its realizations are run."""
        return ((self.r.get("tfm") or {}).get(f"{bed}_tfm_peer - {bed}_m1", {}).get(self.w, {}).get(f"{key} {part}"))

    def peer_text(self, bed, key, scale=1.0, unit=""):
        """The peer's ensemble mean ± error, its TF-DEM difference in the combined error."""
        v = self.peer(bed, key)
        if not v:
            return f"- (`{bed}_tfm_peer` realizations not run)", "-"
        u = f" {unit}" if unit else ""
        value = f"{pm(v['tfm']['mean'], v['tfm']['error'], scale)}{u} (`{bed}_tfm_peer`, n = {v['tfm']['n']})"
        return value, "peer − TF-DEM " + self.signed_diff(v["difference"], scale, unit)

    def peer_dp(self, bed):
        """(ours, difference) of the peer's Δp at 20 cm: mean and fluctuation std, each against
        TF-DEM's in the combined error."""
        mean, std = self.peer(bed, "dp20"), self.peer(bed, "dp20", "std")
        if not (mean and std):
            return f"- (`{bed}_tfm_peer` realizations not run)", "-"
        return (f"{pm(mean['tfm']['mean'], mean['tfm']['error'])} Pa, std {pm(std['tfm']['mean'], std['tfm']['error'])} Pa "
                f"(`{bed}_tfm_peer`, n = {mean['tfm']['n']})",
                f"peer − TF-DEM {self.signed_diff(mean['difference'], unit='Pa')}; std "
                f"{self.signed_diff(std['difference'], unit='Pa')}")

    def signed_diff(self, d, scale=1.0, unit=""):
        if not d:
            return "-"
        return f"{signed(d['mean'], d['error'], scale)}{' ' + unit if unit else ''} ({d['mean'] / d['error']:+.1f} SE)"

    def against(self, value, reference, scale=1.0, unit=""):
        """value - reference and its size in standard errors: a reference number (the paper's) is
        exact; a reference with its own error (an ensemble's {mean, error}) adds it in
        quadrature."""
        if not value:
            return "-"
        reference_error = reference["error"] if isinstance(reference, dict) else 0.0
        reference_mean = reference["mean"] if isinstance(reference, dict) else reference
        d = {"mean": value["mean"] - reference_mean, "error": math.hypot(value["error"], reference_error)}
        return self.signed_diff(d, scale, unit)

    def map_comparison(self, pair):
        c = self.r["maps"]["comparisons"].get(pair, {}).get(self.w)
        if not c:
            return f"- ({pair} not run)"
        return (f"L1 {c['cross_mean']:.4f} against a floor of {c['within_mean']:.4f} "
                f"(p = {c['permutation']['p']:.3f})")

    def force_ratio(self, config):
        e = self.r["ensembles"].get(config, {}).get(self.w)
        if not e:
            return f"- (`{config}` not run)"
        f = e["force_ratio"]

        def part(key):
            return pm(f[key]["mean"], f[key]["error"]) if f.get(key) else "-"
        return (f"share of bed cells in 2-10 {part('share_2_to_10')}, median {part('median')}, largest "
                f"{part('largest')}, largest in the bottom corners {part('largest_in_corners')} (`{config}`, "
                f"n = {f['median']['n'] if f.get('median') else '-'})")

    # Fig. 8 ---------------------------------------------------------------------------------
    def fig8_numbers(self):
        """Per run or ensemble: the jet axis' solids fraction at AXIS_HEIGHTS, the bottom
        corners' mean and the mirror L1 of the time-averaged map (an ensemble: each
        realization's, as mean ± error)."""
        start, end = self.report.windows[0]
        out = {}
        sources = ([("jet_m1", self.groups.get("jet_m1", []))] + [(n, [n]) for n in ("jet_tfm", "jet_tfm_phase_pressure")]
                   + [("jet_tfm_peer", self.tfm_groups.get("jet_tfm_peer", []))])
        for name, members in sources:
            members = [m for m in members if m in self.report.records]
            if not members:
                continue
            values = []
            for m in members:
                record = self.report.records[m]
                solids = record.window_map("solids", start, end)
                values.append(axis_profile(solids, record) + [corner_mean(solids, record, *self.corner),
                                                              mirror_l1(solids, record)])
            columns = list(zip(*values))
            if len(members) > 1:
                stats = [ensemble(c) for c in columns]
            else:
                stats = [{"mean": c[0], "error": float("nan"), "n": 1} for c in columns]
            out[name] = {"axis": stats[:len(AXIS_HEIGHTS)], "corners": stats[-2], "mirror_l1": stats[-1],
                         "n": len(members)}
        return out

    def fig8_text(self, numbers):
        heights = ", ".join(f"{100 * h:g}" for h in AXIS_HEIGHTS)
        parts = []
        for name, v in numbers.items():
            axis = ", ".join(pm(a["mean"], a["error"]) if a["error"] == a["error"] else f"{a['mean']:.2f}"
                             for a in v["axis"])
            c, m = v["corners"], v["mirror_l1"]
            corners = pm(c["mean"], c["error"]) if c["error"] == c["error"] else f"{c['mean']:.2f}"
            mirror = pm(m["mean"], m["error"]) if m["error"] == m["error"] else f"{m['mean']:.2g}"
            count = f" (n = {v['n']})" if v["n"] > 1 else ""
            parts.append(f"`{name}`{count}: axis {axis}; corners {corners}; mirror L1 {mirror}")
        width, height = self.corner
        return (f"time-averaged solids fraction on the jet axis at {heights} cm; bottom corners (x < {100 * width:g} cm "
                f"from a wall, y < {100 * height:g} cm); L1 of the map against its mirror image. " + "; ".join(parts))

    # The table ------------------------------------------------------------------------------
    def rows(self):
        P = self.paper
        jet_m1_dp = self.ens("jet_m1", "dp20")
        jet_std = self.ens("jet_m1", "dp20", "std")
        rows = [
            ("jet: Δp at 20 cm, method 1 (Fig. 3)", "figure only: fluctuation in good agreement with experiments",
             f"{self.dp('jet_m1')}; lattice packing {self.dp_single('jet_m1')}", "-"),
            ("jet: Δp at 20 cm, method 2", "-", self.dp("jet_m2"),
             "method 2 − method 1: " + self.signed_diff(self.diff("method 2 - method 1", "jet_m2 - jet_m1", "dp20 mean"),
                                                         unit="Pa")),
            ("jet: Δp at 20 cm, TFM peer (kinetic theory, MFIX's slip production and −∇P_s, effective e)",
             "similar mean, smaller fluctuating amplitude", *self.peer_dp("jet")),
            ("jet: Δp at 20 cm, stock TFMs", "similar mean, smaller fluctuating amplitude",
             f"kinetic theory {self.dp_single('jet_tfm')}; phase pressure {self.dp_single('jet_tfm_phase_pressure')}",
             "; ".join(f"{label} − TF-DEM {self.against(self.single(run, 'dp20'), jet_m1_dp, unit='Pa')}, "
                       f"std {self.single(run, 'dp20')['std'] / jet_std['mean']:.2g}× TF-DEM's"
                       for label, run in (("kinetic theory", "jet_tfm"), ("phase pressure", "jet_tfm_phase_pressure"))
                       if self.single(run, "dp20") and jet_m1_dp)),
            ("jet: bulk coordination number (Fig. 5)", P["bulk_coordination_jet"],
             f"method 1 {self.realized('jet_m1', 'bulk_coordination')}; method 2 "
             f"{self.realized('jet_m2', 'bulk_coordination')}; fine grid {self.realized('jet_fine_m1', 'bulk_coordination')}; "
             f"lattice packing {self.one_run('jet_m1', 'bulk_coordination')}",
             "method 1 − paper " + self.against(self.ens("jet_m1", "bulk_coordination"), P["bulk_coordination_jet_value"])),
            ("jet: multicontact ratio (Fig. 11)", P["multicontact_jet"],
             f"method 1 {self.realized('jet_m1', 'multicontact')}; method 2 {self.realized('jet_m2', 'multicontact')}", "-"),
            ("jet: contact / drag per cell (Fig. 7, time-averaged maps, cells with solids fraction > 0.1)",
             P["force_ratio_jet"], self.force_ratio("jet_m1"), "-"),
            ("jet: grid dependence (Fig. 4; coarse 1 × 2 cm, fine 1 × 1 cm)",
             "fine grid: slightly higher bed expansion, a more asymmetric solids distribution",
             f"mean particle height coarse {self.realized('jet_m1', 'mean_height', 100, 'cm')}, fine "
             f"{self.realized('jet_fine_m1', 'mean_height', 100, 'cm')}; solids-fraction maps (bottom 45 cm) coarse vs "
             f"fine: centroid {self.map_comparison('jet_m1 vs jet_fine_m1')}; diffusion b = 6 d_p "
             f"{self.map_comparison('jet_diff24 vs jet_fine_diff24')}",
             "fine − coarse height " + self.signed_diff(self.diff("fine - coarse", "jet_fine_m1 - jet_m1", "mean_height mean"),
                                                        100, "cm")),
            ("jet: TF-DEM vs TFM solids fraction (Fig. 8)", "TFM more homogeneous and symmetric, similar jet penetration",
             self.fig8_text(self.fig8_numbers()), "-"),
            ("uniform: mean particle height, method 1 (Fig. 9)",
             f"{P['mean_height_m1']} cm (experiment {P['mean_height_experiment']} cm)",
             self.realized("uniform_m1", "mean_height", 100, "cm"),
             "− paper " + self.against(self.ens("uniform_m1", "mean_height"), P["mean_height_m1"] / 100, 100, "cm")),
            ("uniform: mean particle height, method 2", f"{P['mean_height_m2']} cm",
             self.realized("uniform_m2", "mean_height", 100, "cm"),
             "− paper " + self.against(self.ens("uniform_m2", "mean_height"), P["mean_height_m2"] / 100, 100, "cm")),
            ("uniform: method 2 − method 1 (Fig. 13)",
             f"+{P['mean_height_m2'] - P['mean_height_m1']:.1f} cm (higher expansion with method 2)",
             "mean height " + self.signed_diff(self.diff("method 2 - method 1", "uniform_m2 - uniform_m1",
                                                         "mean_height mean"), 100, "cm")
             + "; solids-fraction maps " + self.map_comparison("uniform_m1 vs uniform_m2"),
             self.paper_rejection()),
            ("uniform: mean particle height, TFM peer (kinetic theory, MFIX's slip production and −∇P_s, effective e)",
             f"{P['mean_height_tfm']} cm (TF-DEM {P['mean_height_m1']} cm: +{P['mean_height_tfm'] - P['mean_height_m1']:.2f})",
             *self.peer_text("uniform", "mean_height", 100, "cm")),
            ("uniform: Δp at 20 cm, TFM peer", "-", *self.peer_dp("uniform")),
            ("uniform: mean particle height, stock TFMs", f"{P['mean_height_tfm']} cm",
             f"kinetic theory {self.one_run('uniform_tfm', 'mean_height', 100, 'cm')}; phase pressure "
             f"{self.one_run('uniform_tfm_phase_pressure', 'mean_height', 100, 'cm')}",
             "; ".join(f"{label} − TF-DEM {self.against(self.single(run, 'mean_height'), self.ens('uniform_m1', 'mean_height'), 100, 'cm')}"
                       for label, run in (("kinetic theory", "uniform_tfm"), ("phase pressure", "uniform_tfm_phase_pressure"))
                       if self.single(run, "mean_height") and self.ens("uniform_m1", "mean_height"))),
            ("uniform: Δp at 20 cm", "-",
             f"TF-DEM {self.dp('uniform_m1')}; kinetic theory {self.dp_single('uniform_tfm')}; phase pressure "
             f"{self.dp_single('uniform_tfm_phase_pressure')}", "-"),
            ("uniform: bulk coordination number (Fig. 5)", P["bulk_coordination_uniform"],
             f"method 1 {self.realized('uniform_m1', 'bulk_coordination')}; method 2 "
             f"{self.realized('uniform_m2', 'bulk_coordination')}",
             "method 1 − paper " + self.against(self.ens("uniform_m1", "bulk_coordination"),
                                               P["bulk_coordination_uniform_value"])),
            ("uniform: multicontact ratio (Fig. 11)", P["multicontact_uniform"],
             f"method 1 {self.realized('uniform_m1', 'multicontact')}; method 2 {self.realized('uniform_m2', 'multicontact')}",
             "method 1 − paper " + self.against(self.ens("uniform_m1", "multicontact"), P["multicontact_uniform_value"])),
            ("uniform: contact / drag per cell (Fig. 12)", P["force_ratio_uniform"], self.force_ratio("uniform_m1"), "-"),
        ]
        rows += self.theta_rows() + self.cost_rows()
        return rows

    def paper_rejection(self):
        d = self.diff("method 2 - method 1", "uniform_m2 - uniform_m1", "mean_height mean")
        if not d or "paper_in_errors" not in d:
            return "-"
        verdict = "rejected" if abs(d["paper_in_errors"]) >= 2 else "not rejected"
        return f"the paper's value is {abs(d['paper_in_errors']):.1f} SE away: {verdict}"

    def theta_rows(self):
        theta = self.report.numbers.get("granular_temperature") or {}
        if not theta:
            return []
        text = "; ".join(f"{bed}: TF-DEM {v['runs'][bed + '_m1']['bed_mean']:.2g}, TFM (kinetic theory) "
                         f"{v['runs'][bed + '_tfm']['bed_mean']:.2g} m²/s²" for bed, v in theta.items())
        ratio = "; ".join(f"{bed} TFM {v['tfm_over_tfdem']:.3g}× TF-DEM" for bed, v in theta.items())
        return [("granular temperature (eq. 6; solids-weighted over the bed, one run each)", "not in the paper", text,
                 ratio)]

    def cost_rows(self):
        P, runs = self.paper, self.runs
        end = self.report.end_time
        tfdem = self.r["ensembles"].get("jet_m1", {}).get("cpu_seconds")
        if not tfdem:
            return []
        scale = 20.0 / end
        parts = [f"TF-DEM {pm(scale * tfdem['mean'], scale * tfdem['error'])} s (`jet_m1`, n = {tfdem['n']})"]
        ratios = [f"TF-DEM {P['cost_tfdem_jet'] / (scale * tfdem['mean']):.2g}× less than the paper's"]
        for label, run in (("TFM kinetic theory", "jet_tfm"), ("TFM phase pressure", "jet_tfm_phase_pressure")):
            if run in runs:
                cpu = scale * runs[run]["cpu_seconds"]
                parts.append(f"{label} {cpu:.0f} s")
                ratios.append(f"{label} {cpu / (scale * tfdem['mean']):.2g}× TF-DEM")
        rows = [("cost, jet bed, 20 s on one core (processor time)",
                 f"TF-DEM {P['cost_tfdem_jet']:.0f} s, TFM {P['cost_tfm_jet']:.0f} s (2.0 GHz Opteron 270)",
                 "; ".join(parts), "; ".join(ratios))]
        timed = [(n, v) for n, v in runs.items() if v.get("timing")]
        if timed:
            shares = [statistics_share(v["timing"]) for _, v in timed]
            rows.append(("statistics' cost (N_c, contact forces, maps every 0.01 s; the solver's `TFDEM timing`)",
                         "< 5 % asked", f"{min(shares):.2g}-{max(shares):.2g} % of the solver's timed parts over "
                         f"{len(timed)} runs that recorded it ({', '.join(f'`{n}`' for n, _ in timed)})", "-"))
        return rows

    def markdown(self):
        lines = [f"Over {self.w} s (the paper's window). Ensembles: mean ± the standard error across "
                 "realizations (n poured packings); one run: ± its batch-means error; SE: the difference in its "
                 "standard errors.", "", "| quantity | paper | ours | difference |", "|---|---|---|---|"]
        lines += [f"| {a} | {b} | {c} | {d} |" for a, b, c, d in self.rows()]
        check = self.r.get("batch_error_check", {})
        notes = []
        for bed, windows in check.items():
            ratio = windows[self.w]["dp20"]["ratio"]
            notes.append(f"{bed} {ratio:.2f}")
        if notes:
            lines += ["", "One run's batch-means error against the realizations' spread (Δp at 20 cm, pooled over a "
                          f"bed's configurations, {self.w} s; 1 if it is right): " + ", ".join(notes)
                      + ". A single run's ± is to be read with that factor."]
        return lines


def statistics_share(timing):
    """The statistics' share (%) of a run's `TFDEM timing` (tfdem.outputs.solver_timing): its
    seconds over the sum of the timed parts, all on the solver's one clock (not over the
    processor time, which an oversubscribed rank spends partly waiting)."""
    return 100.0 * timing["statistics"] / sum(timing[part] for part in TIMING_PARTS)


def pair_lines(replicates_result, window):
    """The pairs table: every comparison of two configurations the replicates make (method 2 -
    method 1, fine - coarse, the separation test's parts, the gas step's, N ranks - 1 rank, the
    interpolated gas velocity - its cell's),
    over `window`: the solids-fraction maps' L1 across the two against the realizations' floor
    (and the permutation p), and the differences of the ensemble means with their size in
    standard errors."""
    r = replicates_result
    comparisons = r["maps"]["comparisons"]
    quantities = (("mean_height mean", "mean height (cm)", 100.0), ("dp20 mean", "Δp at 20 cm (Pa)", 1.0),
                  ("dp20 std", "Δp std (Pa)", 1.0), ("bulk_coordination mean", "N_c", 1.0))
    counts = {config: len(names) for config, names in r.get("configurations", {}).items()}

    def named(config):
        n = counts.get(config, 4)
        return f"`{config}`" + (f" (n = {n})" if n != 4 else "")
    lines = [f"Ensemble means over {window} s (four realizations a configuration, else its n): b − a ± the two standard errors "
             "in quadrature, in brackets in standard errors; maps: the mean L1 of the time-averaged solids fraction "
             "(bottom 45 cm, on the coarser cells) over every pair of realizations across the two, against the mean "
             "within one configuration (the floor), with the exact permutation test's p (0.029 is the smallest 4 + 4 "
             "maps can give).", "",
             "| comparison | b − a | maps: L1 (floor; ratio; p) | " + " | ".join(q[1] for q in quantities) + " |",
             "|---|---|---|" + "---|" * len(quantities)]
    for kind, pairs in r["differences"].items():
        for pair, values in pairs.items():
            b, a = pair.split(" - ")
            c = (comparisons.get(f"{a} vs {b}") or comparisons.get(f"{b} vs {a}") or {}).get(window)
            maps = (f"{c['cross_mean']:.4f} ({c['within_mean']:.4f}; {c['cross_over_within']:.2f}; "
                    f"{c['permutation']['p']:.3f})") if c else "-"
            cells = [f"{signed(values[window][q]['mean'], values[window][q]['error'], scale)} "
                     f"({values[window][q]['in_errors']:+.1f})" for q, _, scale in quantities]
            lines.append(f"| {kind} | {named(b)} − {named(a)} | {maps} | " + " | ".join(cells) + " |")
    return lines


def markers(name):
    """The two lines that enclose a generated block `name` in a README."""
    return (f"<!-- {name}: written by study.py report; do not edit by hand -->", f"<!-- end of {name} -->")


def replace_block(text, name, block):
    """text with its block `name` (between markers(name), kept) holding the lines `block`;
    ValueError when the markers are missing or out of order."""
    begin_mark, end_mark = markers(name)
    begin, end = text.find(begin_mark), text.find(end_mark)
    if begin < 0 or end < begin:
        raise ValueError(f"README: the markers of {name} are missing ({begin_mark!r} ... {end_mark!r})")
    return text[:begin] + "\n".join([begin_mark, ""] + block + ["", end_mark]) + text[end + len(end_mark):]
