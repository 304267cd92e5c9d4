"""Fluidization curve: superficial velocity stepped up then down, pressure drop per level.

The bed (bed.data, about 825 spheres of seed 000 Table 1, d = 2.5 mm, rho = 2526 kg/m^3) rests
on a porous distributor plate at FLOOR = 1 cm in a 10 cm wide column one diameter deep; the gas
enters at y = 0 and crosses the plate's porous body (the cell row below it, constant/fvOptions).
Each level of LEVELS is held for its duration (0/U's inlet table, written here); its pressure
drop is the mean, once the bed has settled to the level (SETTLING), of p(inlet, area average) -
p(PROBE_HEIGHT) less the gas weight rho_g g h between the two (p here includes the hydrostatic gas
head) and less the plate's own pressure drop mu d L U (Darcy).

Expected:
  - plateau (levels >= FLUIDIZED, mean of BATCH-long batch means) = net bed weight per
    cross-section N m_p (1 - rho_g/rho_p) g / (W D);
  - U_mf near Wen and Yu (1966), computed from Ar below; and, since the drag closure below
    eps = 0.8 is Ergun's, near Ergun's U_mf at the voidage the bed actually has at U_mf.
U_mf is measured the standard way: the fixed-bed points of the falling branch (pressure drop
below FIXED_BED_LIMIT x plateau) are fitted with Ergun's form dp = a U + b U^2 and the fit is
intersected with the plateau.
"""
import math
import os
import re
import subprocess
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
from case_copy import copy_case  # noqa: E402

# (superficial velocity m/s, duration s). Fixed-bed levels settle within a few gas steps; the
# fluidized bed bubbles with a period of ~0.3 s, so its three rising levels are held 6 s each:
# the plateau's standard error is then about 0.1 % of the weight (0.3 s of averaging gives 0.4 %).
LEVELS = (
    (0.4, 0.2), (0.7, 0.2), (0.9, 0.2), (1.1, 0.2), (1.3, 0.3), (1.5, 0.5),
    (1.8, 6.0), (2.0, 6.0), (2.2, 6.0),
    (1.8, 1.5), (1.5, 0.6), (1.3, 0.4),
    (1.2, 0.2), (1.1, 0.2), (1.0, 0.2), (0.9, 0.2), (0.7, 0.2), (0.4, 0.2),
)
RISING_COUNT = 9  # LEVELS[:9] rise to the top level, the rest fall
SETTLING = 1.0  # s: each level is averaged after min(SETTLING, half its duration)
BATCH = 0.5  # s: plateau batch means (about two bubble periods) for its standard error
FLUIDIZED = 1.8  # m/s: levels at or above it make the plateau (about 1.3 x U_mf)
FIXED_BED_LIMIT = 0.85  # falling-branch levels below 0.85 x plateau are fitted as fixed bed

D, RHO_P, RHO_G, MU, G = 0.0025, 2526.0, 1.2, 1.8e-5, 9.81
WIDTH, DEPTH, FLOOR, PROBE_HEIGHT = 0.10, 0.0025, 0.01, 0.155


HERE = os.path.dirname(os.path.abspath(__file__))
# The packed bed: 825 spheres settled on the plate, created 2-9.5 cm above the inlet
PACKING_SCRIPT = os.path.join(HERE, "..", "bubbling_bed_packing", "in.pack")
PACKING_VARIABLES = (("width", WIDTH), ("height", 0.2), ("floor", FLOOR), ("fill_top", 0.095),
                     ("steps", 30000), ("out", "bed.data"))


def prepare_run(source, dest, runner):
    """Copy the case from source to dest (unless they are the same), pack its bed, write the
    inlet table and run blockMesh and tfdemFoam there via runner(args, cwd, log_name)."""
    if os.path.abspath(source) != os.path.abspath(dest):
        copy_case(source, dest, ("coupling.yaml", "in.bed"))
    packing = ["tfdem-liggghts", "-in", PACKING_SCRIPT, "-log", "log.packing"]
    for name, value in PACKING_VARIABLES:
        packing += ["-var", name, str(value)]
    runner(packing, dest, "log.packing.screen")
    write_velocity_file(dest)
    runner(["blockMesh"], dest, "log.blockMesh")
    runner(["tfdemFoam"], dest, "log.tfdemFoam")


def run_locally(args, cwd, log_name):
    with open(os.path.join(cwd, log_name), "w") as log:
        subprocess.run(args, cwd=cwd, stdout=log, stderr=subprocess.STDOUT, check=True)


def distributor_darcy(case="."):
    """The plate's Darcy coefficient d (1/m^2) from constant/fvOptions; its Forchheimer f must be
    zero (a linear plate's area-averaged pressure drop is mu d L U_0 however the gas spreads)."""
    path = os.path.join(case, "constant", "fvOptions")
    text = open(path).read()
    d = re.search(r"^\s*d\s+\(\s*(\S+)\s+(\S+)\s+(\S+)\s*\)\s*;", text, re.M)
    f = re.search(r"^\s*f\s+\(\s*(\S+)\s+(\S+)\s+(\S+)\s*\)\s*;", text, re.M)
    if not d or not f:
        raise SystemExit(f"{path}: expected the distributor's 'd (dx dy dz);' and 'f (fx fy fz);'")
    if any(float(v) != 0 for v in f.groups()):
        raise SystemExit(f"{path}: f {f.groups()} is not zero; fluidization.py subtracts a linear"
                         " (Darcy) plate's pressure drop only: set f (0 0 0);")
    return float(d.group(2))


