"""Batches of long runs, a few side by side, that survive being stopped: each run is a case
folder with a status file; a finished run is skipped, a stopped one resumes from its last
complete time folder (the coupled solver's joint checkpoint, or the fields a plain OpenFOAM
solver wrote). The seed 000 study and the speed-against-error sweeps are such batches.
"""
import argparse
import json
import math
import os
import re
import shutil
import signal
import subprocess
import sys
import time

import tfdem.run
from tfdem import outputs
from tfdem.case import Case
from tfdem.errors import Reported
from tfdem.frontdoor import write_text_atomic
from tfdem.inputs import positive_count, positive_number
from tfdem.run import environment

STATUS = "study.status.json"
STOPPED_AT_CHECKPOINT = 75  # tfdemFoam's exit status when a signal stopped it at a checkpoint (tfdemStop.H)


class BatchError(Reported):
    """A batch definition or run problem, named."""


class CaseRun:
    """One run: a name, its case folder and the command that solves it. Subclasses prepare the
    folder (prepare(end_time)) and may say what makes a time folder complete."""

    solver = "tfdemFoam"

    def __init__(self, name, path):
        self.name = name
        self.case = Case(path)

    def command(self):
        return [self.solver]

    def complete_fields(self):
        """Files a time folder needs to resume from (the coupled solver's checkpoint marker)."""
        return ("tfdem.checkpoint",)

    # Status ------------------------------------------------------------------------------
    def status(self):
        try:
            with open(self.case.file(STATUS)) as f:
                return json.load(f)
        except (OSError, ValueError):
            return {"state": "new"}

    def set_status(self, **values):
        """Update the status file (written whole: a full disk or a kill leaves the previous one)."""
        status = self.status()
        status.update(values)
        write_text_atomic(self.case.file(STATUS), json.dumps(status, indent=1))

    def done(self):
        return self.status().get("state") == "done"

    def running_elsewhere(self):
        """The process id of a solver still running this case (started by another or a killed
        batch), else None."""
        status = self.status()
        pid = status.get("pid")
        if status.get("state") != "running" or not pid:
            return None
        try:
            return pid if os.path.samefile(f"/proc/{pid}/cwd", self.case.path) else None
        except OSError:
            return None

    def wall_seconds(self):
        """Wall time over every segment: the last ClockTime OpenFOAM printed in each log."""
        return self._last_over_segments(r"ClockTime = (\d+(?:\.\d*)?)")

    def cpu_seconds(self):
        """The solver's processor time over every segment (OpenFOAM's ExecutionTime): less
        sensitive than wall time to what else runs on the machine."""
        return self._last_over_segments(r"ExecutionTime = (\d+(?:\.\d*)?)")

    def timing_seconds(self):
        """The coupled solver's own split of its time (the `TFDEM timing:` line each segment
        prints at its end), summed over the segments that printed one: {part: s}, with
        "segments" and "segments_timed"; None when none did (a TFM run, or no segment ended)."""
        total, timed, logs = dict.fromkeys(outputs.TIMING_PARTS, 0.0), 0, self.logs()
        for log in logs:
            try:
                split = outputs.solver_timing(log)
            except outputs.OutputError:
                continue
            timed += 1
            for part, seconds in split.items():
                total[part] += seconds
        return dict(total, segments=len(logs), segments_timed=timed) if timed else None

    def _last_over_segments(self, pattern):
        total = 0.0
        for log in self.logs():
            value = None
            with open(log, errors="replace") as f:
                for line in f:
                    found = re.search(pattern, line)
                    if found:
                        value = float(found.group(1))
            total += value or 0.0
        return total

    def logs(self):
        if not os.path.isdir(self.case.path):
            return []
        return sorted((self.case.file(n) for n in os.listdir(self.case.path) if re.match(r"log\.solver\.\d+$", n)),
                      key=lambda p: int(p.rsplit(".", 1)[1]))

    # Running -----------------------------------------------------------------------------
    def resume_point(self):
        """Remove time folders a stopped run left incomplete; return the time to resume from
        (None: start afresh)."""
        times = sorted((float(n), n) for n in os.listdir(self.case.path) if _is_time(self.case.file(n)))
        complete = [t for t in times if t[0] > 0 and self._complete(t[1])]
        last = complete[-1][0] if complete else 0.0
        for value, name in times:
            if value > last:
                shutil.rmtree(self.case.file(name))
        return complete[-1][1] if complete else None

    def _complete(self, time_name):
        folder = self.case.file(time_name)
        return all(os.path.isfile(os.path.join(folder, n)) and os.path.getsize(os.path.join(folder, n)) > 0
                   for n in self.complete_fields())

    def start(self):
        """Start (or resume) the solver in the background, in its own session; returns the
        process."""
        resume = self.resume_point()
        self.case.set_control(startFrom="latestTime" if resume else "startTime")
        if not resume:  # starting afresh: earlier segments' work is gone, and their wall time
            for old in self.logs():
                os.remove(old)
        logs = self.logs()
        segment = int(logs[-1].rsplit(".", 1)[1]) + 1 if logs else 1
        log = self.case.file(f"log.solver.{segment}")
        with open(log, "w") as out:
            # PWD as the folder: OpenFOAM warns when it is not the working directory
            proc = subprocess.Popen(self.command(), cwd=self.case.path, env=dict(environment(), PWD=self.case.path),
                                    stdout=out,
                                    stderr=subprocess.STDOUT, start_new_session=True)
        _keep_niceness(proc.pid)
        self.set_status(state="running", resumed_from=resume, pid=proc.pid)
        return proc

    def write_interval(self, end_time):
        """The checkpoint interval of a run to end_time; None keeps the case's own."""
        return None

    def extend(self, end_time):
        """Carry a prepared or started run on to another end time, keeping its checkpoints:
        its next start resumes from the last one; a run whose last checkpoint is at or past
        end_time is done."""
        interval = self.write_interval(end_time)
        self.case.set_control(endTime=end_time, **({} if interval is None else {"writeInterval": interval}))
        resume = self.resume_point()
        self.set_status(state="done" if resume and float(resume) >= end_time else "stopped", end_time=end_time)

    def finish(self, code):
        log = self.logs()[-1]
        text = open(log, errors="replace").read()
        ok = code == 0 and re.search(r"(?m)^End\s*$", text)
        if code == STOPPED_AT_CHECKPOINT:
            self.set_status(state="stopped", exit_code=code, wall_seconds=self.wall_seconds())
            print(f"\n{self.name}: {self.solver} was stopped by a signal at a checkpoint; run again to resume",
                  file=sys.stderr, flush=True)
            return False
        self.set_status(state="done" if ok else "failed", exit_code=code, wall_seconds=self.wall_seconds())
        if not ok:
            tail = "\n".join(text.splitlines()[-25:])
            print(f"\n{self.name}: {self.solver} failed (exit code {code}); last lines of {log}:\n{tail}\n",
                  file=sys.stderr, flush=True)
        return bool(ok)

    def progress(self):
        """(simulated time, end time) from the last segment's log."""
        logs = self.logs()
        end = float(self.case.control("endTime"))
        if not logs:
            return 0.0, end
        t = 0.0
        with open(logs[-1], errors="replace") as f:
            for line in f:
                found = re.match(r"(?:TFDEM progress: t = |Time = )(\S+)", line)
                if found:
                    try:
                        t = float(found.group(1))
                    except ValueError:
                        pass
        return t, end


