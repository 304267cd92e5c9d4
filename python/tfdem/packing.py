"""Random poured packings for any box case (tutorials/poured_packing/in.pour): the column's
width, depth and height come from the case's mesh, the particle sizes and density from its
coupling.yaml, and what only the packing needs from the case's packing.yaml:

    count: 8000                 # particles
    mass_fraction_small: 0.25   # two sizes: mass (= volume) fraction of the smaller size
    mass_fractions: [0.2, 0.5, 0.3]   # or, for any number of sizes: each size's mass fraction,
                                # in coupling.yaml's order of diameters, smallest first
    floor: 0.0                  # optional: height of the plate the bed rests on (m)
    seed: 15485863              # optional: a prime; another one gives another packing

The data file's box is the column, so the case's DEM script can read_data it. A column one
particle deep (seed 000's 2-D rule) leaves no room to insert a sphere: it is poured into a slab
PLANE_SLAB diameters deep, where spheres of one size cannot pass one another, and every centre
is then moved onto the mid-plane (overlaps of at most d - sqrt(d^2 - ((PLANE_SLAB - 1) d)^2),
0.13 % of d). Smaller spheres could pass the larger ones in such a slab (a 1.5 mm sphere has
1.1 mm of play beside a 2.5 mm one, and moved onto the mid-plane they would overlap by half a
diameter): two or more sizes are poured with every centre on the slab's mid-plane from their
insertion on and held there (in.pour's `plane`).

The packed bed is written at rest: every velocity and spin set to zero (what the pour leaves
is contact vibration and rattlers, up to a few cm/s and hundreds of rad/s for 1 mm spheres),
and its largest overlap, a fraction of the smaller diameter of the pair, is printed and must
stay below MAX_OVERLAP (the poured beds of the tutorials: 0.17 % for 800 beads of 1 mm, 2.2 %
for Goldschmidt's 45,000 spheres 45 layers deep under the pour's k_n of 800 N/m) unless the run's
own contacts are no stiffer than the pour's (then it is the run's rest state: seed 000's jet bed,
k_n 800 N/m, 6.9 %).
"""
import argparse
import contextlib
import hashlib
import json
import math
import os
import re

import numpy

import tfdem.run
from tfdem import TUTORIALS
from tfdem.case import Case, CaseError
from tfdem.contacts import contact_pairs
from tfdem.frontdoor import add_debug_option, doing, replace_atomic, run_command, write_text_atomic
from tfdem.inputs import Source, load_yaml, positive_count
from tfdem.liggghts import DemScript, contact_properties, read_data_file

POUR_SCRIPT = os.path.join(TUTORIALS, "poured_packing", "in.pour")
PLANE_SLAB = 1.05  # depth of the slab a one-layer bed is poured into, in diameters
MAX_OVERLAP = 0.05  # of the smaller diameter: the largest a packed bed may keep (5 %, the usual DEM bound)
SIZES_FILE = "pour_sizes.in"  # three or more sizes: in.pour's templates (written, read, removed)
# LIGGGHTS' random seeds are primes, each fix's its own: the first primes above 11, 12, ...
# 20 million, apart from in.pour's insertion seed (15485863, or packing.yaml's)
TEMPLATE_SEEDS = (11000027, 12000017, 13000027, 14000029, 15000017, 16000057, 17000023, 18000041, 19000013)
DISTRIBUTION_SEED = 20000003
SMALLEST_SEED = 10000  # LIGGGHTS' random seeds: primes above it
PACKING_KEYS = ("count", "mass_fraction_small", "mass_fractions", "floor", "seed")
POURING = ".tfdem-pour"    # the pour's data file until it is finished: <data file>.tfdem-pour
STAMP = ".tfdem-packed"    # written last by tfdem pack: <data file>.tfdem-packed


def one_layer(case):
    """Whether the case's column is one particle deep (depth < 1.5 of the largest diameter)."""
    case = case if isinstance(case, Case) else Case(case)
    lo, hi = case.mesh_bounds()
    return hi[2] - lo[2] < 1.5 * case.particle_diameters()[-1]