def distributor_pressure_drop(u, darcy):
    """Pressure drop of the plate's porous body, FLOOR thick, at superficial velocity u (Pa)."""
    return MU * darcy * FLOOR * u


def end_time():
    return sum(duration for _, duration in LEVELS)


def level_windows():
    """(velocity, start, end) of each level's averaging window, in run order."""
    windows, t = [], 0.0
    for u, duration in LEVELS:
        windows.append((u, t + min(SETTLING, duration / 2), t + duration))
        t += duration
    return windows


def particle_count(case="."):
    for line in open(os.path.join(case, "bed.data")):
        if line.strip().endswith("atoms"):
            return int(line.split()[0])
    raise ValueError(f"{os.path.join(case, 'bed.data')}: no 'N atoms' line")


def particle_volume():
    return math.pi * D ** 3 / 6


def bed_weight_per_area(n):
    """Net weight (weight less buoyancy) of n particles per cross-section (Pa)."""
    return n * particle_volume() * (RHO_P - RHO_G) * G / (WIDTH * DEPTH)


def archimedes():
    return RHO_G * (RHO_P - RHO_G) * G * D ** 3 / MU ** 2


def wen_yu_minimum_fluidization():
    """Wen and Yu (1966): Re_mf = sqrt(33.7^2 + 0.0408 Ar) - 33.7."""
    return (math.sqrt(33.7 ** 2 + 0.0408 * archimedes()) - 33.7) * MU / (RHO_G * D)


def ergun_minimum_fluidization(eps):
    """U_mf where Ergun's pressure drop at voidage eps equals the net bed weight:
    1.75/eps^3 Re^2 + 150 (1 - eps)/eps^3 Re = Ar."""
    a, b = 1.75 / eps ** 3, 150 * (1 - eps) / eps ** 3
    re = (-b + math.sqrt(b * b + 4 * a * archimedes())) / (2 * a)
    return re * MU / (RHO_G * D)


def voidage(n, mean_height):
    """Bed voidage from the mean particle height above the plate (bed height = 2 x mean)."""
    height = 2 * (mean_height - FLOOR)
    return 1 - n * particle_volume() / (WIDTH * DEPTH * height), height


def ergun_pressure_drop(u, eps, height):
    """Ergun (1952) for a bed of voidage eps and height `height` (Pa)."""
    return (150 * (1 - eps) ** 2 * MU * u / (eps ** 3 * D ** 2)
            + 1.75 * (1 - eps) * RHO_G * u * u / (eps ** 3 * D)) * height


def inlet_table():
    """OpenFOAM table of the inlet velocity: each level held, switched over 10 ms."""
    rows, t = [], 0.0
    for u, duration in LEVELS:
        rows.append(f"({t + (0.01 if t else 0):.4f} (0 {u} 0))")
        t += duration
        rows.append(f"({t:.4f} (0 {u} 0))")
    return "\n".join(rows)


def check_end_time(case):
    """system/controlDict's endTime must be the sum of the level durations."""
    path = os.path.join(case, "system", "controlDict")
    match = re.search(r"^endTime\s+([^;\s]+)\s*;", open(path).read(), re.M)
    if not match:
        raise SystemExit(f"{path}: no endTime entry; expected endTime {end_time():g};")
    if abs(float(match.group(1)) - end_time()) > 1e-9:
        raise SystemExit(f"{path}: endTime {match.group(1)} differs from the sum of the level"
                         f" durations in fluidization.py LEVELS, {end_time():g} s; make them equal")


def write_velocity_file(case):
    check_end_time(case)
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
    with open(os.path.join(case, "0", "U"), "w") as f:
        f.write(text)


def dem_time_step(case="."):
    """The DEM step of in.bed (forces.txt counts DEM steps)."""
    path = os.path.join(case, "in.bed")
    match = re.search(r"^timestep\s+(\S+)", open(path).read(), re.M)
    if not match:
        raise ValueError(f"{path}: no timestep command")
    return float(match.group(1))


def rows(path):
    out = []
    for line in open(path):
        if line.startswith("#") or not line.strip():
            continue
        out.append([float(v) for v in line.split()])
    return out


def mean_in(series, start, end, column=1):
    values = [r[column] for r in series if start < r[0] <= end + 1e-9]
    if not values:
        raise ValueError(f"no samples between {start} and {end} s: did the run finish?")
    return sum(values) / len(values)


def pressure_drops(case="."):
    """(t, dp) samples of p(inlet, area average) - p(PROBE_HEIGHT) - rho_g g h (Pa), the plate's
    drop still included."""
    inlet = rows(os.path.join(case, "postProcessing", "inletPressure", "0", "surfaceFieldValue.dat"))
    above = {r[0]: r[1] for r in rows(os.path.join(case, "postProcessing", "abovePressure", "0", "p"))}
    return [(t, p - above[t] - RHO_G * G * PROBE_HEIGHT) for t, p in inlet if t in above]


