"""Fluidization curve: superficial velocity stepped up then down, pressure drop per level.

Levels of LEVEL_DURATION s each (0/U's inlet table, written here); the pressure drop of a
level is the mean of p(inlet, area average) - p(15.5 cm) over its last AVERAGED_PART, plus
the gas weight between them. Expected (seed 000 Table 1 particles, 425 of them in a 5 cm wide
layer one diameter deep):
  - plateau (fluidized levels) = bed weight per area = N m_p g / (W D), less buoyancy;
  - U_mf where the falling branch leaves the plateau: Wen and Yu (1966) U_mf = 1.26 m/s.
"""
import math
import os

RISING = (0.4, 0.7, 0.9, 1.0, 1.1, 1.2, 1.3, 1.4, 1.6, 1.8)
LEVELS = RISING + tuple(reversed(RISING[:-1]))
LEVEL_DURATION, AVERAGED_PART = 0.3, 0.5
PARTICLES, D, RHO_P, RHO_G, MU, G = 425, 0.0025, 2526.0, 1.2, 1.8e-5, 9.81
WIDTH, DEPTH, PROBE_HEIGHT = 0.05, 0.0025, 0.155
FLUIDIZED = 1.6  # m/s: levels at or above it count for the plateau


def bed_weight_per_area():
    """Net weight (weight less buoyancy) of the particles per cross-section (Pa)."""
    volume = PARTICLES * math.pi * D ** 3 / 6
    return (RHO_P - RHO_G) * G * volume / (WIDTH * DEPTH)


def wen_yu_minimum_fluidization():
    ar = RHO_G * (RHO_P - RHO_G) * G * D ** 3 / MU ** 2
    return (math.sqrt(33.7 ** 2 + 0.0408 * ar) - 33.7) * MU / (RHO_G * D)


def inlet_table():
    """OpenFOAM table of the inlet velocity: each level held, switched over 10 ms."""
    rows, t = [], 0.0
    for u in LEVELS:
        rows.append(f"({t + (0.01 if t else 0):.4f} (0 {u} 0))")
        t += LEVEL_DURATION
        rows.append(f"({t:.4f} (0 {u} 0))")
    return "\n".join(rows)


def write_velocity_file(case):
    text = f"""FoamFile {{ version 2.0; format ascii; class volVectorField; object U; }}
dimensions      [0 1 -1 0 0 0 0];
internalField   uniform (0 0 0);
boundaryField
{{
    // superficial inflow velocity (eps = 1 at the inlet face), stepped up then down
    inlet        {{ type uniformFixedValue; uniformValue table
(
{inlet_table()}
); }}
    outlet       {{ type pressureInletOutletVelocity; value uniform (0 0 0); }}
    walls        {{ type noSlip; }}
    frontAndBack {{ type empty; }}
}}
"""
    open(os.path.join(case, "0", "U"), "w").write(text)


def series(path, column=1):
    out = []
    for line in open(path):
        if line.startswith("#") or not line.strip():
            continue
        parts = line.split()
        out.append((float(parts[0]), float(parts[column])))
    return out


def level_pressure_drops(case):
    """(velocity, mean dp) per level, in run order."""
    inlet = series(os.path.join(case, "postProcessing", "inletPressure", "0", "surfaceFieldValue.dat"))
    above = dict(series(os.path.join(case, "postProcessing", "abovePressure", "0", "p")))
    drops = [(t, p - above[t] + RHO_G * G * PROBE_HEIGHT) for t, p in inlet if t in above]
    result = []
    for k, u in enumerate(LEVELS):
        end = (k + 1) * LEVEL_DURATION
        start = end - AVERAGED_PART * LEVEL_DURATION
        values = [dp for t, dp in drops if start < t <= end + 1e-9]
        result.append((u, sum(values) / len(values)))
    return result


def plateau(drops):
    values = [dp for u, dp in drops if u >= FLUIDIZED]
    return sum(values) / len(values)


def minimum_fluidization(drops):
    """Velocity where the falling branch's pressure drop reaches the plateau (linear
    interpolation between the two levels that bracket it)."""
    top = plateau(drops)
    falling = drops[len(RISING) - 1:]
    for (u_hi, dp_hi), (u_lo, dp_lo) in zip(falling, falling[1:]):
        if dp_lo < top <= dp_hi or (dp_lo < top and dp_hi >= top * 0.98):
            return u_lo + (top - dp_lo) * (u_hi - u_lo) / (dp_hi - dp_lo)
    return float("nan")
