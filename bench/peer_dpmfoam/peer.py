#!/usr/bin/env python3
"""TFDEM against a peer: OpenFOAM's DPMFoam on its own Goldschmidt tutorial (Debian package
openfoam-examples: 24,750 glass beads of 2.5 mm, 2526 kg/m^3, in a 15 x 150 x 450 mm column
of 2 x 30 x 90 cells, air at 1.875 m/s through the bottom), both codes started from the same
packed bed and run for the same simulated time on this machine.

    peer.py run [--start packed|fluidized] [--end-time 0.01] [--root DIR] [--only tfdem|dpmfoam]
    peer.py report [--start packed|fluidized] [--root DIR]

`--start packed` (the default): 0.01 s from the packed bed is the bed lifting off, every
particle in contact, the gas through the whole bed. DPMFoam needs about 13 processor minutes
for it on this machine (77,000 s per simulated second); longer spans scale with it.
`--start fluidized [--fluidize 0.3]`: TFDEM first fluidizes the packed bed for 0.3 s; both codes
then start from that expanded, bubbling bed (positions; at rest, as DPMFoam's manual injection
gives every particle one velocity) and run --end-time from there (runs/fluidized/).

Both actions first check that case/ states the tutorial's air, inflow and particles (read from
the tutorial's files) and stop naming any that differs. `run` (each step skipped when done):
1. the tutorial's particle lattice (constant/kinematicCloudPositions) settled into a packed
   bed by LIGGGHTS alone (in.pack);
2. TFDEM: case/ (the tutorial's domain, mesh, gas, inflow and particles; DPMFoam's Hertz
   contact, case/in.bed says how its damping maps onto LIGGGHTS') from the packed bed;
3. DPMFoam: the tutorial unchanged except its initial positions (the packed bed), its end
   time, ascii output and the same two pressure probes as TFDEM's.
With `--start fluidized`, a TFDEM run from the packed bed (runs/fluidize/) gives the start.
Each run's processor time (the solver's, from the operating system) and wall time are kept.
`report` writes root/report/README.md and peer.png: processor seconds per simulated second
side by side and their ratio, and the bed statistic both compute, the pressure drop across
the column, its mean and fluctuation over the second half against the bed's weight per unit
area (the fluidized bed carries its weight: N m_p g / A).
"""
import argparse
import gzip
import json
import math
import os
import re
import resource
import shutil
import sys
import time

from tfdem.case import Case, CaseError, number, set_dict_entries, sphere_volume, sub_dict
from tfdem.liggghts import read_data_file
from tfdem.outputs import OutputError, probes, solver_timing, vtk_particles
from tfdem.physics import ergun_gradient
from tfdem.run import RunError, run

HERE = os.path.dirname(os.path.abspath(__file__))
TUTORIAL = "/usr/share/doc/openfoam-examples/examples/lagrangian/DPMFoam/Goldschmidt"


class PeerError(Exception):
    """A missing prerequisite or a failed step, with its fix."""


def timed(args, cwd, log_name):
    """Run args in cwd (output to log_name); (wall seconds, processor seconds of the child)."""
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    start = time.monotonic()
    run(args, cwd, log_name)
    wall = time.monotonic() - start
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    return wall, (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)


def tutorial():
    if not os.path.isdir(TUTORIAL):
        raise PeerError(f"{TUTORIAL} is missing: install Debian's OpenFOAM tutorials with "
                        "`apt-get install openfoam-examples`")
    return TUTORIAL


def cloud_entry(text, dotted):
    """Number of entry `a.b.key` of the tutorial's constant/kinematicCloudProperties text."""
    *parents, key = dotted.split(".")
    for name in parents:
        text = sub_dict(text, name, "kinematicCloudProperties")
    found = re.search(rf"(?<![\w.]){re.escape(key)}\s+([^;{{}}]+);", text)
    if not found:
        raise PeerError(f"{TUTORIAL}/constant/kinematicCloudProperties: no entry '{dotted}'")
    return number(found.group(1))


def restitution(alpha):
    """Restitution e of LIGGGHTS' hertz damping equal to DPMFoam's eta_n = alpha sqrt(m k)
    delta^1/4 (case/in.bed): beta = -alpha / sqrt(5), e = exp(beta pi / sqrt(1 - beta^2))."""
    beta = -alpha / math.sqrt(5)
    return math.exp(beta * math.pi / math.sqrt(1 - beta * beta))


