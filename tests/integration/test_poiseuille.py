"""tfdemFoam at void fraction 1 solves laminar plane Poiseuille flow.

Analytic values (channel height h of system/blockMeshDict, mean velocity U of the 0/U inlet,
dynamic viscosity mu = rho nu of constant/transportProperties, probe distance L of
system/controlDict): centreline velocity u_c = 3/2 U;  pressure drop over L: dp = 12 mu U L / h^2.
Tolerance 1 %: the second-order finite-volume solution on 41 cells across is within
about 0.1 % of both; the flow is developed at the probes (entry length ~ 0.05 Re h = 0.5 mm).
The run on 2 ranks (decomposePar, split in x) must give the same probe values to 1e-8
relative: solver tolerances are 1e-12, so ranks may differ only by round-off.
"""
import os

from tfdem import TUTORIALS
from tfdem.case import Case
from tfdem.physics import PlanePoiseuille
from tfdem_testlib import Checks, copy_case, read_probe, run

TUTORIAL = os.path.join(TUTORIALS, "poiseuille_channel")


def analytic():
    """(dp over the probes (Pa), centreline velocity (m/s)) of the case's own files."""
    case = Case(TUTORIAL)
    flow = PlanePoiseuille(case)
    upstream, downstream = case.probe_locations("centreline")[:2]
    return flow.pressure_drop(downstream[0] - upstream[0]), flow.centreline_velocity()


def probe_values(case):
    _, (p_upstream, p_downstream) = read_probe(case, "p")
    _, (u_upstream, u_downstream) = read_probe(case, "U")
    return p_upstream - p_downstream, u_downstream[0]


def main():
    checks = Checks()
    serial = copy_case(TUTORIAL, "poiseuille_serial")
    run(["blockMesh"], serial, "log.blockMesh")
    run(["tfdemFoam"], serial, "log.tfdemFoam")
    dp, u_centre = probe_values(serial)
    dp_exact, u_centre_exact = analytic()
    checks.close("pressure drop (Pa), serial", dp, dp_exact, 0.01)
    checks.close("centreline velocity (m/s), serial", u_centre, u_centre_exact, 0.01)

    parallel = copy_case(TUTORIAL, "poiseuille_parallel")
    run(["blockMesh"], parallel, "log.blockMesh")
    run(["decomposePar"], parallel, "log.decomposePar")
    run(["tfdemFoam", "-parallel"], parallel, "log.tfdemFoam", ranks=2)
    checks.true("two processor directories", os.path.isdir(os.path.join(parallel, "processor1")))
    dp2, u_centre2 = probe_values(parallel)
    checks.close("pressure drop, 2 ranks vs serial", dp2, dp, 1e-8)
    checks.close("centreline velocity, 2 ranks vs serial", u_centre2, u_centre, 1e-8)
    checks.finish()


if __name__ == "__main__":
    main()
