"""Joint checkpoint/restart of gas and particles (seed 000's uniform-inflow bed, 0.2 s).

For 1 rank, and 2 ranks with the gas whole on each and split between them: run 0.2 s straight through; run it again, kill it with SIGKILL after the
checkpoint at 0.1 s was written, and resume with startFrom latestTime. Expected: bit for bit
the same state at 0.2 s -- the gas fields (p, U, voidFraction) and the whole DEM state (the
LIGGGHTS restart file: positions, velocities, spins, contact histories, held fluid forces) --
and the same particle statistics and pressure probes once the resumed series are joined.
Bitwise holds because the checkpoint keeps every value the next step reads (fields at 17
digits, the superficial flux, the momentum pressure gradient, the held forces) and the DEM
sets up at every coupling interval, as a resumed DEM does at its first.

Stopped by a signal between write times and resumed, the same holds: the run writes a joint
checkpoint at the step its ranks agree on and exits 75 (SIGTERM to the one solver; Ctrl-C,
SIGINT to the process group of scripts/bin/tfdem-solve on 2 ranks with the gas whole; SIGTERM
to tfdem-solve with the gas split); resumed, it writes the straight run's times (0.1 and 0.2 s,
counted from the start, not from the stop) and ends at 0.2 s bit for bit as above. A run whose
end time is off the write grid writes its end (a run can always be carried on from it). Then:
a checkpoint without its marker (a run killed while writing it) is refused as a start time.

On another rank count (the packed bed at 0.6 m/s, steady, so round-off does not grow): a
checkpoint written at 0.2 s by 2 ranks with the gas split resumes to 0.4 s on 3 ranks split
(re-decomposed by tfdem.run.decompose: reconstructPar of every time, so the older checkpoint
at 0.1 s keeps its gas fields, then decomposePar -latestTime), on 1 rank
(reconstructPar) and on 4 ranks with the gas whole; each ends with the straight serial run's
pressure drop to 1e-8 (the parallel identity test's tolerance). Run on 3 ranks without
re-decomposing, it stops before OpenFOAM would, naming both counts and the fixes.

Asked to stop (SIGUSR1 to mpirun of 2 ranks, the gas whole; SIGTERM to one solver) once
past 0.1 s: the run writes a joint checkpoint at the step its ranks agree on and exits 75;
resumed, it ends at the straight serial run's pressure drop to 1e-8.
"""
import os
import re
import shutil
import signal
import subprocess
import time

from tfdem import TUTORIALS
from tfdem.case import Case
from tfdem.outputs import joined_series, probes
from tfdem.run import RunError, decompose, environment, prepare_gas, run, start
from tfdem_testlib import PACKED_BED, Checks, packed_bed_copy, scratch

END_TIME, WRITE_INTERVAL, KILL_AFTER, STOP_AFTER = 0.2, 0.1, 0.15, 0.123


def packed_bed():
    where = scratch("restart_packing")
    run(["tfdem-liggghts", "-in", os.path.join(TUTORIALS, "bubbling_bed_packing", "in.pack"), "-var", "steps",
         "20000", "-var", "out", "bed.data", "-log", "log.liggghts"], where, "log.screen")
    return os.path.join(where, "bed.data")


def prepared(name, bed, ranks, gas):
    case = Case(os.path.join(TUTORIALS, "bubbling_bed")).copy_to(scratch(name))
    os.symlink(bed, case.file("bed.data"))
    case.set_control(endTime=END_TIME, writeInterval=WRITE_INTERVAL, writePrecision=17)
    case.set_coupling("output.statistics_interval", 0.01)
    run(["blockMesh"], case.path, "log.blockMesh")
    prepare_gas(case.path, ranks, gas)
    return case


def kill_after(case, ranks, gas, t_kill):
    """Run from the start and SIGKILL the whole run once the log reaches t_kill."""
    proc = start(["tfdemFoam"], case.path, "log.killed", ranks, gas)
    log = case.file("log.killed")
    while proc.poll() is None:
        if f"\nTime = {t_kill}\n" in open(log, errors="replace").read():
            os.killpg(proc.pid, signal.SIGKILL)
            break
        time.sleep(0.2)
    proc.wait()


