"""granularSlipProduction (tfm_models/) replaces v1912's production of Theta by gas-particle
slip: the first step of a uniformly fluidized column, Theta against its value by hand.

The TFM peer's template (studies/seed000/tfm_bubbling_bed) made a column one cell wide and 20
tall, alpha_s = 0.4 everywhere, solids at rest, the gas at the inflow's interstitial velocity
(1.92 / 0.6 m/s), Theta uniform at THETA_0 with zero-gradient walls and inlet, a gas 55 times as
viscous as air (so Koch & Sangani's term, which scales with mu_g^2, is visible in one step), run
for one step of 1e-4 s by Debian's twoPhaseEulerFoam three times: with OpenFOAM's slip production,
with ours set to `none`, and to `KochSangani`. In the middle cell every gradient is zero, so the
granular energy equation of kineticTheoryModel::correct is, per unit volume (Gidaspow 1994 eq.
9.86-9.88 as v1912 writes it),
    1.5 alpha rho_s (Theta_1 - Theta_0) / dt
        = -(gamma + J1) Theta_1 + J2 Theta_1 / (Theta_0 + 1e-6) + S,
    gamma = 12 (1 - e^2) alpha^2 rho_s g0 sqrt(Theta_0) / (d sqrt(pi))   (Lun et al. 1984)
    J1 = 3 beta,  J2 = beta^2 d |du|^2 / (4 alpha rho_s sqrt(pi) (sqrt(Theta_0) + 1e-3))
    S = 81 alpha mu_g^2 |du|^2 / (g0 d^3 rho_s sqrt(pi) (sqrt(Theta_0) + 1e-3))  (Koch & Sangani 1999)
with J2 only in the stock run, S only with KochSangani; beta = 150 alpha^2 mu_g / ((1 - alpha)
d^2) + 1.75 alpha rho_g |du| / d (Ergun, below gas fraction 0.8), g0 = (1 - alpha/2) / (1 -
alpha)^3 (Carnahan & Starling), du the slip the step ends with (read from the written fields).
"""
import math
import os

from tfdem import STUDIES, tfm_models
from tfdem.outputs import field
from tfdem_testlib import Checks, dict_number, edit_once, require_tfm_models, run, set_internal_field, tfm_column

TEMPLATE = os.path.join(STUDIES, "seed000", "tfm_bubbling_bed")
ALPHA_S = 0.4
THETA_0 = 2e-3  # m^2/s^2
GAS_VISCOSITY = 1e-3  # Pa s
STEP = 1e-4  # s
CELLS = 20
U_INFLOW = 1.92  # m/s, the template's superficial inflow


def column(name, production):
    """The column case under build/test-runs/name, run one step (production None: v1912's own)."""
    path = tfm_column(name, CELLS, STEP)
    control = os.path.join(path, "system/controlDict")
    edit_once(os.path.join(path, "constant/thermophysicalProperties.air"), r"\n(\s*)mu\s+[^;]*;", f"\n\\g<1>mu {GAS_VISCOSITY:g};")
    edit_once(os.path.join(path, "system/fvSolution"), r"(\"Theta\.\*\"\s*\{[^}]*tolerance\s+)[^;]*;", r"\g<1>1e-14;")
    if production:
        edit_once(control, r"\napplication\s", f"\n{tfm_models.library_entry()}\napplication ")
        with open(os.path.join(path, "constant/fvOptions"), "w") as f:
            f.write(tfm_models.slip_production_options(production))
    theta = os.path.join(path, "0.orig/Theta.particles")
    edit_once(theta, r"\nreferenceLevel\s[^;]*;", "\n")
    edit_once(theta, r"inlet\s*\{[^}]*\}", "inlet\n    {\n        type            zeroGradient;\n    }")
    run(["./Allprepare"], path, "log.Allprepare")
    set_internal_field(os.path.join(path, "0/alpha.particles"), f"uniform {ALPHA_S}")
    set_internal_field(os.path.join(path, "0/Theta.particles"), f"uniform {THETA_0:g}")
    set_internal_field(os.path.join(path, "0/U.air"), f"uniform (0 {U_INFLOW / (1 - ALPHA_S):.12g} 0)")
    run(["twoPhaseEulerFoam"], path, "log.twoPhaseEulerFoam")
    return path


def main():
    checks = Checks()
    require_tfm_models()
    props = os.path.join(TEMPLATE, "constant")
    rho_s = dict_number(os.path.join(props, "thermophysicalProperties.particles"), "rho")
    rho_g = dict_number(os.path.join(props, "thermophysicalProperties.air"), "rho")
    e = dict_number(os.path.join(props, "turbulenceProperties.particles"), "e")
    d = dict_number(os.path.join(props, "phaseProperties"), "d")
    middle, written = CELLS // 2, f"{STEP:g}"
    theta_1 = {}
    for production in (None, "none", "KochSangani"):
        path = column(f"granular_slip_production_{production or 'stock'}", production)
        alpha = field(path, written, "alpha.particles")[middle]
        slip = math.dist(field(path, written, "U.particles")[middle], field(path, written, "U.air")[middle])
        g0 = (1 - alpha / 2) / (1 - alpha) ** 3
        beta = 150 * alpha ** 2 * GAS_VISCOSITY / ((1 - alpha) * d ** 2) + 1.75 * alpha * rho_g * slip / d
        root = math.sqrt(math.pi) * (math.sqrt(THETA_0) + 1e-3)
        gamma = 12 * (1 - e ** 2) * alpha ** 2 * rho_s * g0 * math.sqrt(THETA_0) / (d * math.sqrt(math.pi))
        j2 = beta ** 2 * d * slip ** 2 / (4 * alpha * rho_s * root) if production is None else 0.0
        s = 81 * alpha * GAS_VISCOSITY ** 2 * slip ** 2 / (g0 * d ** 3 * rho_s * root) if production == "KochSangani" else 0.0
        inertia = 1.5 * alpha * rho_s / STEP
        expected = (inertia * THETA_0 + s) / (inertia + gamma + 3 * beta - j2 / (THETA_0 + 1e-6))
        theta_1[production] = field(path, written, "Theta.particles")[middle]
        checks.close(f"Theta after one step, slip production {production or 'of v1912'} (m2/s2)", theta_1[production],
                     expected, 1e-6)
        if production == "KochSangani":
            increment = s / (inertia + gamma + 3 * beta)
            checks.close("Koch & Sangani's increment of Theta (m2/s2)", theta_1[production] - theta_1["none"],
                         increment, 1e-3)
            checks.true("the increment is not lost in round-off", increment > 1e-4 * THETA_0, f"{increment:.3g}")
            print(f"slip {slip:.4f} m/s, beta {beta:.1f} kg/m3/s, S {s:.3g} W/m3")
        if production is None:
            print(f"v1912's J2 {j2:.4g} W/m3 at Theta_0")
    checks.true("v1912's production is taken away", theta_1[None] - theta_1["none"] > 0.1 * THETA_0,
                f"{theta_1[None]:.6g} against {theta_1['none']:.6g}")
    checks.finish()


if __name__ == "__main__":
    main()
