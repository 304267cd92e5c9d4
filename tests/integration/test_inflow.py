"""Inflow options at a fixed-velocity inlet: what a fixedValue U means for the gas flux.

tfdemFoam's U is the interstitial gas velocity; the face flux that satisfies continuity is the
superficial one, eps_f phi (written as voidFractionPhi). At an inlet with fixedValue U and
fixedFluxPressure p, the voidFraction boundary condition selects the meaning of U_in:
  superficial:  voidFraction fixedValue 1   ->  superficial flux = U_in A_f on every face;
  interstitial: voidFraction zeroGradient   ->  superficial flux = eps_c U_in A_f, eps_c of the
                                                cell behind the face.
Case tests/cases/inflow: a 4 x 10 column of 1 cm cells, depth d = 2.5 mm, with 0, 4, 6 and 9
fixed spheres in the inlet cells, so eps_c = 1 - n pi d^3 / 6 / (1e-4 m^2 d); the cells, d, U_in
and the spheres per cell are read from the case's files (class Inlet).
Tolerance 1e-6 relative: the flux is set exactly through the fixedFluxPressure gradient, so
only round-off and the 15 written digits remain. The cells' eps is checked first (1e-12).

Usage: test_inflow.py [superficial|interstitial] (default both).
"""
import os
import sys

from tfdem import SOURCE_DIR
from tfdem.case import Case
from tfdem.outputs import boundary_values, field, times
from tfdem.physics import sphere_volume
from tfdem_testlib import Checks, copy_case, run

CASE = os.path.join(SOURCE_DIR, "tests", "cases", "inflow")
INLET_BC = {"superficial": "inlet        { type fixedValue; value uniform 1; }",
            "interstitial": "inlet        { type zeroGradient; }"}


class Inlet:
    """The inlet row of the case, from its own files: sphere diameter (coupling.yaml), cells
    (system/blockMeshDict), U_in (0/U), and the spheres in each inlet cell (the lattice sites of
    the DEM script's create_atoms regions)."""

    def __init__(self, path):
        case = Case(path)
        d, _ = case.particle_properties()
        grid = case.grid()
        dx, dy, dz = grid.spacing
        self.cells = grid.cell_count
        self.face_area = dx * dz
        self.u_in = case.patch_value("U", "inlet")[1]
        dem = case.dem()
        sites = [site for words in dem.commands("create_atoms") if words[2] == "region"
                 for site in dem.lattice_sites(words[3])]
        x0, y0, _ = grid.origin
        self.centres = [sum(1 for x, y, _ in sites if int((x - x0) // dx) == i and y - y0 < dy)
                        for i in range(grid.counts[0])]
        self.eps = [1 - n * sphere_volume(d) / (dx * dy * dz) for n in self.centres]


def expand(values, count):
    """A field's values, a uniform one repeated count times."""
    return values * count if len(values) == 1 else values


def run_option(option, checks):
    inlet = Inlet(CASE)
    case = copy_case(CASE, f"inflow_{option}")
    path = os.path.join(case, "0", "voidFraction")
    text = open(path).read()
    open(path, "w").write(text.replace(INLET_BC["superficial"], INLET_BC[option]))
    run(["blockMesh"], case, "log.blockMesh")
    run(["tfdemFoam"], case, "log.tfdemFoam")
    end = times(case)[-1]
    eps_cells = expand(field(case, end, "voidFraction"), inlet.cells)[:len(inlet.centres)]  # bottom row first
    for i, (eps, expected) in enumerate(zip(eps_cells, inlet.eps)):
        checks.within(f"{option}: eps of inlet cell {i} ({inlet.centres[i]} spheres)", eps, expected, 1e-12)
    flux = expand(boundary_values(case, end, "voidFractionPhi", "inlet"), len(inlet.centres))
    scale = inlet.eps if option == "interstitial" else [1.0] * len(inlet.centres)
    for i, (f, s) in enumerate(zip(flux, scale)):
        checks.close(f"{option}: superficial inflow through inlet face {i} (m^3/s)", -f,
                     s * inlet.u_in * inlet.face_area, 1e-6)
    checks.close(f"{option}: superficial inflow through the inlet (m^3/s)", -sum(flux),
                 sum(scale) * inlet.u_in * inlet.face_area, 1e-6)


def main(options):
    checks = Checks()
    for option in options:
        if option not in INLET_BC:
            print(f"test_inflow.py: unknown option '{option}' (expected superficial or interstitial)")
            sys.exit(2)
        run_option(option, checks)
    checks.finish()


if __name__ == "__main__":
    main(sys.argv[1:] or list(INLET_BC))
