"""A porous plate from fvOptions (explicitPorositySource, Darcy-Forchheimer) in tfdemFoam.

Case tests/cases/porous_plate: plug flow (slip walls) at U = 0.5 m/s up a column with a plate
L = 2 cm thick; gas only (void fraction 1). OpenFOAM's Darcy-Forchheimer source is
S = -(mu d + rho |U| f / 2) U, so in steady plug flow the pressure falls by
  dp = (mu d U + rho f U^2 / 2) L + rho g dy
between probes dy = 9 cm apart on either side of the plate. Tolerance 1e-8 relative: the flow
is uniform, the face fluxes are exact for cells in series and the solver tolerance is 1e-12.
"""
import os

from tfdem_testlib import SOURCE_DIR, Checks, copy_case, read_probe, run

CASE = os.path.join(SOURCE_DIR, "tests", "cases", "porous_plate")
RHO, NU, G = 1.2, 1.5e-5, 9.81          # constant/transportProperties, constant/g
U = 0.5                                 # m/s, 0/U
DARCY, FORCHHEIMER = 5e8, 1000.0        # constant/fvOptions d (1/m^2), f (1/m)
THICKNESS, PROBE_DY = 0.02, 0.09        # m: the plate zone, the probes' distance


def main():
    checks = Checks()
    case = copy_case(CASE, "porous_plate")
    run(["blockMesh"], case, "log.blockMesh")
    run(["tfdemFoam"], case, "log.tfdemFoam")
    _, (below, above) = read_probe(case, "p", "pressure")
    plate = (RHO * NU * DARCY * U + 0.5 * RHO * FORCHHEIMER * U * U) * THICKNESS
    checks.close("pressure drop across the plate and the gas column (Pa)", below - above,
                 plate + RHO * G * PROBE_DY, 1e-8)
    checks.finish()


if __name__ == "__main__":
    main()
