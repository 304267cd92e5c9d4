"""A poured pseudo-2-D bed (six diameters deep between front and back walls) with gas through
it: tutorials/pseudo2d_packed_bed, packed by tfdem.packing from its packing.yaml.

- The pour: every particle of packing.yaml inserted, at rest, with a random packing's gas
  fraction in the probe slab (0.36-0.44: random close to random loose packing of spheres).
- Pressure drop between the probe rows against Ergun (1952) at the slab's measured solid
  fraction (exact sphere-slab volumes, tfdem.physics.slab_solid_fraction), one cell deep and
  in the 3-D variant (tfdem.fixed_bed.DEEP_CELLS cells in depth): within 1 % (the issue asks
  3 %; measured -0.44 to +0.25 % over three pours, the spread from the cells' gas fraction varying about the
  mean, as Ergun is not linear in it).
- Front and back walls: slip one cell deep; noSlip in the 3-D variant. How much the noSlip
  walls add is computed independently of the solver: the fully developed flow across the
  depth written out by hand on the DEEP_CELLS layers of cells (layer_model: per layer its
  drag K_i U_i from Ergun at the layer's own gas fraction, read from the run's voidFraction
  over the probe slab; the viscous flux eps_f mu dU/dz between layers and eps mu U/(dz/2) into
  a noSlip wall, as the gas equation's laplacian(eps nu, U) discretises it; the layers' flow
  summing to the superficial velocity), solved for the pressure gradient with noSlip and slip
  walls. The measured noSlip/slip - 1 must be that model's within 10 % of it (the model leaves
  out the gas fraction's variation along the height inside a layer).
"""
import os

import numpy

from tfdem import TUTORIALS, outputs
from tfdem.physics import ergun_gradient
from tfdem.fixed_bed import DEEP_CELLS, PouredBed, poured_bed_runs
from tfdem_testlib import Checks, poured_copy, run

TUTORIAL = os.path.join(TUTORIALS, "pseudo2d_packed_bed")


def layer_gas_fractions(case_path, time_name, grid, below, above):
    """The run's voidFraction averaged per layer of cells across the depth (z), over the cells
    whose centres lie between the probe rows."""
    eps = numpy.array(outputs.field(case_path, time_name, "voidFraction"))
    centres = numpy.array(grid.centres())
    inside = (centres[:, 1] > below) & (centres[:, 1] < above)
    layers = numpy.round((centres[:, 2] - grid.origin[2]) / grid.spacing[2] - 0.5).astype(int)
    return [float(eps[inside & (layers == k)].mean()) for k in range(grid.counts[2])]


def layer_model(eps, u, d, rho, mu, depth, noslip):
    """Pressure gradient G (Pa/m) of fully developed flow through layers of gas fraction eps_i
    across the depth, superficial velocity u: per layer (thickness dz, per unit area)
    eps_i G dz = K_i U_i dz + sum of its viscous fluxes, eps_f mu (U_i - U_j) / dz to a
    neighbour (eps_f the two layers' mean) and eps_i mu U_i / (dz / 2) to a noSlip wall, with
    sum eps_i U_i dz = u depth; K_i = eps_i^2 Ergun(eps_i U_i) / (eps_i U_i), Picard-iterated on
    the inertial term."""
    n, dz = len(eps), depth / len(eps)
    velocity = [u / e for e in eps]
    for _ in range(100):
        a, b = numpy.zeros((n + 1, n + 1)), numpy.zeros(n + 1)
        for i, e in enumerate(eps):
            k = e ** 2 * ergun_gradient(e * velocity[i], e, d, rho, mu) / (e * velocity[i])
            a[i, i] += k * dz
            for j in (i - 1, i + 1):
                if 0 <= j < n:
                    conductance = 0.5 * (e + eps[j]) * mu / dz
                    a[i, i] += conductance
                    a[i, j] -= conductance
                elif noslip:
                    a[i, i] += e * mu / (dz / 2)
            a[i, n] = -e * dz
            a[n, i] = e * dz
        b[n] = u * depth
        solution = numpy.linalg.solve(a, b)
        converged = numpy.allclose(solution[:n], velocity, rtol=1e-12)
        velocity = list(solution[:n])
        if converged:
            break
    return float(solution[n])


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
    deep = os.path.join(runs, f"deep_noslip_U{u}")
    deep_bed = PouredBed(deep)
    eps = layer_gas_fractions(deep, outputs.times(deep)[-1], deep_bed.case.grid(), deep_bed.below, deep_bed.above)
    model = [layer_model(eps, u, bed.d, bed.rho_g, bed.mu, bed.depth, walls) for walls in (True, False)]
    expected = model[0] / model[1] - 1
    excess = noslip / slip - 1
    checks.true("noSlip front and back walls add the shear of the layer model", abs(excess - expected) <= 0.1 * expected,
                f"(noSlip {noslip:.3f} Pa, slip {slip:.3f} Pa: +{100 * excess:.4f} %; model +{100 * expected:.4f} % "
                f"with layer gas fractions {[round(e, 4) for e in eps]})")
    checks.finish()


if __name__ == "__main__":
    main()