def pour_variables(case, count, mass_fraction_small=None, mass_fractions=None, floor=None, seed=None, friction=None):
    """The -var settings of in.pour for `case` (a Case or its path); `friction`: the pour's
    mu (in.pour's own default otherwise); the mixture as mass_fraction_small (two sizes) or
    mass_fractions (one per size, smallest first). A one-layer column is poured PLANE_SLAB
    diameters deep. Three or more sizes add `sizes`, the file sizes_file() writes."""
    case = case if isinstance(case, Case) else Case(case)
    lo, hi = case.mesh_bounds()
    if abs(lo[0]) > 1e-12 or abs(lo[2]) > 1e-12:
        raise CaseError(f"{case.file('system', 'blockMeshDict')}: the pour needs the column's corner at"
                        f" x = z = 0, the mesh starts at ({lo[0]}, {lo[2]})")
    diameters = case.particle_diameters()
    fractions = mixture(case, diameters, mass_fraction_small, mass_fractions)
    values = {"width": hi[0], "depth": hi[2], "height": hi[1], "floor": lo[1] if floor is None else floor,
              "count": int(count), "dp_small": diameters[0], "dp_large": diameters[-1],
              "mass_fraction_small": fractions[0] if len(diameters) == 2 else 1.0,
              "rho": case.particle_density()}
    if len(diameters) > 2:
        values["sizes"], values["size_count"] = SIZES_FILE, len(diameters)
    if seed is not None:
        values["seed"] = int(seed)
    if friction is not None:
        values["mu"] = float(friction)
    if one_layer(case):
        values["depth"] = PLANE_SLAB * diameters[-1]
        values["plane"] = int(len(diameters) > 1)
        # in the slab the spheres keep rattling at ~7 mm/s (the jet bed's 2400 of 4 mm, its
        # mean height steady to 1e-5 m over 40,000 steps): at rest below 1 cm/s
        values["rest_speed"] = 0.01
    return values


def mixture(case, diameters, mass_fraction_small=None, mass_fractions=None):
    """Each size's mass fraction (smallest first) from packing.yaml's mass_fraction_small (two
    sizes) or mass_fractions (any number); one size: [1]."""
    path = case.file("packing.yaml")
    if mass_fractions is not None:
        if mass_fraction_small is not None:
            raise CaseError(f"{path}: give mass_fractions or mass_fraction_small, not both")
        if not isinstance(mass_fractions, list) or len(mass_fractions) != len(diameters) or \
                not all(isinstance(f, (int, float)) and 0 < f <= 1 for f in mass_fractions):
            raise CaseError(f"{path}: mass_fractions: expected {len(diameters)} fractions in (0, 1], one per size of "
                            f"coupling.yaml's particles.diameter {diameters}, got {mass_fractions!r}")
        if abs(sum(mass_fractions) - 1) > 1e-9:
            raise CaseError(f"{path}: mass_fractions sum to {sum(mass_fractions):g}, not 1")
        return [float(f) for f in mass_fractions]
    if len(diameters) == 1:
        return [1.0]
    if len(diameters) == 2:
        small = 1.0 if mass_fraction_small is None else float(mass_fraction_small)
        return [small, 1.0 - small]
    raise CaseError(f"{path}: {len(diameters)} sizes in coupling.yaml's particles.diameter: give mass_fractions, "
                    "one per size, smallest first")


def sizes_file(case, diameters, fractions):
    """in.pour's templates for three or more sizes: one particletemplate/sphere a size (all of
    atom type 1: the pour's contacts are the same for every pair; retype() sorts them after),
    the distribution `sizes`, and the mixture's mean volume for the waves."""
    if len(diameters) > len(TEMPLATE_SEEDS):
        raise CaseError(f"{case.file('coupling.yaml')}: {len(diameters)} sizes; the pour takes up to "
                        f"{len(TEMPLATE_SEEDS)}")
    lines = ["# Written by tfdem.packing for in.pour: one template a size, by mass fraction"]
    for k, (d, seed) in enumerate(zip(diameters, TEMPLATE_SEEDS), 1):
        lines.append(f"fix             size{k} all particletemplate/sphere {seed} atom_type 1 density constant "
                     f"${{rho}} radius constant {d / 2!r}")
    pairs = " ".join(f"size{k} {f!r}" for k, f in enumerate(fractions, 1))
    lines.append(f"fix             sizes all particledistribution/discrete {DISTRIBUTION_SEED} {len(diameters)} {pairs}")
    mean_volume = 1 / sum(f / (math.pi * d ** 3 / 6) for f, d in zip(fractions, diameters))
    lines.append(f"variable        mean_volume equal {mean_volume!r}")
    write_text_atomic(case.file(SIZES_FILE), "\n".join(lines) + "\n")


