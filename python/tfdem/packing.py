"""Random poured packings for any box case (tutorials/poured_packing/in.pour): the column's
width, depth and height come from the case's mesh, the particle sizes and density from its
coupling.yaml, and what only the packing needs from the case's packing.yaml:

    count: 8000                 # particles
    mass_fraction_small: 0.25   # mixtures only: mass (= volume) fraction of the smaller size
    floor: 0.0                  # optional: height of the plate the bed rests on (m)
    seed: 15485863              # optional: a prime; another one gives another packing

The data file's box is the column, so the case's DEM script can read_data it.
"""
import os

import yaml

import tfdem.run
from tfdem import TUTORIALS
from tfdem.case import Case, CaseError

POUR_SCRIPT = os.path.join(TUTORIALS, "poured_packing", "in.pour")


def pour_variables(case, count, mass_fraction_small=1.0, floor=None, seed=None):
    """The -var settings of in.pour for `case` (a Case or its path)."""
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
    return values


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
    return lines[-1]
