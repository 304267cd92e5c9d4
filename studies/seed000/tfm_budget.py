#!/usr/bin/env python3
"""The granular-energy budget of a TFM run of the uniform-inflow bed, term by term and row by
row: where the bottom row's heat comes from (issue 26).

    tfm_budget.py CASE [--from T] [--rows N]

CASE is a twoPhaseEulerFoam (v1912) kinetic-theory case of tfm_bubbling_bed (uniform mesh,
uniform inflow), its fields written in ASCII; where gs0, kappa and lambda were written too (a
writeObjects function object) the recomputed closures are checked against them. `--from`: the
first written time averaged, default the second half. Each term of the solver's granular
temperature equation (kineticTheoryModel::correct, Gidaspow 1994 eq. 3.20 with the
closures of Table 3.1-3.3; the constitutive relations recomputed here from alpha, Theta and
the velocities, and checked against the solver's own gs0, kappa and lambda) is evaluated per
cell with Gauss linear differences on the uniform mesh and the case's boundary conditions,
then averaged over each row of cells and over the written times:

  1.5 alpha rho_s DTheta/Dt = conduction + pressure work + shear + slip - collisions - drag

  conduction      div(kappa grad Theta)             (the inlet face at its fixed Theta)
  pressure work   -P_s div(U_s)                     P_s = rho_s alpha (1 + 2 (1 + e) alpha g0) Theta (Lun)
  shear           tau : grad(U_s)                   tau = rho_s (2 nu D + (lambda - 2/3 nu) tr(D) I)
  slip            J2 = beta^2 d |U_g - U_s|^2 / (4 alpha rho_s sqrt(pi Theta))   (gas-slip heating)
  collisions      gamma = 12 (1 - e^2) alpha^2 rho_s g0 Theta^1.5 / (d sqrt(pi))
  drag            J1 = 3 beta Theta                 (damping of fluctuations by the gas)

beta is GidaspowErgunWenYu's K (Ergun below a gas fraction of 0.8, Wen-Yu above; seed 000
eq. 30-31 with OpenFOAM's exponent -2.65). The remainder (sum of the right-hand side) is the
transport 1.5 alpha rho_s DTheta/Dt left to balance it. Also per row: alpha_s, Theta, P_s and
the solids' vertical velocity; and how much of the solids' weight their own pressure holds
up, as the solver applies it (-p' grad alpha, p' = dP_s/dalpha at the local Theta: the
dP_s/dTheta grad(Theta) part of grad P_s is left out) against -grad P_s. Writes
CASE/tfm_budget.csv and prints a table of the bottom rows and the bed above them.
"""
import argparse
import csv
import math
import os
import re
import subprocess
import sys

import numpy

from tfdem.outputs import boundary_values, field, times

SQRT_PI = math.sqrt(math.pi)
THETA_SMALL = 1e-6  # m^2/s^2, the solver's ThetaSmall
GRAVITY = 9.81      # m/s^2, constant/g
TERMS = ("conduction", "pressure_work", "shear", "slip", "collisions", "drag")


class BudgetError(Exception):
    """A case this budget cannot read, named."""


def entry(path, key):
    text = re.sub(r"//.*", "", open(path).read())
    found = re.search(rf"(?m)^\s*{key}\s+([-+0-9.eE]+)\s*;", text)
    if not found:
        raise BudgetError(f"{path}: no '{key}' entry")
    return float(found.group(1))


def properties(case):
    c = lambda *p: os.path.join(case, "constant", *p)  # noqa: E731
    return {"rho_s": entry(c("thermophysicalProperties.particles"), "rho"),
            "rho_g": entry(c("thermophysicalProperties.air"), "rho"),
            "mu_g": entry(c("thermophysicalProperties.air"), "mu"),
            "d": entry(c("phaseProperties"), "d"),
            "e": entry(c("turbulenceProperties.particles"), "e"),
            "residual_alpha": entry(c("turbulenceProperties.particles"), "residualAlpha"),
            "alpha_min_friction": entry(c("turbulenceProperties.particles"), "alphaMinFriction"),
            "alpha_max": entry(c("turbulenceProperties.particles"), "alphaMax"),
            "friction": {k: entry(c("turbulenceProperties.particles"), k) for k in ("Fr", "eta", "p", "alphaDeltaMin")}}


