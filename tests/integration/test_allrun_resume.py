"""A case `tfdem new` wrote, run with its own Allrun on 2 ranks (the gas whole), the way a user
runs it, stopped and resumed with nothing but Allrun:

1. Straight: `Allrun 2` to the end (0.1 s, writes every 0.05 s): exit 0, summary.csv and
   summary.png named in its last lines.
2. Stopped as Ctrl-C does (SIGINT to Allrun's process group) once past 0.02 s: the run writes a
   checkpoint where its ranks agree and Allrun exits 75, saying how to carry on (by the path
   it was run as); the terminal names the signal sent once (not the SIGTERM and SIGUSR1
   passed on inside) and the time the run stopped at. Then a time
   folder written after that checkpoint and never completed (as a run killed while writing
   leaves, 1 ms after it) is planted; `Allrun 2` again moves it aside into incomplete/ (kept, not deleted),
   carries on from the checkpoint and ends at 0.1 s with the straight run's write times and
   its fields and DEM state at 0.1 s byte for byte.
3. Stopped by `timeout -s TERM`, a time limit half-way between the wall times at which the
   straight run passed 0.02 s and 0.08 s: the same, exit 124 from timeout with the checkpoint
   written.
4. A mistake in coupling.yaml on 2 ranks: Allrun exits non-zero and its terminal output (not
   only the log) holds the solver's message with the key and the nearest valid name.
"""
import os
import re
import shutil
import signal
import subprocess
import time

from tfdem.case import Case
from tfdem.newcase import derive, load_bed, write_case
from tfdem.packing import pack_case
from tfdem.run import environment
from tfdem_testlib import Checks, run, scratch

BED = """box: {width: 0.03, height: 0.1, depth: one_layer}
particles: {density: 2500, sizes: [{diameter: 0.001, number: 400}], restitution: 0.9, friction: 0.1}
gas: {density: 1.2, viscosity: 1.8e-5}
inflow: {velocity: 0.9}
run: {end_time: 0.1, write_interval: 0.05}
"""
RANKS = "2"


def generated(name, template=None):
    """A generated and poured case under build/test-runs/name (a copy of `template` when given)."""
    root = scratch(name)
    case = os.path.join(root, "case")
    if template:
        shutil.copytree(template, case, symlinks=True)
        return case
    source = os.path.join(root, "bed.yaml")
    with open(source, "w") as f:
        f.write(BED)
    bed = load_bed(source)
    write_case(case, bed, derive(bed, source), source)
    print(pack_case(case, runner=lambda *a, **k: run(*a[:3])))
    return case


def solver_times(case):
    log = os.path.join(case, "log.tfdemFoam")
    text = open(log, errors="replace").read() if os.path.isfile(log) else ""
    return [float(t) for t in re.findall(r"\nTime = (\S+)\n", text)]


def allrun(case, prefix=(), stop_after=None, clock=None):
    """Run the case's Allrun on RANKS ranks (after `prefix`, a command such as timeout) in its own
    process group; with stop_after, SIGINT to the group (Ctrl-C) once the solver's log reaches
    that time; with clock (a dict), the wall seconds from the start at which the solver's log first
    reached each simulated time in it. (exit code, terminal output)."""
    start = time.monotonic()
    proc = subprocess.Popen(list(prefix) + [os.path.join(case, "Allrun"), RANKS], cwd=case, env=environment(),
                            stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True, errors="replace",
                            start_new_session=True)
    if stop_after is not None or clock is not None:
        while proc.poll() is None:
            times = solver_times(case)
            if clock is not None:
                for t in clock:
                    if clock[t] is None and times and times[-1] >= t:
                        clock[t] = time.monotonic() - start
            if stop_after is not None and times and times[-1] >= stop_after:
                os.killpg(proc.pid, signal.SIGINT)
                break
            time.sleep(0.05)
    output, _ = proc.communicate()
    return proc.returncode, output


def written(case):
    return sorted(float(t) for t in os.listdir(case) if re.fullmatch(r"0\.[0-9]+", t))


def same_state(checks, label, straight, case):
    for name in ("p", "U", "voidFraction", "dem.restart"):
        a, b = os.path.join(straight, "0.1", name), os.path.join(case, "0.1", name)
        checks.true(f"{label}: 0.1/{name} as the straight run's, byte for byte",
                    os.path.isfile(b) and open(a, "rb").read() == open(b, "rb").read())


