"""The study's realizations (study.yaml `realizations`: <run>_r1 ... _rn, each from its own
random poured packing): what the single-run errors are worth.

For every configuration with two or more realizations, over each averaging window:
- every statistic as the ensemble mean with its standard error across realizations
  (tfdem.stats.ensemble), beside the single run's batch-means error (the mean of the
  realizations' errors) and the realizations' spread, the error one run really has;
- the batch-means error put to the test: the spread over the batch error, pooled over a
  bed's configurations, against its 90 % range were the batch error right (chi-square);
- each metric's integrated autocorrelation time and blocking curve over the longest window;
- L1 noise floors of the time-averaged solids fraction from pairs of realizations over the
  same window, and two configurations' maps compared against them (exact permutation test);
- method 2 - method 1 and fine - coarse as differences of ensemble means, and the lattice
  packing's bulk coordination number against the poured realizations';
- and the plain statements these numbers support, written by rules stated below.
"""
import math
import os

import matplotlib.pyplot as plt
import numpy

from tfdem.bed import cross_l1, l1_noise_floor, l1_permutation_test, mirror_mean, to_grid
from tfdem.stats import (blocking_curve, difference, ensemble, equivalence_test, grid_convergence,
                         integrated_autocorrelation_time, spread_ratio_range, window)

# (key, label, unit, scale of the stored SI value to the unit)
METRICS = (("dp20", "Δp at 20 cm", "Pa", 1.0), ("mean_height", "mean particle height", "cm", 100.0),
           ("bulk_coordination", "bulk coordination number", "", 1.0),
           ("multicontact", "multicontact ratio", "", 1.0))
BATCH_LENGTHS = (0.01, 0.02, 0.05, 0.1, 0.2, 0.5, 1.0, 1.5, 2.5, 3.75)  # s, of a 20 s run (scaled with it)
PLATEAU_FROM = 1.5  # s: the blocking curve's plateau is its mean from this batch length on
METHOD_PAIRS = (("jet_m1", "jet_m2"), ("jet_fine_m1", "jet_fine_m2"), ("uniform_m1", "uniform_m2"))
DIFFERENCE_QUANTITIES = (("dp20", "mean"), ("dp20", "std"), ("mean_height", "mean"), ("bulk_coordination", "mean"),
                         ("multicontact", "mean"))
# The TFM runs with realizations (perturbed starts) against the TF-DEM's: (TF-DEM, TFM) per bed,
# the quantities compared, and seed 000's statement on each (TFM - TF-DEM, the paper's numbers
# where it gives them)
TFM_PAIRS = (("jet_m1", "jet_tfm_peer"), ("uniform_m1", "uniform_tfm_peer"))
TFM_QUANTITIES = (("dp20", "mean"), ("dp20", "std"), ("mean_height", "mean"))
RESOLVED = 2.0  # a difference is resolved when it is at least this many standard errors from zero
MAP_DEPTH = 0.45  # m: the maps are compared over the cells below this height (the bed)
REFINEMENTS = ("refine_x", "refine_y")
# The grid study's quantities and the margins within which two grids give the same value (two
# one-sided tests at 5 %, tfdem.stats.equivalence_test): Delta p 2 % of its value, the mean
# particle height half a particle diameter (0.2 cm, the size of the method difference seed 000
# draws in Fig. 13), the bulk coordination number 0.05 (4 % of the jet bed's 1.2-1.3)
GRID_QUANTITIES = ("dp20", "mean_height", "bulk_coordination")
EQUIVALENCE_MARGIN = {"dp20": ("of its value", 0.02), "mean_height": ("m", 0.002), "bulk_coordination": ("", 0.05)}
MARGIN_TEXT = "Δp ±2 % of its value, mean particle height ±0.2 cm, bulk coordination number ±0.05"
ALPHA = 0.05


class ReplicatesError(ValueError):
    """Realizations or configurations that cannot be combined or compared, named."""


def _refinement(spec):
    return spec.get("refine_x", 1), spec.get("refine_y", 1)


def _cells(spec):
    rx, ry = _refinement(spec)
    return rx * ry


def _rest(spec, keys):
    """The spec without `keys` and without dp_from: where Delta p is measured is not part of a
    configuration (same_dp checks the records' levels where Delta p is compared)."""
    return {k: v for k, v in spec.items() if k not in keys and k != "dp_from"}


def grid_pairs(runs, configs):
    """(coarser, finer) pairs of the configurations that differ in their cells alone (study.yaml's
    refine_x, refine_y, and the gas step, which follows the cells unless a run sets its own),
    e.g. jet_m1 and jet_fine_m1."""
    keys = REFINEMENTS + ("gas_step",)
    return tuple(sorted((a, b) for a in configs for b in configs
                        if _rest(runs[a], keys) == _rest(runs[b], keys) and _cells(runs[a]) < _cells(runs[b])))


def step_pairs(runs, configs):
    """(template's step, own step) pairs of configurations on the same cells that differ in
    study.yaml's gas_step alone, e.g. jet_diff24 and jet_diff24_step02."""
    return tuple(sorted((a, b) for a in configs for b in configs if "gas_step" not in runs[a]
                        and "gas_step" in runs[b] and _rest(runs[a], ("gas_step",)) == _rest(runs[b], ("gas_step",))))


def ranks_pairs(runs, configs):
    """(one rank, N ranks) pairs of configurations that differ in study.yaml's ranks and gas
    layout alone, e.g. uniform_m1 and uniform_m1_ranks4: a chaotic bed on more ranks is another
    realization, so its statistics are to agree within the replicate noise, not bit for bit."""
    keys = ("ranks", "gas")
    return tuple(sorted((a, b) for a in configs for b in configs if runs[a].get("ranks", 1) == 1
                        and runs[b].get("ranks", 1) > 1 and _rest(runs[a], keys) == _rest(runs[b], keys)))


GAS_VELOCITY_KEY = "coupling.gas_velocity_at_particle"


def interpolation_pairs(runs, configs):
    """(its cell's, interpolated) pairs of configurations that differ in the gas velocity a
    particle sees alone (coupling.yaml's gas_velocity_at_particle), e.g. uniform_m2 and
    uniform_m2_interpolated."""
    def rest(spec):
        coupling = {k: v for k, v in spec.get("coupling", {}).items() if k != GAS_VELOCITY_KEY}
        return dict(_rest(spec, ("coupling",)), coupling=coupling)
    return tuple(sorted((a, b) for a in configs for b in configs
                        if runs[a].get("coupling", {}).get(GAS_VELOCITY_KEY, "cell") == "cell"
                        and runs[b].get("coupling", {}).get(GAS_VELOCITY_KEY) == "interpolated"
                        and rest(runs[a]) == rest(runs[b])))