def integrated_restitution(alpha, speed=1.0):
    """e of one head-on collision integrated (RK4, 20,000 steps per unit time) with DPMFoam's
    law m x'' = -k x^1.5 - alpha sqrt(m k) x^0.25 x' (m = k = 1): an independent check of
    restitution(alpha)."""
    def accel(x, v):
        x = max(x, 0.0)
        return -x ** 1.5 - alpha * x ** 0.25 * v
    x, v, dt = 0.0, speed, 5e-5
    while not (x < 0 and v < 0):
        k1 = (v, accel(x, v))
        k2 = (v + 0.5 * dt * k1[1], accel(x + 0.5 * dt * k1[0], v + 0.5 * dt * k1[1]))
        k3 = (v + 0.5 * dt * k2[1], accel(x + 0.5 * dt * k2[0], v + 0.5 * dt * k2[1]))
        k4 = (v + dt * k3[1], accel(x + dt * k3[0], v + dt * k3[1]))
        x += dt / 6 * (k1[0] + 2 * k2[0] + 2 * k3[0] + k4[0])
        v += dt / 6 * (k1[1] + 2 * k2[1] + 2 * k3[1] + k4[1])
    return -v / speed


def cloud_contacts():
    """DPMFoam's contact properties (constant/kinematicCloudProperties of the tutorial)."""
    with open(os.path.join(tutorial(), "constant", "kinematicCloudProperties")) as f:
        text = f.read()
    pair = "subModels.pairCollisionCoeffs.pairSpringSliderDashpotCoeffs."
    wall = "subModels.pairCollisionCoeffs.wallSpringSliderDashpotCoeffs."
    return {"particle_modulus": cloud_entry(text, "constantProperties.youngsModulus"),
            "particle_poisson": cloud_entry(text, "constantProperties.poissonsRatio"),
            "wall_modulus": cloud_entry(text, wall + "youngsModulus"),
            "wall_poisson": cloud_entry(text, wall + "poissonsRatio"),
            "pair_alpha": cloud_entry(text, pair + "alpha"),
            "wall_alpha": cloud_entry(text, wall + "alpha"),
            "pair_friction": cloud_entry(text, pair + "mu"),
            "wall_friction": cloud_entry(text, wall + "mu")}


def contact_variables(contacts):
    """{LIGGGHTS variable: value} of case/in.bed's contact properties: DPMFoam's, its damping
    alpha as a restitution."""
    variables = {k: v for k, v in contacts.items() if not k.endswith("_alpha")}
    variables.update(pair_restitution=restitution(contacts["pair_alpha"]),
                     wall_restitution=restitution(contacts["wall_alpha"]))
    return variables


def tutorial_value(relative, pattern):
    """The number (or vector) the regular expression's group matches in a tutorial file."""
    with open(os.path.join(tutorial(), relative)) as f:
        found = re.search(pattern, f.read())
    if not found:
        raise PeerError(f"{TUTORIAL}/{relative}: no match for {pattern!r}")
    return tuple(float(v) for v in found.group(1).split()) if "(" in found.group(0) else number(found.group(1))


def check_same_scene():
    """case/ must state the tutorial's air, inflow and particles (it writes them out as
    OpenFOAM and coupling.yaml need them); PeerError names any that differs."""
    case = Case(os.path.join(HERE, "case"))
    rho, mu = case.gas()
    diameter, density = case.particle_properties()
    pairs = {
        "air density (kg/m^3)": (rho, tutorial_value("constant/transportProperties", r"rho\.air\s+(\S+);")),
        "air kinematic viscosity (m^2/s)": (mu / rho, tutorial_value("constant/transportProperties", r"\bnu\s+(\S+);")),
        "particle density (kg/m^3)": (density, tutorial_value("constant/kinematicCloudProperties", r"rho0\s+(\S+);")),
        "particle diameter (m)": (diameter, tutorial_value("constant/kinematicCloudProperties",
                                                           r"fixedValueDistribution\s*\{\s*value\s+(\S+);")),
        "inflow velocity (m/s)": (case.patch_value("U", "inlet"),
                                  tutorial_value("0/U.air", r"inletVelocity\s+uniform\s+\(([^)]*)\)")),
    }
    for name, (ours, theirs) in pairs.items():
        as_tuple = lambda v: v if isinstance(v, tuple) else (v,)
        if not all(math.isclose(a, b, rel_tol=1e-9, abs_tol=1e-12) for a, b in zip(as_tuple(ours), as_tuple(theirs))):
            raise PeerError(f"{HERE}/case: {name} is {ours}, DPMFoam's tutorial has {theirs}: make case/ state the "
                            "tutorial's value")


