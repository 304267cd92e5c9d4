"""Fluidization curve (tutorials/fluidization_curve): the superficial velocity stepped up
through U_mf to 2.2 m/s and back down, 825 spheres on a porous distributor plate.

Checks, with the tutorial's own schedule (levels.yaml) and analysis (tfdem.fluidization), what
is physically robust:
- fluidized, the gas carries the bed: the plateau (0.5 s batch means over the fluidized levels)
  within 5 % of the net bed weight per area. What it lacks is the weight the distributor plate
  carries (particles raining through bubbles land on it), about as large as the tutorial's 2 %
  target (its README): another compiler or CPU, another realisation of the bubbling, may land on
  either side of the target, so the plateau is printed against it with its standard error, not
  asserted at it;
- U_mf of the falling branch (Ergun-form fit through the fixed-bed levels, intersected with the
  plateau) within 10 % of Wen and Yu (1966);
- at every level the bed's pressure drop times the cross-section equals the gas force on the
  particles less their buoyancy, to 1 % of the bed weight: what the gas carries is what the
  pressure drop shows (the level means still hold the bed's momentum change while it expands).
"""
import os

from tfdem import TUTORIALS, fluidization
from tfdem_testlib import Checks, run, scratch

TUTORIAL = os.path.join(TUTORIALS, "fluidization_curve")
PLATEAU_TOLERANCE = 0.05   # of the net bed weight: fluidized, the gas carries >= 95 % of it
PLATEAU_TARGET = 0.02      # the tutorial's target, printed with the plateau's standard error
WEN_YU_TOLERANCE = 0.10   # the U_mf target
FORCE_BALANCE_TOLERANCE = 0.01   # of the bed weight


def main():
    checks = Checks()
    schedule = fluidization.Schedule.load(os.path.join(TUTORIAL, "levels.yaml"))
    case = scratch("fluidization_curve")
    fluidization.prepare_run(TUTORIAL, case, schedule, run)
    s = fluidization.summary(case, schedule)
    for line in fluidization.report(s, schedule):
        print(line)
    bed = s["bed"]
    area = bed.width * bed.depth
    weight = bed.weight() / area
    buoyancy = bed.solid_volume * bed.rho_g * bed.g / area
    print(f"plateau standard error {100 * s['plateau_error'] / s['weight']:.2f} % of the weight"
          f" ({s['plateau_batches']} batches); the plate carries {100 * s['plate_share']:.1f} %")
    deficit, error = 1 - s["plateau"] / s["weight"], s["plateau_error"] / s["weight"]
    print(f"plateau {100 * deficit:.2f} % ± {100 * error:.2f} % below the weight: "
          f"{'within' if abs(deficit) <= PLATEAU_TARGET else 'outside'} the {100 * PLATEAU_TARGET:g} % target "
          f"by {abs(PLATEAU_TARGET - abs(deficit)) / error:.1f} standard errors (reported, not asserted)")
    checks.close("plateau vs net bed weight / area (Pa)", s["plateau"], s["weight"], PLATEAU_TOLERANCE)
    checks.close("U_mf, falling branch, vs Wen-Yu (m/s)", s["u_mf"], s["wen_yu"], WEN_YU_TOLERANCE)
    for k, r in enumerate(s["levels"]):
        branch = "rising" if k < schedule.rising_count else "falling"
        checks.within(f"{branch} {r['u']} m/s: pressure drop vs gas force on the particles less"
                      " buoyancy, per area (Pa)", r["dp"], r["gas"] * weight - buoyancy,
                      FORCE_BALANCE_TOLERANCE * weight)
    checks.finish()


if __name__ == "__main__":
    main()
