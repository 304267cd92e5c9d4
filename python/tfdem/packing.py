"""Random poured packings for any box case (tutorials/poured_packing/in.pour): the column's
width, depth and height come from the case's mesh, the particle sizes and density from its
coupling.yaml, and what only the packing needs from the case's packing.yaml:

    count: 8000                 # particles
    mass_fraction_small: 0.25   # mixtures only: mass (= volume) fraction of the smaller size
    floor: 0.0                  # optional: height of the plate the bed rests on (m)
    seed: 15485863              # optional: a prime; another one gives another packing

The data file's box is the column, so the case's DEM script can read_data it. A column one
particle deep (seed 000's 2-D rule) leaves no room to insert a sphere: it is poured into a slab
PLANE_SLAB diameters deep, where spheres cannot pass one another, and every centre is then
moved onto the mid-plane (overlaps of at most d - sqrt(d^2 - ((PLANE_SLAB - 1) d)^2), 0.13 %
of d).
"""
import argparse
import os
import re
import sys

import yaml

import tfdem.engines
import tfdem.run
from tfdem import TUTORIALS
from tfdem.case import Case, CaseError

POUR_SCRIPT = os.path.join(TUTORIALS, "poured_packing", "in.pour")
PLANE_SLAB = 1.05  # depth of the slab a one-layer bed is poured into, in diameters


def one_layer(case):
    """Whether the case's column is one particle deep (depth < 1.5 of the largest diameter)."""
    case = case if isinstance(case, Case) else Case(case)
    lo, hi = case.mesh_bounds()
    return hi[2] - lo[2] < 1.5 * case.particle_diameters()[-1]


def pour_variables(case, count, mass_fraction_small=1.0, floor=None, seed=None, friction=None):
    """The -var settings of in.pour for `case` (a Case or its path); `friction`: the pour's
    mu (in.pour's own default otherwise). A one-layer column is poured PLANE_SLAB diameters
    deep."""
    case = case if isinstance(case, Case) else Case(case)
    lo, hi = case.mesh_bounds()
    if abs(lo[0]) > 1e-12 or abs(lo[2]) > 1e-12:
        raise CaseError(f"{case.file('system', 'blockMeshDict')}: the pour needs the column's corner at"
                        f" x = z = 0, the mesh starts at ({lo[0]}, {lo[2]})")
    diameters = case.particle_diameters()
    if len(diameters) > 2:
        raise CaseError(f"{case.file('coupling.yaml')}: particles.diameter lists {len(diameters)} sizes;"
                        " the pour makes mono- and bidisperse beds")
    values = {"width": hi[0], "depth": hi[2], "height": hi[1], "floor": lo[1] if floor is None else floor,
              "count": int(count), "dp_small": diameters[0], "dp_large": diameters[-1],
              "mass_fraction_small": mass_fraction_small if len(diameters) == 2 else 1.0,
              "rho": float(case.coupling_value("particles.density"))}
    if seed is not None:
        values["seed"] = int(seed)
    if friction is not None:
        values["mu"] = float(friction)
    if one_layer(case):
        values["depth"] = PLANE_SLAB * diameters[-1]
        # in the slab the spheres keep rattling at ~7 mm/s (the jet bed's 2400 of 4 mm, its
        # mean height steady to 1e-5 m over 40,000 steps): at rest below 1 cm/s
        values["rest_speed"] = 0.01
    return values


def set_atom_types(path, count):
    """Declare `count` atom types in a data file (the DEM script's type count: in.pour writes
    3, small, large and the walls, where a template may use 2); every atom's type must be in
    1 .. count."""
    text = open(path).read()
    section, highest = "", 0
    for line in text.split("\n"):
        words = line.split()
        if words and words[0][0].isalpha():
            section = words[0]
        elif section == "Atoms" and len(words) >= 7:
            highest = max(highest, int(words[1]))
    if highest > count:
        raise CaseError(f"{path}: atoms of type {highest}, more than the {count} types to declare")
    text, n = re.subn(r"(?m)^\s*\d+\s+atom types\s*$", f"{count} atom types", text)
    if n != 1:
        raise CaseError(f"{path}: no 'N atom types' line in its header")
    with open(path, "w") as f:
        f.write(text)