def lattice_positions():
    path = os.path.join(tutorial(), "constant", "kinematicCloudPositions.gz")
    with gzip.open(path, "rt") as f:
        text = f.read()
    value = r"([-+.0-9eE]+)"
    row = re.compile(rf"^\([ \t]*{value}[ \t]+{value}[ \t]+{value}[ \t]*\)", re.M)
    return [tuple(float(v) for v in m) for m in row.findall(text)]


def write_bed_data(path, positions, diameter, density):
    """A LIGGGHTS data file (atom style granular, 2 types: 1 particles, 2 walls) of the
    positions in DPMFoam's box, at rest."""
    (x0, y0, z0), (x1, y1, z1) = Case(os.path.join(HERE, "case")).mesh_bounds()
    lines = ["DPMFoam Goldschmidt bed (bench/peer_dpmfoam/peer.py)", "", f"{len(positions)} atoms",
             "2 atom types", "", f"{x0} {x1} xlo xhi", f"{y0} {y1} ylo yhi", f"{z0} {z1} zlo zhi", "", "Atoms", ""]
    lines += [f"{i + 1} 1 {diameter} {density} {x} {y} {z} 0 0 0" for i, (x, y, z) in enumerate(positions)]
    with open(path, "w") as f:
        f.write("\n".join(lines) + "\n")


def packed_bed(root):
    """The settled bed (root/pack/packed_bed.data), made once."""
    pack = os.path.join(root, "pack")
    out = os.path.join(pack, "packed_bed.data")
    if os.path.isfile(out):
        return out
    os.makedirs(pack, exist_ok=True)
    diameter, density = Case(os.path.join(HERE, "case")).particle_properties()
    write_bed_data(os.path.join(pack, "lattice.data"), lattice_positions(), diameter, density)
    shutil.copy(os.path.join(HERE, "in.pack"), pack)
    print("settling the tutorial's lattice (LIGGGHTS only) ...", flush=True)
    contact = cloud_contacts()
    run(["tfdem-liggghts", "-in", "in.pack", "-var", "out", "packed_bed.tmp", "-log", "log.liggghts",
         "-var", "modulus", str(contact["particle_modulus"]), "-var", "poisson", str(contact["particle_poisson"])],
        pack, "log.pack")
    os.replace(os.path.join(pack, "packed_bed.tmp"), out)
    return out


def save(path, record):
    with open(path, "w") as f:
        json.dump(record, f, indent=1)


def tfdem_case(path, bed):
    """case/ copied to path with DPMFoam's contacts and the start bed, meshed."""
    if os.path.isdir(path):
        shutil.rmtree(path)
    case = Case(os.path.join(HERE, "case")).copy_to(path)
    script = case.dem_script()
    with open(script) as f:
        text = f.read()
    variables = contact_variables(cloud_contacts())
    with open(script, "w") as f:
        f.write("".join(f"variable        {k} index {v:.6g}\n" for k, v in variables.items()) + text)
    shutil.copy(bed, case.file(os.path.basename(case.dem().read_data())))
    run(["blockMesh"], path, "log.blockMesh")
    return case


def fluidized_bed(root, fluidize_time):
    """The start of `--start fluidized` (root/fluidize/fluidized_bed.data), made once: the
    packed bed fluidized by TFDEM for fluidize_time, its particles' positions at rest."""
    path = os.path.join(root, "fluidize")
    out = os.path.join(path, "fluidized_bed.data")
    if os.path.isfile(out):
        return out
    case = tfdem_case(path, packed_bed(root))
    case.set_control(endTime=fluidize_time, writeInterval=fluidize_time)
    print(f"fluidizing the packed bed with TFDEM for {fluidize_time} s ...", flush=True)
    run(["tfdemFoam"], path, "log.tfdemFoam")
    vtk = os.path.join(path, "VTK", f"particles_{fluidize_time:g}.vtk")
    if not os.path.isfile(vtk):
        raise PeerError(f"{vtk} is missing: the fluidizing run ended without its particle file "
                        f"(case/coupling.yaml must keep output.particles_vtk on; log: {path}/log.tfdemFoam)")
    final = vtk_particles(vtk)
    diameter, density = case.particle_properties()
    write_bed_data(out + ".tmp", final["position"], diameter, density)
    os.replace(out + ".tmp", out)
    return out


def start_bed(root, start, fluidize_time):
    return packed_bed(root) if start == "packed" else fluidized_bed(root, fluidize_time)


def runs_folder(root, start):
    """Where the two codes' runs from `start` and their report go."""
    return root if start == "packed" else os.path.join(root, "fluidized")


