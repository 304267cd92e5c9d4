"""Seed 000's study pipeline end to end on a short run (studies/seed000).

1. `study.py run` and `report` on the uniform bed, TF-DEM (method 1) and the TFM peer, 0.2 s
   each (windows and intervals scale with the end time): every figure the two runs allow, the
   README table and the runs' records (results/<run>/: CSVs, maps, run.json) are written and
   every statistic is finite; the report made again from the records alone (no runs/, as a
   clone) gives the same numbers.
2. A study stopped by SIGTERM stops its solver (no orphan left running) and exits 130; a
   second study on the same runs while one is running refuses, naming the process; run again,
   the stopped run finishes.
3. Bad input, each a clear message: an unknown study name (./tfdem study); no
   twoPhaseEulerFoam on PATH; a run that fails (cells 1 mm tall, 2.5 mm particles, with
   the centroid mapping stop at t = 0) -- the study exits 1 naming it, the other run finishes
   and keeps its results, and the report covers it.
"""
import json
import math
import os
import re
import shutil
import signal
import subprocess
import time

import numpy
import yaml

from tfdem import SOURCE_DIR, STUDIES, outputs
from tfdem.case import Case
from tfdem.run import environment
from tfdem_testlib import Checks, scratch

STUDY = os.path.join(STUDIES, "seed000")


def study(args, env=None):
    proc = subprocess.run(["/usr/bin/python3", os.path.join(STUDY, "study.py")] + args, env=env or environment(),
                          stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True, errors="replace")
    print(proc.stdout[-3000:])
    return proc.returncode, proc.stdout


def check_pipeline(checks):
    root = scratch("study_quick")
    args = ["--runs", "uniform_m1,uniform_tfm", "--end-time", "0.2", "--root", root]
    code, _ = study(["run"] + args)
    checks.true("quick study ran", code == 0, f"(exit code {code})")
    code, output = study(["report"] + args)
    checks.true("report written, every statistic finite", code == 0 and "NOT FINITE" not in output, f"(exit code {code})")
    report = os.path.join(root, "report")
    for name in ("README.md", "numbers.json", "fig5_coordination.png", "fig9_uniform_mean_height.png",
                 "fig10_uniform_particles.png", "fig11_multicontact.png", "fig12_uniform_forces.png",
                 "fig13_uniform_methods.png"):
        path = os.path.join(report, name)
        checks.true(f"report/{name} written", os.path.isfile(path) and os.path.getsize(path) > 0)
    for name in [os.path.join(run, f) for run in ("uniform_m1", "uniform_tfm")
                 for f in ("run.json", "pressure.csv", "particles.csv", "maps.csv")] + ["numbers.json", "README.md"]:
        path = os.path.join(root, "results", name)
        checks.true(f"results/{name} written", os.path.isfile(path) and os.path.getsize(path) > 0)
    check_from_records(checks, root, args)
    check_granular_temperature(checks, os.path.join(root, "runs", "uniform_m1"))
    check_tfm_budget(checks, os.path.join(root, "runs", "uniform_tfm"))
    if os.path.isfile(os.path.join(report, "numbers.json")):
        theta = json.load(open(os.path.join(report, "numbers.json"))).get("granular_temperature", {})
        ratio = theta.get("uniform", {}).get("tfm_over_tfdem", float("nan"))
        checks.true("the report compares the TFM's Theta with the particles' (uniform bed)",
                    math.isfinite(ratio) and ratio > 0, f"(TFM / TF-DEM {ratio})")
    if os.path.isfile(os.path.join(report, "numbers.json")):
        numbers = json.load(open(os.path.join(report, "numbers.json")))
        m1 = numbers["runs"]["uniform_m1"]["0.05-0.1"]
        for key in ("mean_height", "bulk_coordination", "multicontact", "dp20"):
            checks.true(f"uniform_m1 {key} has a mean and an error", m1[key]["mean"] == m1[key]["mean"]
                        and m1[key]["error"] == m1[key]["error"], f"({m1[key]})")
    code, output = study(["run"] + args)
    checks.true("a second run skips the finished runs", code == 0 and output.count("skipped") == 2)


