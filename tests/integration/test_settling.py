"""One sphere settling from rest in still air, coupled tfdemFoam + LIGGGHTS.

Expected values come from tfdem.physics.SettlingSphere, built from the case's own files (the
sphere's ODE with the paper's drag law, seed 000 eq. 28-31, RK4 at 1e-6 s), independent of
the solver:
  - terminal velocity: DEM value at 0.5 s (~10 drag relaxation times) within 1 %;
  - velocity-time curve: every 0.01 s within 1 % of the terminal velocity.
The 1 % covers the explicit coupling lag (forces held for 1e-3 s, 2 % of the 0.05 s drag
relaxation time) and the gas the particle drags along (~0.1 % of u_t in a 2 cm cell).

The void-fraction floor's account, by hand: with the floor at 1 - V_p / (2 V_cell) the
sphere's cell (eps = 1 - V_p / V_cell) is floored at every coupling step, it holds 100 % of
the particles' volume, the floored map leaves out V_p - (1 - floor) V_cell = V_p / 2 (50 %),
and the run's end names that share as one that may matter (above 0.1 %).
"""
import re
import os

from tfdem import TUTORIALS
from tfdem.case import Case, sphere_volume
from tfdem.outputs import dump_track
from tfdem.physics import SettlingSphere
from tfdem_testlib import Checks, copy_case, run

TUTORIAL = os.path.join(TUTORIALS, "settling_particle")


def main():
    checks = Checks()
    case = copy_case(TUTORIAL, "settling")
    run(["blockMesh"], case, "log.blockMesh")
    run(["tfdemFoam"], case, "log.tfdemFoam")
    sphere = SettlingSphere.from_case(Case(case))
    track = dump_track(case, "vy")
    checks.true("51 samples over 0.5 s", len(track) == 51, f"(got {len(track)})")
    expected = sphere.velocity([t for t, _ in track])
    u_t = sphere.terminal_velocity()
    # Independently, by hand: the force balance (rho_p - rho_g) g pi d^3/6 = C_D rho_g pi d^2/8 u^2
    # with Schiller-Naumann's C_D (seed 000 eq. 31) for d = 100 um, 2500 kg/m^3 in air, solved
    # by fixed-point iteration: u_t = 0.553186076 m/s (Re = 3.69). The reference ODE includes
    # the particle's own cell's gas fraction, 1 - 6.5e-8 (eps_g^-2.7 of eq. 30): 1e-6.
    checks.close("reference terminal velocity vs the force balance by hand", u_t, 0.553186076, 1e-6)
    checks.close("terminal velocity (m/s) at t = 0.5 s", -track[-1][1], u_t, 0.01)
    worst = max(abs(v - e) for (_, v), e in zip(track, expected)) / u_t
    checks.within("max |v - v_ODE| / u_t over 0-0.5 s", worst, 0.0, 0.01)
    check_floor_account(checks)
    checks.finish()


def check_floor_account(checks):
    case = copy_case(TUTORIAL, "settling_floored")
    c = Case(case)
    grid = c.grid()
    cell = grid.spacing[0] * grid.spacing[1] * grid.spacing[2]
    share = sphere_volume(c.particle_diameters()[0]) / cell
    c.set_coupling("coupling.void_fraction.floor", 1 - share / 2)
    c.set_control(endTime=0.02)
    run(["blockMesh"], case, "log.blockMesh")
    run(["tfdemFoam"], case, "log.tfdemFoam")
    log = open(os.path.join(case, "log.tfdemFoam")).read()
    found = re.search(r"TFDEM void fraction floor \S+: used in (\d+) of (\d+) coupling steps .*? were (\S+) % of the "
                      r"particles' volume over the run .*? left out at most (\S+) % .*?(Above|Below) 0\.1 %", log)
    checks.true("the floor's account printed at the end", found is not None)
    if found:
        checks.true("floored at every coupling step", found.group(1) == found.group(2) and int(found.group(2)) > 0,
                    f"({found.group(1)} of {found.group(2)})")
        checks.close("share of the particles' volume in floored cells (%)", float(found.group(3)), 100.0, 5e-3)
        checks.close("share the map left out (%): V_p / 2", float(found.group(4)), 50.0, 5e-3)
        checks.true("named as a share that may matter", found.group(5) == "Above")


if __name__ == "__main__":
    main()