def run_tfdem(folder, bed, end_time):
    path = os.path.join(folder, "tfdem")
    result = os.path.join(path, "peer.json")
    if os.path.isfile(result):
        return
    case = tfdem_case(path, bed)
    case.set_control(endTime=end_time, writeInterval=end_time)
    print(f"TFDEM, {end_time} s ...", flush=True)
    wall, cpu = timed(["tfdemFoam"], path, "log.tfdemFoam")
    save(result, {"end_time": end_time, "wall": wall, "cpu": cpu, "split": solver_timing(case.file("log.tfdemFoam"))})
    print(f"  wall {wall:.0f} s, processor {cpu:.0f} s", flush=True)


def run_dpmfoam(folder, bed, end_time):
    path = os.path.join(folder, "dpmfoam")
    result = os.path.join(path, "peer.json")
    if os.path.isfile(result):
        return
    atoms = read_data_file(bed)
    if os.path.isdir(path):
        shutil.rmtree(path)
    shutil.copytree(tutorial(), path)
    positions = os.path.join(path, "constant", "kinematicCloudPositions")
    with gzip.open(positions + ".gz", "rt") as f:
        header = f.read().split("(", 1)[0]
    os.remove(positions + ".gz")
    with open(positions, "w") as f:
        f.write(header + "(\n" + "".join(f"({x:.9g} {y:.9g} {z:.9g})\n" for x, y, z in
                                         zip(atoms["x"], atoms["y"], atoms["z"])) + ")\n")
    probes_text = "(" + " ".join(f"({x:g} {y:g} {z:g})" for x, y, z in
                                 Case(os.path.join(HERE, "case")).probe_locations("pressure")) + ")"
    control = os.path.join(path, "system", "controlDict")
    set_dict_entries(control, endTime=end_time, writeInterval=end_time, writeFormat="ascii", startFrom="startTime")
    with open(control) as f:
        text = f.read()
    text = text.rstrip() + ("\n\nfunctions\n{\n    pressure\n    {\n        type probes;\n"
                            "        libs (\"libsampling.so\");\n        writeControl timeStep;\n"
                            f"        writeInterval 1;\n        fields (p);\n        probeLocations {probes_text};\n"
                            "    }\n}\n")
    with open(control, "w") as f:
        f.write(text)
    run(["blockMesh"], path, "log.blockMesh")
    print(f"DPMFoam, {end_time} s ...", flush=True)
    wall, cpu = timed(["DPMFoam"], path, "log.DPMFoam")
    save(result, {"end_time": end_time, "wall": wall, "cpu": cpu})
    print(f"  wall {wall:.0f} s, processor {cpu:.0f} s", flush=True)


def pressure_drop(path, density_factor):
    """(t, p(bottom probe) - p(top probe) in Pa) of a run; DPMFoam's p is kinematic (p/rho)."""
    rows = probes(path, "pressure", "p")
    return [t for t, _ in rows], [density_factor * (v[0] - v[1]) for _, v in rows]


def window_stats(t, values, start):
    import numpy
    t, values = numpy.asarray(t), numpy.asarray(values)
    pick = values[t >= start]
    return float(pick.mean()), float(pick.std())


def bed_weight_per_area(root):
    """N m_p g / A of the packed bed (Pa): what the fluidized bed's pressure drop must carry."""
    case = Case(os.path.join(HERE, "case"))
    atoms = read_data_file(packed_bed(root))
    diameter, density = case.particle_properties()
    rho_gas = case.gas()[0]
    (x0, y0, _), (x1, y1, _) = case.mesh_bounds()
    mass = len(atoms["id"]) * sphere_volume(diameter) * (density - rho_gas)
    return mass * case.gravity_magnitude() / ((x1 - x0) * (y1 - y0))


def packed_ergun(root):
    """(gas fraction, Ergun pressure drop in Pa) of the packed bed at the inflow velocity: its
    height twice its mean particle height (a uniform bed), eps = 1 - N V_p / (A H)."""
    case = Case(os.path.join(HERE, "case"))
    atoms = read_data_file(packed_bed(root))
    diameter, _ = case.particle_properties()
    (x0, y0, z0), (x1, y1, _) = case.mesh_bounds()
    height = 2 * (sum(atoms["z"]) / len(atoms["z"]) - z0)
    eps = 1 - len(atoms["z"]) * sphere_volume(diameter) / ((x1 - x0) * (y1 - y0) * height)
    u = case.patch_value("U", "inlet")[2]
    rho, mu = case.gas()
    return eps, ergun_gradient(u, eps, diameter, rho, mu) * height