def _keep_niceness(pid):
    """Give a solver's own session the batch's niceness: the kernel shares the cores between
    sessions (autogroups) before it weighs their processes' nice values, so a `nice` batch's
    solvers, each in its own session, would otherwise compete with other work at full weight."""
    niceness = os.nice(0)
    if niceness == 0:
        return
    try:
        with open(f"/proc/{pid}/autogroup", "w") as f:
            f.write(str(niceness))
    except OSError:  # no autogroups (a kernel without them, or not allowed): nice alone holds
        pass


def _is_time(path):
    try:
        float(os.path.basename(path))
    except ValueError:
        return False
    return os.path.isdir(path)


def clock(seconds):
    """Seconds as 1h02m or 3m04s."""
    seconds = int(seconds)
    return f"{seconds // 3600}h{seconds % 3600 // 60:02d}m" if seconds >= 3600 else f"{seconds // 60}m{seconds % 60:02d}s"


def eta_seconds(wall, t, t_start, end):
    """Wall time left, at the rate since this batch started the run at t_start (a resumed run's
    checkpoint, not 0); NaN until 2 % of the span left at the start is done."""
    span = end - t_start
    done = (t - t_start) / span if span > 0 else 0.0
    return wall * (1.0 - done) / done if done > 0.02 else float("nan")