def retype(path, diameters):
    """Give every atom of a data file the type of its size: 1 + the index of its diameter in
    `diameters` (ascending; the walls' type comes after them)."""
    lines, out, section = open(path).read().split("\n"), [], ""
    for line in lines:
        words = line.split()
        if words and words[0][0].isalpha():
            section = words[0]
        elif section == "Atoms" and len(words) >= 7 and words[0].isdigit():
            d = float(words[2])
            k = min(range(len(diameters)), key=lambda i: abs(diameters[i] - d))
            if abs(diameters[k] - d) > 1e-9 * d:
                raise CaseError(f"{path}: atom {words[0]} of diameter {d} is none of the sizes {diameters}")
            words[1] = str(k + 1)
            line = " ".join(words)
        out.append(line)
    write_text_atomic(path, "\n".join(out))


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
    write_text_atomic(path, text)


def to_mid_plane(path, depth):
    """Move every centre of a data file onto the plane z = depth/2 and make its box `depth`
    deep (a bed poured PLANE_SLAB diameters deep)."""
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
        out.append(line)
    write_text_atomic(path, "\n".join(out))


def _set_velocities(path, velocity_of):
    """Rewrite a data file's Velocities section: each line id vx vy vz wx wy wz gets
    velocity_of(id), six numbers."""
    lines, out, section = open(path).read().split("\n"), [], ""
    for line in lines:
        words = line.split()
        if words and words[0][0].isalpha():
            section = words[0]
        elif section == "Velocities" and len(words) >= 7 and words[0].isdigit():
            line = " ".join([words[0]] + [repr(float(v)) if v else "0" for v in velocity_of(int(words[0]))] + words[7:])
        out.append(line)
    write_text_atomic(path, "\n".join(out))


def at_rest(path):
    """Set every velocity and spin of a data file to zero (its Velocities section)."""
    _set_velocities(path, lambda _: (0,) * 6)


def jiggle(path, speed, seed):
    """Give every particle of a data file a random velocity, each component normal with
    standard deviation `speed` (m/s), spins zero: a perturbation far below a bed's own motion
    that makes runs from one packing independent realizations once the bed's chaos has grown it
    (another `seed`, another realization)."""
    rng = numpy.random.default_rng(seed)
    _set_velocities(path, lambda _: tuple(rng.normal(0.0, speed, 3)) + (0, 0, 0))


def largest_overlap(path):
    """The largest overlap of two spheres of a data file, as a fraction of the pair's smaller
    diameter (0 when none overlap)."""
    atoms = read_data_file(path)
    positions = numpy.array([atoms["x"], atoms["y"], atoms["z"]]).T
    radii = 0.5 * numpy.array(atoms["diameter"])
    pairs = contact_pairs(positions, radii)
    if len(pairs) == 0:
        return 0.0
    a, b = pairs[:, 0], pairs[:, 1]
    distance = numpy.linalg.norm(positions[a] - positions[b], axis=1)
    return float(((radii[a] + radii[b] - distance) / (2 * numpy.minimum(radii[a], radii[b]))).max())


