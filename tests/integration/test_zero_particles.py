"""With a coupling.yaml but no particles, tfdemFoam reproduces the single-phase solution.

The Poiseuille tutorial runs once gas-only and once coupled to an empty LIGGGHTS domain
(eps = 1, K = 0 everywhere; tests/cases/zero_particles adds coupling.yaml, the DEM script and
the 0/voidFraction a coupled case with an inlet needs); the centreline probes must agree to
1e-10 relative (solver tolerances are 1e-12; the two runs differ only in the order of
identical operations).
"""
import os
import shutil

from tfdem import SOURCE_DIR, TUTORIALS
from tfdem.outputs import log_numbers
from tfdem_testlib import Checks, copy_case, read_probe, run

TUTORIAL = os.path.join(TUTORIALS, "poiseuille_channel")
COUPLING = os.path.join(SOURCE_DIR, "tests", "cases", "zero_particles")


def probes(case):
    _, p = read_probe(case, "p")
    _, u = read_probe(case, "U")
    return p + [v[0] for v in u]


def main():
    checks = Checks()
    gas_only = copy_case(TUTORIAL, "zero_particles_gas_only")
    coupled = copy_case(TUTORIAL, "zero_particles_coupled")
    for name in ("coupling.yaml", "in.empty", os.path.join("0", "voidFraction")):
        shutil.copy(os.path.join(COUPLING, name), os.path.join(coupled, name))
    for case in (gas_only, coupled):
        run(["blockMesh"], case, "log.blockMesh")
        run(["tfdemFoam"], case, "log.tfdemFoam")
    count = log_numbers(os.path.join(coupled, "log.tfdemFoam"), r"TFDEM coupling: (\d+) particles")
    checks.true("coupled run started LIGGGHTS with 0 particles", count == [0.0], f"(log: {count})")
    names = ["p upstream", "p downstream", "Ux upstream", "Ux downstream"]
    for name, a, b in zip(names, probes(coupled), probes(gas_only)):
        checks.close(f"{name}: coupled with no particles vs gas only", a, b, 1e-10)
    checks.finish()


if __name__ == "__main__":
    main()
