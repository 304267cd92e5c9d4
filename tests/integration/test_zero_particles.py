"""With a coupling.yaml but no particles, tfdemFoam reproduces the single-phase solution.

The Poiseuille tutorial runs once gas-only and once coupled to an empty LIGGGHTS domain
(eps = 1, K = 0 everywhere); the centreline probes must agree to 1e-10 relative (solver
tolerances are 1e-12; the two runs differ only in the order of identical operations).
"""
import os
import shutil

from tfdem_testlib import SOURCE_DIR, Checks, copy_case, read_probe, run

TUTORIAL = os.path.join(SOURCE_DIR, "tutorials", "poiseuille_channel")
COUPLING = os.path.join(SOURCE_DIR, "tests", "cases", "zero_particles")


def probes(case):
    _, p = read_probe(case, "p")
    _, u = read_probe(case, "U")
    return p + [v[0] for v in u]


def main():
    checks = Checks()
    gas_only = copy_case(TUTORIAL, "zero_particles_gas_only")
    coupled = copy_case(TUTORIAL, "zero_particles_coupled")
    for name in ("coupling.yaml", "in.empty"):
        shutil.copy(os.path.join(COUPLING, name), coupled)
    for case in (gas_only, coupled):
        run(["blockMesh"], case, "log.blockMesh")
        run(["tfdemFoam"], case, "log.tfdemFoam")
    _, log = run(["grep", "-c", "TFDEM coupling: 0 particles", os.path.join(coupled, "log.tfdemFoam")], coupled, "log.grep")
    checks.true("coupled run started LIGGGHTS with 0 particles", log.strip() == "1")
    names = ["p upstream", "p downstream", "Ux upstream", "Ux downstream"]
    for name, a, b in zip(names, probes(coupled), probes(gas_only)):
        checks.close(f"{name}: coupled with no particles vs gas only", a, b, 1e-10)
    checks.finish()


if __name__ == "__main__":
    main()