def packing_settings(case):
    """The case's packing.yaml, checked, as keyword arguments of pour() (count and the options)."""
    case = case if isinstance(case, Case) else Case(case)
    path = case.file("packing.yaml")
    if not os.path.exists(path):
        raise CaseError(f"{path}: missing; it gives the packing's particle count (see tfdem.packing)")
    source = Source(path, CaseError)
    settings = source.mapping("", load_yaml(path, CaseError), PACKING_KEYS)
    settings["count"] = source.count("count", source.required("", settings, "count", "the number of particles to pour"),
                                     what="the number of particles to pour (a whole number of 1 or more)")
    if "mass_fraction_small" in settings:
        settings["mass_fraction_small"] = source.number(
            "mass_fraction_small", settings["mass_fraction_small"], 0.0, 1.0, low_open=True,
            what="the smaller size's mass fraction in (0, 1]")
    if "mass_fractions" in settings:
        fractions = source.sequence("mass_fractions", settings["mass_fractions"], 1,
                                    what="a list of mass fractions, one per size, smallest first")
        settings["mass_fractions"] = [source.number(f"mass_fractions[{k}]", f, 0.0, 1.0, low_open=True,
                                                    what="a mass fraction in (0, 1]") for k, f in enumerate(fractions)]
    if "floor" in settings:
        settings["floor"] = source.number("floor", settings["floor"], 0.0,
                                          what="the height in m of the plate the bed rests on (0 or more)")
    if "seed" in settings:
        settings["seed"] = source.count("seed", settings["seed"], SMALLEST_SEED + 1,
                                        what=f"a prime above {SMALLEST_SEED} (e.g. 15485863)")
        if not _prime(settings["seed"]):
            source.fail("seed", f"{settings['seed']} is not a prime: give a prime above {SMALLEST_SEED} "
                        "(e.g. 15485863), as LIGGGHTS' random seeds are")
    return settings


def _prime(n):
    return n > 1 and all(n % k for k in range(2, math.isqrt(n) + 1))


def pour_case(case, out="bed.data", ranks=1, runner=None):
    """pour() with the case's packing.yaml."""
    return pour(case, out=out, ranks=ranks, runner=runner, **packing_settings(case))


def pour(case, count, out="bed.data", ranks=1, runner=None, types=None, **options):
    """Pour `count` particles into `case`'s column and write the packed bed to case/out, whole
    or not at all: LIGGGHTS writes out + POURING, which is finished there (atom types, at rest,
    the mid-plane, `types` declared when given) and then renamed to out; a failure leaves the
    previous out. `runner`: tfdem.run.run's stand-in (tfdem.run.run when None). Returns the
    printed summary line ('TFDEM packed bed: N particles, ...')."""
    case = case if isinstance(case, Case) else Case(case)
    runner = runner or tfdem.run.run
    pouring = out + POURING
    args = ["tfdem-liggghts", "-in", POUR_SCRIPT, "-log", "log.pour.liggghts"]
    variables = pour_variables(case, count, **options)
    for name, value in variables.items():
        args += ["-var", name, repr(value) if isinstance(value, float) else str(value)]
    args += ["-var", "out", pouring]
    diameters = case.particle_diameters()
    try:
        if "sizes" in variables:
            sizes_file(case, diameters, mixture(case, diameters, options.get("mass_fraction_small"),
                                                options.get("mass_fractions")))
        try:
            _, output = runner(args, case.path, "log.pour", ranks=ranks)
        finally:
            if os.path.exists(case.file(SIZES_FILE)):
                os.remove(case.file(SIZES_FILE))
        lines = [for_display(line) for line in output.splitlines() if line.startswith("TFDEM packed bed")]
        if not lines or not os.path.isfile(case.file(pouring)):
            raise CaseError(f"{case.file('log.pour')}: the pour printed no 'TFDEM packed bed' line or wrote no "
                            f"{pouring}: see that log")
        with doing("finishing the poured bed", case.file(pouring)):
            summary = _finish(case, pouring, diameters, lines[-1], types)
        with doing("putting the packed bed in place at", case.file(out)):
            replace_atomic(case.file(pouring), case.file(out))
    finally:
        with contextlib.suppress(OSError):
            os.remove(case.file(pouring))
    return summary


LONG_NUMBER = re.compile(r"(?<![\w.])-?\d+\.\d{5,}(?:[eE][-+]?\d+)?(?![\w.])")


def for_display(line, digits=4):
    """A line with its long decimals (LIGGGHTS prints 20 digits) rounded to `digits`
    significant ones: 0.012779559550864403802 -> 0.01278."""
    return LONG_NUMBER.sub(lambda m: f"{float(m.group()):.{digits}g}", line)


