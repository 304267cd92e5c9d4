"""Probing the solver the way a demanding user does: many bad inputs and hard cases, each run
to its end (or its time limit) and classified, so a suite reports how every case ended, not
only whether one failed.

Classes (the README's table counts them):
- clear: a bad input stopped non-zero with every key word of its message (the file or key,
  the value, the cause and the fix), no crash;
- handled: a hard case ran to the end and its checks held (nothing lost), or stopped as
  expected with its message, or warned as expected;
- unclear: it stopped non-zero, but the message lacks a key word;
- crash: it ended on a signal or with a stack trace (even after a TFDEM diagnosis line);
- hang: it ran past its time limit and was killed;
- silent: a bad input ran to the end, or a hard case ran and its checks failed.
Only clear and handled pass.
"""
import json
import os
import re
import shutil
import signal
import subprocess
import time

VERDICTS = ("clear", "handled", "unclear", "crash", "hang", "silent")
PASSING = ("clear", "handled")
# What a crash prints: OpenFOAM's signal handlers' stack trace, the shell's and Open MPI's
# reports of a process killed by a signal
CRASH_SIGNS = ("printStack", "sigFpe::sigHandler", "sigSegv::sigHandler", "Segmentation fault", "core dumped",
               "*** Process received signal ***", "exited on signal")


def run(args, cwd, log_name, ranks=1, gas="whole", timeout=120, env=None):
    """Run a program as tfdem.run.run does, killed (its whole process group) after `timeout`
    s; returns (exit code, output, timed out). Negative exit code: killed by that signal."""
    import tfdem.run  # here: the table below needs no environment
    log = os.path.join(cwd, log_name)
    env = dict(env or tfdem.run.environment())
    env["PWD"] = cwd  # as a shell started there would have it (OpenFOAM compares the two)
    with open(log, "w") as out:
        proc = subprocess.Popen(tfdem.run.command(args, ranks, gas), cwd=cwd, env=env,
                                stdout=out, stderr=subprocess.STDOUT, start_new_session=True)
        try:
            proc.wait(timeout=timeout)
            timed_out = False
        except subprocess.TimeoutExpired:
            os.killpg(proc.pid, signal.SIGKILL)
            proc.wait()
            timed_out = True
    with open(log, errors="replace") as f:
        return proc.returncode, f.read(), timed_out


def crashed(code, output):
    """Ended on a signal (a negative code, or 128 + signal from mpirun or a shell) or with a
    stack trace."""
    return code < 0 or code in (128 + signal.SIGFPE, 128 + signal.SIGSEGV, 128 + signal.SIGABRT,
                                128 + signal.SIGBUS) or any(s in output for s in CRASH_SIGNS)


def verdict_of_failure(code, output, timed_out, words):
    """How a run that must stop ended; (verdict, the words its message lacks)."""
    if timed_out:
        return "hang", []
    if crashed(code, output):
        return "crash", []
    if code == 0:
        return "silent", []
    missing = [w for w in words if w not in output]
    return ("unclear" if missing else "clear"), missing


class Suite:
    """Outcomes of one suite's cases, printed as they come and written as JSON at the end."""

    def __init__(self, name, where):
        self.name = name
        self.where = where
        self.outcomes = []

    def record(self, group, case, verdict, seconds, detail="", missing=()):
        assert verdict in VERDICTS, verdict
        self.outcomes.append({"group": group, "case": case, "verdict": verdict, "seconds": round(seconds, 2),
                              "detail": detail[-600:], "missing": list(missing)})
        mark = "PASS" if verdict in PASSING else "FAIL"
        extra = f" (missing: {', '.join(repr(m) for m in missing)})" if missing else ""
        print(f"{mark} [{group}] {case}: {verdict}{extra} ({seconds:.1f} s)", flush=True)
        if verdict not in PASSING and detail:
            print("    " + "\n    ".join(detail.strip().splitlines()[-25:]), flush=True)

    def counts(self):
        table = {}
        for o in self.outcomes:
            row = table.setdefault(o["group"], {v: 0 for v in VERDICTS})
            row[o["verdict"]] += 1
        return table

    def finish(self):
        """Write outcomes.json, print the counts per group and class; exit 1 unless every case
        passed."""
        os.makedirs(self.where, exist_ok=True)
        path = os.path.join(self.where, "outcomes.json")
        with open(path, "w") as f:
            json.dump({"suite": self.name, "outcomes": self.outcomes}, f, indent=1)
        print(f"\n{self.name}: {len(self.outcomes)} cases ({path})")
        print(f"{'group':<28}" + "".join(f"{v:>9}" for v in VERDICTS))
        for group, row in self.counts().items():
            print(f"{group:<28}" + "".join(f"{row[v]:>9}" for v in VERDICTS))
        failed = [o for o in self.outcomes if o["verdict"] not in PASSING]
        print(f"{len(self.outcomes) - len(failed)} passed, {len(failed)} failed")
        raise SystemExit(1 if failed or not self.outcomes else 0)


def edit(path, old, new):
    """Replace every `old` in a file by `new`; `old` must be there."""
    text = open(path).read()
    assert old in text, (path, old)
    with open(path, "w") as f:
        f.write(text.replace(old, new))


def all_of(*changes):
    """One change (of a case folder) made of several, in order."""
    def change(case):
        for c in changes:
            c(case)
    return change


def timed(function, *args, **kwargs):
    start = time.monotonic()
    result = function(*args, **kwargs)
    return result, time.monotonic() - start


def fresh_copy(template, path):
    """A copy of a prepared case folder (mesh, checkpoints, ...) at path."""
    shutil.rmtree(path, ignore_errors=True)
    shutil.copytree(template, path, symlinks=True)
    return path


def slug(text):
    return re.sub(r"\W+", "_", text).strip("_")[:60]


def markdown_table(paths):
    """The README's table: cases per group and class, from outcomes.json files."""
    lines = ["| suite | group | cases | " + " | ".join(VERDICTS) + " |",
             "|---|---|---|" + "---|" * len(VERDICTS)]
    totals = {v: 0 for v in VERDICTS}
    for path in paths:
        with open(path) as f:
            data = json.load(f)
        table = {}
        for o in data["outcomes"]:
            table.setdefault(o["group"], {v: 0 for v in VERDICTS})[o["verdict"]] += 1
        for group, row in table.items():
            lines.append(f"| {data['suite']} | {group} | {sum(row.values())} | "
                         + " | ".join(str(row[v]) for v in VERDICTS) + " |")
            for v in VERDICTS:
                totals[v] += row[v]
    lines.append(f"| all | | {sum(totals.values())} | " + " | ".join(str(totals[v]) for v in VERDICTS) + " |")
    return "\n".join(lines)


if __name__ == "__main__":
    import sys
    if len(sys.argv) < 3 or sys.argv[1] != "table":
        sys.exit("usage: python3 tests/integration/probe.py table OUTCOMES.json ...")
    print(markdown_table(sys.argv[2:]))
