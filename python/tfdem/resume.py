"""A case set to carry on from its newest checkpoint, or to start when it has none:

    python3 -m tfdem.resume CASE      (tfdem resume CASE; a generated case's Allrun runs it)

A coupled run writes a joint checkpoint at every write time and when a signal stops it, each
completed by its marker, <time>/tfdem.checkpoint, written last (openfoam_solver/
tfdemCheckpoint.H). A time folder after the newest marked one was being written when the run
was killed (SIGKILL, a node lost, a disk that filled), as is a split checkpoint one of whose
processor*/<time> folders is gone: it is moved aside, whole, into
CASE/incomplete/<time>/ (its processor*/<time> folders beside it as processor*-<time>), never
deleted, and named. Then system/controlDict gets startFrom latestTime when a checkpoint is
left, startTime otherwise. The solver itself verifies the checkpoint it starts from (every
file against its size and hash, the marker against its data) and names the newest earlier one
that verifies when it does not.
"""
import argparse
import os
import re

from tfdem.case import Case, CaseError
from tfdem.frontdoor import add_debug_option, doing, run_command
from tfdem.outputs import times

MARKER = "tfdem.checkpoint"
INCOMPLETE = "incomplete"


def complete(case_path, time_name):
    """Whether a time folder is a whole checkpoint: its marker written, and, when the marker
    says the gas was split over N ranks, processor0 ... processor<N-1> holding that time."""
    marker = os.path.join(case_path, time_name, MARKER)
    if not os.path.isfile(marker):
        return False
    with open(marker, errors="replace") as f:
        text = f.read()
    split = re.search(r"(?m)^layout\s+split;", text)
    ranks = re.search(r"(?m)^ranks\s+(\d+);", text)
    if not (split and ranks):
        return True
    return all(os.path.isdir(os.path.join(case_path, f"processor{r}", time_name)) for r in range(int(ranks.group(1))))


def checkpoints(case_path):
    """The case's whole checkpoints, oldest first (time names)."""
    return [t for t in times(case_path) if complete(case_path, t)]


def incomplete_folders(case_path, after):
    """Time folders later than `after` (a time name, or None for any after the first time), in
    the case and in its processor*/ folders: [(path, name to keep it under)]."""
    limit = float(after) if after is not None else float(times(case_path)[0]) if times(case_path) else 0.0
    found = [(os.path.join(case_path, t), t) for t in times(case_path) if float(t) > limit]
    for name in sorted(os.listdir(case_path)):
        processor = os.path.join(case_path, name)
        if name.startswith("processor") and os.path.isdir(processor):
            found += [(os.path.join(processor, t), f"{name}-{t}") for t in times(processor) if float(t) > limit]
    return found


def set_aside(case_path, folders):
    """Move each (path, name) into case/incomplete/name; a name taken already gets a suffix."""
    where = os.path.join(case_path, INCOMPLETE)
    moved = []
    if folders:
        os.makedirs(where, exist_ok=True)
    for path, name in folders:
        target, k = os.path.join(where, name), 1
        while os.path.exists(target):
            k += 1
            target = os.path.join(where, f"{name}.{k}")
        with doing("moving an incomplete checkpoint aside from", path):
            os.replace(path, target)
        moved.append(os.path.relpath(target, case_path))
    return moved


def prepare(case_path):
    """Set the case to resume from its newest checkpoint (or to start); returns what was done,
    as lines to print."""
    case = Case(case_path)
    if not os.path.isfile(case.file("system", "controlDict")):
        raise CaseError(f"{case_path}: not a case folder (no system/controlDict): give the case's folder")
    if not os.path.isfile(case.file("coupling.yaml")):
        raise CaseError(f"{case_path}: no coupling.yaml: a gas-only case writes no checkpoints to resume from; "
                        "set startFrom latestTime in its system/controlDict by hand")
    marked = checkpoints(case_path)
    newest = marked[-1] if marked else None
    lines = []
    moved = set_aside(case_path, incomplete_folders(case_path, newest))
    if moved:
        lines.append(f"set aside {len(moved)} time folder(s) after the newest whole checkpoint, never completed "
                     f"(a run killed while writing them) or missing a processor's part: {', '.join(moved)}")
    if newest is not None:
        case.set_control(startFrom="latestTime")
        lines.append(f"resuming from the checkpoint at t = {newest} s")
        end = case.end_time()
        if float(newest) >= end * (1 - 1e-12):
            lines.append(f"the run has reached its end time ({end:g} s): nothing is left to run; raise endTime in "
                         f"{case.file('system', 'controlDict')} to run longer")
    else:
        case.set_control(startFrom="startTime")
        lines.append("no checkpoint: starting at the start time")
    return lines


def _main(argv):
    parser = argparse.ArgumentParser(prog="tfdem resume", description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("case", help="the case's folder")
    add_debug_option(parser)
    args = parser.parse_args(argv)
    for line in prepare(args.case):
        print(f"tfdem resume: {line}")
    return 0


def main(argv=None):
    return run_command("tfdem resume", _main, argv)


if __name__ == "__main__":
    raise SystemExit(main())