def eta_text(eta, wall):
    """The ETA, or '?' while unknown, with the reason when the machine is busier than its cores
    after the first minute (a loaded machine, not a stuck run)."""
    if eta == eta:
        return clock(eta)
    load, cores = os.getloadavg()[0], os.cpu_count() or 1
    if wall >= 60 and load > cores:
        return f"? (the machine is loaded: load average {load:.1f} on {cores} cores)"
    return "?"


def print_progress(active, started):
    for r, _ in active:
        t, end = r.progress()
        start_clock, t_start = started[r.name]
        wall = time.monotonic() - start_clock
        eta = eta_seconds(wall, t, t_start, end)
        print(f"  {r.name:<26} t = {t:8.3f} / {end:g} s   wall {clock(wall)}   ETA {eta_text(eta, wall)}", flush=True)


def end_time_change(before, after, done):
    """What a new end time does to a prepared run: carried on to a later one, or, to an earlier
    one, done (its last checkpoint is at or past it) or run on to it."""
    before = float(before) if before is not None else math.nan
    if not after < before:
        return f"carried on from {before:g} s to {after:g} s"
    if done:
        return (f"end time lowered from {before:g} s to {after:g} s: its last checkpoint is at or past {after:g} s, "
                "so it is done (what it wrote past that time is kept, and left out of windows ending there)")
    return f"end time lowered from {before:g} s to {after:g} s: runs on to {after:g} s from its last checkpoint"


def run_batch(runs, end_time, jobs, poll=2.0, report_every=60.0):
    """Run the runs, `jobs` at a time; True when all finished. A new run is prepared; one
    prepared for another end time is carried on to this one from its last checkpoint (one
    with a checkpoint at or past end_time is done). Interrupted (Ctrl-C, SIGTERM), it stops
    its solvers, which resume from their last checkpoint on the next call."""
    if not (isinstance(jobs, int) and jobs >= 1):
        raise BatchError(f"{jobs!r} runs at a time: give a whole number of 1 or more")
    busy = [f"{r.name} (process {r.running_elsewhere()})" for r in runs if r.running_elsewhere()]
    if busy:
        raise BatchError(f"still running from another or a killed batch: {', '.join(busy)}; wait for it, or "
                         "stop it (kill -- -<process>) and run again: the run resumes from its checkpoint")
    for r in runs:
        status = r.status()
        if r.done() and status.get("end_time") == end_time:
            print(f"{r.name}: done ({clock(status.get('wall_seconds', 0))} wall), skipped", flush=True)
            continue
        if status.get("state") in ("new", "preparing") or not os.path.isdir(r.case.path):
            # a preparation that failed or was stopped part-way is made again from the start
            print(f"{r.name}: preparing {r.case.path}", flush=True)
            r.prepare(end_time)
            r.set_status(state="prepared", end_time=end_time)
        elif status.get("end_time") != end_time:
            r.extend(end_time)
            print(f"{r.name}: {end_time_change(status.get('end_time'), end_time, r.done())}", flush=True)
    pending = [r for r in runs if not r.done()]
    active = []
    previous = signal.signal(signal.SIGTERM, _interrupt)
    try:
        return _run_pending(pending, active, jobs, poll, report_every)
    except KeyboardInterrupt:
        print("stopped; the runs resume from their last checkpoint when run again", file=sys.stderr)
        raise
    finally:
        for r, proc in active:
            if proc.poll() is None:
                stop(proc, getattr(r, "ranks", 1))
                proc.wait()
                r.set_status(state="stopped", pid=None)
        signal.signal(signal.SIGTERM, previous)


def _interrupt(signum, frame):
    raise KeyboardInterrupt


def stop(proc, ranks):
    """Ask a solver to write a checkpoint and stop (openfoam_solver/tfdemStop.H): SIGTERM to the
    one process, SIGUSR1 to mpirun alone, which forwards it to its ranks once (sent SIGTERM,
    mpirun kills its ranks within a second, before they can write)."""
    if ranks > 1:
        os.kill(proc.pid, signal.SIGUSR1)
    else:
        os.killpg(proc.pid, signal.SIGTERM)


