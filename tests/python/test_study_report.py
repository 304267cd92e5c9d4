"""The seed 000 study's statistics and report functions on hand-made inputs with answers
worked out by hand or from a closed form (no simulation):

- tfdem.stats: the ensemble mean and its standard error, differences, the blocking curve
  (alternating and step series by hand; white noise and AR(1) plateaus from the closed form
  sigma^2 tau / N), the autocorrelation and Sokal's window (by hand), the integrated
  autocorrelation time of white noise (1) and AR(1) ((1 + phi) / (1 - phi)), chi-square
  quantiles against the tables;
- tfdem.bed: Delta p at 20 cm from the row probes, extrapolated to the inlet and
  interpolated between rows (also through BedOutputs on a hand-made case; an old layout
  refused), the mirror mean, pairwise and cross L1, the noise floor, the permutation test;
- the study's record (written and read back, a missing file or window named) and report.py's
  ratio_numbers on hand-made records;
- headline.py's Fig. 8 numbers (axis profile, corners, mirror L1), its pairs table and the
  README blocks it replaces, by hand; and the study README's generated tables are what
  report.py makes from the committed records (results/), cell for cell.
"""
import math
import os
import shutil
import sys
import tempfile

import numpy

from tfdem import STUDIES
from tfdem.bed import (BedOutputs, cross_l1, l1_noise_floor, l1_permutation_test, mirror_mean, pairwise_l1,
                       section_pressure_drop, write_bed_probes)
from tfdem.case import Case
from tfdem.stats import (autocorrelation, blocking_curve, chi_square_quantile, difference, ensemble,
                         equivalence_test, grid_convergence, integrated_autocorrelation_time, sokal_window,
                         spread_ratio_range, student_t_cdf, student_t_quantile, welch_difference)

STUDY = os.path.join(STUDIES, "seed000")
sys.path.insert(0, STUDY)
import headline  # noqa: E402
import report  # noqa: E402
import study as study_definition  # noqa: E402
from record import Record, RecordError  # noqa: E402

failures = []


def check(name, condition, detail=""):
    print(("PASS " if condition else "FAIL ") + name + (f" {detail}" if detail else ""))
    if not condition:
        failures.append(name)


def close(a, b, tol=1e-12):
    return abs(a - b) <= tol * max(1.0, abs(b))


def raises(function, *args, **kwargs):
    try:
        function(*args, **kwargs)
    except ValueError as e:
        return str(e)
    return None


def ar1(phi, n, seed):
    """x_i = phi x_{i-1} + e_i with unit normal e, started in its stationary distribution."""
    rng = numpy.random.default_rng(seed)
    e = rng.standard_normal(n)
    x = numpy.empty(n)
    x[0] = e[0] / math.sqrt(1 - phi ** 2)
    for i in range(1, n):
        x[i] = phi * x[i - 1] + e[i]
    return x


def study_refusal(run_line):
    """load_study's message for a study.yaml of the jet bed and the one run `run_line` ('' when
    it loads)."""
    from study import StudyError, load_study
    path = os.path.join(tempfile.mkdtemp(), "study.yaml")
    with open(path, "w") as f:
        f.write(f"beds: {{jet: {{template: jet_bed}}}}\nruns:\n  {run_line}\n")
    try:
        load_study(path)
    except StudyError as e:
        return str(e)
    return ""


