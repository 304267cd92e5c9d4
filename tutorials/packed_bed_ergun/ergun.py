"""Ergun pressure drop of the fixed bed in this case, and the runs that measure it.

The bed: 960 spheres d = 2.5 mm on a square lattice of spacing s = 2.55 mm in one layer of
depth d (in.fixed_bed), so eps_g = 1 - pi d^2 / (6 s^2) = 0.4967 and height L = 40 s.
Ergun (1952), with superficial velocity U:
  dp/L = 150 eps_s^2 mu U / (eps^3 d^2) + 1.75 eps_s rho U^2 / (eps^3 d).
The probes sit 2.55 cm (below the bed) and 17.85 cm (above it) above the inlet, so they also
see the gas weight rho g (0.1785 - 0.0255).
"""
import math
import os
import re
import subprocess
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
from case_copy import copy_case  # noqa: E402

D, SPACING, MU, RHO, G = 0.0025, 0.00255, 1.8e-5, 1.2, 9.81
BED_HEIGHT = 40 * SPACING
WIDTH, PARTICLES = 24 * SPACING, 960  # the column is 24 lattice sites wide
PROBE_GAP = 0.1785 - 0.0255
VELOCITIES = (0.3, 0.6, 1.0)  # superficial, m/s
EPS = 1.0 - math.pi * D ** 2 / (6 * SPACING ** 2)


def ergun_gradient(u):
    """Ergun (1952): the bed's pressure drop per length (Pa/m) at superficial velocity u."""
    eps_s = 1.0 - EPS
    return (150 * eps_s ** 2 * MU * u / (EPS ** 3 * D ** 2)
            + 1.75 * eps_s * RHO * u * u / (EPS ** 3 * D))


def ergun_pressure_drop(u):
    """Expected p(below) - p(above) (Pa) at superficial velocity u."""
    return ergun_gradient(u) * BED_HEIGHT + RHO * G * PROBE_GAP


def expected_particle_force(u):
    """Sum of the fluid forces on the particles (N, upward) at superficial velocity u: the
    Ergun pressure drop of the bed over the cross-section W D (Newton's third law between the
    phases) plus the buoyancy of the gas weight, rho g sum V_p."""
    return ergun_gradient(u) * BED_HEIGHT * WIDTH * D + RHO * G * PARTICLES * math.pi * D ** 3 / 6


def measured_particle_force(case):
    """Last row of fluid_force.txt (in.fixed_bed): sum of the particles' fluid forces, y (N)."""
    rows = [line.split() for line in open(os.path.join(case, "fluid_force.txt"))
            if line.strip() and not line.startswith("#")]
    return float(rows[-1][1])


def measured_pressure_drop(case):
    """Last probe row of a finished run: p(below) - p(above) (Pa)."""
    rows = [line.split() for line in open(os.path.join(case, "postProcessing", "pressure", "0", "p"))
            if line.strip() and not line.startswith("#")]
    return float(rows[-1][1]) - float(rows[-1][2])


def set_inlet_velocity(case, u):
    """Set the inlet's fixed velocity in case/0/U to (0 u 0)."""
    path = os.path.join(case, "0", "U")
    text = open(path).read()
    open(path, "w").write(re.sub(r"inlet(\s*\{[^}]*value\s+uniform\s+)\(0 [0-9.]+ 0\)", rf"inlet\g<1>(0 {u} 0)", text))


def prepare_run(source, dest, u, runner):
    """Copy the case to dest with inlet velocity u and run blockMesh and tfdemFoam there via
    runner(args, cwd, log_name)."""
    copy_case(source, dest, ("coupling.yaml", "in.fixed_bed"))
    set_inlet_velocity(dest, u)
    runner(["blockMesh"], dest, "log.blockMesh")
    runner(["tfdemFoam"], dest, "log.tfdemFoam")
    return measured_pressure_drop(dest)


def run_locally(args, cwd, log_name):
    with open(os.path.join(cwd, log_name), "w") as log:
        subprocess.run(args, cwd=cwd, stdout=log, stderr=subprocess.STDOUT, check=True)