def _finish(case, path, diameters, summary, types):
    """The poured data file made the run's: each atom the type of its size, at rest, a
    one-layer column's centres on its mid-plane, `types` atom types declared (when given);
    CaseError when its largest overlap would spring it apart. Returns the summary."""
    retype(case.file(path), diameters)
    at_rest(case.file(path))
    summary += "; written at rest"
    if one_layer(case):
        lo, hi = case.mesh_bounds()
        to_mid_plane(case.file(path), hi[2] - lo[2])
        summary += (" (poured on the mid-plane)" if len(diameters) > 1 else
                    f" (poured {PLANE_SLAB} diameters deep, centres moved onto the mid-plane)")
    if types is not None:
        set_atom_types(case.file(path), types)
    overlap = largest_overlap(case.file(path))
    summary += f"; largest overlap {overlap:.2%} of d"
    if overlap <= MAX_OVERLAP:
        return summary
    pour_kn, run_kn = DemScript(POUR_SCRIPT).value("${kn}"), script_stiffness(case)
    if run_kn is not None and run_kn <= pour_kn:
        # the run's contacts are no stiffer than the pour's: the overlap is the run's own rest
        # state (seed 000's k_n of 800 N/m under 2400 spheres of 4 mm: 6.9 %), nothing springs apart
        return summary + f" (above {MAX_OVERLAP:.0%}, the rest state of the run's own k_n of {run_kn:g} N/m)"
    out = path[:-len(POURING)]
    raise CaseError(f"{case.file(out)}: the packed bed's largest overlap is {overlap:.2%} of a diameter, above "
                    f"{MAX_OVERLAP:.0%}, and the run's contacts are stiffer than the pour's {pour_kn:g} N/m: its "
                    f"spheres would spring apart at the start; pour at the run's stiffness (tfdem-liggghts -in "
                    f"{POUR_SCRIPT} -var kn ...) or pour a shallower bed (nothing was written)")


def script_stiffness(case):
    """The softest k_n (N/m) of the case's DEM script (its fix property/global kn
    peratomtypepair N followed by the N x N values), None for a case without one."""
    if case.hard_sphere():
        return None
    dem = case.dem()
    words = stiffness_command(dem)
    if words is None:
        return None
    types = int(words[6])
    return min(dem.value(w) for w in words[7:7 + types * types])


def stiffness_command(dem):
    """The words of the DEM script's `fix ... property/global kn peratomtypepair N ...`, or None."""
    for words in dem.commands("fix"):
        if len(words) > 6 and words[3] == "property/global" and words[4] == "kn" and words[5] == "peratomtypepair":
            return words
    return None


def script_type_count(case):
    """The atom types the case's DEM script declares (its property/global kn peratomtypepair N)."""
    case = case if isinstance(case, Case) else Case(case)
    words = stiffness_command(case.dem())
    if words is not None and words[6].isdigit() and int(words[6]) >= 1:
        return int(words[6])
    raise CaseError(f"{case.dem_script()}: no 'fix ... property/global kn peratomtypepair N' with N a whole number: "
                    "the number of atom types the packing must declare is not known")


def pack_case(case, ranks=1, runner=None):
    """`tfdem pack`: pour the case's packing.yaml into the data file its particle engine reads,
    with the friction of the particle pairs and the atom types it declares: the DEM script's,
    or for the hard-sphere engine its dem.hard_sphere.friction and a type per size. The data
    file is put in place whole, and its stamp (stamp()) written after it."""
    case = case if isinstance(case, Case) else Case(case)
    out = case.particles_file()
    if not isinstance(out, str) or not out.strip():
        raise CaseError(f"{case.file('coupling.yaml')}: dem.particles: expected the data file's name, got {out!r}")
    if case.hard_sphere():
        friction = case.coupling_value("dem.hard_sphere.friction")
        while isinstance(friction, list) and friction:
            friction = friction[0]
        friction = Source(case.file("coupling.yaml"), CaseError).number(
            "dem.hard_sphere.friction", friction, 0.0, what="the particles' friction coefficient (0 or more)")
        types = len(case.particle_diameters())
    else:
        friction = contact_properties(case.dem())["coefficientFriction"][0][0]
        types = script_type_count(case)
    settings = packing_settings(case)
    summary = pour(case, out=out, ranks=ranks, runner=runner, friction=float(friction), types=types, **settings)
    with doing("writing the packed bed's stamp", case.file(out + STAMP)):
        write_stamp(case, out, settings)
    return summary