def check_refined_runs():
    # A refined run's gas step: 12.5 DEM steps of 0.02 ms at the target 0.25 ms; the 10 ms
    # interval is 500 steps, whose largest divisor up to 12 is 10: 0.2 ms
    from study import whole_gas_step
    check("gas step on 0.5 x 0.5 cm: 0.2 ms", abs(whole_gas_step(2.5e-4, 2e-5, 0.01) - 2e-4) < 1e-15)
    check("gas step on 1 x 1 cm: 0.5 ms (25 steps divide 500)", abs(whole_gas_step(5e-4, 2e-5, 0.01) - 5e-4) < 1e-15)
    # a refinement that is not a whole number of cells is refused, naming the run and the key
    half = study_refusal("jet_half: {bed: jet, refine_x: 1.5}")
    check("refine_x 1.5 refused", "run jet_half: refine_x must be a whole number" in half and "1.5" in half, half)
    step = study_refusal("jet_step: {bed: jet, gas_step: -1}")
    check("gas_step -1 refused", "run jet_step: gas_step must be a time step in seconds above 0" in step, step)
    yes = study_refusal("jet_step: {bed: jet, gas_step: yes}")
    check("gas_step yes (a YAML boolean) refused", "gas_step must be a time step in seconds above 0" in yes, yes)
    plate = study_refusal("jet_plate: {bed: jet, dp_from: plate}")
    check("dp_from plate refused, the levels named", "run jet_plate: dp_from is where Delta p's lower level is, one of "
          "inlet, bottom_row, got 'plate'" in plate, plate)
    check("dp_from bottom_row loads", study_refusal("jet_rows: {bed: jet, dp_from: bottom_row}") == "")
    # fine-coarse pairs: runs that differ in their cells alone
    from replicates import grid_pairs
    levels = {"c": {"bed": "jet", "dp_from": "bottom_row"}, "f": {"bed": "jet", "refine_y": 2}}
    check("grid pairs: where Delta p is measured does not part a pair", grid_pairs(levels, list(levels)) == (("c", "f"),),
          str(grid_pairs(levels, list(levels))))
    runs = {"c": {"bed": "jet"}, "f": {"bed": "jet", "refine_y": 2}, "ff": {"bed": "jet", "refine_x": 2, "refine_y": 4},
            "m2": {"bed": "jet", "coupling": {"coupling.transfer": "per_particle"}}}
    check("grid pairs: coarse-fine, coarse-finest, fine-finest, no other", grid_pairs(runs, list(runs)) ==
          (("c", "f"), ("c", "ff"), ("f", "ff")), str(grid_pairs(runs, list(runs))))
    # separation: the fine run with its particle field on blocks of the coarse run's cells; its
    # fine run is the one without the block, its coarse one the run whose cells are the blocks
    from replicates import BLOCK_KEY, separation_triples
    cons = {"coupling.transfer": "per_particle_conservative"}
    runs.update({"f_cf": {"bed": "jet", "refine_y": 2, "coupling": {BLOCK_KEY: [1, 2, 1]}},
                 "ff_cf": {"bed": "jet", "refine_x": 2, "refine_y": 4, "coupling": {BLOCK_KEY: [2, 4, 1]}},
                 "ff_f": {"bed": "jet", "refine_x": 2, "refine_y": 4, "coupling": {BLOCK_KEY: [2, 2, 1]}},
                 "f_cons_cf": {"bed": "jet", "refine_y": 2, "coupling": {**cons, BLOCK_KEY: [1, 2, 1]}}})
    triples = separation_triples(runs, list(runs))
    check("separation triples: (coarse, separated, fine) by the block; none without its coarse and fine runs",
          triples == (("c", "f_cf", "f"), ("c", "ff_cf", "ff"), ("f", "ff_f", "ff")), str(triples))
    from replicates import step_pairs
    runs["c_step"] = {"bed": "jet", "gas_step": 2e-4}
    check("step pairs: the same cells, gas_step alone differs", step_pairs(runs, list(runs)) == (("c", "c_step"),),
          str(step_pairs(runs, list(runs))))
    check("a run of its own gas step pairs with the finer grids, not its own",
          grid_pairs(runs, list(runs)) == (("c", "f"), ("c", "ff"), ("c_step", "f"), ("c_step", "ff"), ("f", "ff")),
          str(grid_pairs(runs, list(runs))))
    from replicates import ranks_pairs
    runs["c_4"] = {"bed": "jet", "ranks": 4}
    runs["f_4"] = {"bed": "jet", "refine_y": 2, "ranks": 4, "gas": "split"}
    check("ranks pairs: the same run on 1 and N ranks, any gas layout; no cross-grid pair",
          ranks_pairs(runs, list(runs)) == (("c", "c_4"), ("f", "f_4")), str(ranks_pairs(runs, list(runs))))
    check("a run on N ranks pairs with no grid", ("c_4", "f_4") not in grid_pairs(runs, list(runs))
          and ("c", "c_4") not in grid_pairs(runs, list(runs)), str(grid_pairs(runs, list(runs))))
    from replicates import GAS_VELOCITY_KEY, interpolation_pairs
    runs["m2_interp"] = {"bed": "jet", "coupling": {"coupling.transfer": "per_particle", GAS_VELOCITY_KEY: "interpolated"}}
    runs["c_cell"] = {"bed": "jet", "coupling": {GAS_VELOCITY_KEY: "cell"}}
    runs["c_interp"] = {"bed": "jet", "coupling": {GAS_VELOCITY_KEY: "interpolated"}}
    check("interpolation pairs: the same run with its cell's (the default or named) and the interpolated gas "
          "velocity, no other", interpolation_pairs(runs, list(runs)) ==
          (("c", "c_interp"), ("c_cell", "c_interp"), ("m2", "m2_interp")), str(interpolation_pairs(runs, list(runs))))
    del runs["c_4"], runs["f_4"], runs["m2_interp"], runs["c_cell"], runs["c_interp"]
    for line, expect in (("jet_r: {bed: jet, ranks: 0}", "run jet_r: ranks must be a whole number of MPI ranks"),
                         ("jet_r: {bed: jet, ranks: 2.5}", "run jet_r: ranks must be a whole number of MPI ranks"),
                         ("jet_r: {bed: jet, ranks: 2, gas: halved}", "run jet_r: gas: gas layout 'halved'")):
        message = study_refusal(line)
        check(f"refused: {line}", expect in message, message)
    del runs["c_step"]
    check("a separated run pairs with no grid", grid_pairs(runs, list(runs)) == (("c", "f"), ("c", "ff"), ("f", "ff")),
          str(grid_pairs(runs, list(runs))))


def check_ensemble():
    # 1, 2, 3, 4: mean 2.5, sample variance (2.25 + 0.25 + 0.25 + 2.25) / 3 = 5/3
    e = ensemble([1, 2, 3, 4])
    check("ensemble mean", close(e["mean"], 2.5), str(e))
    check("ensemble spread: std with ddof = 1", close(e["spread"], math.sqrt(5 / 3)))
    check("ensemble error: spread / sqrt(n)", close(e["error"], math.sqrt(5 / 3) / 2) and e["n"] == 4)
    check("ensemble of one value refused", raises(ensemble, [5.0]) is not None)
    d = difference({"mean": 3.0, "error": 0.3}, {"mean": 1.0, "error": 0.4})
    check("difference: errors in quadrature", close(d["mean"], 2.0) and close(d["error"], 0.5), str(d))