def check_granular_temperature(checks, run):
    """The solver's granularTemperature field at its last write time against seed 000 eq. 6
    recomputed here from that time's particle file: per cell of the 1 cm grid, the volume-
    weighted <|v|^2> - |<v>|^2 over 3 of the particles whose centre is in it."""
    case = Case(run)
    last = [t for t in outputs.times(run) if float(t) > 0][-1]
    theirs = numpy.array(outputs.field(run, last, "granularTemperature"))
    particles = outputs.vtk_particles(os.path.join(run, "VTK", f"particles_{last}.vtk"))
    grid = case.grid()
    x, v = numpy.array(particles["position"]), numpy.array(particles["velocity"])
    volume = numpy.array(particles["diameter"]) ** 3
    ij = numpy.floor((x[:, :2] - numpy.array(grid.origin[:2])) / numpy.array(grid.spacing[:2])).astype(int)
    cell = ij[:, 1] * grid.counts[0] + ij[:, 0]
    ours = numpy.zeros(grid.counts[0] * grid.counts[1])
    for c in numpy.unique(cell):
        pick = cell == c
        w = volume[pick] / volume[pick].sum()
        mean = (w[:, None] * v[pick]).sum(axis=0)
        ours[c] = max(0.0, (w * (v[pick] ** 2).sum(axis=1)).sum() - mean @ mean) / 3.0
    scale = float(ours.max())
    worst = float(numpy.max(numpy.abs(theirs - ours))) if theirs.size == ours.size else float("inf")
    checks.true(f"granularTemperature at {last} s = eq. 6 from the particle file, cell by cell",
                scale > 0 and worst <= 1e-6 * scale, f"(largest difference {worst:.2e} of a largest "
                f"{scale:.3e} m^2/s^2; {int((ours > 0).sum())} cells with a fluctuation)")


