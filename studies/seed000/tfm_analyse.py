"""Summary of a finished TFM peer run (tfm_jet_bed or tfm_bubbling_bed), from its
postProcessing/ time series and log.twoPhaseEulerFoam.

Usage: python3 tfm_analyse.py CASE_DIR [AVERAGE_FROM_S]
Averages are over [AVERAGE_FROM_S, end], by default the last half of the run. Prints:
wall time per simulated second, time step, Delta p between the two `pressure` probes (bottom
cell centre and 20 cm above it, seed 000 Fig. 3), the whole-bed Delta p (bottom patches to
the outlet) against the bed weight per area, the mean solids height
sum(y alpha_s V)/sum(alpha_s V) and the solids inventory.
"""
import math
import os
import re
import sys

from tfdem.case import Case
from tfdem.outputs import OutputError, joined_series


def fail(message):
    sys.exit(f"tfm_analyse.py: {message}")


def series(case, name, filename):
    """Rows (t, values...) of postProcessing/<name>/<start>/<filename>, restarts joined."""
    try:
        rows = [[t] + values for t, values in joined_series(case, name, filename)]
    except OutputError as e:
        fail(str(e))
    if not rows:
        fail(f"postProcessing/{name} in {case} has no samples")
    return rows


def mean_from(rows, t0, column):
    values = [r[column] for r in rows if r[0] >= t0]
    if not values:
        fail(f"no samples after t = {t0} s")
    mean = sum(values) / len(values)
    std = math.sqrt(sum((v - mean) ** 2 for v in values) / len(values))
    return mean, std


def number(path, pattern):
    match = re.search(pattern, open(path).read(), re.M)
    if not match:
        fail(f"{path}: no match for {pattern!r}")
    return float(match.group(1))


def patch_faces(case):
    """{patch name: face count} of constant/polyMesh/boundary."""
    text = open(os.path.join(case, "constant", "polyMesh", "boundary")).read()
    return {m.group(1): int(m.group(2))
            for m in re.finditer(r"(\w+)\s*\{[^}]*?nFaces\s+(\d+);", text)}


def main():
    if len(sys.argv) not in (2, 3):
        fail("usage: tfm_analyse.py CASE_DIR [AVERAGE_FROM_S]")
    case = sys.argv[1]
    g = math.sqrt(sum(c * c for c in Case(case).gravity()))
    p_outlet = float(re.search(r"outlet\s*\{[^}]*?\sp\s+uniform\s+([^;]+);",
                               open(os.path.join(case, "0.orig", "p_rgh")).read()).group(1))
    allrun = os.path.join(case, "Allprepare")
    n = number(allrun, r"^n_particles=(\S+)")
    d = number(allrun, r"^d_p=(\S+)")
    width = number(allrun, r"^width=(\S+)")
    height = number(allrun, r"^height=(\S+)")
    rho_p = number(os.path.join(case, "constant", "thermophysicalProperties.particles"),
                   r"^\s*rho\s+(\S+);")
    rho_g = number(os.path.join(case, "constant", "thermophysicalProperties.air"),
                   r"^\s*rho\s+(\S+);")

    probes = series(case, "pressure", "p")
    t_end = probes[-1][0]
    t0 = float(sys.argv[2]) if len(sys.argv) == 3 else t_end / 2
    print(f"{os.path.basename(os.path.abspath(case))}: {t_end:.3f} s simulated, averages over "
          f"{t0:.3f}-{t_end:.3f} s")

    # Speed, time step and largest solids fraction, from Allrun's one line a time step
    log = open(os.path.join(case, "log.twoPhaseEulerFoam")).read()
    steps = [(float(t), float(dt), float(a), float(c)) for t, dt, a, c in re.findall(
        r"^Time = (\S+)  deltaT = (\S+) .* maxAlpha = (\S+)  ExecutionTime = \S+ s  "
        r"ClockTime = (\S+) s", log, re.M)]
    if not steps:
        fail(f"{case}/log.twoPhaseEulerFoam has no time-step lines")
    late = [s for s in steps if s[0] >= t0]
    t_end_log, clock_end = steps[-1][0], steps[-1][3]
    late_rate = ((clock_end - late[0][3]) / (t_end_log - late[0][0])
                 if t_end_log > late[0][0] else float("nan"))
    print(f"  wall time {clock_end:.0f} s: {clock_end / t_end_log:.0f} s per simulated s "
          f"({late_rate:.0f} s/s after {t0:.2f} s; ClockTime is in whole seconds)")
    dts = [s[1] for s in late]
    print(f"  time step: {len(steps)} steps, mean {sum(dts) / len(dts):.3g} s after {t0:.2f} s "
          f"(min {min(dts):.3g}, max {max(dts):.3g})")
    print(f"  largest solids fraction: {max(s[2] for s in steps):.4f} over the run, "
          f"{max(s[2] for s in late):.4f} after {t0:.2f} s")

    # Delta p at 20 cm (Fig. 3)
    dp20 = [(r[0], r[1] - r[2]) for r in probes]
    mean, std = mean_from(dp20, t0, 1)
    print(f"  Delta p(bottom cell centre - 20 cm above): mean {mean:.0f} Pa, std {std:.0f} Pa")

    # Whole bed: area-weighted p of the bottom patches minus the outlet and the gas column
    faces = patch_faces(case)
    bottom = [(name, faces[name]) for name in ("inlet", "bottom") if name in faces]
    p_bottom = None
    for name, count in bottom:
        rows = series(case, "p" + name[0].upper() + name[1:], "surfaceFieldValue.dat")
        m, _ = mean_from(rows, t0, 1)
        p_bottom = (p_bottom or 0.0) + m * count / sum(c for _, c in bottom)
        print(f"  p on {name} ({count} faces): mean {m - p_outlet:.0f} Pa above the outlet")
    weight = n * math.pi * d ** 2 / 6 * (rho_p - rho_g) * g / width
    whole = p_bottom - p_outlet - rho_g * g * height
    print(f"  whole-bed Delta p (bottom - outlet - rho_g g H): {whole:.0f} Pa; bed weight per area "
          f"N pi d^2/6 (rho_p - rho_g) g / W = {weight:.0f} Pa; ratio {whole / weight:.3f}")

    # Mean solids height and inventory
    heights = series(case, "solidsHeight", "volFieldValue.dat")
    m, s = mean_from(heights, t0, 1)
    print(f"  mean solids height: {heights[-1][1] * 100:.2f} cm at {heights[-1][0]:.3f} s, "
          f"{m * 100:.2f} cm +- {s * 100:.2f} averaged")
    volume = series(case, "solidsVolume", "volFieldValue.dat")
    expected = n * math.pi * d ** 3 / 6
    print(f"  solids volume: {volume[-1][1]:.6e} m^3 at the end, inventory {expected:.6e} m^3 "
          f"({(volume[-1][1] / expected - 1) * 100:+.2e} %)")


if __name__ == "__main__":
    main()