def check_blocking():
    # +1, -1, ... (16): one-sample batches have mean 0 and s^2 = 16/15, error s / 4; any even
    # batch length averages to exactly 0
    curve = blocking_curve([1.0, -1.0] * 8, [1, 2, 4])
    check("blocking: alternating series, single samples",
          close(curve[0]["error"], math.sqrt(16 / 15) / 4) and curve[0]["batches"] == 16, str(curve[0]))
    check("blocking: error of the error 1 / sqrt(2 (n - 1))",
          close(curve[0]["error_of_error"], curve[0]["error"] / math.sqrt(30)))
    check("blocking: alternating series, even batches give 0", curve[1]["error"] == 0 and curve[2]["error"] == 0)
    # 0 x 8 then 1 x 8, batches of 8: means 0 and 1, s = 1/sqrt(2), error s / sqrt(2) = 0.5
    step = blocking_curve([0.0] * 8 + [1.0] * 8, [8])
    check("blocking: step series, two batches", close(step[0]["error"], 0.5) and step[0]["batches"] == 2, str(step))
    # the remainder is left out: 17 samples in batches of 8 are two batches of the first 16
    check("blocking: remainder left out", close(blocking_curve([0.0] * 8 + [1.0] * 8 + [100.0], [8])[0]["error"], 0.5))
    check("blocking: a batch length leaving one batch refused", raises(blocking_curve, [1.0, 2.0, 3.0], [2]) is not None)
    n = 2 ** 16
    noise = numpy.random.default_rng(7).standard_normal(n)
    flat = blocking_curve(noise, [1, 16, 256])
    expected = 1 / math.sqrt(n)
    check("blocking: white noise is flat at sigma / sqrt(N)",
          all(abs(c["error"] - expected) < 3 * c["error_of_error"] for c in flat), str([c["error"] for c in flat]))
    # AR(1), phi = 0.8: var = 1 / (1 - phi^2), tau = 9; the plateau sqrt(var tau / N), single
    # samples sqrt(var / N), 3 times lower
    x = ar1(0.8, n, 11)
    plateau = math.sqrt(9 / (1 - 0.64) / n)
    c = {k["size"]: k for k in blocking_curve(x, [1, 256, 1024])}
    check("blocking: AR(1) plateau sqrt(var tau / N)",
          abs(c[256]["error"] - plateau) < 3 * c[256]["error_of_error"]
          and abs(c[1024]["error"] - plateau) < 3 * c[1024]["error_of_error"], f"{c[256]['error']} {plateau}")
    check("blocking: AR(1) single samples underestimate by sqrt(tau) = 3",
          abs(c[1]["error"] - plateau / 3) < 0.02 * plateau / 3, f"{c[1]['error']} {plateau / 3}")


def check_autocorrelation():
    # 1, 1, -1, -1 (mean 0, C0 = 1): C1 = (1 - 1 + 1) / 4, C2 = (-1 - 1) / 4, C3 = -1 / 4
    rho = autocorrelation([1, 1, -1, -1])
    check("autocorrelation by hand", numpy.allclose(rho, [1, 0.25, -0.5, -0.25]), str(rho))
    check("autocorrelation of a constant refused", raises(autocorrelation, [2.0, 2.0, 2.0]) is not None)
    # rho = 1, 1/2, 1/4, 1/8, 0 ...: tau(1) = 2, tau(2) = 2.5, tau(3) = 2.75, tau(4) = 2.75
    rho = [1, 0.5, 0.25, 0.125, 0, 0, 0, 0, 0, 0]
    check("Sokal window, c = 1: M = 3 (3 >= 2.75; 2 < 2.5)", sokal_window(rho, 1) == (2.75, 3), str(sokal_window(rho, 1)))
    check("Sokal window, c = 0.5: M = 1 (1 >= 1)", sokal_window(rho, 0.5) == (2.0, 1))
    message = raises(sokal_window, rho, 5)
    check("Sokal window, c = 5: no M < N / 2, refused", message is not None and "too short" in message, str(message))
    tau, _ = integrated_autocorrelation_time(numpy.random.default_rng(3).standard_normal(2 ** 16))
    check("tau_int of white noise = 1", abs(tau - 1) < 0.05, f"{tau:.3f}")
    for phi, seed in ((0.5, 5), (0.8, 13)):
        expected = (1 + phi) / (1 - phi)
        tau, m = integrated_autocorrelation_time(ar1(phi, 2 ** 17, seed))
        # the estimate's relative error is about sqrt(2 (2M + 1) / N) < 4 %
        check(f"tau_int of AR(1), phi = {phi}: (1 + phi) / (1 - phi) = {expected:g}",
              abs(tau - expected) < 0.1 * expected and m >= 5 * tau, f"{tau:.3f}, M = {m}")