def check_tfm_budget(checks, run):
    """tfm_budget.py on the short TFM run: it runs, writes a row per cell row, and the solids'
    weight per area it reads from the fields is Table 1's, N pi d^2/6 (rho_p - rho_g) g / W
    with N = 4000, d = 2.5 mm, rho_p = 2526, rho_g = 1.2 kg/m^3, W = 0.15 m: 2161.4 Pa."""
    proc = subprocess.run(["/usr/bin/python3", os.path.join(STUDY, "tfm_budget.py"), run, "--from", "0"],
                          env=environment(), stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    print(proc.stdout[-2000:])
    checks.true("tfm_budget.py on the TFM run", proc.returncode == 0, f"(exit code {proc.returncode})")
    rows = open(os.path.join(run, "tfm_budget.csv")).read().splitlines() if proc.returncode == 0 else []
    checks.true("... a budget row per row of cells (45)", len(rows) == 46, f"({len(rows)} lines)")
    weight = 4000 * math.pi * 0.0025 ** 2 / 6 * (2526 - 1.2) * 9.81 / 0.15
    found = re.search(r"weight per area \((\d+) Pa\)", proc.stdout)
    checks.true(f"... the solids' weight per area {weight:.1f} Pa", found is not None
                and abs(float(found.group(1)) - weight) <= 1.0, f"({found.group(1) if found else 'not printed'})")


def check_from_records(checks, root, args):
    """The report from the records alone (a root with results/ and no runs/) gives the same
    numbers as from the run folders."""
    clone = scratch("study_records_only")
    shutil.copytree(os.path.join(root, "results"), os.path.join(clone, "results"))
    code, output = study(["report"] + args[:-1] + [clone])
    checks.true("report from the records alone", code == 0 and "NOT FINITE" not in output, f"(exit code {code})")
    try:
        first = json.load(open(os.path.join(root, "report", "numbers.json")))["runs"]
        again = json.load(open(os.path.join(clone, "report", "numbers.json")))["runs"]
    except (OSError, ValueError) as e:
        checks.true("numbers.json of both reports", False, str(e))
        return
    checks.true("... the same numbers as from the run folders", first == again)


def check_bad_input(checks):
    code = subprocess.run([os.path.join(SOURCE_DIR, "tfdem"), "study", "seed0"], stdout=subprocess.PIPE,
                          stderr=subprocess.STDOUT, text=True)
    checks.true("unknown study name", code.returncode == 2 and re.search(r"unknown study 'seed0'; studies: .*\bseed000\b", code.stdout) is not None,
                f"(exit code {code.returncode})")

    env = environment()
    env["PATH"] = os.path.join(SOURCE_DIR, "build", "nothing-here")
    root = scratch("study_no_tfm")
    code, output = study(["run", "--runs", "uniform_tfm", "--end-time", "0.2", "--root", root], env)
    checks.true("no twoPhaseEulerFoam", code == 2 and "twoPhaseEulerFoam is not on PATH" in output, f"(exit code {code})")

    root = scratch("study_failing_run")
    definition = yaml.safe_load(open(os.path.join(STUDY, "study.yaml")))
    definition["runs"] = {"uniform_m1": {"bed": "uniform"}, "uniform_small_cells": {"bed": "uniform", "refine_y": 10}}
    definition.pop("realizations")
    path = os.path.join(root, "study.yaml")
    yaml.safe_dump(definition, open(path, "w"))
    args = ["--end-time", "0.2", "--root", root, "--study", path]
    code, output = study(["run"] + args)
    checks.true("a failing run makes the study exit 1", code == 1, f"(exit code {code})")
    checks.true("the failing run is named with its cause", "uniform_small_cells: tfdemFoam failed" in output
                and "fill it: gas fraction" in output)
    checks.true("the other run finished", "uniform_m1: finished" in output)
    code, output = study(["report"] + args)
    checks.true("the report covers the finished run", code == 0 and "1 runs" in output, f"(exit code {code})")
    bad_key = dict(definition)
    bad_key["runs"] = {"uniform_m1": {"bed": "uniform", "refine": 2}}
    yaml.safe_dump(bad_key, open(path, "w"))
    code, output = study(["run"] + args)
    checks.true("a misspelt run key", code == 2 and "unknown key 'refine' (did you mean 'refine_y'?)" in output)
    realized = dict(definition, runs={"uniform_m1": {"bed": "uniform"}, "uniform_m2": {"bed": "uniform"}},
                    realizations={"runs": ["uniform_m1", "uniform_m2"], "seeds": [15485863], "lattice": ["uniform_m1"]})
    yaml.safe_dump(realized, open(path, "w"))
    code, output = study(["status", "--root", root, "--study", path])
    listed = [line.split()[0] for line in output.splitlines() if line.strip()]
    checks.true("realizations.lattice: only its runs run from the lattice too",
                code == 0 and listed == ["uniform_m1", "uniform_m1_r1", "uniform_m2_r1"], str(listed))
    code, output = study(["run", "--runs", "uniform_m2"] + args[2:])
    checks.true("a run made only as realizations is refused by name, with the fix",
                code == 2 and "uniform_m2: run only as realizations (uniform_m2_r1" in output
                and "realizations.lattice" in output, output[-300:])
    yaml.safe_dump(dict(realized, realizations=dict(realized["realizations"], lattice=["uniform_m3"])), open(path, "w"))
    code, output = study(["status", "--root", root, "--study", path])
    checks.true("a misspelt lattice run", code == 2 and "realizations.lattice: no run 'uniform_m3' (did you mean" in output,
                output[-300:])


def alive(pid):
    try:
        os.kill(pid, 0)
        return True
    except ProcessLookupError:
        return False


def check_interrupt(checks):
    root = scratch("study_interrupt")
    args = ["run", "--runs", "uniform_m1", "--end-time", "0.2", "--root", root]
    first = subprocess.Popen(["/usr/bin/python3", os.path.join(STUDY, "study.py")] + args, env=environment(),
                             stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    status_file = os.path.join(root, "runs", "uniform_m1", "study.status.json")
    pid, deadline = None, time.monotonic() + 120
    while pid is None and time.monotonic() < deadline and first.poll() is None:
        time.sleep(0.5)
        try:
            pid = json.load(open(status_file)).get("pid")
        except (OSError, ValueError):
            pass
    checks.true("the solver started", pid is not None)
    if pid is None:
        first.kill()
        return
    code, output = study(args)
    checks.true("a second study on a running run refuses, naming it",
                code == 2 and f"uniform_m1 (process {pid})" in output, f"(exit code {code})")
    first.send_signal(signal.SIGTERM)
    output = first.communicate(timeout=60)[0]
    print(output[-2000:])
    checks.true("SIGTERM stops the study with exit code 130", first.returncode == 130, f"(exit code {first.returncode})")
    checks.true("... and its solver", not alive(pid), f"(process {pid})")
    checks.true("... saying the runs resume", "resume from their last checkpoint" in output)
    checks.true("the run is marked stopped", json.load(open(status_file)).get("state") == "stopped")
    code, output = study(args)
    checks.true("run again, the stopped run finishes", code == 0 and "uniform_m1: finished" in output,
                f"(exit code {code})")


def main():
    checks = Checks()
    check_pipeline(checks)
    check_interrupt(checks)
    check_bad_input(checks)
    checks.finish()


if __name__ == "__main__":
    main()