def to_mid_plane(path, depth):
    """Move every centre of a data file onto the plane z = depth/2, keep its motion in the
    plane (v_z, omega_x, omega_y = 0: a bed under the 2-D rule may have no walls in z) and
    make its box `depth` deep (a bed poured PLANE_SLAB diameters deep)."""
    lines, out, section = open(path).read().split("\n"), [], ""
    for line in lines:
        words = line.split()
        if words and words[0][0].isalpha():
            section = words[0]
        if line.rstrip().endswith("zlo zhi"):
            line = f"0 {depth!r} zlo zhi"
        elif section == "Atoms" and len(words) >= 7 and words[0].isdigit():
            words[6] = repr(depth / 2)
            line = " ".join(words)
        elif section == "Velocities" and len(words) >= 7 and words[0].isdigit():  # id vx vy vz wx wy wz
            words[3] = words[4] = words[5] = "0"
            line = " ".join(words)
        out.append(line)
    with open(path, "w") as f:
        f.write("\n".join(out))


def packing_settings(case):
    """The case's packing.yaml as keyword arguments of pour() (count and the options)."""
    case = case if isinstance(case, Case) else Case(case)
    path = case.file("packing.yaml")
    if not os.path.exists(path):
        raise CaseError(f"{path}: missing; it gives the packing's particle count (see tfdem.packing)")
    with open(path) as f:
        settings = yaml.safe_load(f) or {}
    known = ("count", "mass_fraction_small", "floor", "seed")
    unknown = sorted(set(settings) - set(known))
    if unknown:
        raise CaseError(f"{path}: unknown key '{unknown[0]}'; valid keys: {', '.join(known)}")
    if "count" not in settings:
        raise CaseError(f"{path}: no 'count' (the number of particles to pour)")
    return settings


def pour_case(case, out="bed.data", ranks=1, runner=tfdem.run.run):
    """pour() with the case's packing.yaml."""
    return pour(case, out=out, ranks=ranks, runner=runner, **packing_settings(case))


def pour(case, count, out="bed.data", ranks=1, runner=tfdem.run.run, **options):
    """Pour `count` particles into `case`'s column and write the packed bed to case/out;
    returns the printed summary line ('TFDEM packed bed: N particles, mean height ...')."""
    case = case if isinstance(case, Case) else Case(case)
    args = ["tfdem-liggghts", "-in", POUR_SCRIPT, "-log", "log.pour.liggghts"]
    for name, value in pour_variables(case, count, **options).items():
        args += ["-var", name, repr(value) if isinstance(value, float) else str(value)]
    args += ["-var", "out", out]
    _, output = runner(args, case.path, "log.pour", ranks=ranks)
    lines = [line for line in output.splitlines() if line.startswith("TFDEM packed bed")]
    if not lines:
        raise CaseError(f"{case.file('log.pour')}: the pour printed no 'TFDEM packed bed' line")
    if one_layer(case):
        lo, hi = case.mesh_bounds()
        to_mid_plane(case.file(out), hi[2] - lo[2])
        return lines[-1] + f" (poured {PLANE_SLAB} diameters deep, centres moved onto the mid-plane)"
    return lines[-1]


def script_type_count(case):
    """The atom types the case's DEM script declares (its property/global kn peratomtypepair N)."""
    case = case if isinstance(case, Case) else Case(case)
    for words in case.dem().commands("fix"):
        if len(words) > 6 and words[3] == "property/global" and words[4] == "kn" and words[5] == "peratomtypepair":
            return int(words[6])
    raise CaseError(f"{case.dem_script()}: no 'fix ... property/global kn peratomtypepair N': the number of atom "
                    "types the packing must declare is not known")


def pack_case(case, ranks=1, runner=tfdem.run.run):
    """`tfdem pack`: pour the case's packing.yaml with the friction of its DEM script's particle
    pairs, into the data file its script reads, with the atom types the script declares."""
    case = case if isinstance(case, Case) else Case(case)
    script = case.dem()
    out = script.command("read_data")[1]
    tables = tfdem.engines.contact_properties(script)
    summary = pour(case, out=out, ranks=ranks, runner=runner, friction=tables["coefficientFriction"][0][0],
                   **packing_settings(case))
    set_atom_types(case.file(out), script_type_count(case))
    return summary


def main(argv=None):
    parser = argparse.ArgumentParser(prog="tfdem pack", description="Pour a case's bed (its packing.yaml) into "
                                     "the data file its DEM script reads.")
    parser.add_argument("case", nargs="?", default=".")
    parser.add_argument("--ranks", type=int, default=1)
    args = parser.parse_args(argv)
    try:
        print(pack_case(args.case, ranks=args.ranks))
    except (CaseError, tfdem.run.RunError, tfdem.engines.ScriptError) as e:
        print(f"tfdem pack: {e}", file=sys.stderr)
        return 2
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
