"""Goldschmidt's bidisperse bed (studies/bidisperse_segregation), short: its own files with
a tenth of the particles (packing.yaml count / 10, a bed ~1.5 cm deep instead of ~15 cm) poured
mixed, then 0.1 s under the polydisperse drag on 2 ranks through the tutorial's driver: first
to 0.06 s, then carried on to 0.1 s from its 0.06 s checkpoint, as a long run is extended.

- The pour: every particle inserted; the small size's share of the mass as packing.yaml asks
  (within the sampling error of drawing sizes at random by mass, 3 binomial sigmas).
- The extension resumes from the checkpoint (a second solver segment that says so), not
  afresh; asked for the earlier end time again, the run is done without a solver.
- The run ends, conserves the particles, and its particle statistics carry the degree of
  segregation (seed 001 eq. 49) at 0.1 s: a poured mixture starts mixed, |s| < 0.15 (a
  random pour of equal volumes of the two sizes gives |s| of order 0.02; a bed segregated by
  the pour would be near 1).
"""
import math
import os
import sys

from tfdem import STUDIES
from tfdem.batch import run_batch
from tfdem.outputs import particle_statistics
from tfdem.packing import packing_settings
from tfdem.physics import sphere_volume
from tfdem_testlib import Checks, poured_copy

TUTORIAL = os.path.join(STUDIES, "bidisperse_segregation")
sys.path.insert(0, TUTORIAL)
import segregation  # noqa: E402


def main():
    checks = Checks()
    case, count = poured_copy(TUTORIAL, "segregation", 0.1)
    root = case.path
    particles = case.particles()
    small, large = case.particle_diameters()
    mass = {d: sum(sphere_volume(x) for x in particles["diameter"] if abs(x - d) < 1e-9) for d in (small, large)}
    checks.true("every particle poured", len(particles["id"]) == count, f"({len(particles['id'])} of {count})")
    fraction = mass[small] / (mass[small] + mass[large])
    expected = packing_settings(case)["mass_fraction_small"]
    p_small = (expected / sphere_volume(small)) / (expected / sphere_volume(small) + (1 - expected) / sphere_volume(large))
    sigma = expected * (1 - expected) / math.sqrt(count * p_small * (1 - p_small))  # of the binomial N_small
    checks.within("small size's mass fraction", fraction, expected, 3 * sigma)

    runs = [segregation.segregation_run("polydisperse", 2, root=root)]
    checks.true("run to 0.06 s finished", run_batch(runs, 0.06, 1))
    checks.true("carried on to 0.1 s", run_batch(runs, 0.1, 1))
    logs = runs[0].logs()
    checks.true("two solver segments", len(logs) == 2, f"({logs})")
    checks.true("the second resumed from the 0.06 s checkpoint",
                "resuming gas and particles from t = 0.06 s" in open(logs[-1]).read())
    checks.true("asked for 0.06 s again, the run past it is done without a solver",
                run_batch(runs, 0.06, 1) and runs[0].done() and len(runs[0].logs()) == 2)
    stats = particle_statistics(runs[0].case.path)
    checks.true("particles conserved", stats["particles"] and all(n == count for n in stats["particles"]),
                f"({stats['particles']})")
    checks.true("segregation degree written at 0.1 s", "segregation" in stats and abs(stats["t"][-1] - 0.1) < 1e-9,
                f"({stats.get('t')})")
    if "segregation" in stats:
        checks.true("the poured mixture starts mixed", abs(stats["segregation"][-1]) < 0.15, f"(s = {stats['segregation'][-1]:.4f})")
    checks.finish()


if __name__ == "__main__":
    main()