def report(root, start):
    folder = runs_folder(root, start)
    codes = {}
    for code, factor in (("tfdem", 1.0), ("dpmfoam", Case(os.path.join(HERE, "case")).gas()[0])):
        result = os.path.join(folder, code, "peer.json")
        if not os.path.isfile(result):
            raise PeerError(f"{result} is missing: run `peer.py run --start {start}` first")
        with open(result) as f:
            record = json.load(f)
        record["t"], record["dp"] = pressure_drop(os.path.join(folder, code), factor)
        record["dp_mean"], record["dp_std"] = window_stats(record["t"], record["dp"], record["end_time"] / 2)
        codes[code] = record
    tf, dp = codes["tfdem"], codes["dpmfoam"]
    if abs(tf["end_time"] - dp["end_time"]) > 1e-12:
        raise PeerError(f"the runs simulated different times ({tf['end_time']} and {dp['end_time']} s): run both again")
    weight = bed_weight_per_area(root)
    eps, ergun = packed_ergun(root)
    out = os.path.join(folder, "report")
    os.makedirs(out, exist_ok=True)
    rows = ["| code | simulated (s) | processor (s) | per simulated s | wall (s) | Δp mean, 2nd half (Pa) | "
            "Δp std (Pa) | Δp mean ÷ bed weight per area |", "|---|---|---|---|---|---|---|---|"]
    for name, r in (("TFDEM", tf), ("DPMFoam", dp)):
        rows.append(f"| {name} | {r['end_time']:g} | {r['cpu']:.0f} | {r['cpu'] / r['end_time']:.0f} | "
                    f"{r['wall']:.0f} | {r['dp_mean']:.0f} | {r['dp_std']:.0f} | {r['dp_mean'] / weight:.3f} |")
    ratio = dp["cpu"] / tf["cpu"]
    alphas = {name: cloud_contacts()[name + "_alpha"] for name in ("pair", "wall")}
    checks = ", ".join(f"{name} alpha {alpha:g} -> e = {restitution(alpha):.5f} (a collision integrated with "
                       f"DPMFoam's law: {integrated_restitution(alpha):.5f})" for name, alpha in alphas.items())
    text = ("# TFDEM against DPMFoam on DPMFoam's Goldschmidt tutorial (bench/peer_dpmfoam/peer.py), "
            f"from the {start} bed\n\n"
            + "\n".join(rows) + f"\n\nDPMFoam ÷ TFDEM processor time: **{ratio:.1f}**. Bed weight per unit area "
            f"(N m_p g / A, buoyancy removed): {weight:.0f} Pa; Ergun's pressure drop over the packed bed "
            f"(gas fraction {eps:.3f}) at the inflow velocity: {ergun:.0f} Pa. TFDEM's restitution from "
            f"DPMFoam's damping: {checks}.\n")
    with open(os.path.join(out, "README.md"), "w") as f:
        f.write(text)
    plot(codes, weight, os.path.join(out, "peer.png"))
    print(text + f"report: {out}")


def plot(codes, weight, path):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(figsize=(6, 3.5))
    for code, label in (("tfdem", "TFDEM"), ("dpmfoam", "DPMFoam")):
        ax.plot(codes[code]["t"], codes[code]["dp"], label=label, lw=0.8)
    ax.axhline(weight, color="k", ls="--", lw=0.8, label="bed weight / area")
    ax.set_ylim(0, 3 * weight)  # the gas start's first-step spike (DPMFoam ~20 weights) off the scale
    ax.set_xlabel("t (s)")
    ax.set_ylabel("Δp bottom - top (Pa)")
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(path, dpi=120)


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("action", choices=("run", "report"))
    parser.add_argument("--start", choices=("packed", "fluidized"), default="packed")
    parser.add_argument("--fluidize", type=float, default=0.3, help="s of TFDEM from the packed bed that make "
                        "the fluidized start")
    parser.add_argument("--end-time", type=float, default=0.01)
    parser.add_argument("--root", default=os.path.join(HERE, "runs"))
    parser.add_argument("--only", choices=("tfdem", "dpmfoam"))
    args = parser.parse_args(argv)
    if args.end_time <= 0 or args.fluidize <= 0:
        parser.error("--end-time and --fluidize must be positive")
    try:
        check_same_scene()
        if args.action == "run":
            bed = start_bed(args.root, args.start, args.fluidize)
            folder = runs_folder(args.root, args.start)
            if args.only in (None, "tfdem"):
                run_tfdem(folder, bed, args.end_time)
            if args.only in (None, "dpmfoam"):
                run_dpmfoam(folder, bed, args.end_time)
            if args.only:
                return 0
        report(args.root, args.start)
    except (PeerError, CaseError, RunError, OutputError) as e:
        sys.exit(f"peer.py: {e}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