def check_chi_square():
    # tables: chi2(0.05; 6) = 1.635, chi2(0.95; 6) = 12.592, chi2(0.05; 10) = 3.940,
    # chi2(0.95; 10) = 18.307, chi2(0.05; 12) = 5.226, chi2(0.95; 12) = 21.026
    table = ((0.05, 6, 1.635), (0.95, 6, 12.592), (0.05, 10, 3.940), (0.95, 10, 18.307), (0.05, 12, 5.226),
             (0.95, 12, 21.026))
    worst = max(abs(chi_square_quantile(p, dof) / value - 1) for p, dof, value in table)
    check("chi-square quantiles within 1 % of the tables", worst < 0.01, f"(worst {100 * worst:.2f} %)")
    low, high = spread_ratio_range(10)
    check("spread ratio range sqrt(chi2 / dof)", abs(high - math.sqrt(18.307 / 10)) < 0.005
          and abs(low - math.sqrt(3.940 / 10)) < 0.005, f"{low} {high}")


def check_student_t_and_equivalence():
    # closed forms: 1 degree of freedom (Cauchy) 1/2 + atan(t) / pi; 2: 1/2 + t / (2 sqrt(2 + t^2))
    cauchy = max(abs(student_t_cdf(t, 1) - (0.5 + math.atan(t) / math.pi)) for t in (-7.0, -0.3, 0.0, 1.1, 40.0))
    two = max(abs(student_t_cdf(t, 2) - (0.5 + t / (2 * math.sqrt(2 + t * t)))) for t in (-5.0, -0.4, 0.7, 3.0))
    check("Student's t CDF against its closed forms at 1 and 2 degrees of freedom", cauchy < 1e-13 and two < 1e-13,
          f"({cauchy:.1e}, {two:.1e})")
    # tables: t(0.95; 3) = 2.353, t(0.95; 6) = 1.943, t(0.975; 10) = 2.228, t(0.95; 30) = 1.697
    table = ((0.95, 3, 2.353), (0.95, 6, 1.943), (0.975, 10, 2.228), (0.95, 30, 1.697))
    worst = max(abs(student_t_quantile(p, dof) - value) for p, dof, value in table)
    check("Student's t quantiles within the tables' 0.0005", worst < 0.0005, f"(worst {worst:.5f})")
    # Welch by hand: [1, 2, 3, 4] (var 5/3, / 4) and [2, 4, 6] (var 4, / 3): d = -1.5,
    # e = sqrt(5/12 + 4/3) = sqrt(1.75), dof = 1.75^2 / ((5/12)^2 / 3 + (4/3)^2 / 2) = 3.23466
    w = welch_difference([1, 2, 3, 4], [2, 4, 6])
    check("Welch's difference, error and degrees of freedom by hand", close(w["mean"], -1.5)
          and close(w["error"], math.sqrt(1.75)) and abs(w["dof"] - 3.0625 / (25 / 144 / 3 + 16 / 9 / 2)) < 1e-12, str(w))
    # TOST by hand at 2 degrees of freedom: [1, -1] and [1.2, -0.8], both of variance 2: d =
    # -0.2, e = sqrt(2), dof 2. Tolerance 3: the one-sided p's 1 - F((3 - 0.2) / e) = 0.09314
    # and F((-0.2 - 3) / e) = 0.07600 (F the closed form above): p = 0.0931, not equivalent at
    # 0.05; the 90 % interval -0.2 -+ 2.91999 e reaches past -3.
    f2 = lambda t: 0.5 + t / (2 * math.sqrt(2 + t * t))
    e = equivalence_test([1, -1], [1.2, -0.8], 3.0)
    expected_p = max(1 - f2(2.8 / math.sqrt(2)), f2(-3.2 / math.sqrt(2)))
    check("equivalence test: p by hand (0.0931), not equivalent", abs(e["p"] - expected_p) < 1e-12
          and abs(expected_p - 0.09314) < 1e-5 and not e["equivalent"], str(e))
    check("equivalence test: the 90 % interval by hand (t(0.95; 2) = 2.91999)",
          abs(e["interval"][0] - (-0.2 - 2.919986 * math.sqrt(2))) < 1e-5 and e["interval"][0] < -3, str(e["interval"]))
    wide = equivalence_test([1, -1], [1.2, -0.8], 10.0)
    check("equivalence test: a wide tolerance is met, its interval inside it", wide["equivalent"]
          and -10 < wide["interval"][0] and wide["interval"][1] < 10, str(wide))
    check("equivalence test: a tolerance of 0 refused", raises(equivalence_test, [1, 2], [1, 3], 0.0) is not None)