# The stamp: what tfdem pack finished --------------------------------------------------------------
def _digest(path):
    sha = hashlib.sha256()
    with open(path, "rb") as f:
        for block in iter(lambda: f.read(1 << 20), b""):
            sha.update(block)
    return sha.hexdigest()


def write_stamp(case, out, settings):
    """<data file>.tfdem-packed: the data file's size and SHA-256 and the packing.yaml settings
    it was poured from, written last (a data file without it, or that differs from it, is not
    a finished tfdem pack)."""
    path = case.file(out)
    stamp = {"data_file": out, "bytes": os.path.getsize(path), "sha256": _digest(path), "packing.yaml": settings,
             "written_by": "tfdem pack"}
    write_text_atomic(path + STAMP, json.dumps(stamp, indent=1) + "\n")


def verify_stamp(case):
    """The case's data file is the one tfdem pack finished for its packing.yaml: returns a line
    saying so, else CaseError naming what differs and the fix."""
    case = case if isinstance(case, Case) else Case(case)
    out = case.particles_file()
    path = case.file(out)
    again = f"run tfdem pack {case.path} again"
    if not os.path.isfile(path):
        raise CaseError(f"{path}: no packed bed: run tfdem pack {case.path}")
    try:
        with open(path + STAMP) as f:
            stamp = json.load(f)
    except FileNotFoundError:
        raise CaseError(f"{path}: no stamp of a finished tfdem pack ({os.path.basename(path + STAMP)}): a pour "
                        f"stopped before its end, or a file from elsewhere; {again}") from None
    except (OSError, ValueError) as e:
        raise CaseError(f"{path + STAMP}: unreadable stamp ({e}); {again}") from None
    if not isinstance(stamp, dict) or stamp.get("data_file") != out:
        raise CaseError(f"{path + STAMP}: not the stamp of {out}; {again}")
    if os.path.getsize(path) != stamp.get("bytes") or _digest(path) != stamp.get("sha256"):
        raise CaseError(f"{path}: changed since tfdem pack wrote it (its size or SHA-256 differs from its stamp "
                        f"{os.path.basename(path + STAMP)}); {again}")
    settings = packing_settings(case)
    if json.loads(json.dumps(settings)) != stamp.get("packing.yaml"):
        raise CaseError(f"{case.file('packing.yaml')}: changed since the bed was poured (now {settings}, poured "
                        f"{stamp.get('packing.yaml')}); {again}")
    return f"{path}: the bed tfdem pack poured for packing.yaml ({stamp['bytes']} bytes, SHA-256 matches)"


def main(argv=None):
    return run_command("tfdem pack", _pack, argv)


def _pack(argv):
    parser = argparse.ArgumentParser(prog="tfdem pack", description="Pour a case's bed (its packing.yaml) into "
                                     "the data file its DEM script reads; --verify checks a packed bed is the one "
                                     "tfdem pack finished (its stamp).")
    parser.add_argument("case", nargs="?", default=".")
    parser.add_argument("--ranks", type=positive_count("the pour's MPI ranks (1 or more)"), default=1,
                        help="MPI ranks of the pour (LIGGGHTS; default 1); the bed poured is the same on any count "
                             "to within the pour's randomness")
    parser.add_argument("--verify", action="store_true",
                        help="check the case's data file against the stamp tfdem pack wrote; pour nothing")
    add_debug_option(parser)
    args = parser.parse_args(argv)
    if not os.path.isdir(args.case):
        raise CaseError(f"{args.case}: no such case folder: give the case's folder (tfdem new CASE --from BED.yaml "
                        "writes one)")
    if args.verify:
        print(verify_stamp(args.case))
    else:
        print(pack_case(args.case, ranks=args.ranks))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
