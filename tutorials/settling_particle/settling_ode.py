"""Reference solution of a single sphere settling from rest in still gas.

m dv/dt = -(m - rho_g V) g + V beta/eps_s (u_g - v)  (seed 000 eq. 28-29; buoyancy from the
hydrostatic gas pressure gradient), beta of seed 000 eq. 30-31 (Wen-Yu branch, C_D of eq. 31)
at eps_g = 1 - V_p/V_cell. Integrated with RK4; shared by the test and plot.py.
"""
import math

D, RHO_P, RHO_G, MU, G = 1.0e-4, 2500.0, 1.2, 1.8e-5, 9.81  # coupling.yaml, constant/g
CELL_VOLUME = 0.02 ** 3                                     # system/blockMeshDict
V_P = math.pi * D ** 3 / 6


def drag_per_volume(slip):
    """beta/eps_s (kg/m^3/s) of seed 000 eq. 30 (Wen-Yu branch) with C_D of eq. 31."""
    eps = 1.0 - V_P / CELL_VOLUME
    re = eps * RHO_G * abs(slip) * D / MU
    if re == 0.0:
        return 18.0 * MU / D ** 2 * eps ** -2.7
    cd = 24.0 * (1.0 + 0.15 * re ** 0.687) / re if re < 1000 else 0.43
    return 0.75 * cd * eps * RHO_G * abs(slip) / D * eps ** -2.7


def acceleration(v):
    """dv/dt of the settling sphere at vertical velocity v (m/s, up positive)."""
    return -(1.0 - RHO_G / RHO_P) * G + drag_per_volume(-v) * (-v) / RHO_P


def velocity(times, dt=1e-6):
    """v(t) at the given increasing times (s), from rest at t = 0."""
    out, v, t = [], 0.0, 0.0
    for target in times:
        while t < target - 1e-12:
            h = min(dt, target - t)
            k1 = acceleration(v)
            k2 = acceleration(v + 0.5 * h * k1)
            k3 = acceleration(v + 0.5 * h * k2)
            k4 = acceleration(v + h * k3)
            v += h * (k1 + 2 * k2 + 2 * k3 + k4) / 6
            t += h
        out.append(v)
    return out


def terminal_velocity():
    """Settling speed (m/s) where weight less buoyancy equals drag, by bisection."""
    lo, hi = 0.0, 100.0
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if acceleration(-mid) < 0 else (lo, mid)
    return 0.5 * (lo + hi)


def read_track(path, dt_dem=1e-4):
    """(t, v_y) of the particle from the LIGGGHTS dump particle.dump (DEM step dt_dem)."""
    samples, step = [], None
    lines = open(path).read().splitlines()
    for i, line in enumerate(lines):
        if line == "ITEM: TIMESTEP":
            step = int(lines[i + 1])
        if line.startswith("ITEM: ATOMS"):
            samples.append((step * dt_dem, float(lines[i + 1].split()[2])))
    return samples
