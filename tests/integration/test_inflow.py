"""Inflow options at a fixed-velocity inlet: what a fixedValue U means for the gas flux.

tfdemFoam's U is the interstitial gas velocity; the face flux that satisfies continuity is the
superficial one, eps_f phi (written as voidFractionPhi). At an inlet with fixedValue U and
fixedFluxPressure p, the voidFraction boundary condition selects the meaning of U_in:
  superficial:  voidFraction fixedValue 1   ->  superficial flux = U_in A_f on every face;
  interstitial: voidFraction zeroGradient   ->  superficial flux = eps_c U_in A_f, eps_c of the
                                                cell behind the face.
Case tests/cases/inflow: a 4 x 10 column of 1 cm cells, depth d = 2.5 mm, with 0, 4, 6 and 9
fixed spheres in the inlet cells, so eps_c = 1 - n pi d^3 / 6 / (1e-4 m^2 d) (formula below).
Tolerance 1e-6 relative: the flux is set exactly through the fixedFluxPressure gradient, so
only round-off and the 15 written digits remain. The cells' eps is checked first (1e-12).

Usage: test_inflow.py [superficial|interstitial] (default both).
"""
import math
import os
import re
import sys

from tfdem_testlib import SOURCE_DIR, Checks, copy_case, run

CASE = os.path.join(SOURCE_DIR, "tests", "cases", "inflow")
D = 0.0025                       # m, sphere diameter (in.inflow)
CELL_AREA = 0.01 * 0.01          # m^2, cell face in the x-y plane
FACE_AREA = 0.01 * D             # m^2, one inlet face
U_IN = 0.5                       # m/s, 0/U inlet value
CENTRES = (0, 4, 6, 9)           # spheres per inlet cell, left to right (in.inflow)
EPS = [1 - n * math.pi * D ** 3 / 6 / (CELL_AREA * D) for n in CENTRES]
CELLS = 4 * 10                   # the column's cells (system/blockMeshDict)
END_TIME = "0.02"

INLET_BC = {"superficial": "inlet        { type fixedValue; value uniform 1; }",
            "interstitial": "inlet        { type zeroGradient; }"}


def field_values(text, count):
    """Values of an OpenFOAM 'value'/'internalField' entry: uniform x or nonuniform List."""
    text = text.strip()
    if text.startswith("uniform"):
        return [float(text.split()[1].rstrip(";"))] * count
    body = text[text.index("(") + 1:text.index(")")]
    return [float(v) for v in body.split()]


def read_field(path):
    """(internal values, {patch: text of its dictionary}) of an ascii scalar field file."""
    text = open(path).read()
    internal = re.search(r"internalField\s+(uniform\s+\S+|nonuniform\s+List<scalar>\s*\d+\s*\([^)]*\))", text)
    patches = dict(re.findall(r"\n    (\w+)\s*\n    \{(.*?)\n    \}", text, re.S))
    return internal.group(1), patches


def inlet_values(path):
    _, patches = read_field(path)
    value = re.search(r"value\s+(uniform\s+\S+|nonuniform\s+List<scalar>\s*\d+\s*\([^)]*\))", patches["inlet"], re.S)
    return field_values(value.group(1), len(CENTRES))


def run_option(option, checks):
    case = copy_case(CASE, f"inflow_{option}")
    path = os.path.join(case, "0", "voidFraction")
    text = open(path).read()
    open(path, "w").write(text.replace(INLET_BC["superficial"], INLET_BC[option]))
    run(["blockMesh"], case, "log.blockMesh")
    run(["tfdemFoam"], case, "log.tfdemFoam")
    internal, _ = read_field(os.path.join(case, END_TIME, "voidFraction"))
    eps_cells = field_values(internal, CELLS)[:len(CENTRES)]  # blockMesh numbers the bottom row first
    for i, (eps, expected) in enumerate(zip(eps_cells, EPS)):
        checks.within(f"{option}: eps of inlet cell {i} ({CENTRES[i]} spheres)", eps, expected, 1e-12)
    flux = inlet_values(os.path.join(case, END_TIME, "voidFractionPhi"))
    scale = EPS if option == "interstitial" else [1.0] * len(CENTRES)
    for i, (f, s) in enumerate(zip(flux, scale)):
        checks.close(f"{option}: superficial inflow through inlet face {i} (m^3/s)", -f, s * U_IN * FACE_AREA, 1e-6)
    checks.close(f"{option}: superficial inflow through the inlet (m^3/s)", -sum(flux),
                 sum(scale) * U_IN * FACE_AREA, 1e-6)


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