class Grid:
    """The case's cells as an (ny, nx) array of a uniform mesh, from the cell centres 0/C."""

    def __init__(self, case):
        if not os.path.isfile(os.path.join(case, "0", "C")):  # Allprepare keeps 0/Cy alone
            subprocess.run(["postProcess", "-func", "writeCellCentres", "-time", "0"], cwd=case, check=True,
                           stdout=subprocess.DEVNULL, stderr=subprocess.STDOUT)
        centres = numpy.array(field(case, "0", "C"))
        xs, ys = numpy.unique(numpy.round(centres[:, 0], 9)), numpy.unique(numpy.round(centres[:, 1], 9))
        self.nx, self.ny = len(xs), len(ys)
        if self.nx * self.ny != len(centres):
            raise BudgetError(f"{case}: {len(centres)} cells are not an nx x ny grid (one cell deep)")
        self.dx, self.dy = xs[1] - xs[0], ys[1] - ys[0]
        if not (numpy.allclose(numpy.diff(xs), self.dx) and numpy.allclose(numpy.diff(ys), self.dy)):
            raise BudgetError(f"{case}: the budget needs a uniform mesh")
        self.i = numpy.rint((centres[:, 0] - xs[0]) / self.dx).astype(int)
        self.j = numpy.rint((centres[:, 1] - ys[0]) / self.dy).astype(int)
        self.y = ys

    def to_grid(self, values):
        values = numpy.asarray(values, dtype=float)
        out = numpy.empty((self.ny, self.nx) + values.shape[1:])
        out[self.j, self.i] = values
        return out


def face_gradient(f, dx, dy, left, right, bottom, top):
    """Gauss-linear gradient of a cell field f (ny, nx) on a uniform mesh: the face values are
    the neighbours' mean inside and the given boundary values (None: zero gradient)."""
    def faces(a, axis, lo, hi):
        inner = 0.5 * (numpy.take(a, range(1, a.shape[axis]), axis) + numpy.take(a, range(a.shape[axis] - 1), axis))
        first = numpy.take(a, [0], axis) if lo is None else numpy.full_like(numpy.take(a, [0], axis), lo)
        last = numpy.take(a, [-1], axis) if hi is None else numpy.full_like(numpy.take(a, [-1], axis), hi)
        return numpy.concatenate([first, inner, last], axis)
    fx, fy = faces(f, 1, left, right), faces(f, 0, bottom, top)
    return (fx[:, 1:] - fx[:, :-1]) / dx, (fy[1:, :] - fy[:-1, :]) / dy


def drag(alpha_s, ur, p):
    """GidaspowErgunWenYu's K (v1912): Ergun below a gas fraction of 0.8, Wen-Yu at and above."""
    alpha_g = 1.0 - alpha_s
    re = ur * p["d"] * p["rho_g"] / p["mu_g"]
    ergun = alpha_s * (150.0 * alpha_s * p["mu_g"] / (alpha_g * p["d"] ** 2) + 1.75 * p["rho_g"] * ur / p["d"])
    res = alpha_g * re
    cds_res = numpy.where(res < 1000.0, 24.0 * (1.0 + 0.15 * res ** 0.687), 0.44 * res)
    wen_yu = 0.75 * cds_res * alpha_g ** -2.65 * p["mu_g"] / p["d"] ** 2 * numpy.maximum(alpha_s, 1e-6)
    return numpy.where(alpha_g >= 0.8, wen_yu, ergun)