def stopped_and_resumed(checks, template, straight, label, prefix, expected_code, named, stop_after=None):
    others = [s for s in ("SIGINT", "SIGTERM", "SIGUSR1") if s not in named]
    case = generated(f"allrun_{label}", template=template)
    code, output = allrun(case, prefix, stop_after=stop_after)
    stop = re.search(r"stopped at t = (\S+) s", open(os.path.join(case, "log.tfdemFoam")).read())
    checks.true(f"{label}: exit {expected_code}, a checkpoint written", code == expected_code and stop is not None
                and os.path.isfile(os.path.join(case, stop.group(1), "tfdem.checkpoint")), f"(exit {code})\n{output[-800:]}")
    if not stop:
        return
    allrun_path = os.path.join(case, "Allrun")
    checks.true(f"{label}: Allrun says how to carry on, by the path it was run as",
                f"{allrun_path} {RANKS} carries on from it" in output, output[-400:])
    checks.true(f"{label}: the terminal names the signal sent ({named}) once and no other, and where the run stopped",
                output.count(f"{named} received") == 1 and all(other not in output for other in others)
                and f"stopped at t = {stop.group(1)} s, its fields and checkpoint written" in output, output[-1200:])
    # a time folder after the checkpoint, as a killed run leaves; not one the resumed run writes
    # itself (a stop at 0.049 s would plant 0.05, a write time, and the run's own 0.05 replace it)
    planted_name = next(name for name in (f"{float(stop.group(1)) + step:g}" for step in (0.001, 0.002))
                        if float(name) not in written(straight))
    planted = os.path.join(case, planted_name)
    os.makedirs(planted)
    open(os.path.join(planted, "dem.restart.tmp"), "w").write("cut short")
    code, output = allrun(case)
    checks.true(f"{label}: Allrun again: exit 0", code == 0, output[-1500:])
    checks.true(f"{label}: the half-written {planted_name} moved aside, kept",
                not os.path.exists(planted) and os.path.isfile(os.path.join(case, "incomplete", planted_name,
                                                                            "dem.restart.tmp")), output[-600:])
    checks.true(f"{label}: resumed from the stop", f"resuming from the checkpoint at t = {stop.group(1)} s" in output,
                output[:600])
    checks.true(f"{label}: the straight run's write times and the stop's",
                written(case) == sorted(set(written(straight) + [float(stop.group(1))])), f"({written(case)})")
    same_state(checks, label, straight, case)


def main():
    checks = Checks()
    template = generated("allrun_template")
    straight = generated("allrun_straight", template=template)
    clock = {0.02: None, 0.08: None}
    code, output = allrun(straight, clock=clock)
    last = output.strip().splitlines()[-2:]
    checks.true("straight: Allrun 2 exit 0", code == 0, output[-1500:])
    checks.true("straight: summary.csv and summary.png named last and written",
                any("summary.csv" in line for line in last) and any("summary.png" in line for line in last)
                and all(os.path.isfile(os.path.join(straight, f)) for f in ("summary.csv", "summary.png")), str(last))
    checks.true("straight: wrote 0.05 and 0.1 s", written(straight) == [0.05, 0.1], f"({written(straight)})")
    stopped_and_resumed(checks, template, straight, "Ctrl-C", (), 75, "Ctrl-C (SIGINT)", stop_after=0.02)
    # the time limit falls half-way between the straight run's 0.02 s and 0.08 s, so that a
    # loaded machine still stops the solver mid-run
    checks.true("straight: the solver's progress seen at 0.02 s and 0.08 s", None not in clock.values(), str(clock))
    if None not in clock.values():
        limit = 0.5 * (clock[0.02] + clock[0.08])
        stopped_and_resumed(checks, template, straight, "timeout", ("timeout", "-s", "TERM", f"{limit:.1f}"), 124,
                            "SIGTERM")

    broken = generated("allrun_broken", template=template)
    Case(broken).set_coupling("coupling.drag_law", "ergun_wenyu")
    code, output = allrun(broken)
    checks.true("a misspelt drag law on 2 ranks: Allrun fails", code != 0, f"(exit {code})")
    checks.true("its message on the terminal: the key, the value and the nearest name",
                "coupling.drag_law" in output and "ergun_wenyu" in output and "did you mean" in output, output[-1500:])
    checks.finish()


if __name__ == "__main__":
    main()