def check_grid_convergence():
    # Celik et al. (2008), J. Fluids Eng. 130, 078001, Table 1, its first column: r_21 = 1.5,
    # r_32 = 1.333, phi = 6.063, 5.972, 5.863; published p = 1.53, phi_ext = 6.1685,
    # e_a = 1.5 %, e_ext = 1.7 %, GCI_fine = 2.2 %
    g = grid_convergence([1.0, 1.5, 2.0], [6.063, 5.972, 5.863])
    check("GCI: Celik et al. 2008 Table 1's column 1", round(g["order"], 2) == 1.53
          and round(g["extrapolated"], 4) == 6.1685 and round(100 * g["relative_error"], 1) == 1.5
          and round(100 * g["extrapolated_error"], 1) == 1.7 and round(100 * g["gci_fine"], 1) == 2.2
          and not g["oscillatory"], str(g))
    # phi = 1 + h^2 on h = 1, 2, 4: order 2, extrapolated 1 exactly; GCI 1.25 (3 / 2) / 3
    g = grid_convergence([1.0, 2.0, 4.0], [2.0, 5.0, 17.0])
    check("GCI: a second-order sequence by hand", abs(g["order"] - 2) < 1e-10 and abs(g["extrapolated"] - 1) < 1e-10
          and abs(g["gci_fine"] - 1.25 * 1.5 / 3) < 1e-10, str(g))
    check("GCI: oscillation named", grid_convergence([1.0, 2.0, 4.0], [1.0, 1.5, 1.2])["oscillatory"])
    check("GCI: two grids that agree exactly refused", raises(grid_convergence, [1, 2, 4], [1.0, 1.0, 2.0]) is not None)


def check_maps():
    heights = [0.05] * 3 + [0.25] * 3
    on_rows = ([(0.05, 1.0)], [(0.25, 1.0)])
    check("Delta p: bottom row mean minus upper row mean",
          numpy.allclose(section_pressure_drop([[100, 110, 120, 10, 20, 60], [5, 5, 5, 1, 2, 3]], heights, on_rows),
                         [80, 3]))
    # p at 0 m extrapolated from the rows at 0.05 and 0.25 m (weights 1.25, -0.25): 1.25 (110)
    # - 0.25 (30) = 130 and 1.25 (5) - 0.25 (2) = 5.75; the upper level on the upper row
    check("Delta p: a level extrapolated from two rows",
          numpy.allclose(section_pressure_drop([[100, 110, 120, 10, 20, 60], [5, 5, 5, 1, 2, 3]], heights,
                                               ([(0.05, 1.25), (0.25, -0.25)], [(0.25, 1.0)])), [100, 3.75]))
    check("Delta p: a sample of the wrong width refused",
          raises(section_pressure_drop, [[1, 2, 3, 4]], heights, on_rows) is not None)
    missing = raises(section_pressure_drop, [[1, 2, 3, 4, 5, 6]], heights, ([(0.15, 1.0)], [(0.25, 1.0)]))
    check("Delta p: a row the run did not probe named", missing is not None
          and "no pressure probe on the row at y = 0.15 m (probed: 0.05, 0.25 m)" in missing, str(missing))
    check("mirror mean", numpy.allclose(mirror_mean(numpy.array([[1.0, 2, 3], [4, 0, 6]])), [[2, 2, 2], [5, 0, 5]]))
    maps = [numpy.full((2, 2), v) for v in (0.0, 0.1, 0.3)]
    maps[2][1] = 9.0  # the second row differs wildly: left out with rows = 1
    check("pairwise L1 in order (0,1), (0,2), (1,2)", numpy.allclose(pairwise_l1(maps, rows=1), [0.1, 0.3, 0.2]))
    floor = l1_noise_floor(maps, rows=1)
    check("noise floor: mean, min, max of the pairs",
          close(floor["mean"], 0.2, 1e-9) and close(floor["min"], 0.1, 1e-9) and close(floor["max"], 0.3, 1e-9)
          and floor["pairs"] == 3, str(floor))
    check("noise floor of one map refused", raises(l1_noise_floor, maps[:1]) is not None)
    check("cross L1: every pair across", numpy.allclose(cross_l1(maps[:1], maps[1:], rows=1), [0.1, 0.3]))
    zeros, ones = [numpy.zeros((2, 2))] * 4, [numpy.ones((2, 2))] * 4
    test = l1_permutation_test(zeros, ones)
    # only the true split and its swap reach the largest statistic 1 - 0: p = 2 / C(8, 4)
    check("permutation test: separated maps, p = 2/70", close(test["statistic"], 1.0) and close(test["p"], 2 / 70)
          and test["relabellings"] == 70, str(test))
    test = l1_permutation_test(zeros, zeros)
    check("permutation test: identical maps, p = 1", close(test["statistic"], 0.0) and test["p"] == 1.0, str(test))


def write(path, text):
    os.makedirs(os.path.dirname(path), exist_ok=True)
    with open(path, "w") as f:
        f.write(text)