def closures(alpha, theta, p):
    """Carnahan-Starling g0, Gidaspow nu and kappa, Lun's P_s coefficient, the bulk viscosity."""
    e, d, rho = p["e"], p["d"], p["rho_s"]
    g0 = 1 / (1 - alpha) + 3 * alpha / (2 * (1 - alpha) ** 2) + alpha ** 2 / (2 * (1 - alpha) ** 3)
    sqrt_theta = numpy.sqrt(theta)
    nu = d * sqrt_theta * (0.8 * alpha ** 2 * g0 * (1 + e) / SQRT_PI + SQRT_PI * g0 * (1 + e) * alpha ** 2 / 15
                           + SQRT_PI * alpha / 6 + 10 * SQRT_PI / (96 * (1 + e) * g0))
    kappa = rho * d * sqrt_theta * (2 * alpha ** 2 * g0 * (1 + e) / SQRT_PI + 9 / 16 * SQRT_PI * g0 * (1 + e) * alpha ** 2
                                    + 15 / 16 * SQRT_PI * alpha + 25 * SQRT_PI / (64 * (1 + e) * g0))
    lam = 4 / 3 * alpha ** 2 * d * g0 * (1 + e) * sqrt_theta / SQRT_PI
    ps_coeff = rho * alpha * (1 + 2 * (1 + e) * alpha * g0)
    return g0, nu, kappa, lam, ps_coeff


def p_prime(alpha, theta, p):
    """The solids pressure's alpha-derivative the solver's momentum equation uses
    (kineticTheoryModel::pPrime): Lun's at the local Theta (Carnahan-Starling g0 and g0') and
    the Johnson-Jackson-Schaeffer frictional one."""
    e, rho, f = p["e"], p["rho_s"], p["friction"]
    g0 = 1 / (1 - alpha) + 3 * alpha / (2 * (1 - alpha) ** 2) + alpha ** 2 / (2 * (1 - alpha) ** 3)
    g0_prime = 2.5 / (1 - alpha) ** 2 + 4 * alpha / (1 - alpha) ** 3 + 1.5 * alpha ** 2 / (1 - alpha) ** 4
    kinetic = theta * rho * (1 + alpha * (1 + e) * (4 * g0 + 2 * g0_prime * alpha))
    excess = numpy.maximum(alpha - p["alpha_min_friction"], 0.0)
    frictional = f["Fr"] * (f["eta"] * excess ** (f["eta"] - 1) * (p["alpha_max"] - alpha) + f["p"] * excess ** f["eta"]) \
        / numpy.maximum(p["alpha_max"] - alpha, f["alphaDeltaMin"]) ** (f["p"] + 1)
    return kinetic + frictional


def granular_support(alpha, theta, grid, p):
    """The upward force per bed area on the solids from their pressure, (a) as the solver applies
    it, -p' grad(alpha) on the interior faces (p' linear to the faces; zero on the boundaries,
    where alpha has zero gradient), and (b) as -grad(P_s) would: the two differ by the
    dP_s/dTheta grad(Theta) part the first leaves out, and (b) sums to the bottom row's P_s
    alone. Column means, Pa."""
    pp = p_prime(alpha, theta, p)
    face_pp = 0.5 * (pp[1:, :] + pp[:-1, :])
    applied = -(face_pp * (alpha[1:, :] - alpha[:-1, :])).sum(axis=0).mean()
    ps = closures(alpha, theta, p)[4] * theta
    conservative = -(ps[1:, :] - ps[:-1, :]).sum(axis=0).mean()
    return float(applied), float(conservative)