def _run_pending(pending, active, jobs, poll, report_every):
    started, ok = {}, True
    last_report = 0.0
    while pending or active:
        while pending and len(active) < jobs:
            r = pending.pop(0)
            resume = r.resume_point()
            print(f"{r.name}: {'resuming' if resume else 'starting'} {r.solver}", flush=True)
            active.append((r, r.start()))
            started[r.name] = (time.monotonic(), float(resume) if resume else 0.0)
        time.sleep(poll)
        for entry in list(active):
            r, proc = entry
            code = proc.poll()
            if code is None:
                continue
            active.remove(entry)
            finished = r.finish(code)
            ok = ok and finished
            print(f"{r.name}: {'finished' if finished else 'FAILED'} ({clock(r.wall_seconds())} wall)", flush=True)
        if active and time.monotonic() - last_report > report_every:
            print_progress(active, started)
            last_report = time.monotonic()
    return ok


class VariantRun(CaseRun):
    """A run of a tutorial case under runs/<name>/ with some coupling.yaml settings changed
    (e.g. the drag law), from the tutorial's own initial bed (bed.data), on `ranks` ranks.
    Subclasses may add steps after the mesh (prepare_mesh)."""

    def __init__(self, name, settings, ranks, root):
        super().__init__(name, os.path.join(root, "runs", name))
        self.settings, self.ranks, self.root = settings, ranks, root

    def command(self):
        return tfdem.run.command(["tfdemFoam"], self.ranks)

    def prepare(self, end_time):
        if os.path.isdir(self.case.path):
            shutil.rmtree(self.case.path)
        self.case = Case(self.root).copy_to(self.case.path, extra=("bed.data",))
        self.set_status(state="preparing", end_time=end_time)  # "prepared" once all of it is done (run_batch)
        self.case.set_control(endTime=end_time, writeInterval=self.write_interval(end_time), startFrom="startTime")
        for key, value in self.settings.items():
            self.case.set_coupling(key, value)
        tfdem.run.run(["blockMesh"], self.case.path, "log.blockMesh")
        self.prepare_mesh()
        tfdem.run.prepare_gas(self.case.path, self.ranks)

    def write_interval(self, end_time):
        """The tutorial's checkpoint interval, or end_time when shorter."""
        return min(float(Case(self.root).control("writeInterval")), end_time)

    def prepare_mesh(self):
        """Steps between blockMesh and the decomposition (none here)."""


def variants_command_line(doc, root, variants, make_run, report, default_end_time, argv=None, default_variants=None):
    """`run [--end-time T] [--jobs J] [--ranks R] [--variants ...]` and `report` of a tutorial
    whose runs are variants of it (`variants`: their names; `default_variants` those run
    without --variants, all when None): `run` pours the tutorial's bed
    once (bed.data from its packing.yaml), runs the variants (make_run(name, ranks)) and then
    reports; returns the exit code."""
    from tfdem.packing import pour_case  # the pour needs the packing module only here
    parser = argparse.ArgumentParser(description=doc, formatter_class=argparse.RawDescriptionHelpFormatter)
    sub = parser.add_subparsers(dest="action", required=True)
    chosen = list(default_variants or variants)
    run_parser = sub.add_parser("run", help="run the variants (resumed from their checkpoints), then report",
                                epilog="variants: " + ", ".join(sorted(variants)))
    run_parser.add_argument("--end-time", type=positive_number("the simulated time in s"), default=default_end_time,
                            help=f"simulated seconds (default {default_end_time:g})")
    run_parser.add_argument("--jobs", type=positive_count("the runs side by side"), default=2,
                            help="runs side by side (default 2)")
    run_parser.add_argument("--ranks", type=positive_count("each run's MPI ranks"), default=1,
                            help="MPI ranks of each run (default 1)")
    run_parser.add_argument("--variants", nargs="+", choices=sorted(variants), default=chosen, metavar="NAME",
                            help=f"the variants to run (default: {' '.join(chosen)}; the list below)")
    sub.add_parser("report", help="s against t of every run there is: results/*.csv and the figure")
    args = parser.parse_args(argv)
    if args.action == "run":
        if not os.path.exists(os.path.join(root, "bed.data")):
            print("pouring the bed (tfdem.packing, packing.yaml)", flush=True)
            print(pour_case(root), flush=True)
        ok = run_batch([make_run(name, args.ranks) for name in args.variants], args.end_time, args.jobs)
    report()
    return 0 if args.action == "report" or ok else 1