def check_bed_outputs(root):
    """A 3 x 3 grid of 1 x 10 cm cells (rows of centres at 5, 15 and 25 cm): Delta p from the
    inlet (y = 0) to 20 cm read through BedOutputs from hand-written probe files. By hand: the
    rows' means 110, 60, 30 Pa (then 8, 5, 2): p at 0 extrapolated from the first two rows,
    1.5 (110) - 0.5 (60) = 135 (9.5); p at 20 cm midway between the second and third, 45 (3.5):
    Delta p 90 and 6 Pa."""
    case_dir = os.path.join(root, "bed_case")
    write(os.path.join(case_dir, "system", "blockMeshDict"),
          "convertToMeters 1;\nvertices\n(\n    (0 0 0) (0.03 0 0) (0.03 0.3 0) (0 0.3 0)\n"
          "    (0 0 0.01) (0.03 0 0.01) (0.03 0.3 0.01) (0 0.3 0.01)\n);\n"
          "blocks\n(\n    hex (0 1 2 3 4 5 6 7) (3 3 1) simpleGrading (1 1 1)\n);\n")
    write(os.path.join(case_dir, "system", "controlDict"), "deltaT 0.001;\nendTime 1;\n")
    case = Case(case_dir)
    write_bed_probes(case, 0.05, 0.01)
    text = open(case.file("system", "controlDict")).read()
    check("probes: the rows either side of the inlet's and 20 cm's levels, 5, 15 and 25 cm", "(0.005 0.25 0.005)" in text
          and "(0.025 0.05 0.005)" in text and "(0.015 0.15 0.005)" in text and "writeInterval 10;" in text)
    post = os.path.join(case_dir, "postProcessing")
    rows = "".join(f"# Probe {k} ({x} {y} 0.005)\n" for k, (y, x) in enumerate(
        (y, x) for y in (0.05, 0.15, 0.25) for x in (0.005, 0.015, 0.025)))
    write(os.path.join(post, "studyPressure", "0", "p"),
          rows + "# Time p\n0.01 100 110 120 50 60 70 10 20 60\n0.02 7 8 9 4 5 6 1 2 3\n")
    cells = "".join(f"# Probe {k} ({c[0]} {c[1]} {c[2]})\n" for k, c in enumerate(case.grid().centres()))
    for field in ("voidFraction", "contactForceByWeight", "dragForceByWeight"):
        write(os.path.join(post, "studyFields", "0", field), cells + "# Time\n0.05" + " 0.5" * 9 + "\n")
    write(os.path.join(post, "tfdemParticles", "0", "particles.dat"), "# t\n0.01 10 0.1 0.05 1.0 0.5\n")
    d = BedOutputs(case)
    check("BedOutputs: Delta p from the inlet to 20 cm, 90 and 6 Pa", numpy.allclose(d.dp, [90, 6])
          and numpy.allclose(d.p_t, [0.01, 0.02]) and numpy.allclose(d.levels, [0.0, 0.2]), f"{d.dp} {d.levels}")
    d = BedOutputs(case, dp_from="bottom_row")
    # by hand: the rows at 5 and 25 cm, means 110 and 30 Pa (then 8 and 2): 80 and 6 Pa
    check("BedOutputs: Delta p from the bottom row (5 cm) to 20 cm above it (25 cm), 80 and 6 Pa",
          numpy.allclose(d.dp, [80, 6]) and numpy.allclose(d.levels, [0.05, 0.25]), f"{d.dp} {d.levels}")
    bad = raises(BedOutputs, case, dp_from="plate")
    check("BedOutputs: an unknown dp_from refused, the choices named", bad is not None and "inlet, bottom_row" in bad,
          str(bad))
    # the same case's layout of before 2026-12-07, two rows at 5 and 25 cm: refused, named
    rows = "".join(f"# Probe {k} ({x} {y} 0.005)\n" for k, (y, x) in enumerate(
        (y, x) for y in (0.05, 0.25) for x in (0.005, 0.015, 0.025)))
    write(os.path.join(post, "studyPressure", "0", "p"), rows + "# Time p\n0.01 100 110 120 10 20 60\n")
    d = BedOutputs(case, dp_from="bottom_row")
    check("BedOutputs: the old two rows read from the bottom row, as they were measured: 110 - 30 = 80 Pa",
          numpy.allclose(d.dp, [80]), f"{d.dp}")
    old = raises(BedOutputs, case)
    check("BedOutputs: a run probed on the old two rows refused, the fix named", old is not None
          and "no pressure probe on the row at y = 0.15 m" in old and "prepare and run it again" in old, str(old))


def hand_record(name, counts, spacing, maps, tfm=False, dp_from="inlet"):
    """A record with a flat series and the given {window: {field: map}}."""
    meta = {"name": name, "tfm": tfm, "wall_seconds": 10.0, "cpu_seconds": 9.0,
            "grid": {"counts": list(counts), "origin": [0.0, 0.0], "spacing": list(spacing)}, "windows": [],
            "dp_from": dp_from}
    t = numpy.array([0.0, 0.5, 1.0])
    heights = {"t": t, "mean_height": numpy.array([0.1, 0.1, 0.1])}
    if not tfm:
        heights.update(bulk_coordination=numpy.ones(3), multicontact=numpy.ones(3), particles=numpy.full(3, 10.0))
    return Record(name, meta, (t, numpy.array([1.0, 2.0, 3.0])), heights,
                  {k: {f: numpy.asarray(v, dtype=float) for f, v in fields.items()} for k, fields in maps.items()})


def check_ratio_numbers():
    # 5 x 4 cells of 2 cm: x 1, 3, 5, 7, 9 cm, y 1, 3, 5, 7 cm; corners x < 4 or x > 6 cm and
    # y < 6 cm; the top row is not bed (solids 0.05), the cell (row 2, column 2) has no drag
    ratio = numpy.array([[20, 3, 30, 1, 12], [4, 6, 8, 2, 9], [3, 3, 3, 3, 3], [100, 100, 100, 100, 100]], float)
    drag = numpy.full((4, 5), 2.0)
    drag[2, 2] = 0.0
    solids = numpy.full((4, 5), 0.5)
    solids[3] = 0.05
    d = hand_record("ratio", (5, 4), (0.02, 0.02), {"0-1": {"solids": solids, "contact": 2 * ratio, "drag": drag}})
    r = report.Report.ratio_numbers(None, d, 0, 1)
    # bed values 20 3 30 1 12 4 6 8 2 9 3 3 3 3: 10 of 14 in [2, 10]; median (3 + 4) / 2
    check("ratio_numbers: share of bed cells in 2-10", close(r["share_2_to_10"], 10 / 14), str(r))
    check("ratio_numbers: median and largest over the bed", close(r["median"], 3.5) and close(r["largest"], 30))
    check("ratio_numbers: largest in the bottom corners", close(r["largest_in_corners"], 20))