def budget(case, time_name, grid, p):
    """Per-cell terms (W/m^3) and state of one written time, as (ny, nx) arrays."""
    read = lambda name: grid.to_grid(field(case, time_name, name))  # noqa: E731
    alpha = numpy.maximum(read("alpha.particles"), 0.0)
    theta = numpy.maximum(read("Theta.particles"), 0.0)
    us, ug = read("U.particles")[..., :2], read("U.air")[..., :2]
    theta_inlet = boundary_values(case, time_name, "Theta.particles", "inlet")
    if len(theta_inlet) != 1:
        raise BudgetError(f"{case}/{time_name}/Theta.particles: the budget needs a uniform inlet Theta")
    theta_inlet = theta_inlet[0]
    g0, nu, kappa, lam, ps_coeff = closures(alpha, theta, p)
    # the solver's kappa is of the step's starting Theta (computed before the Theta equation), so
    # it is checked in the median to 5 % (a step changes Theta by up to a few per cent in a bubbling bed); gs0 and lambda (after
    # it) cell by cell to 1e-3
    check = {"gs0.particles": (g0, numpy.max, 1e-3), "kappa.particles": (kappa, numpy.median, 5e-2),
             "lambda.particles": (lam, numpy.max, 1e-3)}
    for name, (ours, over, tolerance) in check.items():
        if not os.path.isfile(os.path.join(case, time_name, name)):
            continue  # not written (no writeObjects): the closures are this script's alone
        theirs = read(name)
        worst = float(over(numpy.abs(ours - theirs) / numpy.maximum(numpy.abs(theirs), 1e-30)))
        if worst > tolerance:
            raise BudgetError(f"{case}/{time_name}/{name}: the recomputed closure differs from the solver's by "
                              f"{worst:.1e} (relative): the budget's formulas are not this case's models")
    # grad(U_s): the solids are at rest on every boundary (noSlip walls, fixed zero at the inlet and outlet)
    du = [face_gradient(us[..., k], grid.dx, grid.dy, 0.0, 0.0, 0.0, 0.0) for k in range(2)]
    g = {(0, 0): du[0][0], (1, 0): du[0][1], (0, 1): du[1][0], (1, 1): du[1][1]}  # g[(i, j)] = d u_j / d x_i
    tr = g[(0, 0)] + g[(1, 1)]
    d_xy = 0.5 * (g[(0, 1)] + g[(1, 0)])
    d_colon_d = g[(0, 0)] ** 2 + g[(1, 1)] ** 2 + 2 * d_xy ** 2
    rho = p["rho_s"]
    ur = numpy.linalg.norm(ug - us, axis=-1)
    beta = drag(alpha, ur, p)
    sqrt_theta = numpy.sqrt(theta)
    terms = {
        "conduction": conduction(theta, kappa, theta_inlet, alpha, grid, p),
        "pressure_work": -ps_coeff * theta * tr,
        "shear": rho * (2 * nu * d_colon_d + (lam - 2.0 / 3.0 * nu) * tr ** 2),
        "slip": 0.25 * beta ** 2 * p["d"] * ur ** 2 / (numpy.maximum(alpha, p["residual_alpha"]) * rho * SQRT_PI
                                                       * (sqrt_theta + math.sqrt(THETA_SMALL)))
                * theta / (theta + THETA_SMALL),
        "collisions": 12 * (1 - p["e"] ** 2) * numpy.maximum(alpha ** 2, p["residual_alpha"]) * rho * g0 * sqrt_theta
                      / (p["d"] * SQRT_PI) * theta,
        "drag": 3 * beta * theta,
    }
    state = {"alpha_s": alpha, "theta": theta, "p_s": ps_coeff * theta, "v_s": us[..., 1], "slip_speed": ur,
             "beta": beta}
    applied, conservative = granular_support(alpha, theta, grid, p)
    weight = float(alpha.sum(axis=0).mean() * grid.dy * (p["rho_s"] - p["rho_g"]) * GRAVITY)
    support = {"applied": applied, "conservative": conservative, "weight": weight}
    return terms, state, support


def conduction(theta, kappa, theta_inlet, alpha, grid, p):
    """div(kappa grad Theta) per unit volume: zero gradient at the walls and the outlet, the
    inlet face at its fixed Theta with kappa of the face's own Theta (as the solver's boundary
    kappa, from the boundary values)."""
    kx = 0.5 * (kappa[:, 1:] + kappa[:, :-1])
    flux_x = kx * (theta[:, 1:] - theta[:, :-1]) / grid.dx
    ky = 0.5 * (kappa[1:, :] + kappa[:-1, :])
    flux_y = ky * (theta[1:, :] - theta[:-1, :]) / grid.dy
    zero_x = numpy.zeros((grid.ny, 1))
    fx = numpy.concatenate([zero_x, flux_x, zero_x], axis=1)
    kappa_inlet = closures(alpha[0], numpy.full(grid.nx, theta_inlet), p)[2]
    inlet = kappa_inlet * (theta[0] - theta_inlet) / (0.5 * grid.dy)  # out of the bed through the inlet face
    fy = numpy.concatenate([-inlet[None, :], flux_y, numpy.zeros((1, grid.nx))], axis=0)
    return (fx[:, 1:] - fx[:, :-1]) / grid.dx + (fy[1:, :] - fy[:-1, :]) / grid.dy