BLOCK_KEY = "coupling.void_fraction.particle_field_block"


def _without_block(spec):
    coupling = _rest(spec.get("coupling", {}), (BLOCK_KEY,))
    return {**_rest(spec, REFINEMENTS + ("coupling",)), **({"coupling": coupling} if coupling else {})}


def _block_matches(runs, configs, config):
    """(coarse, fine) of a configuration whose particle field is on blocks of its gas cells:
    the same run on the blocks' cells and on its own cells, each None when absent."""
    block = runs[config]["coupling"][BLOCK_KEY]
    rest, (rx, ry) = _without_block(runs[config]), _refinement(runs[config])
    match = {_refinement(runs[c]): c for c in configs if c != config and _without_block(runs[c]) == rest
             and BLOCK_KEY not in runs[c].get("coupling", {})}
    return match.get((rx // block[0], ry // block[1])), match.get((rx, ry))


def separation_triples(runs, configs):
    """(coarse, separated, fine) for each configuration whose particle field is estimated on
    blocks of its gas cells (study.yaml's coupling.void_fraction.particle_field_block): fine is
    the same run without the block, coarse the one whose cells are the blocks (refine_x,
    refine_y divided by the block's k_x, k_y), e.g. (jet_m2, jet_fine_m2_coarse_field,
    jet_fine_m2). Only those whose three configurations are all present."""
    out = []
    for config in configs:
        if not runs[config].get("coupling", {}).get(BLOCK_KEY):
            continue
        coarse, fine = _block_matches(runs, configs, config)
        if coarse and fine:
            out.append((coarse, config, fine))
    return tuple(sorted(out))


def linked_families(pairs):
    """The pairs joined into families: each pair goes into the first family that holds either
    of its members, else starts one (members in the order met)."""
    families = []
    for a, b in pairs:
        family = next((f for f in families if a in f or b in f), None)
        if family is None:
            families.append([a, b])
        else:
            family += [c for c in (a, b) if c not in family]
    return families


def grid_chains(runs, configs):
    """The grid studies, {name: configurations, coarsest gas first}: each family of
    configurations that differ in their cells alone (grid_pairs), named by its coarsest; and
    each coarse configuration's two-grid series (after Deb & Tafti 2013), it and the
    configurations whose particle field is on its cells while the gas is refined, named
    '<coarsest> two-grid'. Only chains of two or more."""
    own_step = [c for c in configs if "gas_step" in runs[c]]  # the gas step's test, not a grid's
    chains = {f[0]: f for f in linked_families(grid_pairs(runs, [c for c in configs if c not in own_step]))}
    for config in configs:
        if runs[config].get("coupling", {}).get(BLOCK_KEY):
            coarse, _ = _block_matches(runs, configs, config)
            if coarse:
                chains.setdefault(f"{coarse} two-grid", [coarse]).append(config)
    return {name: sorted(chain, key=lambda c: _cells(runs[c])) for name, chain in sorted(chains.items())}


def representative_cell(spec):
    """The gas cells' representative size relative to the template's, 1 / sqrt(refine_x refine_y)
    (Celik et al. 2008's h for a 2-D grid)."""
    return 1.0 / math.sqrt(_cells(spec))


def pm(value, error, scale=1.0):
    """'value ± error', the error to two significant digits and the value to the same place."""
    value, error = value * scale, error * scale
    if not (math.isfinite(error) and error > 0):
        return f"{value:.4g}"
    places = max(0, 1 - int(math.floor(math.log10(error))))
    return f"{value:.{places}f} ± {error:.{places}f}"


def signed(value, error, scale=1.0):
    text = pm(value, error, scale)
    return text if text.startswith("-") else "+" + text


class Replicates:
    """The ensemble analysis of a Report's records (report.Report: records, numbers["runs"],
    windows, batch, study)."""

    def __init__(self, report, paper):
        self.report, self.paper = report, paper
        self.windows = [f"{a:g}-{b:g}" for a, b in report.windows]
        self.long = report.windows[-1]
        spec = report.study.get("realizations") or {}
        seeds = spec.get("seeds") or []
        self.groups, self.tfm_groups = {}, {}
        for config in spec.get("runs") or []:
            names = [f"{config}_r{k}" for k in range(1, len(seeds) + 1) if f"{config}_r{k}" in report.records]
            if len(names) >= 2:
                tfm = report.study["runs"][config].get("tfm", False)
                (self.tfm_groups if tfm else self.groups)[config] = names
        self.seeds = seeds
        self.scale = report.end_time / report.study["end_time"]
        self.out = None
        self.dp_from = {config: self._dp_from(config, names)
                        for config, names in list(self.groups.items()) + list(self.tfm_groups.items())}

    def _dp_from(self, config, names):
        """Where the configuration's realizations measured Delta p from (record.DP_HEADERS):
        ReplicatesError when they differ (an ensemble of two measures is not one quantity)."""
        found = {n: self.report.records[n].dp_from for n in names}
        if len(set(found.values())) > 1:
            raise ReplicatesError(f"{config}: its realizations measured Delta p from different levels "
                             f"({', '.join(f'{n}: {v}' for n, v in found.items())}); record them again from "
                             "their runs, or run again those measured the old way")
        return next(iter(found.values()))

    def same_dp(self, *configs):
        """ReplicatesError unless the configurations measured Delta p from the same level: their
        differences would carry the gap between the levels (100 Pa or more in these beds)."""
        found = {c: self.dp_from[c] for c in configs if c in self.dp_from}
        if len(set(found.values())) > 1:
            raise ReplicatesError("Delta p compared between runs measured from different levels ("
                             + ", ".join(f"{c}: {v}" for c, v in found.items()) + "): set dp_from in study.yaml "
                             "to the other's, or run one of them again")

    # Ensembles ------------------------------------------------------------------------------
    def run_value(self, name, key, *path):
        value = self.report.numbers["runs"][name][key]
        for p in path:
            value = value[p]
        return value

    def ensembles(self, config):
        """Per window: each metric's mean (ensemble, spread, the single run's batch error, and
        spread / batch error) and signal std, the dominant frequency of Δp, the force ratios."""
        names = self.groups[config]
        out = {}
        for w in self.windows:
            entry = {}
            for key, *_ in METRICS:
                stats = [self.run_value(n, w, key) for n in names]
                mean = ensemble([s["mean"] for s in stats])
                batch_error = float(numpy.mean([s["error"] for s in stats]))
                entry[key] = {"mean": mean, "std": ensemble([s["std"] for s in stats]), "batch_error": batch_error,
                              "spread_over_batch_error": mean["spread"] / batch_error}
            entry["dp20_frequency"] = ensemble([self.run_value(n, w, "dp20_frequency") for n in names])
            ratios = [self.run_value(n, w, "force_ratio") for n in names]
            entry["force_ratio"] = {k: _finite_ensemble([r[k] for r in ratios]) for k in ratios[0]}
            out[w] = entry
        out["cpu_seconds"] = ensemble([self.report.numbers["runs"][n]["cpu_seconds"] for n in names])
        return out

    def batch_error_check(self, ensembles):
        """Per bed, window and metric: the realizations' spread over the single-run batch
        error, pooled over the bed's configurations as sqrt(sum (n_c - 1) r_c^2 / dof), dof =
        sum (n_c - 1), against the 90 % range it would have were the batch error the true
        standard error (spread_ratio_range; the batch errors' own scatter left out, which makes
        the range a little narrow)."""
        out = {}
        for bed in sorted({self.bed(c) for c in self.groups}):
            configs = [c for c in self.groups if self.bed(c) == bed]
            for w in self.windows:
                for key, *_ in METRICS:
                    dof = sum(len(self.groups[c]) - 1 for c in configs)
                    pooled = math.sqrt(sum((len(self.groups[c]) - 1) * ensembles[c][w][key]["spread_over_batch_error"] ** 2
                                           for c in configs) / dof)
                    low, high = spread_ratio_range(dof)
                    verdict = ("batch error too small" if pooled > high else "batch error too large" if pooled < low
                               else "consistent")
                    out.setdefault(bed, {}).setdefault(w, {})[key] = {"ratio": pooled, "dof": dof, "range90": [low, high],
                                                                      "verdict": verdict, "configurations": configs}
        return out

    def bed(self, config):
        return self.report.study["runs"][config]["bed"]

    # Correlation ----------------------------------------------------------------------------
    def series(self, name, key):
        record = self.report.records[name]
        if key == "dp20":
            return record.p_t, record.dp
        if key == "mean_height":
            return record.mean_height()
        return record.particles["t"], record.particles[key]

    def correlation(self, name, key):
        """One realization's metric over the longest window: its integrated autocorrelation
        time (s), the window rule's M, the error sqrt(var tau / N) that tau implies, and its
        blocking curve at BATCH_LENGTHS."""
        t, y = self.series(name, key)
        values = numpy.array(window(list(t), list(y), *self.long))
        dt = float(numpy.median(numpy.diff(numpy.asarray(t))))
        try:
            tau, m = integrated_autocorrelation_time(values)
        except ValueError as e:
            raise ReplicatesError(f"{name} {key} over {self.long[0]:g}-{self.long[1]:g} s: {e}") from None
        sizes = sorted({max(1, int(round(length * self.scale / dt))) for length in BATCH_LENGTHS})
        curve = blocking_curve(values, [k for k in sizes if values.size // k >= 2])
        return {"tau_s": tau * dt, "tau_samples": tau, "window_samples": m, "dt": dt, "samples": int(values.size),
                "error_from_tau": float(values.std() * math.sqrt(tau / values.size)),
                "blocking": [dict(c, length_s=c["size"] * dt) for c in curve]}

    def correlations(self, config):
        """Per metric: the realizations' correlation numbers, tau_int's ensemble, the blocking
        curve's root mean square over the realizations, its value at the study's batch length
        and its plateau (mean from PLATEAU_FROM on)."""
        out = {}
        for key, *_ in METRICS:
            runs = {n: self.correlation(n, key) for n in self.groups[config]}
            first = next(iter(runs.values()))["blocking"]
            rms = [float(math.sqrt(numpy.mean([r["blocking"][i]["error"] ** 2 for r in runs.values()])))
                   for i in range(len(first))]
            lengths = [c["length_s"] for c in first]
            at_batch = rms[int(numpy.argmin([abs(length - self.report.batch) for length in lengths]))]
            plateau = [e for e, length in zip(rms, lengths) if length >= PLATEAU_FROM * self.scale - 1e-9]
            plateau = float(numpy.mean(plateau)) if plateau else float("nan")
            out[key] = {"runs": runs, "tau_s": ensemble([r["tau_s"] for r in runs.values()]),
                        "blocking_lengths_s": lengths, "blocking_rms_error": rms, "error_at_batch": at_batch,
                        "plateau": plateau, "at_batch_over_plateau": at_batch / plateau}
        return out

    def grid_pairs(self):
        return grid_pairs(self.report.study["runs"], list(self.groups))

    def separation_triples(self):
        return separation_triples(self.report.study["runs"], list(self.groups))

    def step_pairs(self):
        return step_pairs(self.report.study["runs"], list(self.groups))

    def ranks_pairs(self):
        return ranks_pairs(self.report.study["runs"], list(self.groups))

    def interpolation_pairs(self):
        return interpolation_pairs(self.report.study["runs"], list(self.groups))

    def separation_pairs(self):
        """The map comparisons of the separation test: the separated run against fine and coarse."""
        return tuple(p for c, s, f in self.separation_triples() for p in ((s, f), (c, s)))

    # Maps -----------------------------------------------------------------------------------
    def maps(self, config, w, symmetric):
        """The realizations' time-averaged solids fraction over window w on the coarse cells
        (a refined run's averaged onto them), and the number of rows below MAP_DEPTH."""
        spec = self.report.study["runs"][config]
        out = []
        for name in self.groups[config]:
            record = self.report.records[name]
            shape = (record.shape[0] // spec.get("refine_y", 1), record.shape[1] // spec.get("refine_x", 1))
            field = to_grid(record.window_map("solids", *map(float, w.split("-"))), shape)
            out.append(mirror_mean(field) if symmetric else field)
        rows = int((to_grid(record.y, shape)[:, 0] < MAP_DEPTH).sum())
        return out, rows

    def map_numbers(self):
        floors, comparisons = {}, {}
        for w in self.windows:
            for symmetric, tag in ((False, ""), (True, " symmetric")):
                for config in self.groups:
                    maps, rows = self.maps(config, w, symmetric)
                    floors.setdefault(config, {})[w + tag] = l1_noise_floor(maps, rows)
                for a, b in (METHOD_PAIRS + self.grid_pairs() + self.separation_pairs() + self.step_pairs()
                             + self.ranks_pairs() + self.interpolation_pairs()):
                    if a in self.groups and b in self.groups:
                        (ma, rows), (mb, _) = self.maps(a, w, symmetric), self.maps(b, w, symmetric)
                        cross = cross_l1(ma, mb, rows)
                        within = 0.5 * (floors[a][w + tag]["mean"] + floors[b][w + tag]["mean"])
                        comparisons.setdefault(f"{a} vs {b}", {})[w + tag] = {
                            "cross_mean": float(numpy.mean(cross)), "cross_min": min(cross), "cross_max": max(cross),
                            "within_mean": within, "cross_over_within": float(numpy.mean(cross)) / within,
                            "permutation": l1_permutation_test(ma, mb, rows)}
        return {"floors": floors, "comparisons": comparisons}

    # Differences ----------------------------------------------------------------------------
    def differences(self, ensembles):
        """b - a of the ensemble means for METHOD_PAIRS (method 2 - method 1) and grid_pairs
        (fine - coarse), each with its error and its size in errors."""
        out = {}
        separation = self.separation_triples()
        for kind, pairs in (("method 2 - method 1", METHOD_PAIRS), ("fine - coarse", self.grid_pairs()),
                            ("coarse field - fine", tuple((f, s) for _, s, f in separation)),
                            ("coarse field - coarse", tuple((c, s) for c, s, _ in separation)),
                            ("own gas step - template's", self.step_pairs()),
                            ("N ranks - 1 rank", self.ranks_pairs()),
                            ("interpolated - its cell's", self.interpolation_pairs())):
            for a, b in pairs:
                if a not in ensembles or b not in ensembles:
                    continue
                self.same_dp(a, b)
                for w in self.windows:
                    for key, part in DIFFERENCE_QUANTITIES:
                        d = difference(ensembles[b][w][key][part], ensembles[a][w][key][part])
                        d["in_errors"] = d["mean"] / d["error"]
                        out.setdefault(kind, {}).setdefault(f"{b} - {a}", {}).setdefault(w, {})[f"{key} {part}"] = d
        pair = out.get("method 2 - method 1", {}).get("uniform_m2 - uniform_m1")
        if pair:
            paper = (self.paper["mean_height_m2"] - self.paper["mean_height_m1"]) / 100.0
            for w, values in pair.items():
                d = values["mean_height mean"]
                d["paper"] = paper
                d["paper_in_errors"] = (paper - d["mean"]) / d["error"]
        return out

    def tfm_comparison(self, ensembles):
        """TFM - TF-DEM of the ensemble means for TFM_PAIRS, each side its realizations' mean and
        standard error, the difference's error the two added in quadrature (TFM realizations from
        perturbed starts, TF-DEM's from poured packings)."""
        out = {}
        for dem, tfm in TFM_PAIRS:
            if tfm not in self.tfm_groups or dem not in ensembles:
                continue
            self.same_dp(dem, tfm)
            for w in self.windows:
                for key, part in TFM_QUANTITIES:
                    ours = ensemble([self.run_value(n, w, key)[part] for n in self.tfm_groups[tfm]])
                    theirs = ensembles[dem][w][key][part]
                    d = difference(ours, theirs)
                    d["in_errors"] = d["mean"] / d["error"]
                    out.setdefault(f"{tfm} - {dem}", {}).setdefault(w, {})[f"{key} {part}"] = {
                        "tfm": ours, "tfdem": theirs, "difference": d}
        return out

    # Grid convergence --------------------------------------------------------------------------
    def grid_chains(self):
        return {name: [c for c in chain if c in self.groups]
                for name, chain in grid_chains(self.report.study["runs"], list(self.groups)).items()
                if sum(c in self.groups for c in chain) >= 2}

    def margin(self, key, a, b):
        """The equivalence margin of `key` (SI) for two sets of realizations' values."""
        kind, value = EQUIVALENCE_MARGIN[key]
        return value * abs(numpy.mean(a + b)) if kind == "of its value" else value

    def grid_study(self, ensembles):
        """Per grid chain and window, for each GRID_QUANTITIES: the ensemble means along the
        chain; for every three consecutive grids Celik et al.'s apparent order, extrapolated
        value and GCI of the finest (tfdem.stats.grid_convergence, on the ensemble means, h from
        representative_cell), with whether the finer difference stands clear of the
        realizations' noise (RESOLVED errors: else the order is the noise's); for every pair of
        consecutive grids and the chain's ends, the two one-sided tests of equivalence within
        EQUIVALENCE_MARGIN on the realizations' values."""
        runs = self.report.study["runs"]
        out = {}
        for name, chain in self.grid_chains().items():
            self.same_dp(*chain)
            h = [representative_cell(runs[c]) for c in chain]
            entry = {"configurations": chain, "cells": h}
            for w in self.windows:
                values = {key: {c: [self.run_value(n, w, key)["mean"] for n in self.groups[c]] for c in chain}
                          for key in GRID_QUANTITIES}
                per_window = {}
                for key in GRID_QUANTITIES:
                    means = [ensembles[c][w][key]["mean"] for c in chain]
                    q = {"means": [m["mean"] for m in means], "errors": [m["error"] for m in means],
                         "convergence": [], "equivalence": []}
                    for k in range(len(chain) - 2):
                        coarse, middle, fine = means[k], means[k + 1], means[k + 2]
                        finer = difference(middle, fine)
                        g = {"grids": chain[k:k + 3],
                             "resolved": abs(finer["mean"]) >= RESOLVED * finer["error"]}
                        try:
                            g.update(grid_convergence([h[k + 2], h[k + 1], h[k]],
                                                      [fine["mean"], middle["mean"], coarse["mean"]]))
                        except ValueError as e:
                            g["note"] = str(e)
                        q["convergence"].append(g)
                    pairs = [(chain[k], chain[k + 1]) for k in range(len(chain) - 1)]
                    if len(chain) > 2:
                        pairs.append((chain[0], chain[-1]))
                    for a, b in pairs:
                        va, vb = values[key][a], values[key][b]
                        t = equivalence_test(vb, va, self.margin(key, va, vb), ALPHA)
                        q["equivalence"].append(dict(t, pair=[a, b]))
                    per_window[key] = q
                entry[w] = per_window
            out[name] = entry
        return out

    def packing(self, ensembles):
        """The jet bed's bulk coordination number, lattice packing against the poured
        realizations (jet_m1), and the share of the lattice's excess over the paper's ~1.2
        that the lattice carried: (lattice - poured) / (lattice - 1.2)."""
        if "jet_m1" not in ensembles:
            return None
        out = {}
        for w in self.windows:
            poured = ensembles["jet_m1"][w]["bulk_coordination"]["mean"]
            if "jet_m1" not in self.report.records:
                continue
            lattice = dict(self.run_value("jet_m1", w, "bulk_coordination"), source="lattice run jet_m1 (results/)")
            d = difference(lattice, poured)
            paper = self.paper["bulk_coordination_jet_value"]
            excess = lattice["mean"] - paper
            out[w] = {"lattice": {"mean": lattice["mean"], "error": lattice["error"], "source": lattice["source"]},
                      "poured": poured, "lattice_minus_poured": d, "paper": paper,
                      "share_of_excess_over_paper": {"mean": d["mean"] / excess, "error": d["error"] / abs(excess)},
                      "poured_minus_paper": poured["mean"] - paper}
        return out

    # Assembly -------------------------------------------------------------------------------
    def numbers(self):
        if not self.groups:
            self.result = {"configurations": {}}
            return self.result
        ensembles = {c: self.ensembles(c) for c in self.groups}
        self.result = {
            "configurations": self.groups, "seeds": self.seeds, "ensembles": ensembles,
            "batch_error_check": self.batch_error_check(ensembles),
            "correlation": {c: self.correlations(c) for c in self.groups},
            "maps": self.map_numbers(), "differences": self.differences(ensembles),
            "grid_study": self.grid_study(ensembles),
            "packing": self.packing(ensembles),
            "tfm": self.tfm_comparison(ensembles)}
        self.result["statements"] = self.statements()
        return self.result

    def statements(self):
        """Plain sentences from the numbers, by the rules: a difference is resolved at RESOLVED
        standard errors; a map difference when its permutation p < 0.05; the batch error by
        batch_error_check's verdict."""
        r, w0, w1 = self.result, self.windows[0], self.windows[-1]
        lines = []
        for pair, values in r["differences"].get("method 2 - method 1", {}).items():
            lines.append(self._difference_sentence("method 2 - method 1", pair, values, w0, w1))
        uniform = r["differences"].get("method 2 - method 1", {}).get("uniform_m2 - uniform_m1")
        if uniform:
            d = uniform[w0]["mean_height mean"]
            verdict = "rejected" if abs(d["paper_in_errors"]) >= RESOLVED else "not rejected"
            lines.append(f"Uniform bed, mean particle height, method 2 - method 1 over {w0} s: "
                         f"{signed(d['mean'], d['error'], 100)} cm against the paper's +{100 * d['paper']:.1f} cm "
                         f"(its 9.1 - 8.9 cm): the paper's value is {d['paper_in_errors']:.1f} standard errors away, "
                         f"{verdict} at {RESOLVED:g} standard errors.")
        for pair, values in r["differences"].get("fine - coarse", {}).items():
            lines.append(self._difference_sentence("fine - coarse", pair, values, w0, w1))
        for pair, values in r["differences"].get("own gas step - template's", {}).items():
            lines.append(self._difference_sentence("own gas step - template's", pair, values, w0, w1))
        lines += self._separation_sentences()
        lines += self._tfm_sentences()
        for pair, values in r["maps"]["comparisons"].items():
            v = values[w1]
            s = values[w1 + " symmetric"]
            lines.append(f"Solids-fraction maps {pair}, {w1} s: L1 across configurations {v['cross_mean']:.4f} "
                         f"against {v['within_mean']:.4f} between realizations of one configuration "
                         f"(ratio {v['cross_over_within']:.2f}, permutation p = {v['permutation']['p']:.3f}: "
                         f"{'a resolved difference' if v['permutation']['p'] < 0.05 else 'no resolved difference'}); "
                         f"mirror-averaged {s['cross_mean']:.4f} against {s['within_mean']:.4f} "
                         f"(p = {s['permutation']['p']:.3f}).")
        for bed, windows in r["batch_error_check"].items():
            for w in (w0, w1):
                parts = [f"{label} {v['ratio']:.2f} ({v['verdict']})" for (key, label, *_), v in
                         ((m, windows[w][m[0]]) for m in METRICS)]
                low, high = next(iter(windows[w].values()))["range90"]
                lines.append(f"{bed.capitalize()} bed, {w} s: spread of the realizations over the single run's "
                             f"{self.report.batch:g} s batch-means error, pooled: {'; '.join(parts)} "
                             f"(90 % range were the batch error right: {low:.2f}-{high:.2f}).")
        lines += self._independence_sentences()
        for config, metrics in r["correlation"].items():
            parts = [f"{label} {pm(v['tau_s']['mean'], v['tau_s']['error'])} s, blocking at {self.report.batch:g} s "
                     f"{v['at_batch_over_plateau']:.2f} of its plateau"
                     for (key, label, *_), v in ((m, metrics[m[0]]) for m in METRICS)]
            lines.append(f"{config}, {w1} s: integrated autocorrelation time {'; '.join(parts)}.")
        for w, p in (r["packing"] or {}).items():
            lines.append(f"Jet bed, bulk coordination number over {w} s: lattice {pm(p['lattice']['mean'], p['lattice']['error'])} "
                         f"({p['lattice']['source']}), poured realizations {pm(p['poured']['mean'], p['poured']['error'])}: "
                         f"the lattice carried {signed(p['lattice_minus_poured']['mean'], p['lattice_minus_poured']['error'])}, "
                         f"{pm(p['share_of_excess_over_paper']['mean'], p['share_of_excess_over_paper']['error'], 100)} % "
                         f"of its excess over the paper's ~{p['paper']:g}; the poured bed stands "
                         f"{p['poured_minus_paper']:+.2f} above the paper's.")
        return lines

    def _tfm_sentences(self):
        """Seed 000's TFM statements tested on the peer's realizations, over the paper's window:
        the uniform bed's mean particle height (the paper's TFM 9.16 against TF-DEM 8.9 cm) and
        the jet bed's Delta p at 20 cm ("a similar mean pressure, but a smaller fluctuating
        amplitude", Fig. 3)."""
        w0, lines = self.windows[0], []
        uniform = (self.result.get("tfm") or {}).get("uniform_tfm_peer - uniform_m1")
        if uniform:
            d = uniform[w0]["mean_height mean"]["difference"]
            paper = (self.paper["mean_height_tfm"] - self.paper["mean_height_m1"]) / 100.0
            away = (paper - d["mean"]) / d["error"]
            lines.append(f"Uniform bed, mean particle height, TFM peer - TF-DEM over {w0} s: "
                         f"{signed(d['mean'], d['error'], 100)} cm (combined error of both ensembles) against the "
                         f"paper's {100 * paper:+.2f} cm ({self.paper['mean_height_tfm']} - "
                         f"{self.paper['mean_height_m1']} cm): {abs(away):.1f} standard errors away, "
                         f"{'not reproduced' if abs(away) >= RESOLVED else 'reproduced'} at {RESOLVED:g} standard errors.")
        jet = (self.result.get("tfm") or {}).get("jet_tfm_peer - jet_m1")
        if jet:
            mean, std = jet[w0]["dp20 mean"]["difference"], jet[w0]["dp20 std"]["difference"]
            similar = abs(mean["in_errors"]) < RESOLVED
            smaller = std["mean"] < 0 and abs(std["in_errors"]) >= RESOLVED
            lines.append(f"Jet bed, Δp at 20 cm, TFM peer - TF-DEM over {w0} s: mean {signed(mean['mean'], mean['error'])} "
                         f"Pa ({'similar' if similar else 'a resolved difference'}), fluctuation std "
                         f"{signed(std['mean'], std['error'])} Pa ({'smaller' if smaller else 'not resolved smaller'}): "
                         f"the paper's \"similar mean, smaller fluctuation\" "
                         f"{'reproduced' if similar and smaller else 'not reproduced'}.")
        return lines

    def _separation_sentences(self):
        """Per separation triple (coarse, separated, fine), over the longest window: the grid
        dependence fine - coarse split into the gas's part (separated - coarse: only the gas's
        cells differ) and the particle field's (fine - separated: only the particle field's),
        each metric's and the maps' L1 against their noise floors."""
        r, w1, lines = self.result, self.windows[-1], []
        for coarse, separated, fine in self.separation_triples():
            parts = []
            for key, part in DIFFERENCE_QUANTITIES:
                label, unit, scale = next((m[1], m[2], m[3]) for m in METRICS if m[0] == key)
                e = {c: r["ensembles"][c][w1][key][part] for c in (coarse, separated, fine)}
                total, gas, field = (difference(e[b], e[a]) for a, b in
                                     ((coarse, fine), (coarse, separated), (separated, fine)))
                parts.append(f"{label}{' std' if part == 'std' else ''}: fine - coarse "
                             f"{signed(total['mean'], total['error'], scale)}, the gas's "
                             f"{signed(gas['mean'], gas['error'], scale)}, the particle field's "
                             f"{signed(field['mean'], field['error'], scale)}{' ' + unit if unit else ''}")
            maps = r["maps"]["comparisons"]
            l1 = {pair: maps[pair][w1] for pair in (f"{coarse} vs {fine}", f"{coarse} vs {separated}",
                                                     f"{separated} vs {fine}") if pair in maps}
            map_text = "; ".join(f"{pair} {v['cross_mean']:.4f} ({v['cross_over_within']:.2f} of the floor, "
                                 f"p = {v['permutation']['p']:.3f})" for pair, v in l1.items())
            lines.append(f"Separation test, {separated} (the gas on {fine}'s cells, the particle field on "
                         f"{coarse}'s), ensemble means over {w1} s: " + "; ".join(parts)
                         + f". Solids-fraction maps, L1: {map_text}.")
        return lines

    def _independence_sentences(self):
        """Per bed: are the study's batches independent within a run (the longest tau_int
        against the batch length; the blocking curves at the batch against their plateaus),
        and is a run's batch error its real error (the spread against it, batch_error_check)?"""
        r, lines, batch = self.result, [], self.report.batch
        for bed, windows in r["batch_error_check"].items():
            configs = [c for c in self.groups if self.bed(c) == bed]
            taus = [(r["correlation"][c][key]["tau_s"]["mean"], label, c) for c in configs for key, label, *_ in METRICS]
            longest = max(taus)
            ratios = [r["correlation"][c][key]["at_batch_over_plateau"] for c in configs for key, *_ in METRICS]
            spreads = [v["ratio"] for w in windows.values() for v in w.values()]
            too_small = sum(1 for w in windows.values() for v in w.values() if v["verdict"] == "batch error too small")
            too_large = sum(1 for w in windows.values() for v in w.values() if v["verdict"] == "batch error too large")
            lines.append(
                f"{bed.capitalize()} bed: within one run the longest integrated autocorrelation time is "
                f"{longest[0]:.2g} s ({longest[1]}, {longest[2]}), so {batch:g} s batches are {batch / longest[0]:.1f} "
                f"times as long, and the blocking curves at {batch:g} s lie at {min(ratios):.2f}-{max(ratios):.2f} of "
                f"their plateaus (below 1: the batches are too short, the curve still rising; above 1: an oscillation "
                f"inside a batch, the error falls again at longer batches). Across runs, the realizations' spread is "
                f"{min(spreads):.2f}-{max(spreads):.2f} times the single run's batch error (metrics and windows), "
                f"outside its chance range in {too_small + too_large} of {len(spreads)} cases ({too_small} too small, "
                f"{too_large} too large).")
        return lines

    @staticmethod
    def _difference_sentence(kind, pair, values, w0, w1):
        parts = []
        for (key, part), (k, label, unit, scale) in ((q, next(m for m in METRICS if m[0] == q[0]))
                                                    for q in DIFFERENCE_QUANTITIES):
            d0, d1 = values[w0][f"{key} {part}"], values[w1][f"{key} {part}"]
            what = label + (" std" if part == "std" else "")
            state = "resolved" if abs(d0["in_errors"]) >= RESOLVED else "not resolved"
            parts.append(f"{what} {signed(d0['mean'], d0['error'], scale)}{' ' + unit if unit else ''} "
                         f"({d0['in_errors']:+.1f} SE, {state}; {w1} s: {signed(d1['mean'], d1['error'], scale)}, "
                         f"{d1['in_errors']:+.1f} SE)")
        return f"{pair} ({kind}), ensemble means over {w0} s: " + "; ".join(parts) + "."

    # Figure and tables ----------------------------------------------------------------------
    def figure(self, report):
        """Blocking curves: per bed (rows) and metric (columns) the root mean square over the
        realizations of the batch-means error against the batch length, one line per
        configuration; dashed, the realizations' spread of the window mean (the error one
        run has); dotted, the study's batch length."""
        if not self.groups:
            return
        beds = sorted({self.bed(c) for c in self.groups})
        fig, axes = plt.subplots(len(beds), len(METRICS), figsize=(3.2 * len(METRICS), 3 * len(beds)), squeeze=False)
        w1 = self.windows[-1]
        for i, bed in enumerate(beds):
            for j, (key, label, unit, scale) in enumerate(METRICS):
                ax = axes[i, j]
                for k, config in enumerate(c for c in self.groups if self.bed(c) == bed):
                    c = self.result["correlation"][config][key]
                    line, = ax.loglog(c["blocking_lengths_s"], scale * numpy.array(c["blocking_rms_error"]), "o-",
                                      ms=3, lw=1, label=config)
                    ax.axhline(scale * self.result["ensembles"][config][w1][key]["mean"]["spread"], ls="--", lw=0.8,
                               color=line.get_color())
                ax.axvline(report.batch, ls=":", color="k", lw=0.8)
                ax.set_title(f"{bed}: {label}", fontsize=8)
                ax.set_xlabel("batch length (s)", fontsize=7)
                ax.set_ylabel(f"error of the {w1} s mean" + (f" ({unit})" if unit else ""), fontsize=7)
                ax.tick_params(labelsize=6)
                ax.legend(fontsize=6)
        fig.suptitle("Blocking curves (root mean square over the realizations); dashed: the realizations' spread "
                     f"of the {w1} s mean; dotted: the study's batch", fontsize=8)
        report.save(fig, "replicates_blocking.png")

    def grid_families(self):
        """Rows of the grid figure: each chain of configurations that differ in their cells alone
        (grid_pairs), coarsest first, each separated run after its coarse one."""
        cells = {c: len(self.report.records[self.groups[c][0]].x.ravel()) for c in self.groups}
        out = [sorted(f, key=cells.get) for f in linked_families(self.grid_pairs())]
        for coarse, separated, fine in self.separation_triples():
            family = next(f for f in out if fine in f)
            family.insert(family.index(coarse) + 1, separated)
        return out

    def grid_figure(self, report):
        """Fig. 4 with the realizations: per grid family (rows) the ensemble-mean time-averaged
        solids fraction of each configuration on its own cells over the longest window, titled
        with its L1 against the family's coarsest (on the coarse cells) and the two noise floors."""
        families = self.grid_families()
        if not families:
            return
        w = self.windows[-1]
        start, end = map(float, w.split("-"))
        columns = max(len(f) for f in families)
        fig, axes = plt.subplots(len(families), columns, figsize=(2.3 * columns + 1, 3.6 * len(families)),
                                 squeeze=False, constrained_layout=True)
        comparisons, floors = self.result["maps"]["comparisons"], self.result["maps"]["floors"]
        for i, family in enumerate(families):
            for j in range(columns):
                ax = axes[i, j]
                if j >= len(family):
                    ax.axis("off")
                    continue
                config = family[j]
                records = [self.report.records[n] for n in self.groups[config]]
                mean = numpy.mean([to_grid(r.window_map("solids", start, end), r.shape) for r in records], axis=0)
                r0 = records[0]
                height = r0.y.max() + (r0.y[1, 0] - r0.y[0, 0]) / 2 if r0.shape[0] > 1 else MAP_DEPTH
                image = ax.imshow(mean, origin="lower", extent=(0, r0.width, 0, height), vmin=0, vmax=0.65,
                                  interpolation="nearest", aspect="equal")
                ax.set_ylim(0, MAP_DEPTH)
                title = f"{config}\n{r0.shape[1]} x {r0.shape[0]} cells, n = {len(records)}\nfloor {floors[config][w]['mean']:.3f}"
                pair = f"{family[0]} vs {config}"
                if j > 0 and pair in comparisons:
                    title += f", L1 vs {family[0]} {comparisons[pair][w]['cross_mean']:.3f}"
                ax.set_title(title, fontsize=6)
                ax.tick_params(labelsize=6)
        fig.colorbar(image, ax=axes[:, -1].tolist(), shrink=0.6, label=f"solids fraction, {w} s, ensemble mean")
        fig.suptitle("Fig. 4 with realizations: the jet bed's time-averaged solids fraction on each grid\n(L1 on the "
                     "coarse cells, bottom 45 cm; floor: between realizations of one configuration)", fontsize=8)
        fig.savefig(os.path.join(report.out, "fig4_grids_replicates.png"), dpi=110)
        plt.close(fig)
        report.figures.append("fig4_grids_replicates.png")

    def markdown(self):
        if not self.groups:
            return []
        r, w0, w1 = self.result, self.windows[0], self.windows[-1]
        n = {c: len(v) for c, v in self.groups.items()}
        lines = ["## Replicates", "",
                 f"Realizations (poured packings, seeds {', '.join(str(s) for s in self.seeds)}): "
                 + ", ".join(f"{c} × {n[c]}" for c in self.groups) + ". Ensemble mean ± its standard error "
                 "(std across realizations / sqrt(n)); 'spread': the std across realizations, the error one run's "
                 f"mean really has; 'batch error': one run's {self.report.batch:g} s batch-means error (mean over "
                 "the realizations).", "",
                 f"| quantity | configuration | {w0} s: ensemble | spread | batch error | {w1} s: ensemble | spread | "
                 "batch error |", "|---|---|---|---|---|---|---|---|"]
        for key, label, unit, scale in METRICS:
            for part in ("mean", "std"):
                if part == "std" and key != "dp20":
                    continue
                for config in self.groups:
                    cells = []
                    for w in (w0, w1):
                        e = r["ensembles"][config][w][key]
                        cells += [pm(e[part]["mean"], e[part]["error"], scale), f"{scale * e[part]['spread']:.2g}",
                                  f"{scale * e['batch_error']:.2g}" if part == "mean" else "-"]
                    name = label + (" std" if part == "std" else "") + (f" ({unit})" if unit else "")
                    lines.append(f"| {name} | {config} | " + " | ".join(cells) + " |")
        for config in self.groups:
            cells = []
            for w in (w0, w1):
                e = r["ensembles"][config][w]
                f = e["force_ratio"]
                cells.append(f"{pm(e['dp20_frequency']['mean'], e['dp20_frequency']['error'])} Hz; "
                             f"{_pm_or_dash(f['share_2_to_10'])}; {_pm_or_dash(f['median'])}; "
                             f"{_pm_or_dash(f['largest'])}")
            lines.append(f"| Δp frequency; contact/drag: share 2-10, median, largest | {config} | {cells[0]} | | | "
                         f"{cells[1]} | | |")
        for config in self.groups:
            c = r["ensembles"][config]["cpu_seconds"]
            lines.append(f"| processor time (s) | {config} | {pm(c['mean'], c['error'])} | {c['spread']:.2g} | | | | |")
        lines += ["", "Is the batch-means error right? The realizations' spread over the single run's batch error, "
                      "pooled over a bed's configurations (1 if it is right; the 90 % range that ratio has by chance "
                      "with these degrees of freedom beside it):", "",
                  "| bed | window | " + " | ".join(m[1] for m in METRICS) + " | 90 % range | dof |",
                  "|---|---|" + "---|" * len(METRICS) + "---|---|"]
        for bed, windows in r["batch_error_check"].items():
            for w in (w0, w1):
                v = windows[w]
                any_v = v[METRICS[0][0]]
                lines.append(f"| {bed} | {w} s | " + " | ".join(f"{v[m[0]]['ratio']:.2f} ({v[m[0]]['verdict']})"
                                                              for m in METRICS)
                             + f" | {any_v['range90'][0]:.2f}-{any_v['range90'][1]:.2f} | {any_v['dof']} |")
        lines += ["", f"Integrated autocorrelation time over {w1} s (Sokal's window, c = 5; ensemble mean ± error) "
                      f"and the blocking curve at the study's {self.report.batch:g} s batches over its plateau (its "
                      f"mean from {PLATEAU_FROM * self.scale:g} s batches on); figure `replicates_blocking.png`:", "",
                  "| configuration | " + " | ".join(f"{m[1]}: tau_int (s); at batch / plateau" for m in METRICS) + " |",
                  "|---|" + "---|" * len(METRICS)]
        for config, metrics in r["correlation"].items():
            lines.append(f"| {config} | " + " | ".join(
                f"{pm(metrics[m[0]]['tau_s']['mean'], metrics[m[0]]['tau_s']['error'])}; "
                f"{metrics[m[0]]['at_batch_over_plateau']:.2f}" for m in METRICS) + " |")
        lines += ["", "Differences of ensemble means (± the two standard errors in quadrature; in brackets, in "
                      "standard errors):", "", f"| comparison | quantity | {w0} s | {w1} s |", "|---|---|---|---|"]
        for kind, pairs in r["differences"].items():
            for pair, values in pairs.items():
                for key, part in DIFFERENCE_QUANTITIES:
                    label, unit, scale = next((m[1], m[2], m[3]) for m in METRICS if m[0] == key)
                    cells = [f"{signed(values[w][f'{key} {part}']['mean'], values[w][f'{key} {part}']['error'], scale)}"
                             f" ({values[w][f'{key} {part}']['in_errors']:+.1f})" for w in (w0, w1)]
                    name = label + (" std" if part == "std" else "") + (f" ({unit})" if unit else "")
                    lines.append(f"| {pair} | {name} | {cells[0]} | {cells[1]} |")
        lines += self._grid_study_markdown(w0, w1)
        lines += ["", "Solids-fraction maps (bottom 45 cm, on the coarse cells): noise floor = mean L1 [min-max] "
                      "between the realizations of one configuration over the same window; a comparison = mean L1 "
                      "[min-max] over every pair of realizations across the two, with the exact permutation test's "
                      "p (is it above the floor?):", "", "| configuration or comparison | window | L1 | across / "
                      "within | p |", "|---|---|---|---|---|"]
        for config, values in r["maps"]["floors"].items():
            for w, v in values.items():
                lines.append(f"| {config} (noise floor) | {w} | {v['mean']:.4f} [{v['min']:.4f}-{v['max']:.4f}] | | |")
        for pair, values in r["maps"]["comparisons"].items():
            for w, v in values.items():
                lines.append(f"| {pair} | {w} | {v['cross_mean']:.4f} [{v['cross_min']:.4f}-{v['cross_max']:.4f}] | "
                             f"{v['cross_over_within']:.2f} | {v['permutation']['p']:.3f} |")
        lines += self._tfm_markdown()
        lines += ["", "What the data show (replicates.py's rules: a difference is resolved at "
                      f"{RESOLVED:g} standard errors, about 90 % two-sided with the ~6 degrees of freedom of two "
                      "4-run ensembles; a map difference at p < 0.05):", ""]
        lines += [f"- {s}" for s in r["statements"]]
        return lines


    def _tfm_markdown(self):
        """The TFM peer's realizations against TF-DEM's: a table per window."""
        comparisons = self.result.get("tfm") or {}
        if not comparisons:
            return []
        n = {c: len(v) for c, v in self.tfm_groups.items()}
        lines = ["", "The kinetic-theory TFM peer (realizations from the packed bed's α_s perturbed by ±2 % per cell, "
                     "the same seeds: " + ", ".join(f"{c} × {n[c]}" for c in self.tfm_groups) + ") against TF-DEM "
                     "(method 1), each an ensemble mean ± its standard error, the difference's error both added in "
                     "quadrature:", "",
                 "| quantity | window | TFM | TF-DEM | TFM − TF-DEM | in errors |", "|---|---|---|---|---|---|"]
        units = {key: (label, unit, scale) for key, label, unit, scale in METRICS}
        for pair, values in comparisons.items():
            for w, entry in values.items():
                for name, v in entry.items():
                    key, part = name.split()
                    label, unit, scale = units[key]
                    text = label + (" std" if part == "std" else "") + f" ({unit}), {pair.split(' - ')[0]}"
                    d = v["difference"]
                    lines.append(f"| {text} | {w} s | {pm(v['tfm']['mean'], v['tfm']['error'], scale)} | "
                                 f"{pm(v['tfdem']['mean'], v['tfdem']['error'], scale)} | "
                                 f"{signed(d['mean'], d['error'], scale)} | {d['in_errors']:+.1f} |")
        return lines

    def _grid_study_markdown(self, w0, w1):
        study = self.result["grid_study"]
        if not study:
            return []
        lines = ["", "Grid convergence (Celik et al. 2008, on the ensemble means, h = 1 / sqrt(cells per template "
                     "cell); 'in noise': the finer two grids' difference is below "
                     f"{RESOLVED:g} standard errors, so the order is the noise's) and equivalence of two grids (two "
                     f"one-sided tests at {ALPHA:g}, margins {MARGIN_TEXT}; the 90 % interval of the difference "
                     "must lie inside the margin):", "",
                 "| chain | quantity | window | means, coarsest first | order; extrapolated; GCI of the finest | "
                 "equivalence: pair, difference [90 % interval], p |", "|---|---|---|---|---|---|"]
        for name, entry in study.items():
            for key in GRID_QUANTITIES:
                label, unit, scale = next((m[1], m[2], m[3]) for m in METRICS if m[0] == key)
                for w in (w0, w1):
                    q = entry[w][key]
                    means = ", ".join(pm(m, e, scale) for m, e in zip(q["means"], q["errors"]))
                    gci = "; ".join(
                        (f"{g['order']:.2f}; {scale * g['extrapolated']:.4g}; {100 * g['gci_fine']:.2g} %"
                         + (" (oscillating)" if g["oscillatory"] else "") if "order" in g else g["note"])
                        + ("" if g["resolved"] else " (in noise)") for g in q["convergence"]) or "-"
                    equal = "; ".join(
                        f"{t['pair'][1]} − {t['pair'][0]}: {scale * t['mean']:+.3g} "
                        f"[{scale * t['interval'][0]:+.3g}, {scale * t['interval'][1]:+.3g}], p {t['p']:.3f} "
                        f"({'equivalent' if t['equivalent'] else 'not shown equivalent'})" for t in q["equivalence"])
                    lines.append(f"| {name} | {label}{f' ({unit})' if unit else ''} | {w} | {means} | {gci} | "
                                 f"{equal} |")
        return lines


def _finite_ensemble(values):
    """ensemble() of the finite values (a run may have no cell of a kind: nan), None with
    fewer than two."""
    finite = [v for v in values if math.isfinite(v)]
    return ensemble(finite) if len(finite) >= 2 else None


def _pm_or_dash(e):
    return pm(e["mean"], e["error"]) if e else "-"