def check_missing_window_named():
    r = hand_record("c", (2, 3), (0.1, 0.2), {"0-1": {"solids": [[0.5, 0.5], [0.3, 0.3], [0.0, 0.0]]}})
    try:
        r.window_map("solids", 2, 3)
        check("a window the record does not keep is named", False)
    except RecordError as e:
        check("a window the record does not keep is named", "c: no solids map over 2-3 s" in str(e), str(e))


def check_record(root):
    maps = {"0-1": {"solids": [[0.1, 0.2], [0.3, 0.4]], "contact": [[1, 2], [3, 4]], "drag": [[5, 6], [7, 8.5]]}}
    record = hand_record("run_a", (2, 2), (0.1, 0.1), maps)
    folder = os.path.join(root, "results", "run_a")
    record.write(folder)
    back = Record.read(folder, "run_a")
    check("record read back: series", numpy.allclose(back.dp, [1, 2, 3]) and numpy.allclose(back.p_t, [0, 0.5, 1])
          and numpy.allclose(back.particles["multicontact"], 1.0))
    check("record read back: maps", all(numpy.allclose(back.window_map(f, 0, 1), maps["0-1"][f]) for f in maps["0-1"]))
    check("record read back: grid centres", numpy.allclose(back.x, [[0.05, 0.15]] * 2)
          and numpy.allclose(back.y[:, 0], [0.05, 0.15]) and close(back.width, 0.2))
    check("record read back: Delta p from the inlet, by its header", back.dp_from == "inlet")
    rows = hand_record("run_b", (2, 2), (0.1, 0.1), maps, dp_from="bottom_row")
    rows.write(os.path.join(root, "results", "run_b"))
    header = open(os.path.join(root, "results", "run_b", "pressure.csv")).readline().strip()
    check("record: Delta p from the bottom row says so in its header, and is read back so",
          header == "t (s),dp 20 cm (Pa): p(bottom row) - p(row 20 cm above)"
          and Record.read(os.path.join(root, "results", "run_b"), "run_b").dp_from == "bottom_row", header)
    os.remove(os.path.join(folder, "maps.csv"))
    try:
        Record.read(folder, "run_a")
        check("a missing record file is named with its run", False)
    except RecordError as e:
        check("a missing record file is named with its run", "run_a" in str(e) and "maps.csv" in str(e), str(e))


def check_dp_levels_compared():
    """replicates.Replicates refuses Delta p compared between runs measured from different
    levels: within a configuration's realizations, and between two configurations."""
    from replicates import Replicates
    maps = {"0-1": {"solids": [[0.5]]}}

    class FakeReport:
        windows, end_time = [(0.0, 1.0)], 1.0
        study = {"end_time": 1.0, "realizations": {"runs": ["a", "b"], "seeds": [10007, 10009]},
                 "runs": {"a": {}, "b": {}}}

        def __init__(self, levels):
            self.records = {f"{c}_r{k}": hand_record(f"{c}_r{k}", (1, 1), (0.1, 0.1), maps, dp_from=levels[c][k - 1])
                            for c in levels for k in (1, 2)}

    same = Replicates(FakeReport({"a": ("inlet", "inlet"), "b": ("inlet", "inlet")}), {})
    check("Delta p from the same level: compared", raises(same.same_dp, "a", "b") is None)
    across = Replicates(FakeReport({"a": ("inlet", "inlet"), "b": ("bottom_row", "bottom_row")}), {})
    message = raises(across.same_dp, "a", "b")
    check("Delta p from the inlet against the bottom row: refused, both named, the fix given",
          message is not None and "a: inlet" in message and "b: bottom_row" in message and "dp_from" in message,
          str(message))
    mixed = raises(Replicates, FakeReport({"a": ("inlet", "bottom_row"), "b": ("inlet", "inlet")}), {})
    check("realizations of one configuration from different levels: refused, named",
          mixed is not None and "a_r1: inlet" in mixed and "a_r2: bottom_row" in mixed, str(mixed))