def row_budget(case, start):
    p = properties(case)
    grid = Grid(case)
    written = [t for t in times(case) if float(t) >= start and float(t) > 0]
    if not written:
        raise BudgetError(f"{case}: no written time at or after {start} s")
    sums, supports = None, []
    for t in written:
        terms, state, support = budget(case, t, grid, p)
        rows = {k: v.mean(axis=1) for k, v in {**terms, **state}.items()}
        sums = rows if sums is None else {k: sums[k] + rows[k] for k in rows}
        supports.append(support)
    rows = {k: v / len(written) for k, v in sums.items()}
    rows["transport"] = sum(rows[k] for k in TERMS[:4]) - rows["collisions"] - rows["drag"]
    support = {k: float(numpy.mean([s[k] for s in supports])) for k in supports[0]}
    return grid, rows, written, support


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("case")
    parser.add_argument("--from", dest="start", type=float, default=None,
                        help="first written time averaged (default: the second half)")
    parser.add_argument("--rows", type=int, default=6, help="bottom rows printed one by one")
    args = parser.parse_args(argv)
    try:
        written = [float(t) for t in times(args.case) if float(t) > 0]
        start = args.start if args.start is not None else (written[-1] / 2 if written else 0.0)
        grid, rows, used, support = row_budget(args.case, start)
    except (BudgetError, OSError, subprocess.CalledProcessError) as e:
        print(f"tfm_budget.py: {e}", file=sys.stderr)
        return 2
    columns = ("y", "alpha_s", "theta", "p_s", "v_s", "slip_speed", "beta") + TERMS + ("transport",)
    out = os.path.join(args.case, "tfm_budget.csv")
    with open(out, "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(columns)
        for j in range(grid.ny):
            w.writerow([f"{grid.y[j]:.4f}"] + [f"{rows[c][j]:.6g}" for c in columns[1:]])
    bed = [j for j in range(args.rows, grid.ny) if rows["alpha_s"][j] > 0.3]
    print(f"{args.case}: granular-energy budget, W/m^3, row means over {len(used)} written times "
          f"{used[0]}-{used[-1]} s ({out})")
    print(f"{'row':>10} {'alpha_s':>7} {'Theta':>9} {'P_s Pa':>8} " + " ".join(f"{t:>13}" for t in TERMS + ("transport",)))

    def line(label, sel):
        values = [float(numpy.mean(rows[c][sel])) for c in ("alpha_s", "theta", "p_s") + TERMS + ("transport",)]
        print(f"{label:>10} {values[0]:7.3f} {values[1]:9.2e} {values[2]:8.1f} "
              + " ".join(f"{v:13.4g}" for v in values[3:]))
    for j in range(args.rows):
        line(f"y {100 * grid.y[j]:.1f} cm", [j])
    if bed:
        line(f"bed {100 * grid.y[bed[0]]:.0f}-{100 * grid.y[bed[-1]]:.0f}", bed)
    w = support["weight"]
    print(f"the solids' own pressure holds up {support['applied']:.0f} Pa = {support['applied'] / w:.3f} of their "
          f"weight per area ({w:.0f} Pa) as the solver applies it (-p' grad alpha), where -grad P_s would hold "
          f"{support['conservative']:.0f} Pa = {support['conservative'] / w:.3f} (the bottom row's P_s); the gas "
          f"carries the rest")
    return 0


if __name__ == "__main__":
    sys.exit(main())
