"""tfdem resume on hand-made cases: time folders after the newest checkpoint marker are moved
aside whole into CASE/incomplete/ (processor*/ ones too), never deleted; controlDict's
startFrom becomes latestTime when a checkpoint is left, startTime otherwise; a run whose newest
checkpoint is at the end time is said to be finished; a gas-only case
(no coupling.yaml) and a folder that is no case are refused with exit 2."""
import os
import re
import shutil
import sys
import tempfile

from tfdem.resume import main, prepare

failures = []


def check(name, ok, detail=""):
    print(("PASS " if ok else "FAIL ") + name + (f" {detail}" if detail and not ok else ""))
    if not ok:
        failures.append(name)


CONTROL = "FoamFile { object controlDict; }\nstartFrom       startTime;\nendTime 1;\n"


def case(root, marked, unmarked, processors=0):
    """A case with time folders `marked` (with a marker) and `unmarked` (a file inside each)."""
    os.makedirs(os.path.join(root, "system"))
    open(os.path.join(root, "system", "controlDict"), "w").write(CONTROL)
    open(os.path.join(root, "coupling.yaml"), "w").write("gas: {}\n")
    for t in ["0"] + marked + unmarked:
        for where in [root] + [os.path.join(root, f"processor{p}") for p in range(processors)]:
            os.makedirs(os.path.join(where, t), exist_ok=True)
            open(os.path.join(where, t, "U"), "w").write(t)
        if t in marked:
            open(os.path.join(root, t, "tfdem.checkpoint"), "w").write("time 0;\n")
    return root


def start_from(root):
    return re.search(r"startFrom\s+(\w+);", open(os.path.join(root, "system", "controlDict")).read()).group(1)


with tempfile.TemporaryDirectory() as tmp:
    root = case(os.path.join(tmp, "a"), ["0.1", "0.2"], ["0.25"], processors=2)
    lines = prepare(root)
    check("a checkpoint left: startFrom latestTime", start_from(root) == "latestTime")
    check("the newest checkpoint named", any("t = 0.2 s" in line for line in lines), str(lines))
    check("the half-written 0.25 moved aside whole",
          not os.path.exists(os.path.join(root, "0.25")) and
          open(os.path.join(root, "incomplete", "0.25", "U")).read() == "0.25")
    check("its processor folders moved beside it",
          all(os.path.isfile(os.path.join(root, "incomplete", f"processor{p}-0.25", "U")) for p in (0, 1)) and
          not os.path.exists(os.path.join(root, "processor0", "0.25")))
    check("the checkpoints and the start kept",
          all(os.path.isdir(os.path.join(root, t)) for t in ("0", "0.1", "0.2")) and
          os.path.isdir(os.path.join(root, "processor1", "0.2")))
    os.makedirs(os.path.join(root, "0.25"))
    prepare(root)
    check("a second 0.25 kept beside the first", os.path.isdir(os.path.join(root, "incomplete", "0.25.2")))

    root = case(os.path.join(tmp, "s"), ["0.1", "0.2"], [], processors=2)
    for t in ("0.1", "0.2"):
        open(os.path.join(root, t, "tfdem.checkpoint"), "w").write("layout           split;\nranks            2;\n")
    shutil.rmtree(os.path.join(root, "processor1", "0.2"))
    lines = prepare(root)
    check("a split checkpoint missing processor1/0.2: resumes from 0.1", any("t = 0.1 s" in line for line in lines),
          str(lines))
    check("its remaining parts moved aside",
          os.path.isdir(os.path.join(root, "incomplete", "0.2")) and
          os.path.isdir(os.path.join(root, "incomplete", "processor0-0.2")))

    root = case(os.path.join(tmp, "b"), [], ["0.05"])
    lines = prepare(root)
    check("no checkpoint: startFrom startTime", start_from(root) == "startTime")
    check("no checkpoint: the unmarked 0.05 moved aside, 0 kept",
          os.path.isdir(os.path.join(root, "incomplete", "0.05")) and os.path.isdir(os.path.join(root, "0")))

    root = case(os.path.join(tmp, "c"), ["0.1"], [])
    lines = prepare(root)
    check("nothing incomplete: no incomplete/ folder", not os.path.exists(os.path.join(root, "incomplete")))
    check("a checkpoint before the end time (1 s): no word of the end", not any("end time" in l for l in lines),
          str(lines))

    root = case(os.path.join(tmp, "f"), ["0.5", "1"], [])
    lines = prepare(root)
    check("a finished run (its checkpoint at the end time, 1 s): said so, with endTime to raise",
          any("reached its end time (1 s)" in l and "raise endTime" in l for l in lines), str(lines))

    gas_only = case(os.path.join(tmp, "d"), [], ["0.1"])
    os.remove(os.path.join(gas_only, "coupling.yaml"))
    check("a gas-only case refused, exit 2, its times kept",
          main([gas_only]) == 2 and os.path.isdir(os.path.join(gas_only, "0.1")))
    check("a folder that is no case refused, exit 2", main([os.path.join(tmp, "nowhere")]) == 2)

print(f"{len(failures)} failed" if failures else "all passed")
sys.exit(1 if failures else 0)
