"""The kinetic-theory peer of seed 000's uniform bed bubbles, and v1912's own kinetic theory
does not: 2 s of each, the rows' lateral spread of alpha_s against a bound.

Both runs are the TFM template (studies/seed000/tfm_bubbling_bed, 15 x 45 cells of 1 cm) with
the changes tfm_mechanism.py names, taken from there so the test runs what the study runs:
`restitution_0.859` (v1912's kinetic theory at Jenkins & Zhang's effective restitution of
Table 1's e and friction) and the study's peer, `slip_production_koch_sangani_restitution_0.859_
conservative` (the same with MFIX's production of Theta by gas-particle slip, Koch & Sangani
1999, in place of v1912's, tfm_models/granularSlipProduction, and the solids pressure force as
-grad P_s, tfm_models/kineticTheoryConservative). Measured on the fields written every 0.1 s over 1-2 s: the
standard deviation of alpha_s across each row of the bed (the rows initially at least half
full), averaged over the rows and the writes. Flat layers and 1-D slugs keep it at the walls'
profile (0.002-0.004 in the study's 6-s runs); bubbles a few cells wide raise it to 0.03-0.07.
The bound is the study's BUBBLING, 0.02.
"""
import os
import sys

from tfdem import STUDIES
from tfdem_testlib import Checks, fail, require_tfm_models, scratch

sys.path.insert(0, os.path.join(STUDIES, "seed000"))
import tfm_mechanism as mechanism  # noqa: E402

END_TIME = 2.0  # s
FROM = 1.0  # s: the bubbles of the peer are formed by 0.6 s
PEER = "slip_production_koch_sangani_restitution_0.859_conservative"
STOCK = "restitution_0.859"


def run_case(name):
    """The variant's case under build/test-runs/, run to END_TIME as the study runs it; its path."""
    case = scratch(f"tfm_bubbles_{name}")
    try:
        mechanism.run_case(name, case, END_TIME)
    except (mechanism.MechanismError, mechanism.Reported) as error:
        fail(str(error))
    return case


def spread(case):
    """The rows' mean lateral std of alpha_s, averaged over the writes from FROM on."""
    nx, _ = mechanism.grid(case)
    order = mechanism.row_major(case)
    rows = mechanism.bed_rows(mechanism.rows_of(mechanism.field(case, "0", "alpha.particles"), order), nx)
    late = [t for t in mechanism.times(case) if float(t) >= FROM - 1e-9]
    if not late:
        fail(f"{case}: no fields written from {FROM} s")
    values = [mechanism.lateral_std(mechanism.rows_of(mechanism.field(case, t, "alpha.particles"), order), nx, rows)
              for t in late]
    return sum(values) / len(values), len(values)


def main():
    checks = Checks()
    require_tfm_models()
    peer, writes = spread(run_case(PEER))
    stock, _ = spread(run_case(STOCK))
    checks.true(f"the peer bubbles: lateral std of alpha_s over {FROM:g}-{END_TIME:g} s above {mechanism.BUBBLING}",
                peer > mechanism.BUBBLING, f"{peer:.4f} over {writes} writes")
    checks.true(f"v1912's kinetic theory at the same e stays in layers: below {mechanism.BUBBLING}",
                stock < mechanism.BUBBLING, f"{stock:.4f}")
    checks.finish()


if __name__ == "__main__":
    main()
