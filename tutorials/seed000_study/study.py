#!/usr/bin/env python3
"""Seed 000's study, end to end: every run of study.yaml, two at a time (one per core), then
the report (report.py).

    study.py run [--runs a,b] [--end-time T] [--jobs N] [--root DIR]
    study.py report [--end-time T] [--root DIR]
    study.py status [--root DIR]

A run that finished is skipped; one that was stopped resumes from its last checkpoint (a
killed study continues where it was). A run that fails is reported with its log's last lines
and the others go on; the command then exits non-zero. --end-time shortens every run (the
averaging windows scale with it), for a quick check of the whole pipeline.
"""
import argparse
import difflib
import json
import os
import re
import shutil
import signal
import subprocess
import sys
import time

import yaml

from tfdem import TUTORIALS
from tfdem.case import Case, set_dict_entries
from tfdem.run import RunError, environment, run

STUDY_DIR = os.path.dirname(os.path.abspath(__file__))
STATUS = "study.status.json"


class StudyError(Exception):
    """A study definition or run problem, named."""


RUN_KEYS = ("bed", "coupling", "refine_y", "tfm")


def load_study(path=os.path.join(STUDY_DIR, "study.yaml")):
    try:
        with open(path) as f:
            study = yaml.safe_load(f)
    except OSError as e:
        raise StudyError(f"{path}: cannot read the study definition ({e.strerror})") from None
    except yaml.YAMLError as e:
        raise StudyError(f"{path}: malformed YAML: {e}") from None
    for name, spec in study["runs"].items():
        if spec.get("bed") not in study["beds"]:
            raise StudyError(f"{path}: run {name}: bed must be one of {sorted(study['beds'])}, got {spec.get('bed')!r}")
        for key in spec:
            if key not in RUN_KEYS:
                near = difflib.get_close_matches(key, RUN_KEYS, 1)
                raise StudyError(f"{path}: run {name}: unknown key '{key}'"
                                 + (f" (did you mean '{near[0]}'?)" if near else "") + f"; valid: {', '.join(RUN_KEYS)}")
    return study