def check_fig8_numbers():
    # 5 x 3 cells of 2 cm (x 1, 3, 5, 7, 9 cm; y 1, 3, 5 cm); the axis x = 5 cm is column 2
    field = numpy.array([[0.6, 0.5, 0.1, 0.4, 0.6], [0.5, 0.4, 0.2, 0.4, 0.5], [0.3, 0.3, 0.3, 0.3, 0.3]])
    r = hand_record("f8", (5, 3), (0.02, 0.02), {"0-1": {"solids": field}})
    check("axis profile: the mid-plane column at the nearest row centres",
          numpy.allclose(headline.axis_profile(field, r, (0.01, 0.035, 0.05)), [0.1, 0.2, 0.3]))
    # corners x < 3 cm or x > 7 cm, y < 4 cm: columns 0 and 4 of rows 0-1: 0.6 0.6 0.5 0.5
    check("corner mean", close(headline.corner_mean(field, r, 0.03, 0.04), 0.55))
    # |row - mirror|: row 0 |0.6-0.6| |0.5-0.4| 0 |0.4-0.5| 0 -> 0.2 / 5; row 1 0; row 2 0 -> 0.04 / 3
    check("mirror L1", close(headline.mirror_l1(field, r), 0.2 / 15))
    even = hand_record("even", (4, 1), (0.02, 0.02), {"0-1": {"solids": [[0.1, 0.2, 0.4, 0.8]]}})
    check("axis profile on a face: the two columns beside it",
          numpy.allclose(headline.axis_profile(numpy.array([[0.1, 0.2, 0.4, 0.8]]), even, (0.01,)), [0.3]))


def check_pairs_and_blocks():
    d = {"mean": 0.002, "error": 0.001, "in_errors": 2.0}
    result = {"maps": {"comparisons": {"a vs b": {"5-20": {"cross_mean": 0.02, "within_mean": 0.01,
                                                           "cross_over_within": 2.0, "permutation": {"p": 0.029}}}}},
              "differences": {"fine - coarse": {"b - a": {"5-20": {
                  "mean_height mean": d, "dp20 mean": {"mean": -30.0, "error": 10.0, "in_errors": -3.0},
                  "dp20 std": {"mean": 5.0, "error": 5.0, "in_errors": 1.0},
                  "bulk_coordination mean": {"mean": 0.1, "error": 0.05, "in_errors": 2.0}}}}}}
    row = headline.pair_lines(result, "5-20")[-1]
    check("pairs table: the row's maps and differences (height in cm)",
          row == "| fine - coarse | `b` − `a` | 0.0200 (0.0100; 2.00; 0.029) | +0.20 ± 0.10 (+2.0) | "
                 "-30 ± 10 (-3.0) | +5.0 ± 5.0 (+1.0) | +0.100 ± 0.050 (+2.0) |", row)
    result["configurations"] = {"a": ["a_r1", "a_r2", "a_r3", "a_r4"], "b": ["b_r1", "b_r2"]}
    row = headline.pair_lines(result, "5-20")[-1]
    check("pairs table: a configuration of other than four realizations names its n",
          row.startswith("| fine - coarse | `b` (n = 2) − `a` | "), row)
    timing = {"DEM": 4.0, "locate+map": 0.5, "forces": 0.25, "gas": 1.0, "statistics": 0.125, "checkpoints": 0.125,
              "segments": 2, "segments_timed": 2}
    check("statistics' share: 0.125 s of the 6 s timed = 2.0833 %, the segment counts not summed",
          close(headline.statistics_share(timing), 100 * 0.125 / 6), str(headline.statistics_share(timing)))
    begin, end = headline.markers("the x")
    text = f"top\n{begin}\nold\n{end}\nbottom\n"
    check("replace_block: the block between the markers, the rest kept",
          headline.replace_block(text, "the x", ["new"]) == f"top\n{begin}\n\nnew\n\n{end}\nbottom\n")
    message = raises(headline.replace_block, "no markers", "the x", ["new"])
    check("replace_block: missing markers named", message is not None and "the x" in message, str(message))


def block(text, name):
    begin, end = headline.markers(name)
    return text[text.index(begin):text.index(end)]


def check_readme_is_the_report(root):
    """The study README's generated tables against a report made now from the committed records
    (a copy of results/, no run folder): a hand edit or a stale table fails."""
    results = os.path.join(root, "results_copy")
    shutil.copytree(os.path.join(STUDY, "results"), results)
    readme = os.path.join(root, "README.md")
    shutil.copy(os.path.join(STUDY, "README.md"), readme)
    study = study_definition.load_study(os.path.join(STUDY, "study.yaml"))
    runs = [type("Run", (), {"name": r.name, "done": lambda self: False})()
            for r in study_definition.selected_runs(study, [], root)]
    report.write_report(study, runs, study["end_time"], os.path.join(root, "report"), results, readme)
    with open(readme) as f:
        made = f.read()
    with open(os.path.join(STUDY, "README.md")) as f:
        committed = f.read()
    for name in (headline.HEADLINE, headline.PAIRS, headline.REPLICATES):
        check(f"study README: {name} is the report's from results/", block(made, name) == block(committed, name))


def main():
    root = tempfile.mkdtemp()
    check_fig8_numbers()
    check_pairs_and_blocks()
    check_readme_is_the_report(root)
    check_refined_runs()
    check_ensemble()
    check_blocking()
    check_autocorrelation()
    check_chi_square()
    check_student_t_and_equivalence()
    check_grid_convergence()
    check_maps()
    check_bed_outputs(root)
    check_dp_levels_compared()
    check_ratio_numbers()
    check_missing_window_named()
    check_record(root)
    print(f"{'FAILED: ' + ', '.join(failures) if failures else 'all passed'}")
    sys.exit(1 if failures else 0)


if __name__ == "__main__":
    main()
