"""Our kinetic-theory models for Debian's twoPhaseEulerFoam (tfm_models/, the library
libtfdemKineticTheory.so) and the case edits that select them, shared by the TFM studies and
tutorials.

- granularSlipProduction (an fvOption, constant/fvOptions): the production of granular
  temperature by gas-particle slip as MFIX has it (Koch & Sangani 1999, J. Fluid Mech. 400) or
  none, in place of v1912's Gidaspow form (tfm_models/granularSlipProduction.H).
- kineticTheoryConservative (RASModel): the solids pressure force as -grad P_s.
"""
import os

from tfdem import BUILD_DIR
from tfdem.errors import Reported

LIBRARY = os.path.abspath(os.path.join(BUILD_DIR, "tfm_models", "libtfdemKineticTheory.so"))
SLIP_PRODUCTIONS = ("KochSangani", "none")
# The edits of a constant/turbulenceProperties.<solids> file, (pattern, replacement), that select
# kineticTheoryConservative in place of v1912's kineticTheory, with the same coefficients
CONSERVATIVE_PRESSURE_EDITS = ((r"RASModel\s+kineticTheory;", "RASModel        kineticTheoryConservative;"),
                               (r"kineticTheoryCoeffs", "kineticTheoryConservativeCoeffs"))


class TfmModelsError(Reported):
    """The library is not built."""


def check_library():
    """Raise TfmModelsError unless the library is built (a case that loads it would stop with
    OpenFOAM's 'Unknown fvOption type' far from the cause)."""
    if not os.path.isfile(LIBRARY):
        raise TfmModelsError(f"{LIBRARY}: not built; the TFM models are built with the rest by `./tfdem setup` "
                             "(scripts/setup.sh, tfm_models/)")


def library_entry():
    """The controlDict line that loads the library."""
    return f'libs            ("{LIBRARY}");'


def load_library_edit():
    """The edit of system/controlDict, (pattern, replacement), that loads the library: its
    libs line put before the `application` entry."""
    return r"\napplication\s", f"\n{library_entry()}\napplication "


def slip_production_options(production, phase="particles"):
    """constant/fvOptions selecting granularSlipProduction for `phase` with `production`
    (one of SLIP_PRODUCTIONS)."""
    if production not in SLIP_PRODUCTIONS:
        raise ValueError(f"slip production {production!r}: one of {', '.join(SLIP_PRODUCTIONS)}")
    return ("FoamFile\n{\n    version     2.0;\n    format      ascii;\n    class       dictionary;\n"
            "    object      fvOptions;\n}\n\nslipProduction\n{\n    type            granularSlipProduction;\n"
            f"    phase           {phase};\n    production      {production};\n}}\n")
