"""The cluster recipe's batch script (scripts/tfdem.slurm) outside Slurm: three "jobs" of the
packed bed at 0.6 m/s (0.4 s), each run as Slurm would (SLURM_NTASKS, SLURM_SUBMIT_DIR,
SLURM_JOB_ID set) and the first two sent SIGUSR1 as `#SBATCH --signal=B:USR1@...` does:
  1. 2 ranks, the gas whole (the measured rule for its 120 cells): stops at a checkpoint, 75;
  2. 3 ranks, the gas split (TFDEM_GAS_LAYOUT=split): resumes from it (decomposed), stops, 75;
  3. 2 ranks, whole: resumes from the split checkpoint (reconstructed) and ends, 0.
Expected: each stop says so; the last job's pressure drop at 0.4 s equals a straight serial
run's to 1e-8 (the bed is steady, so the layouts' round-off does not grow).
"""
import os
import re
import signal
import subprocess
import time

from tfdem import SOURCE_DIR
from tfdem.run import environment, run
from tfdem_testlib import PACKED_BED, Checks, packed_bed_copy

SCRIPT = os.path.join(SOURCE_DIR, "scripts", "tfdem.slurm")


def job(case, ranks, job_id, stop_after=None, layout=None):
    """Run the script as job `job_id` on `ranks` tasks; with stop_after, send it SIGUSR1 once
    its solver's log passes that many seconds of simulated time beyond where it started.
    Returns (exit status, the solver's log)."""
    env = dict(environment(), TFDEM_ROOT=SOURCE_DIR, SLURM_SUBMIT_DIR=case.path, SLURM_NTASKS=str(ranks),
               SLURM_JOB_ID=str(job_id))
    if layout:
        env["TFDEM_GAS_LAYOUT"] = layout
    out = open(case.file(f"out.{job_id}"), "w")
    proc = subprocess.Popen(["bash", SCRIPT], cwd=case.path, env=env, stdout=out, stderr=subprocess.STDOUT)
    log = case.file(f"log.tfdemFoam.{job_id}")
    start = None
    while stop_after is not None and proc.poll() is None:
        times = re.findall(r"\nTime = (\S+)\n", open(log, errors="replace").read()) if os.path.exists(log) else []
        if times:
            start = float(times[0]) if start is None else start
            if float(times[-1]) >= start + stop_after:
                proc.send_signal(signal.SIGUSR1)
                break
        time.sleep(0.1)
    return proc.wait(), open(log, errors="replace").read()


def main():
    checks = Checks()
    straight = packed_bed_copy("slurm_straight", 0.4)
    run(["tfdemFoam"], straight.path, "log.tfdemFoam")
    expected = PACKED_BED.measured_pressure_drop(straight.path)

    case = packed_bed_copy("slurm_jobs", 0.4, mesh=False)  # the script meshes
    code, log = job(case, 2, 1, stop_after=0.1)
    checks.true("job 1, 2 ranks: the rule keeps 120 cells whole", "120 cells on 2 ranks, the gas whole: as the measured"
                " rule has it" in log)
    stop = re.search(r"TFDEM stop: SIGUSR1 received; stopped at t = (\S+) s", log)
    checks.true("job 1: stopped at a checkpoint on the signal, exit 75", code == 75 and stop is not None,
                f"(exit {code})")
    code, log = job(case, 3, 2, stop_after=0.05, layout="split")
    checks.true("job 2, 3 ranks split: resumed from job 1's checkpoint",
                stop is not None and f"resuming gas and particles from t = {stop.group(1)} s" in log)
    stop = re.search(r"TFDEM stop: SIGUSR1 received; stopped at t = (\S+) s", log)
    checks.true("job 2: stopped at a checkpoint on the signal, exit 75", code == 75 and stop is not None,
                f"(exit {code})")
    code, log = job(case, 2, 3)
    checks.true("job 3, 2 ranks whole: resumed from job 2's split checkpoint, made whole",
                stop is not None and f"resuming gas and particles from t = {stop.group(1)} s" in log
                and "made from the split checkpoint's on 3 rank(s)" in log)
    checks.true("job 3: ran to the end, exit 0", code == 0 and "\nEnd\n" in log, f"(exit {code})")
    checks.close("job 3: pressure drop at 0.4 s vs the straight serial run (Pa)", PACKED_BED.measured_pressure_drop(case.path),
                 expected, 1e-8)
    checks.finish()


if __name__ == "__main__":
    main()
