"""A tutorial copied out of the checkout runs (issue 27: cases relocatable): the settling
particle's folder copied to a scratch folder

- without TFDEM_ROOT stops at once, exit code 2, with the message naming the fix;
- with TFDEM_ROOT set to the checkout it runs to the end, and its terminal velocity matches
  the drag law's (Schiller-Naumann, solved by plot.py) within 0.01 %;
- its Allclean then leaves exactly the files the copy started with (inputs kept, outputs gone).
"""
import os
import re
import shutil
import subprocess

from tfdem import SOURCE_DIR
from tfdem.run import environment
from tfdem_testlib import Checks, scratch


def files_under(folder):
    return sorted(os.path.relpath(os.path.join(d, f), folder) for d, _, names in os.walk(folder) for f in names)


def main():
    checks = Checks()
    case = os.path.join(scratch("relocated_case"), "settling")
    shutil.rmtree(case, ignore_errors=True)
    tutorial = os.path.join(SOURCE_DIR, "tutorials", "settling_particle")
    tracked = subprocess.run(["git", "ls-files"], cwd=tutorial, stdout=subprocess.PIPE, text=True, check=True).stdout
    for name in tracked.split():  # the tutorial as committed, without outputs of runs in place
        os.makedirs(os.path.dirname(os.path.join(case, name)), exist_ok=True)
        shutil.copy2(os.path.join(tutorial, name), os.path.join(case, name))
    inputs = files_under(case)
    env = {k: v for k, v in os.environ.items() if k != "TFDEM_ROOT"}
    proc = subprocess.run([os.path.join(case, "Allrun")], env=env, stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                          text=True)
    checks.true("without TFDEM_ROOT: exit code 2 and the fix named",
                proc.returncode == 2 and "needs export TFDEM_ROOT=<your TFDEM checkout>" in proc.stdout,
                f"(exit code {proc.returncode}: {proc.stdout.strip()[-200:]})")
    env = dict(environment(), TFDEM_ROOT=SOURCE_DIR)
    proc = subprocess.run([os.path.join(case, "Allrun")], env=env, stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                          text=True)
    print(proc.stdout[-1500:])
    checks.true("with TFDEM_ROOT: the copied case runs", proc.returncode == 0, f"(exit code {proc.returncode})")
    found = re.search(r"terminal velocity: tfdemFoam (\S+) m/s, drag law (\S+) m/s", proc.stdout)
    checks.true("its terminal velocity printed", found is not None)
    if found:
        checks.close("terminal velocity against the drag law's", float(found.group(1)), float(found.group(2)), 1e-4)
    subprocess.run([os.path.join(case, "Allclean")], env=env, check=False)
    left = files_under(case)
    checks.true("Allclean leaves the inputs and only them", left == inputs,
                f"(extra {sorted(set(left) - set(inputs))[:5]}, missing {sorted(set(inputs) - set(left))[:5]})")
    checks.finish()


if __name__ == "__main__":
    main()