class Run:
    """One run of the study: its template, the changes, and its folder under runs/."""

    def __init__(self, name, spec, study, root):
        self.name, self.spec, self.study = name, spec, study
        bed = study["beds"][spec["bed"]]
        self.bed = spec["bed"]
        self.tfm = bool(spec.get("tfm", False))
        template = bed["tfm_template"] if self.tfm else bed["template"]
        self.template = os.path.join(STUDY_DIR if self.tfm else TUTORIALS, template)
        self.case = Case(os.path.join(root, "runs", name))
        self.solver = "twoPhaseEulerFoam" if self.tfm else "tfdemFoam"

    # Status ------------------------------------------------------------------------------
    def status(self):
        try:
            with open(self.case.file(STATUS)) as f:
                return json.load(f)
        except (OSError, ValueError):
            return {"state": "new"}

    def set_status(self, **values):
        status = self.status()
        status.update(values)
        with open(self.case.file(STATUS), "w") as f:
            json.dump(status, f, indent=1)

    def done(self):
        return self.status().get("state") == "done"

    def running_elsewhere(self):
        """The process id of a solver still running this case (started by another or a killed
        study), else None."""
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
        return sorted((self.case.file(n) for n in os.listdir(self.case.path) if re.match(r"log\.solver\.\d+$", n)),
                      key=lambda p: int(p.rsplit(".", 1)[1]))

    # Preparation -------------------------------------------------------------------------
    def prepare(self, end_time):
        """A fresh run folder: the template with the study's changes, mesh and initial state."""
        if os.path.isdir(self.case.path):
            shutil.rmtree(self.case.path)
        Case(self.template).copy_to(self.case.path, extra=("Allprepare", "Allsolve", "0.orig"))
        self.set_status(state="prepared", end_time=end_time)
        study = self.study
        self.case.set_control(endTime=end_time, writeInterval=study["write_interval"] * self._scale(end_time),
                              startFrom="startTime", writePrecision=17)
        refine = self.spec.get("refine_y", 1)
        if self.tfm:
            self._prepare_tfm(refine)
        else:
            self._prepare_coupled(refine, end_time)
        self._write_probes()

    def _prepare_coupled(self, refine, end_time):
        case = self.case
        if refine != 1:
            case.scale_cells(1, refine)
        for key, value in self.spec.get("coupling", {}).items():
            case.set_coupling(key, value)
        case.set_coupling("output.statistics_interval", self.study["statistics_interval"])
        case.set_coupling("output.particles_vtk", True)
        self._set_initial_gas(case.file("0", "U"))
        data = self._packing()
        shutil.copy(data, case.file(os.path.basename(data)))
        run(["blockMesh"], case.path, "log.blockMesh")

    def _prepare_tfm(self, refine):
        case = self.case
        path = case.file("system", "blockMeshDict")
        if refine != 1:
            set_dict_entries(path, ny=int(round(float(re.search(r"(?m)^ny\s+(\d+);", open(path).read()).group(1)) * refine)))
        self._set_initial_gas(case.file("0.orig", "U.air"))
        run(["./Allprepare"], case.path, "log.Allprepare")

    def _set_initial_gas(self, path):
        """Seed 000 Table 1: the gas starts at v_g = U_mf (upward) in the whole domain."""
        u = self.study["beds"][self.bed]["initial_gas_velocity"]
        text = open(path).read()
        text, n = re.subn(r"(?m)^internalField\s+uniform\s+\([^)]*\);", f"internalField   uniform (0 {u} 0);", text)
        if n != 1:
            raise StudyError(f"{path}: no 'internalField uniform (...)' to set the initial gas velocity in")
        open(path, "w").write(text)

    def _packing(self):
        """The template's initial packing, made once in the tutorial folder."""
        if self.spec["bed"] == "jet":
            run(["./Allpack"], os.path.join(TUTORIALS, "jet_bed"), "log.Allpack")
            return os.path.join(TUTORIALS, "jet_bed", "packed_bed.data")
        data = os.path.join(TUTORIALS, "bubbling_bed_packing", "bed.data")
        if not os.path.isfile(data):
            run(["./Allrun"], os.path.join(TUTORIALS, "bubbling_bed_packing"), "log.Allrun")
        return data

    def _scale(self, end_time):
        """A shortened run writes checkpoints and particle files as often, relative to its
        length (the sampling intervals stay)."""
        return min(1.0, end_time / self.study["end_time"])

    def _write_probes(self):
        """The study's function objects: every field of the maps at every cell centre, and p
        on the bottom row of cells and the row 20 cm above it (Delta p at 20 cm, Fig. 3)."""
        grid = self.case.grid()
        centres = grid.centres()
        z = grid.origin[2] + 0.5 * grid.spacing[2]
        bottom = grid.origin[1] + 0.5 * grid.spacing[1]
        rows = [(x, y) for y in (bottom, bottom + 0.2) for x, _, _ in centres[:grid.counts[0]]]
        fields = "(alpha.particles)" if self.tfm else "(voidFraction contactForceByWeight dragForceByWeight)"
        field_dt, pressure_dt = self.study["field_interval"], self.study["statistics_interval"]
        if self.tfm:
            control = lambda dt: f"writeControl adjustableRunTime; writeInterval {dt:.10g};"
        else:
            steps = lambda dt: max(1, int(round(dt / self.case.delta_t())))
            control = lambda dt: f"writeControl timeStep; writeInterval {steps(dt)};"
        points = "\n".join(f"            ({x:.10g} {y:.10g} {z:.10g})" for x, y, _ in centres)
        row_points = "\n".join(f"            ({x:.10g} {y:.10g} {z:.10g})" for x, y in rows)
        block = (
            "functions\n{\n"
            "    // written by study.py: every cell centre (maps) and two rows of cells (Delta p)\n"
            "    studyFields\n    {\n        type probes; libs (\"libsampling.so\");\n"
            f"        {control(field_dt)}\n        fields {fields};\n"
            f"        probeLocations\n        (\n{points}\n        );\n    }}\n"
            "    studyPressure\n    {\n        type probes; libs (\"libsampling.so\");\n"
            f"        {control(pressure_dt)}\n        fields (p);\n"
            f"        probeLocations\n        (\n{row_points}\n        );\n    }}\n"
            "}\n")
        path = self.case.file("system", "controlDict")
        text = open(path).read()
        start = re.search(r"(?m)^functions\s*\n?\s*\{", text)
        text = (text[:start.start()] if start else text) + block
        open(path, "w").write(text)

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
        if not self.tfm:
            return os.path.isfile(os.path.join(folder, "tfdem.checkpoint"))
        names = ("U.air", "U.particles", "alpha.particles", "p", "Theta.particles")
        return all(os.path.isfile(os.path.join(folder, n)) and os.path.getsize(os.path.join(folder, n)) > 0
                   for n in names)

    def start(self):
        """Start (or resume) the solver in the background; returns the process."""
        resume = self.resume_point()
        self.case.set_control(startFrom="latestTime" if resume else "startTime")
        if not resume:  # starting afresh: earlier segments' work is gone, and their wall time
            for old in self.logs():
                os.remove(old)
        logs = self.logs()
        segment = int(logs[-1].rsplit(".", 1)[1]) + 1 if logs else 1
        log = self.case.file(f"log.solver.{segment}")
        command = ["./Allsolve"] if self.tfm else [self.solver]
        with open(log, "w") as out:
            proc = subprocess.Popen(command, cwd=self.case.path, env=environment(), stdout=out,
                                    stderr=subprocess.STDOUT, start_new_session=True)
        self.set_status(state="running", resumed_from=resume, pid=proc.pid)
        return proc

    def finish(self, code):
        log = self.logs()[-1]
        text = open(log, errors="replace").read()
        ok = code == 0 and re.search(r"(?m)^End\s*$", text)
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


