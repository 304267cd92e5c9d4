"""tfm_budget.py's pieces (studies/seed000) on hand-made fields with answers by hand:

- the Gauss-linear gradient of linear fields with their boundary values: the slope, exactly;
- conduction of a linear Theta with a uniform kappa: zero inside, -/+ kappa c / dy in the top
  (zero-gradient) and bottom (inlet at the row's own Theta) rows;
- GidaspowErgunWenYu's K on both sides of the switch, worked out by hand from seed 000 eq. 30-31
  as tfm_README.md writes them;
- Carnahan-Starling g0 at alpha 0.48 (5.405 by hand);
- the solids pressure's support: with a uniform Theta, -p' grad(alpha) and -grad(P_s) agree
  (to the grid's second-order error); with Theta rising upwards -p' grad(alpha) holds up more
  than -grad(P_s).
"""
import math
import os
import sys

import numpy

from tfdem import STUDIES

sys.path.insert(0, os.path.join(STUDIES, "seed000"))
import tfm_budget as budget  # noqa: E402

failures = []


def check(name, condition, detail=""):
    print(("PASS " if condition else "FAIL ") + name + (f" {detail}" if detail else ""))
    if not condition:
        failures.append(name)


class FakeGrid:
    def __init__(self, nx, ny, dx, dy):
        self.nx, self.ny, self.dx, self.dy = nx, ny, dx, dy
        self.x = (numpy.arange(nx) + 0.5) * dx
        self.y = (numpy.arange(ny) + 0.5) * dy


PROPERTIES = {"rho_s": 2526.0, "rho_g": 1.2, "mu_g": 1.8e-5, "d": 2.5e-3, "e": 0.97, "residual_alpha": 1e-4,
              "alpha_min_friction": 0.58, "alpha_max": 0.62,
              "friction": {"Fr": 0.05, "eta": 2.0, "p": 5.0, "alphaDeltaMin": 0.05}}


def check_gradient():
    g = FakeGrid(4, 5, 0.01, 0.02)
    x, y = numpy.meshgrid(g.x, g.y)
    width, height = g.nx * g.dx, g.ny * g.dy
    gx, gy = budget.face_gradient(2.0 * x, g.dx, g.dy, 0.0, 2.0 * width, None, None)
    check("d(2x)/dx = 2 and d(2x)/dy = 0 everywhere", numpy.allclose(gx, 2.0, atol=1e-12) and numpy.allclose(gy, 0.0))
    gx, gy = budget.face_gradient(3.0 * y, g.dx, g.dy, None, None, 0.0, 3.0 * height)
    check("d(3y)/dy = 3 and d(3y)/dx = 0 everywhere", numpy.allclose(gy, 3.0, atol=1e-12) and numpy.allclose(gx, 0.0))
    gx, gy = budget.face_gradient(3.0 * y, g.dx, g.dy, None, None, 0.0, 0.0)
    check("a no-slip top face: the top row's slope (0 - 3 y_top-row/2 ...) by hand",
          math.isclose(gy[-1, 0], (0.0 - 0.5 * (3 * g.y[-1] + 3 * g.y[-2])) / g.dy, rel_tol=1e-12), str(gy[-1, 0]))


def check_conduction():
    g = FakeGrid(3, 6, 0.01, 0.01)
    c, k = 2.0, 0.7
    theta = numpy.tile((c * g.y)[:, None], (1, g.nx))
    kappa = numpy.full_like(theta, k)
    alpha = numpy.full_like(theta, 0.5)
    div = budget.conduction(theta, kappa, float(theta[0, 0]), alpha, g, PROPERTIES)
    check("conduction of a linear Theta: zero inside", numpy.allclose(div[1:-1], 0.0, atol=1e-9), str(div[1:-1, 0]))
    check("... -kappa c / dy in the top row (zero gradient above)", numpy.allclose(div[-1], -k * c / g.dy), str(div[-1]))
    check("... +kappa c / dy in the bottom row (the inlet at the row's Theta: no flux)",
          numpy.allclose(div[0], k * c / g.dy), str(div[0]))


def check_drag():
    p = PROPERTIES
    # Ergun at alpha_s 0.5, |u| 1 m/s: 0.5 (150 0.5 1.8e-5 / (0.5 (2.5e-3)^2) + 1.75 1.2 / 2.5e-3) = 0.5 (432 + 840)
    k = float(budget.drag(numpy.array(0.5), numpy.array(1.0), p))
    check("Ergun branch by hand: 636 kg/m^3/s", math.isclose(k, 636.0, rel_tol=1e-12), f"{k}")
    # Wen-Yu at alpha_s 0.1: Re_s = 0.9 * 1 * 2.5e-3 * 1.2 / 1.8e-5 = 150, C_D = 24 (1 + 0.15 Re_s^0.687) / Re_s,
    # beta = 3/4 C_D alpha_s alpha_g rho_g |u| / d alpha_g^-2.65 (seed 000 eq. 31 with OpenFOAM's exponent)
    cd = 24.0 * (1.0 + 0.15 * 150.0 ** 0.687) / 150.0
    expected = 0.75 * cd * 0.1 * 0.9 * 1.2 * 1.0 / 2.5e-3 * 0.9 ** -2.65
    k = float(budget.drag(numpy.array(0.1), numpy.array(1.0), p))
    check("Wen-Yu branch by hand", math.isclose(k, expected, rel_tol=1e-12), f"{k} vs {expected}")


def check_closures():
    g0 = float(budget.closures(numpy.array(0.48), numpy.array(1e-3), PROPERTIES)[0])
    # 1/0.52 + 1.44/(2 0.52^2) + 0.2304/(2 0.52^3) = 1.9231 + 2.6627 + 0.8193
    check("Carnahan-Starling g0(0.48) = 5.405 by hand", abs(g0 - 5.405) < 1e-3, f"{g0:.4f}")


def check_support():
    g = FakeGrid(2, 400, 0.01, 0.001)
    alpha = numpy.tile((0.5 * numpy.clip(1.0 - g.y / 0.3, 0.0, 1.0))[:, None], (1, g.nx))
    uniform = numpy.full_like(alpha, 4e-3)
    applied, conservative = budget.granular_support(alpha, uniform, g, PROPERTIES)
    check("uniform Theta: -p' grad alpha = -grad P_s (to 1 %)", math.isclose(applied, conservative, rel_tol=0.01),
          f"{applied:.2f} vs {conservative:.2f} Pa")
    rising = numpy.tile((4e-3 * (1.0 + g.y / 0.3))[:, None], (1, g.nx))
    more, less = budget.granular_support(alpha, rising, g, PROPERTIES)
    # -grad P_s = -p' grad alpha - dP_s/dTheta grad Theta: the part left out pushes down where Theta rises
    check("Theta rising upwards: -p' grad alpha holds up more than -grad P_s", more > 1.1 * less,
          f"{more:.2f} vs {less:.2f} Pa")


check_gradient()
check_conduction()
check_drag()
check_closures()
check_support()
if failures:
    print(f"{len(failures)} failed: {', '.join(failures)}")
    sys.exit(1)
print("all passed")
