"""kineticTheoryConservative (tfm_models/) applies the solids pressure force as -grad P_s: the
first step of a column at rest with a Theta gradient, against the acceleration by hand.

The TFM peer's template (studies/seed000/tfm_bubbling_bed) made a column one cell wide and 20
tall, closed below (no inflow), gas and solids at rest, alpha_s = 0.4 everywhere and Theta
rising linearly with height, run for one step of 1e-5 s by Debian's twoPhaseEulerFoam, once
with OpenFOAM's kineticTheory and once with ours. With alpha_s uniform, -p' grad(alpha_s) is
zero, so the only granular force is ours, F = -(P_s / Theta) dTheta/dy, P_s / Theta =
rho_s alpha_s (1 + 2 (1 + e) alpha_s g0) (Lun et al. 1984), g0 = (1 - alpha_s/2) / (1 - alpha_s)^3
(Carnahan-Starling). Closed below, the mixture's volume flux is zero in the column, so
alpha_s a_s = -alpha_g a_g; eliminating the gas pressure gradient between the two momentum
equations (drag zero at rest, no other force) gives
    a_s = (-(rho_s - rho_g) g + F / alpha_s) / (rho_s + rho_g alpha_s / alpha_g),
and after one Euler step U_s = a_s dt. Checked in the middle cell: each model's U_s against
a_s dt with F and with F = 0, and the difference of the two, which holds F alone (1e-4
relative: the drag of the relative velocity gained within the step is ~1e-7 of the forces, and
the solver takes Theta as it was at the step's start).
"""
import math
import os

from tfdem import STUDIES, tfm_models
from tfdem.case import Case
from tfdem.outputs import field
from tfdem_testlib import Checks, dict_number, edit_once, require_tfm_models, run, set_internal_field, tfm_column

TEMPLATE = os.path.join(STUDIES, "seed000", "tfm_bubbling_bed")
ALPHA_S = 0.4
THETA_BOTTOM, THETA_TOP = 0.01, 0.05  # m^2/s^2 at the column's bottom and top faces
STEP = 1e-5  # s
CELLS = 20


def scalar_field(values):
    return f"nonuniform List<scalar>\n{len(values)}\n(\n" + "\n".join(f"{v:.12g}" for v in values) + "\n)"


def column(name, conservative):
    """The column case under build/test-runs/name, run one step; its path."""
    path = tfm_column(name, CELLS, STEP)
    control = os.path.join(path, "system/controlDict")
    if conservative:
        edit_once(control, r"\napplication\s", f"\n{tfm_models.library_entry()}\napplication ")
        kinetic = os.path.join(path, "constant/turbulenceProperties.particles")
        edit_once(kinetic, r"RASModel\s+kineticTheory;", "RASModel        kineticTheoryConservative;")
        edit_once(kinetic, r"kineticTheoryCoeffs", "kineticTheoryConservativeCoeffs")
    run(["./Allprepare"], path, "log.Allprepare")
    height = 0.45
    centres = [(j + 0.5) * height / CELLS for j in range(CELLS)]
    theta = [THETA_BOTTOM + (THETA_TOP - THETA_BOTTOM) * y / height for y in centres]
    set_internal_field(os.path.join(path, "0/alpha.particles"), f"uniform {ALPHA_S}")
    set_internal_field(os.path.join(path, "0/Theta.particles"), scalar_field(theta))
    air = os.path.join(path, "0/U.air")
    set_internal_field(air, "uniform (0 0 0)")
    edit_once(air, r"inlet\s*\{[^}]*\}", "inlet\n    {\n        type            noSlip;\n    }")
    run(["twoPhaseEulerFoam"], path, "log.twoPhaseEulerFoam")
    return path


def main():
    checks = Checks()
    require_tfm_models()
    stock, ours = column("kinetic_theory_stock", False), column("kinetic_theory_conservative", True)
    props = os.path.join(TEMPLATE, "constant")
    rho_s = dict_number(os.path.join(props, "thermophysicalProperties.particles"), "rho")
    rho_g = dict_number(os.path.join(props, "thermophysicalProperties.air"), "rho")
    e = dict_number(os.path.join(props, "turbulenceProperties.particles"), "e")
    g = abs(Case(TEMPLATE).gravity_magnitude())
    alpha_g = 1 - ALPHA_S
    g0 = (1 - ALPHA_S / 2) / (1 - ALPHA_S) ** 3
    pressure_per_theta = rho_s * ALPHA_S * (1 + 2 * (1 + e) * ALPHA_S * g0)
    force = -pressure_per_theta * (THETA_TOP - THETA_BOTTOM) / 0.45
    inertia = rho_s + rho_g * ALPHA_S / alpha_g
    expected_stock = -(rho_s - rho_g) * g / inertia * STEP
    expected_ours = (-(rho_s - rho_g) * g + force / ALPHA_S) / inertia * STEP
    middle = CELLS // 2
    written = f"{STEP:g}"
    u_stock = field(stock, written, "U.particles")[middle][1]
    u_ours = field(ours, written, "U.particles")[middle][1]
    checks.close("kineticTheory: U_s after one step (m/s)", u_stock, expected_stock, 1e-4)
    checks.close("kineticTheoryConservative: U_s after one step (m/s)", u_ours, expected_ours, 1e-4)
    checks.close("the difference, -(P_s/Theta) dTheta/dy / alpha_s / inertia * dt (m/s)", u_ours - u_stock,
                 expected_ours - expected_stock, 1e-4)
    checks.true("the force is not lost in round-off", abs(expected_ours - expected_stock) > 0.03 * abs(expected_stock),
                f"{expected_ours - expected_stock:.3g} against {expected_stock:.3g}")
    print(f"P_s/Theta = {pressure_per_theta:.1f} kg/m^3, F = {force:.1f} N/m^3, g0 = {g0:.4f}")
    checks.finish()


if __name__ == "__main__":
    main()
