"""Gas through a fixed bed: pressure drop against Ergun at three superficial velocities.

Expected values: tutorials/packed_bed_ergun/ergun.py (Ergun 1952 with the bed's exact
eps_g = 1 - pi d^2/(6 s^2), plus the gas weight between the probes). Tolerance 0.5 %
(the issue asks 3 %): the closure is Ergun itself and the gas solver's face flux is exact for
a steady flow through the bed's top and bottom faces, so what remains is the gas momentum's
convection and viscous terms and the approach to steady state (measured +0.09 to +0.14 %).
The particles' total fluid force (drag + pressure gradient) must equal the same Ergun pressure
drop over the cross-section plus the gas buoyancy, to the same 0.5 %.
"""
import os
import sys

from tfdem_testlib import SOURCE_DIR, Checks, run, scratch

TUTORIAL = os.path.join(SOURCE_DIR, "tutorials", "packed_bed_ergun")
sys.path.insert(0, TUTORIAL)
import ergun  # noqa: E402


def main():
    checks = Checks()
    for u in ergun.VELOCITIES:
        case = scratch(f"packed_bed_U{u}")
        dp = ergun.prepare_run(TUTORIAL, case, u, run)
        checks.close(f"pressure drop at U = {u} m/s (Pa)", dp, ergun.ergun_pressure_drop(u), 0.005)
        checks.close(f"sum of particle fluid forces at U = {u} m/s (N)", ergun.measured_particle_force(case),
                     ergun.expected_particle_force(u), 0.005)
    checks.finish()


if __name__ == "__main__":
    main()