def _is_time(path):
    try:
        float(os.path.basename(path))
    except ValueError:
        return False
    return os.path.isdir(path)


def _clock(seconds):
    seconds = int(seconds)
    return f"{seconds // 3600}h{seconds % 3600 // 60:02d}m" if seconds >= 3600 else f"{seconds // 60}m{seconds % 60:02d}s"


def print_progress(active, started):
    now = time.monotonic()
    for r, _ in active:
        t, end = r.progress()
        wall = now - started[r.name]
        t0 = r.status().get("resumed_from") or 0.0
        done = (t - float(t0)) / (end - float(t0)) if end > float(t0) else 0
        eta = wall * (1 - done) / done if done > 0 else float("nan")
        print(f"  {r.name:<26} t = {t:8.3f} / {end:g} s   wall {_clock(wall)}   ETA "
              f"{_clock(eta) if eta == eta else '?'}", flush=True)


def run_study(runs, end_time, jobs, poll=2.0, report_every=60.0):
    """Run the runs, `jobs` at a time; True when all finished. Interrupted (Ctrl-C, SIGTERM),
    it stops its solvers, which resume from their last checkpoint on the next call."""
    busy = [f"{r.name} (process {r.running_elsewhere()})" for r in runs if r.running_elsewhere()]
    if busy:
        raise StudyError(f"still running from another or a killed study: {', '.join(busy)}; wait for it, or "
                         "stop it (kill -- -<process>) and run again: the run resumes from its checkpoint")
    for r in runs:
        status = r.status()
        if r.done() and status.get("end_time") == end_time:
            print(f"{r.name}: done ({_clock(status.get('wall_seconds', 0))} wall), skipped", flush=True)
            continue
        if status.get("state") in ("new",) or status.get("end_time") != end_time or not os.path.isdir(r.case.path):
            print(f"{r.name}: preparing {r.case.path}", flush=True)
            r.prepare(end_time)
    pending = [r for r in runs if not r.done()]
    active = []
    previous = signal.signal(signal.SIGTERM, _interrupt)
    try:
        return _run_pending(pending, active, jobs, poll, report_every)
    except KeyboardInterrupt:
        print("study stopped; its runs resume from their last checkpoint when it is run again", file=sys.stderr)
        raise
    finally:
        for r, proc in active:
            if proc.poll() is None:
                os.killpg(proc.pid, signal.SIGTERM)
                proc.wait()
                r.set_status(state="stopped", pid=None)
        signal.signal(signal.SIGTERM, previous)