def levels(case="."):
    """One dict per level, in run order: u, dp (Pa), eps and bed height from the mean particle
    height, Ergun's dp at that voidage, and the mean vertical forces on the particles as
    fractions of their weight (gas, plate, side walls)."""
    n = particle_count(case)
    drops = pressure_drops(case)
    darcy = distributor_darcy(case)
    heights = rows(os.path.join(case, "mean_height.txt"))
    dt = dem_time_step(case)
    forces = [[r[0] * dt] + r[1:] for r in rows(os.path.join(case, "forces.txt"))]
    weight = n * particle_volume() * RHO_P * G
    result = []
    for u, start, end in level_windows():
        eps, height = voidage(n, mean_in(heights, start, end))
        result.append({
            "u": u,
            "dp": mean_in(drops, start, end) - distributor_pressure_drop(u, darcy),
            "eps": eps,
            "height": height,
            "ergun": ergun_pressure_drop(u, eps, height),
            "gas": mean_in(forces, start, end, 1) / weight,
            "plate": mean_in(forces, start, end, 2) / weight,
            "side": (mean_in(forces, start, end, 3) + mean_in(forces, start, end, 4)) / weight,
        })
    return result


def plateau(case="."):
    """Mean and standard error (Pa) of the BATCH-long batch means of the bed's pressure drop in
    the averaging windows of the levels >= FLUIDIZED (a window's remainder shorter than a batch
    is left out), and the number of batches."""
    drops, darcy = pressure_drops(case), distributor_darcy(case)
    batches = []
    for u, start, end in level_windows():
        if u < FLUIDIZED:
            continue
        count = int((end - start) / BATCH + 1e-9)
        batches += [mean_in(drops, start + k * BATCH, start + (k + 1) * BATCH)
                    - distributor_pressure_drop(u, darcy) for k in range(count)]
    if len(batches) < 2:
        raise ValueError(f"{len(batches)} plateau batch(es) of {BATCH} s in the levels >= {FLUIDIZED} m/s of"
                         " LEVELS: hold them at least 2 x BATCH beyond SETTLING for a standard error")
    mean = sum(batches) / len(batches)
    variance = sum((b - mean) ** 2 for b in batches) / (len(batches) - 1)
    return mean, math.sqrt(variance / len(batches)), len(batches)


def fixed_bed_fit(branch, top):
    """Least-squares dp = a U + b U^2 through the branch's fixed-bed levels: (a, b, levels)."""
    fixed = [r for r in branch if r["dp"] < FIXED_BED_LIMIT * top]
    s11 = sum(r["u"] ** 2 for r in fixed)
    s12 = sum(r["u"] ** 3 for r in fixed)
    s22 = sum(r["u"] ** 4 for r in fixed)
    y1 = sum(r["u"] * r["dp"] for r in fixed)
    y2 = sum(r["u"] ** 2 * r["dp"] for r in fixed)
    det = s11 * s22 - s12 * s12
    return (y1 * s22 - y2 * s12) / det, (s11 * y2 - s12 * y1) / det, fixed


def minimum_fluidization(branch, top):
    """Intersection of the fixed-bed fit with the plateau: (U_mf, a, b, fitted levels)."""
    a, b, fixed = fixed_bed_fit(branch, top)
    return (-a + math.sqrt(a * a + 4 * b * top)) / (2 * b), a, b, fixed


def rising(result):
    return result[:RISING_COUNT]


def falling(result):
    return result[RISING_COUNT - 1:]


def summary(case="."):
    """The figures the README reports, as a dict."""
    result = levels(case)
    n = particle_count(case)
    (top, top_error, batches), weight = plateau(case), bed_weight_per_area(n)
    u_mf, a, b, fixed = minimum_fluidization(falling(result), top)
    u_mf_rising = minimum_fluidization(rising(result), top)[0]
    # voidage of the defluidized bed: the falling branch's fixed-bed levels
    eps_mf = sum(r["eps"] for r in fixed) / len(fixed)
    at_1 = [r for r in falling(result) if abs(r["u"] - 1.0) < 1e-9][0]
    fluidized = [r for r in result if r["u"] >= FLUIDIZED]
    return {
        "particles": n, "levels": result, "plateau": top, "plateau_error": top_error,
        "plateau_batches": batches, "weight": weight,
        "u_mf": u_mf, "u_mf_rising": u_mf_rising, "fit": (a, b), "fitted": fixed,
        "wen_yu": wen_yu_minimum_fluidization(), "eps_mf": eps_mf,
        "ergun_u_mf": ergun_minimum_fluidization(eps_mf),
        "fixed_bed_1": at_1,
        "gas_share": sum(r["gas"] for r in fluidized) / len(fluidized),
        "plate_share": sum(r["plate"] for r in fluidized) / len(fluidized),
        "side_share": sum(r["side"] for r in fluidized) / len(fluidized),
    }


if __name__ == "__main__":
    prepare_run(".", ".", run_locally)