def stop_after(case, ranks, gas, t_stop, sig):
    """Run from the start under scripts/bin/tfdem-solve (a session of its own) and send `sig`
    once the log reaches t_stop: to the solver's process group (SIGINT, as Ctrl-C in a
    terminal), else to tfdem-solve; returns its exit status."""
    args = ["tfdem-solve", "log.stopped", str(ranks)] + (["-parallel"] if ranks > 1 and gas == "split" else [])
    proc = subprocess.Popen(args, cwd=case.path, env=environment(), stdout=subprocess.DEVNULL,
                            start_new_session=True)
    log = case.file("log.stopped")
    while proc.poll() is None:
        if os.path.isfile(log) and f"\nTime = {t_stop}\n" in open(log, errors="replace").read():
            if sig == signal.SIGINT:
                os.killpg(proc.pid, sig)
            else:
                proc.send_signal(sig)
            break
        time.sleep(0.05)
    return proc.wait()


def written_times(case, ranks, gas):
    """The time folders a run wrote (of processor0 when the gas is split), as numbers."""
    root = case.file("processor0") if ranks > 1 and gas == "split" else case.path
    return sorted(float(name) for name in os.listdir(root) if re.fullmatch(r"[0-9.e+-]+", name) and float(name) > 0)


def field_files(case, ranks, gas, time_name):
    roots = [case.file(f"processor{r}") for r in range(ranks)] if ranks > 1 and gas == "split" else [case.path]
    return [os.path.join(root, time_name, name) for root in roots for name in ("p", "U", "voidFraction")]


def same_bytes(a, b):
    with open(a, "rb") as fa, open(b, "rb") as fb:
        return fa.read() == fb.read()


def check_ranks(checks, bed, ranks, gas="whole"):
    label = f"{ranks} rank(s)" + (f", gas {gas}" if ranks > 1 else "")
    straight = prepared(f"restart_straight_{ranks}_{gas}", bed, ranks, gas)
    run(["tfdemFoam"], straight.path, "log.tfdemFoam", ranks, gas=gas)
    resumed = prepared(f"restart_resumed_{ranks}_{gas}", bed, ranks, gas)
    kill_after(resumed, ranks, gas, KILL_AFTER)
    checks.true(f"{label}: killed run left the checkpoint at 0.1 s",
                os.path.isfile(resumed.file("0.1", "tfdem.checkpoint")))
    checks.true(f"{label}: killed run stopped before 0.2 s", not os.path.isdir(resumed.file("0.2")))
    resumed.set_control(startFrom="latestTime")
    _, output = run(["tfdemFoam"], resumed.path, "log.tfdemFoam", ranks, gas=gas)
    checks.true(f"{label}: resumed from the checkpoint", "resuming gas and particles from t = 0.1 s" in output)
    for a, b in zip(field_files(straight, ranks, gas, "0.2"), field_files(resumed, ranks, gas, "0.2")):
        checks.true(f"{label}: {os.path.relpath(a, straight.path)} bit for bit", same_bytes(a, b))
    checks.true(f"{label}: DEM state at 0.2 s (LIGGGHTS restart file) bit for bit",
                same_bytes(straight.file("0.2", "dem.restart"), resumed.file("0.2", "dem.restart")))
    for name, filename in (("tfdemParticles", "particles.dat"), ("pressure", "p")):
        a, b = joined_series(straight.path, name, filename), joined_series(resumed.path, name, filename)
        # values bit for bit; times to round-off (the straight run's clock is a sum of steps,
        # the resumed one starts from 0.1 as written)
        same = len(a) == len(b) > 0 and all(abs(ta - tb) < 1e-12 and va == vb for (ta, va), (tb, vb) in zip(a, b))
        checks.true(f"{label}: {name} series joined over the restart equals the straight run's", same,
                    f"({len(b)} rows vs {len(a)})")
    check_stopped(checks, bed, ranks, gas, straight)
    return resumed