def _interrupt(signum, frame):
    raise KeyboardInterrupt


def _run_pending(pending, active, jobs, poll, report_every):
    started, ok = {}, True
    last_report = 0.0
    while pending or active:
        while pending and len(active) < jobs:
            r = pending.pop(0)
            print(f"{r.name}: {'resuming' if r.resume_point() else 'starting'} {r.solver}", flush=True)
            active.append((r, r.start()))
            started[r.name] = time.monotonic()
        time.sleep(poll)
        for entry in list(active):
            r, proc = entry
            code = proc.poll()
            if code is None:
                continue
            active.remove(entry)
            finished = r.finish(code)
            ok = ok and finished
            print(f"{r.name}: {'finished' if finished else 'FAILED'} ({_clock(r.wall_seconds())} wall)", flush=True)
        if active and time.monotonic() - last_report > report_every:
            print_progress(active, started)
            last_report = time.monotonic()
    return ok


def selected_runs(study, names, root):
    runs = [Run(name, spec, study, root) for name, spec in study["runs"].items()]
    if names:
        unknown = [n for n in names if n not in study["runs"]]
        if unknown:
            raise StudyError(f"unknown run(s) {', '.join(unknown)}; study.yaml has: {', '.join(study['runs'])}")
        runs = [r for r in runs if r.name in names]
    # the longest first, so the two cores finish together: the jet bed's (fine grid first, its
    # TFM as long as its coarse TF-DEM), then the uniform bed's (its TFM the shortest)
    return sorted(runs, key=lambda r: (r.bed != "jet", -r.spec.get("refine_y", 1), r.tfm and r.bed != "jet"))


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("command", choices=("run", "report", "status"))
    parser.add_argument("--runs", default="", help="comma-separated run names (default: all)")
    parser.add_argument("--end-time", type=float, default=None, help="simulated seconds per run (default: study.yaml's)")
    parser.add_argument("--jobs", type=int, default=2, help="runs side by side (default 2: one per core)")
    parser.add_argument("--root", default=STUDY_DIR, help="folder for runs/ and report/ (default: the study's)")
    parser.add_argument("--study", default=os.path.join(STUDY_DIR, "study.yaml"), help="study definition")
    args = parser.parse_args(argv)
    try:
        study = load_study(args.study)
        end_time = args.end_time or study["end_time"]
        if not end_time > 0:
            raise StudyError(f"--end-time must be positive, got {end_time}")
        runs = selected_runs(study, [n for n in args.runs.split(",") if n], args.root)
        if args.command == "status":
            for r in runs:
                s = r.status()
                print(f"{r.name:<26} {s.get('state')}  {_clock(s.get('wall_seconds', 0))}")
            return 0
        if args.command == "run":
            if shutil.which("twoPhaseEulerFoam", path=environment()["PATH"]) is None and any(r.tfm for r in runs):
                raise StudyError("twoPhaseEulerFoam is not on PATH: the TFM runs need Debian's openfoam package "
                                 "(./tfdem setup installs it)")
            ok = run_study(runs, end_time, args.jobs)
            if not ok:
                print("some runs failed (above); the others' results are kept. Fix the cause and run again: "
                      "finished runs are skipped, stopped ones resume.", file=sys.stderr)
                return 1
            return 0
        import report
        report.write_report(study, runs, end_time, os.path.join(args.root, "report"))
        return 0
    except (StudyError, RunError) as e:
        print(f"study.py: {e}", file=sys.stderr)
        return 2
    except KeyboardInterrupt:
        return 130


if __name__ == "__main__":
    sys.exit(main())
