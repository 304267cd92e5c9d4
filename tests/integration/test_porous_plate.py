"""A porous plate from fvOptions (explicitPorositySource, Darcy-Forchheimer) in tfdemFoam.

Case tests/cases/porous_plate: plug flow (slip walls) at U = 0.5 m/s up a column with a plate
L = 2 cm thick; gas only (void fraction 1). OpenFOAM's Darcy-Forchheimer source is
S = -(mu d + rho |U| f / 2) U, so in steady plug flow the pressure falls by
  dp = (mu d U + rho f U^2 / 2) L + rho g dy
between probes dy = 9 cm apart on either side of the plate. Tolerance 1e-8 relative: the flow
is uniform, the face fluxes are exact for cells in series and the solver tolerance is 1e-12.
"""
import os

from tfdem import SOURCE_DIR
from tfdem.case import Case
from tfdem_testlib import Checks, copy_case, read_probe, run

CASE = os.path.join(SOURCE_DIR, "tests", "cases", "porous_plate")


def expected_pressure_drop():
    """(mu d U + rho f U^2 / 2) L + rho g dy from the case's files: constant/transportProperties,
    constant/g, the 0/U inlet, constant/fvOptions, the plate zone's block of
    system/blockMeshDict and the probes of system/controlDict (flow along y)."""
    case = Case(CASE)
    rho, mu = case.gas()
    u = case.patch_value("U", "inlet")[1]
    plate = case.porosity()
    darcy, forchheimer = plate["d"][1], plate["f"][1]
    zone_lo, zone_hi = case.block_bounds(plate["zone"])
    below, above = case.probe_locations("pressure")[:2]
    drop = (mu * darcy * u + 0.5 * rho * forchheimer * u * u) * (zone_hi[1] - zone_lo[1])
    return drop + rho * case.gravity_magnitude() * (above[1] - below[1])


def main():
    checks = Checks()
    case = copy_case(CASE, "porous_plate")
    run(["blockMesh"], case, "log.blockMesh")
    run(["tfdemFoam"], case, "log.tfdemFoam")
    _, (below, above) = read_probe(case, "p", "pressure")
    checks.close("pressure drop across the plate and the gas column (Pa)", below - above,
                 expected_pressure_drop(), 1e-8)
    checks.finish()


if __name__ == "__main__":
    main()