def check_stopped(checks, bed, ranks, gas, straight):
    """Stopped by a signal between write times, resumed: the straight run's times and state."""
    sig = signal.SIGTERM if ranks == 1 or gas == "split" else signal.SIGINT
    label = f"{ranks} rank(s)" + (f", gas {gas}" if ranks > 1 else "") + f", {signal.Signals(sig).name}"
    stopped = prepared(f"restart_stopped_{ranks}_{gas}", bed, ranks, gas)
    code = stop_after(stopped, ranks, gas, STOP_AFTER, sig)
    text = open(stopped.file("log.stopped"), errors="replace").read()
    at = re.search(r"TFDEM stop: \S+ received; stopped at t = (\S+) s", text)
    checks.true(f"{label}: exit status 75 at a checkpoint", code == 75 and at is not None, f"(exit {code})")
    if not at:
        return
    stop_time = float(at.group(1))
    checks.true(f"{label}: stopped between the write times ({stop_time} s)", 0.1 < stop_time < 0.2)
    stopped.set_control(startFrom="latestTime")
    _, output = run(["tfdemFoam"], stopped.path, "log.tfdemFoam", ranks, gas=gas)
    checks.true(f"{label}: resumed from the stop", f"resuming gas and particles from t = {at.group(1)} s" in output)
    times = written_times(stopped, ranks, gas)
    checks.true(f"{label}: wrote the straight run's times and the stop's",
                times == sorted(written_times(straight, ranks, gas) + [stop_time]), f"({times})")
    for a, b in zip(field_files(straight, ranks, gas, "0.2"), field_files(stopped, ranks, gas, "0.2")):
        checks.true(f"{label}: {os.path.relpath(a, straight.path)} bit for bit", same_bytes(a, b))
    checks.true(f"{label}: DEM state at 0.2 s bit for bit",
                same_bytes(straight.file("0.2", "dem.restart"), stopped.file("0.2", "dem.restart")))


def check_end_written(checks):
    """An end time off the write grid (0.25 s, writes every 0.1 s) is written."""
    case = packed_bed_copy("end_off_grid", 0.25)
    case.set_control(writeInterval=0.1)
    run(["tfdemFoam"], case.path, "log.tfdemFoam")
    times = written_times(case, 1, "whole")
    checks.true("end time 0.25 s off the 0.1 s write grid: written", times == [0.1, 0.2, 0.25], f"({times})")


def check_incomplete_checkpoint(checks, case):
    os.remove(case.file("0.2", "tfdem.checkpoint"))
    code, output = run(["tfdemFoam"], case.path, "log.incomplete", expect_success=False)
    checks.true("checkpoint without its marker is refused", code != 0, f"(exit code {code})")
    checks.true("the message says it is incomplete and what to delete",
                "the checkpoint at t = 0.2 s is incomplete" in output and "start from the time before" in output)


