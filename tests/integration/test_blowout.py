"""Particles leaving through an outlet (tests/cases/blowout): 16 light spheres blown out of a
column through the patch listed in coupling.yaml dem.outlets (0.05 s: 10 of 16 leave). The coupler removes each from
the DEM when its centre crosses the outlet and counts it; no particle may be lost otherwise.
Expected, by counting: particles at the start = particles in the bed + particles that left,
exactly, and the same for their mass (to round-off, 1e-12); at least one particle left.
"""
import math
import os
import re

from tfdem import SOURCE_DIR
from tfdem.case import Case
from tfdem.outputs import joined_series, particle_statistics
from tfdem_testlib import Checks, copy_case, run

CASE = os.path.join(SOURCE_DIR, "tests", "cases", "blowout")


def main():
    checks = Checks()
    case = Case(copy_case(CASE, "blowout"))
    run(["blockMesh"], case.path, "log.blockMesh")
    _, output = run(["tfdemFoam"], case.path, "log.tfdemFoam")
    initial = int(re.search(r"TFDEM coupling: (\d+) particles", output).group(1))
    d, rho = case.coupling_value("particles.diameter"), case.coupling_value("particles.density")
    particle_mass = rho * math.pi * d ** 3 / 6
    left = joined_series(case.path, "tfdemOutlets", "outlets.dat")
    left_count = sum(int(values[1]) for _, values in left)
    left_mass = sum(values[2] for _, values in left)
    stats = particle_statistics(case.path)
    in_bed, bed_mass = int(stats["particles"][-1]), stats["mass"][-1]
    checks.true("some particles left through the outlet, some are still in the bed", left_count > 0 and in_bed > 0,
                f"({left_count} left, {in_bed} in the bed)")
    checks.true("particles at the start = in the bed + left", initial == in_bed + left_count,
                f"({initial} = {in_bed} + {left_count})")
    checks.close("mass at the start = in the bed + left", bed_mass + left_mass, initial * particle_mass, 1e-12)
    checks.true("no particle lost", "were lost" not in output)
    checks.finish()


if __name__ == "__main__":
    main()
