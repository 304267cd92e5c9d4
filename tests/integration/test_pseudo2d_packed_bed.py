"""A poured pseudo-2-D bed (six diameters deep between front and back walls) with gas through
it: tutorials/pseudo2d_packed_bed, packed by tfdem.packing from its packing.yaml.

- The pour: every particle of packing.yaml inserted, at rest, with a random packing's gas
  fraction in the probe slab (0.36-0.44: random close to random loose packing of spheres).
- Pressure drop between the probe rows against Ergun (1952) at the slab's measured solid
  fraction (exact sphere-slab volumes, tfdem.physics.slab_solid_fraction), one cell deep and
  in the 3-D variant (tfdem.fixed_bed.DEEP_CELLS cells in depth): within 1 % (the issue asks
  3 %; measured -0.44 to +0.25 % over three pours, the spread from the cells' gas fraction varying about the
  mean, as Ergun is not linear in it).
- Front and back walls: slip one cell deep; noSlip in the 3-D variant, whose wall shear adds
  to the pressure drop about 2 mu (U/eps) / (dz/2) / depth per metre (dz = depth/DEEP_CELLS,
  the first cell's velocity gradient): the noSlip drop must exceed the slip one, by less than
  three times that estimate.
"""
import os

from tfdem import TUTORIALS
from tfdem.fixed_bed import DEEP_CELLS, PouredBed, poured_bed_runs
from tfdem_testlib import Checks, poured_copy, run

TUTORIAL = os.path.join(TUTORIALS, "pseudo2d_packed_bed")


def main():
    checks = Checks()
    case, count = poured_copy(TUTORIAL, "pseudo2d_packed_bed", 1.0)
    checks.true("every particle poured", len(case.particles()["id"]) == count, f"({len(case.particles()['id'])})")
    bed = PouredBed(case)
    checks.true("random packing's gas fraction in the slab", 0.36 < bed.eps < 0.44, f"({bed.eps:.4f})")

    runs = case.file("runs")
    results = poured_bed_runs(case, runs, runner=lambda args, cwd, log: run(args, cwd, log))
    for (name, u), (dp, expected) in results.items():
        checks.close(f"{name}: pressure drop at U = {u} m/s (Pa)", dp, expected, 0.01)

    u = next(u for (name, u) in results if name == "deep_slip")
    noslip, slip = results[("deep_noslip", u)][0], results[("deep_slip", u)][0]
    dz = bed.depth / DEEP_CELLS
    wall_gradient = 2 * bed.mu * (u / bed.eps) / (dz / 2) / bed.depth
    estimate = wall_gradient / bed.ergun_gradient(u)
    excess = noslip / slip - 1
    checks.true("noSlip front and back walls add their shear", 0 < excess < 3 * estimate,
                f"(noSlip {noslip:.3f} Pa, slip {slip:.3f} Pa: +{100 * excess:.4f} %, estimate {100 * estimate:.4f} %)")
    checks.finish()


if __name__ == "__main__":
    main()