def check_other_counts(checks):
    source = PACKED_BED
    straight = packed_bed_copy("counts_straight", 0.4)
    run(["tfdemFoam"], straight.path, "log.tfdemFoam")
    expected = source.measured_pressure_drop(straight.path)
    written = packed_bed_copy("counts_written", 0.2)
    written.set_control(writeInterval=0.1)  # two checkpoints: 0.1 s and the one resumed, 0.2 s
    prepare_gas(written.path, 2, "split")
    run(["tfdemFoam"], written.path, "log.tfdemFoam", 2, gas="split")
    written.set_control(endTime=0.4, startFrom="latestTime")

    def copy_of_written(name):
        dest = scratch(name)
        shutil.rmtree(dest)
        shutil.copytree(written.path, dest, symlinks=True)
        return Case(dest)
    unsplit = copy_of_written("counts_on_3_not_decomposed")
    code, output = run(["tfdemFoam"], unsplit.path, "log.tfdemFoam", 3, gas="split", expect_success=False)
    checks.true("split over 2, run split on 3 without decomposing: refused", code != 0, f"(exit code {code})")
    checks.true("the message names both counts and the re-decomposition",
                "the gas is decomposed for 2 ranks (processor0 ... processor1) but this run has 3" in output
                and "decomposePar -force -latestTime" in output, output[-600:])
    for ranks, gas in ((3, "split"), (1, "serial"), (4, "whole")):
        label = f"checkpoint of 2 ranks split, resumed on {ranks} rank(s)" + (f", gas {gas}" if ranks > 1 else "")
        case = copy_of_written(f"counts_on_{ranks}_{gas}")
        if gas == "split":
            decompose(case.path, ranks)
            checks.true(f"{label}: re-decomposed, the older checkpoint (0.1 s) keeps its gas fields, whole",
                        all(os.path.isfile(case.file("0.1", f)) for f in ("p", "U", "voidFraction")))
        else:
            run(["reconstructPar", "-latestTime"], case.path, "log.reconstructPar")
        _, output = run(["tfdemFoam"], case.path, "log.tfdemFoam", ranks, gas="split" if gas == "split" else "whole")
        checks.true(f"{label}: resumed from the checkpoint at 0.2 s, its gas fields made from the split ones",
                    "resuming gas and particles from t = 0.2 s" in output
                    and "made from the split checkpoint's on 2 rank(s)" in output)
        last = probes(case.path, source.probes, "p")[-1][0]
        checks.within(f"{label}: ran on to 0.4 s (last probe row, s)", last, 0.4, 1e-9)
        checks.close(f"{label}: pressure drop at 0.4 s vs the straight serial run (Pa)",
                     source.measured_pressure_drop(case.path), expected, 1e-8)
    return expected


def check_stop_by_signal(checks, expected, ranks, sig):
    """A run sent `sig` (to mpirun, which forwards it, or to the one solver) stops at a joint
    checkpoint with exit status 75; resumed, it ends as the straight serial run."""
    label = f"{signal.Signals(sig).name} to {'mpirun of ' + str(ranks) + ' ranks' if ranks > 1 else 'the solver'}"
    case = packed_bed_copy(f"stopped_{ranks}_{sig}", 0.4)
    proc = start(["tfdemFoam"], case.path, "log.stopped", ranks, "whole")
    log = case.file("log.stopped")
    while proc.poll() is None and "\nTime = 0.1\n" not in open(log, errors="replace").read():
        time.sleep(0.1)
    proc.send_signal(sig)
    code = proc.wait()
    text = open(log, errors="replace").read()
    stopped = re.search(r"TFDEM stop: \S+ received; stopped at t = (\S+) s", text)
    checks.true(f"{label}: exit status 75, the stop said", code == 75 and stopped is not None, f"(exit {code})")
    if not stopped:
        return
    t = stopped.group(1)
    checks.true(f"{label}: a joint checkpoint at the stop, t = {t} s < 0.4 s",
                float(t) < 0.4 and os.path.isfile(case.file(t, "tfdem.checkpoint")))
    case.set_control(startFrom="latestTime")
    _, output = run(["tfdemFoam"], case.path, "log.tfdemFoam", ranks, gas="whole")
    checks.true(f"{label}: resumed from it", f"resuming gas and particles from t = {t} s" in output)
    checks.close(f"{label}: resumed to 0.4 s, pressure drop vs the straight serial run (Pa)",
                 PACKED_BED.measured_pressure_drop(case.path), expected, 1e-8)


def main():
    checks = Checks()
    bed = packed_bed()
    try:
        resumed = check_ranks(checks, bed, 1)
        check_ranks(checks, bed, 2, "whole")
        check_ranks(checks, bed, 2, "split")
        check_incomplete_checkpoint(checks, resumed)
        check_end_written(checks)
        expected = check_other_counts(checks)
        check_stop_by_signal(checks, expected, 2, signal.SIGUSR1)
        check_stop_by_signal(checks, expected, 1, signal.SIGTERM)
    except RunError as e:
        checks.true(str(e), False)
    checks.finish()


if __name__ == "__main__":
    main()
