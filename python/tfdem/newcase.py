"""A complete, runnable case from one short YAML of what a user knows about a bed
(`tfdem new CASE --from bed.yaml`); everything else is derived and printed with the reason.

    box:                       # the column, m: x across, y up (gravity -y), z the depth
      width: 0.04
      height: 0.12
      depth: one_layer         # one particle diameter, seed 000's 2-D rule; or a depth in m
    particles:                 # one density, one to MAX_SIZES sizes
      density: 2500            # kg/m^3
      sizes:                   # each with `number`, or each with `mass_fraction` and `count`
        - {diameter: 0.001, number: 800}
      restitution: 0.9         # e_n of particle pairs
      friction: 0.1            # Coulomb friction of particle pairs
      wall: {restitution: 0.9, friction: 0.1}   # optional: the walls' (default: the pairs')
      stiffness: 80            # optional k_n, N/m (default below)
    gas: {density: 1.2, viscosity: 1.8e-5}
    inflow:                    # superficial velocity through the bottom, m/s ...
      velocity: 0.8
      plate: {pressure_drop_fraction: 0.3}      # optional distributor plate
      # ... or jets through an otherwise closed bottom (velocity: gas through the rest of it):
      # jets: [{centre: 0.075, width: 0.01, velocity: 39}]
    run: {end_time: 1.0, write_interval: 0.1}  # s; write_interval: checkpoints and particle files
    coupling: {transfer: averaged, drag_law: ergun_wen_yu}   # optional, these are the defaults
    dem: {engine: hard_sphere, tangential_restitution: 0.33}  # optional: the default engine is
                               # liggghts (soft spheres); hard_sphere is seed 001's event-driven
                               # engine (section 3.3), with beta_0 (default: the soft contacts')
                               # and, when given, its other keys of coupling.yaml's
                               # dem.hard_sphere: elastic_within, max_collisions_per_particle,
                               # contact_gap, move (HARD_SPHERE_KEYS)
    mesh: {cell_size: 0.004}   # optional: the gas cells' size, m

Derived (each rule stated in `derive`): the gas cells (four of the largest diameter, seed
000's uniform bed; square), the contact stiffness (an impact at U_mf sinks 5 % of d), the
damping of every pair of types from e_n (written into the DEM script as seed 001 eq. 27),
the DEM step (the scene check's rule, `tfdem-scene-check`), the gas step and coupling
interval, the lid, the plate's resistance or the empty windbox row below a bed fed through its
whole bottom, the pressure functions, the packing. The formulas the generated files need are
written into them, so a value edited there stays the only copy. Warnings (a bed under
SHALLOW_BED_CELLS gas cells deep, an inflow that lifts the bed to the lid, a setting outside
TESTED_RANGES) are printed with numbers and a suggestion and kept in derived.txt.
"""
import argparse
import contextlib
import copy
import json
import math
import os
import re
import shutil
import subprocess
import sys
import tempfile

import yaml

import tfdem.run
from tfdem import SOURCE_DIR, TUTORIALS
from tfdem.engines import restitution_of_damping
from tfdem.frontdoor import add_debug_option, default_mode, doing, run_command, write_file_synced
from tfdem.inputs import InputError, Source, load_yaml, shown, suggestion
from tfdem.liggghts import bed_script
from tfdem.physics import wen_yu_minimum_fluidization

ONE_LAYER = "one_layer"
CELL_DIAMETERS = 4.0          # gas cell / largest diameter: seed 000's uniform bed (1 cm, 2.5 mm)
SMALLEST_CELL_DIAMETERS = 3.0  # below it the centroid void fraction is unsafe (scene check)
IMPACT_OVERLAP = 0.05         # default k_n: an impact at U_mf sinks this fraction of d
GAS_STEP = 5e-4               # s: the bubbling bed's measured front (bench/README.md, "Gas step")
INFLOW_COURANT = 1.0          # the gas step keeps the inflow's U dt / dy at or below this
PACKED_SOLID_FRACTION = 0.6   # of a poured bed, for the bed height estimate
LID_OVER_BED = 2.0            # the column should be at least this many packed bed heights tall
LARGEST_COUNT = 2 ** 31 - 1   # OpenFOAM's 32-bit labels: gas cells and time steps
MAX_SIZES = 9                 # particle sizes (the pour's templates; in.bed's per-pair variable names)
FIELDS_TEMPLATE = os.path.join(TUTORIALS, "bubbling_bed", "system")
PLATE_ZONE, WINDBOX_ZONE = "distributor", "windbox"  # the cell zone of the row below the bed


class BedError(InputError):
    """bed.yaml is wrong; the message names the key, the value and the fix."""


REQUIRED = object()  # a key bed.yaml must give
SCHEMA = {
    "box": {"width": REQUIRED, "height": REQUIRED, "depth": REQUIRED},
    "particles": {"density": REQUIRED, "sizes": REQUIRED, "count": 0, "restitution": REQUIRED,
                  "friction": REQUIRED, "wall": {}, "stiffness": 0.0},
    "gas": {"density": 1.2, "viscosity": 1.8e-5},
    "inflow": {"velocity": 0.0, "plate": {}, "jets": []},
    "run": {"end_time": REQUIRED, "write_interval": REQUIRED},
    "coupling": {"transfer": "averaged", "drag_law": "ergun_wen_yu"},
    "mesh": {"cell_size": 0.0},
    "dem": {"engine": "liggghts", "tangential_restitution": "derived", "elastic_within": None,
            "max_collisions_per_particle": None, "contact_gap": None, "move": None},
}
# Every key of bed.yaml: its unit and what it sets (the reference page, docs/reference.py, is
# written from these beside SCHEMA's defaults; a key without a line here fails its test)
BED_KEYS = {
    "box": ("", "the column the bed stands in"),
    "box.width": ("m", "the column's width, x across"),
    "box.height": ("m", "the column's height, y up (gravity along -y); the lid at the top"),
    "box.depth": ("m", "the column's depth, z; one_layer: one particle diameter (seed 000's 2-D rule); a 3-D bed "
                  "several gas cells deep (e.g. 4 cells of 4 d: 16 d)"),
    "particles": ("", "the particles: one density, one to nine sizes, their contacts"),
    "particles.density": ("kg/m^3", "the particles' density, one for every size"),
    "particles.sizes": ("", "one to nine sizes, each with a diameter and a number, or a mass_fraction and the count"),
    "particles.sizes[].diameter": ("m", "the size's diameter"),
    "particles.sizes[].number": ("", "how many particles of this size"),
    "particles.sizes[].mass_fraction": ("", "this size's share of the bed's mass (the fractions sum to 1)"),
    "particles.count": ("", "the particles of all sizes, when the sizes give mass fractions"),
    "particles.restitution": ("", "normal restitution e_n of particle pairs (the damping follows, seed 001 eq. 27)"),
    "particles.friction": ("", "Coulomb friction of particle pairs"),
    "particles.wall": ("", "the walls' own restitution and friction; left out, the pairs'"),
    "particles.wall.restitution": ("", "e_n of a particle against a wall"),
    "particles.wall.friction": ("", "friction of a particle against a wall"),
    "particles.stiffness": ("N/m", "normal stiffness k_n; left out, an impact at U_mf sinks 5 % of d"),
    "gas": ("", "the gas; left out, air"),
    "gas.density": ("kg/m^3", "the gas density"),
    "gas.viscosity": ("Pa s", "the gas dynamic viscosity"),
    "inflow": ("", "the gas into the bed: through the whole bottom, a plate, or jets"),
    "inflow.velocity": ("m/s", "superficial gas velocity through the bottom (with jets: through the rest of it)"),
    "inflow.plate": ("", "a distributor plate below the bed (a porous zone)"),
    "inflow.plate.pressure_drop_fraction": ("", "the plate's pressure drop at U_mf, a fraction of the bed's weight "
                                                "per area"),
    "inflow.jets": ("", "jets through an otherwise closed bottom, each a centre, a width and a velocity; a jet is a "
                    "slot across the whole depth"),
    "inflow.jets[].centre": ("m", "the jet's centre, x"),
    "inflow.jets[].width": ("m", "the jet's width (its edges on the gas cells' faces)"),
    "inflow.jets[].velocity": ("m/s", "the jet's gas velocity"),
    "run": ("", "how long the run goes and how often it writes"),
    "run.end_time": ("s", "simulated time the run ends at"),
    "run.write_interval": ("s", "between checkpoints (gas fields, DEM state) and particle files"),
    "coupling": ("", "coupling.yaml's coupling keys the case takes; left out, the defaults"),
    "coupling.transfer": ("", "coupling.yaml's coupling.transfer (averaged, per_particle, per_particle_conservative)"),
    "coupling.drag_law": ("", "coupling.yaml's coupling.drag_law"),
    "mesh": ("", "the gas cells"),
    "mesh.cell_size": ("m", "the gas cells' size; left out, four of the largest diameter"),
    "dem": ("", "the particle engine and its own keys"),
    "dem.engine": ("", "liggghts (soft spheres) or hard_sphere (seed 001's event-driven engine)"),
    "dem.tangential_restitution": ("", "hard spheres: beta_0; left out, the soft contacts' (seed 001 eq. 30)"),
    "dem.elastic_within": ("s", "hard spheres: the TC model's time (coupling.yaml's dem.hard_sphere key)"),
    "dem.max_collisions_per_particle": ("", "hard spheres: the collisions a flow step may hold per particle"),
    "dem.contact_gap": ("", "hard spheres: the gap within which N_c counts a pair, of the mean diameter"),
    "dem.move": ("", "hard spheres: false for particles that stay where they are (a fixed bed)"),
}

# The hard-sphere engine's own keys of coupling.yaml's dem.hard_sphere (coupling/src/config.cpp
# read_hard_sphere) that bed.yaml's dem passes through when given (None: the solver's default):
# (low, high, what); `move` is true or false
HARD_SPHERE_KEYS = {
    "elastic_within": (0.0, 1.0, "a time in s in [0, 1]: a collision within it of either particle's previous one is "
                       "elastic and smooth (the TC model; 0: off; the solver's default 1e-5)"),
    "max_collisions_per_particle": (1, 100000000, "a whole number of 1 to 1e8: collisions per particle in one flow "
                                    "step above which the run stops (the solver's default 10000)"),
    "contact_gap": (0.0, 1.0, "a fraction in [0, 1] of the pair's mean diameter within which N_c counts a pair "
                    "(the solver's default 0.01)"),
    "move": (None, None, "true, or false for particles that stay where they are (a fixed bed)"),
}
ENGINES = ("liggghts", "hard_sphere")
SIZE_KEYS = ("diameter", "number", "mass_fraction")
WALL_KEYS = ("restitution", "friction")
PLATE_KEYS = ("pressure_drop_fraction",)
JET_KEYS = ("centre", "width", "velocity")
# The solver's own bounds (coupling/src/config.cpp), so that bed.yaml's key is the one named
GAS_DENSITY = (1e-6, 1e4)       # kg/m^3
GAS_VISCOSITY = (1e-9, 1e3)     # Pa s
PARTICLE_DENSITY = (1e-3, 1e5)  # kg/m^3
DIAMETER = (1e-9, 1.0)          # m


def load_bed(path):
    """bed.yaml read and checked, with every default filled in."""
    source = Source(path, BedError)
    given = source.mapping("", load_yaml(path, BedError), SCHEMA)
    bed = {}
    for section, keys in SCHEMA.items():
        values = source.mapping(section, given.get(section, {}), keys)
        bed[section] = {}
        for key, default in keys.items():
            if key not in values and default is REQUIRED:
                source.fail(f"{section}.{key}", "missing: it is required (`tfdem new --help` lists the keys)")
            bed[section][key] = values.get(key, copy.deepcopy(default))
    _check_box(source, bed)
    _check_gas(source, bed)
    _check_particles(source, bed, given["particles"])
    _check_inflow(source, bed, given.get("inflow", {}))
    _check_run(source, bed)
    _check_dem(source, bed)
    _check_optional(source, bed, given)
    return bed


def _check_dem(source, bed):
    dem = bed["dem"]
    source.choice("dem.engine", dem["engine"], ENGINES)
    hard = dem["engine"] == "hard_sphere"
    for key, (low, high, what) in HARD_SPHERE_KEYS.items():
        if dem[key] is None:
            continue
        if not hard:
            source.fail(f"dem.{key}", "only the hard-sphere engine takes it (LIGGGHTS' soft contacts are set by "
                        "e_n, k_n and friction); set dem.engine: hard_sphere, or leave it out")
        if key == "move":
            dem[key] = source.boolean(f"dem.{key}", dem[key], what)
        elif key == "max_collisions_per_particle":
            dem[key] = source.count(f"dem.{key}", dem[key], low, high, what)
        else:
            dem[key] = source.number(f"dem.{key}", dem[key], low, high, what=what)
    if dem["tangential_restitution"] == "derived":
        return
    if not hard:
        source.fail("dem.tangential_restitution", "only the hard-sphere engine takes beta_0 (the soft contacts' "
                    "tangential damping follows from e_n); set dem.engine: hard_sphere, or leave it out")
    dem["tangential_restitution"] = source.number(
        "dem.tangential_restitution", dem["tangential_restitution"], 0.0, 1.0,
        what="the tangential restitution beta_0 in [0, 1] (seed 001 eq. 20)")


def _check_box(source, bed):
    box = bed["box"]
    for key in ("width", "height"):
        box[key] = source.number(f"box.{key}", box[key], 0.0, low_open=True, what="a length in m")
    if isinstance(box["depth"], str) and box["depth"] != ONE_LAYER:
        source.fail("box.depth", f"unknown value {shown(box['depth'])}{suggestion(box['depth'], [ONE_LAYER])}: "
                    f"give a length in m or '{ONE_LAYER}'")
    if box["depth"] != ONE_LAYER:
        box["depth"] = source.number("box.depth", box["depth"], 0.0, low_open=True,
                                     what=f"a length in m or '{ONE_LAYER}'")


def _check_gas(source, bed):
    gas = bed["gas"]
    gas["density"] = source.number("gas.density", gas["density"], *GAS_DENSITY,
                                   what=f"the gas density in kg/m^3 ({GAS_DENSITY[0]:g} to {GAS_DENSITY[1]:g}, "
                                   "the solver's range)")
    gas["viscosity"] = source.number("gas.viscosity", gas["viscosity"], *GAS_VISCOSITY,
                                     what=f"the dynamic viscosity in Pa s ({GAS_VISCOSITY[0]:g} to "
                                     f"{GAS_VISCOSITY[1]:g}, the solver's range; air: 1.8e-5)")


def _check_particles(source, bed, given):
    p = bed["particles"]
    p["density"] = source.number("particles.density", p["density"], *PARTICLE_DENSITY,
                                 what=f"a density in kg/m^3 ({PARTICLE_DENSITY[0]:g} to {PARTICLE_DENSITY[1]:g}, "
                                 "the solver's range)")
    if p["density"] <= bed["gas"]["density"]:
        source.fail("particles.density", f"{shown(p['density'])} kg/m^3 is not above the gas density "
                    f"{bed['gas']['density']:g} kg/m^3: such particles float and make no bed; give the particles' "
                    "density (glass: 2500)")
    _check_sizes(source, p)
    _check_mixture(source, p, given)
    p["restitution"] = source.number("particles.restitution", p["restitution"], 0.0, 1.0, low_open=True,
                                     what="the normal restitution e_n in (0, 1]")
    p["friction"] = source.number("particles.friction", p["friction"], 0.0, what="a friction coefficient >= 0")
    source.mapping("particles.wall", p["wall"], WALL_KEYS)
    wall = {"restitution": p["restitution"], "friction": p["friction"], **p["wall"]}
    wall["restitution"] = source.number("particles.wall.restitution", wall["restitution"], 0.0, 1.0,
                                        low_open=True, what="the normal restitution e_n in (0, 1]")
    wall["friction"] = source.number("particles.wall.friction", wall["friction"], 0.0,
                                     what="a friction coefficient >= 0")
    p["wall"] = wall
    if "stiffness" in given:
        p["stiffness"] = source.number("particles.stiffness", p["stiffness"], 0.0, low_open=True,
                                       what="k_n in N/m (or leave it out: it is derived)")
    if p["restitution"] == 1.0 or wall["restitution"] == 1.0:
        source.fail("particles.restitution", "e_n = 1 (no damping) never lets a bed come to rest in soft-sphere "
                    "DEM; give the material's e_n (glass: ~0.9)")


def _check_sizes(source, p):
    sizes = source.sequence("particles.sizes", p["sizes"], 1, MAX_SIZES, f"a list of 1 to {MAX_SIZES} sizes")
    for i, size in enumerate(sizes):
        key = f"particles.sizes[{i}]"
        source.mapping(key, size, SIZE_KEYS)
        size["diameter"] = source.number(f"{key}.diameter", source.required(key, size, "diameter", "its diameter in m"),
                                         *DIAMETER, what=f"a diameter in m ({DIAMETER[0]:g} to {DIAMETER[1]:g})")
    sizes.sort(key=lambda s: s["diameter"])
    for a, b in zip(sizes, sizes[1:]):
        if a["diameter"] == b["diameter"]:
            source.fail("particles.sizes", f"two sizes have diameter {a['diameter']:g}; give each size once")


def _check_mixture(source, p, given):
    """Each size's `number`, or each size's `mass_fraction` and particles.count."""
    sizes = p["sizes"]
    by_number = [("number" in s) for s in sizes]
    by_fraction = [("mass_fraction" in s) for s in sizes]
    if all(by_number) and not any(by_fraction):
        for i, s in enumerate(sizes):
            s["number"] = source.count(f"particles.sizes[{i}].number", s["number"],
                                       what="a particle count (a whole number of 1 or more)")
        if "count" in given:
            source.fail("particles.count", f"{shown(given['count'])}: the sizes' numbers give the count; leave "
                        "particles.count out (it goes with mass fractions)")
    elif all(by_fraction) and not any(by_number):
        total = 0.0
        for i, s in enumerate(sizes):
            s["mass_fraction"] = source.number(f"particles.sizes[{i}].mass_fraction", s["mass_fraction"], 0.0, 1.0,
                                               low_open=True, what="a mass fraction in (0, 1]")
            total += s["mass_fraction"]
        if abs(total - 1.0) > 1e-9:
            source.fail("particles.sizes", f"the mass fractions sum to {total:g}, not 1: make them sum to 1")
        if "count" not in given:
            source.fail("particles.count", "missing: give the number of particles (with the sizes' mass fractions)")
        p["count"] = source.count("particles.count", p["count"], what="a particle count (a whole number of 1 or more)")
    else:
        source.fail("particles.sizes", "give every size a `number`, or every size a `mass_fraction` and "
                    "particles.count")


def _check_inflow(source, bed, given):
    inflow, box = bed["inflow"], bed["box"]
    inflow["velocity"] = source.number("inflow.velocity", inflow["velocity"], 0.0,
                                       what="a superficial velocity in m/s")
    source.mapping("inflow.plate", inflow["plate"], PLATE_KEYS)
    if "plate" in given:
        fraction = source.required("inflow.plate", inflow["plate"], "pressure_drop_fraction",
                                   "the plate's pressure drop at U_mf over the bed's weight per area (e.g. 0.3)")
        inflow["plate"]["pressure_drop_fraction"] = source.number(
            "inflow.plate.pressure_drop_fraction", fraction, 0.0, 10.0, low_open=True,
            what="the plate's pressure drop at U_mf over the bed's weight per area, in (0, 10]")
    jets = source.sequence("inflow.jets", inflow["jets"], what="a list of jets")
    what = {"centre": f"the jet's centre x in m, in [0, {box['width']:g}] (the box)",
            "width": "the jet's width in m, above 0",
            "velocity": "the jet's superficial velocity in m/s, above 0"}
    for i, jet in enumerate(jets):
        key = f"inflow.jets[{i}]"
        source.mapping(key, jet, JET_KEYS)
        for name in JET_KEYS:
            value = source.required(key, jet, name, what[name])
            high = box["width"] if name == "centre" else math.inf
            jet[name] = source.number(f"{key}.{name}", value, 0.0, high, low_open=name != "centre", what=what[name])
        if jet["centre"] - jet["width"] / 2 < -1e-12 or jet["centre"] + jet["width"] / 2 > box["width"] + 1e-12:
            source.fail(key, f"x = {jet['centre'] - jet['width'] / 2:g} to {jet['centre'] + jet['width'] / 2:g} m "
                        f"reaches past the box (0 to {box['width']:g} m); move its centre or narrow it")
    if jets and inflow["plate"]:
        source.fail("inflow.plate", "a distributor plate with jets is not made; give one of them")
    if not jets and inflow["velocity"] == 0.0:
        source.fail("inflow.velocity", "missing or 0 with no jets: a bed needs gas through its bottom")


def _check_run(source, bed):
    r = bed["run"]
    r["end_time"] = source.number("run.end_time", r["end_time"], 0.0, low_open=True, what="a time in s above 0")
    r["write_interval"] = source.number("run.write_interval", r["write_interval"], 0.0, r["end_time"],
                                        low_open=True, what="a time in s, at most run.end_time")


def _check_optional(source, bed, given):
    """mesh.cell_size (derived when left out; given, a length) and the coupling's names (the
    scene check checks them against the core's lists)."""
    if "cell_size" in given.get("mesh", {}):
        bed["mesh"]["cell_size"] = source.number("mesh.cell_size", bed["mesh"]["cell_size"], 0.0, low_open=True,
                                                 what="the gas cells' size in m (or leave it out: it is derived)")
    names = {"transfer": "a transfer's name (e.g. averaged)", "drag_law": "a drag law's name (e.g. ergun_wen_yu)"}
    for key, what in names.items():
        bed["coupling"][key] = source.text(f"coupling.{key}", bed["coupling"][key], what)


def _cell_shape(box, dx, dy, depth, nz):
    """'one cell deep', 'cubic', or what keeps the cells from being cubes (the box's height or
    depth not a whole number of cells as wide as the width's)."""
    if nz == 1:
        return "one cell deep"
    sides = [dx, dy, depth / nz]
    if max(sides) - min(sides) <= 1e-6 * dx:
        return "cubic"
    off = [(name, length, round(length / dx) * dx) for name, length in (("height", box["height"]), ("depth", depth))
           if abs(length / dx - round(length / dx)) > 1e-6]
    return (f"not cubic: the box's {' and '.join(f'{name} {length:g} m' for name, length, _ in off)} "
            f"{'is not a whole number' if len(off) == 1 else 'are not whole numbers'} of the width's {dx:.4g} m "
            f"cells ({', '.join(f'{name} {whole:.4g} m' for name, _, whole in off)} would make them cubes)")


def _round_down(value):
    """The largest of 1, 2, 2.5, 5 x 10^k not above value (a gas step that sampling intervals
    such as 0.01 s hold a whole number of times)."""
    power = 10.0 ** math.floor(math.log10(value))
    return max(m * power for m in (1, 2, 2.5, 5) if m * power <= value * (1 + 1e-12))


def _mass(d, rho):
    return rho * math.pi * d ** 3 / 6


def _reduced(a, b):
    """(1/a + 1/b)^-1 (seed 001 eq. 16); b = inf for a wall."""
    return a if math.isinf(b) else a * b / (a + b)


def scene_numbers(bed, stiffness, wall_stiffness, cell, path="bed.yaml"):
    """The scene check (tfdem-scene-check --json) of the smallest spheres' contacts: t_c,
    damping and the DEM step rule for the pair and the wall contact, the drag response time. The coupling section's
    names (transfer, drag_law) are checked there, against the core's own lists."""
    p = bed["particles"]
    with tempfile.TemporaryDirectory() as scratch:
        config = os.path.join(scratch, "coupling.yaml")
        with open(config, "w") as f:
            yaml.safe_dump({"gas": bed["gas"],
                            "particles": {"diameter": [s["diameter"] for s in p["sizes"]] if len(p["sizes"]) > 1
                                          else p["sizes"][0]["diameter"], "density": p["density"]},
                            "dem": {"script": "in.bed", "coupling_interval": 1},
                            "coupling": {"transfer": bed["coupling"]["transfer"],
                                         "drag_law": bed["coupling"]["drag_law"]}}, f)
        args = ["tfdem-scene-check", config, "--gas-velocity", repr(_fastest_inflow(bed)), "--cell-size", repr(cell),
                "--kn", repr(stiffness), "--en", repr(p["restitution"]), "--wall-kn", repr(wall_stiffness),
                "--wall-en", repr(p["wall"]["restitution"]), "--json"]
        done = subprocess.run(args, capture_output=True, text=True, env=tfdem.run.environment())
    if done.returncode == 2 or not done.stdout.strip():
        raise BedError(_scene_refusal(done.stderr, config, path, stiffness, cell, _fastest_inflow(bed)))
    numbers = json.loads(done.stdout)
    errors = [f"{f['topic']}: {f['text']}" for f in numbers["findings"] if f["level"] == "error"]
    if errors:
        raise BedError(f"{path}: the scene check finds the bed unsound: {'; '.join(errors)}")
    return numbers


def _scene_refusal(stderr, config, path, stiffness, cell, velocity):
    """The scene check's refusal as one line naming bed.yaml: the core names a key of the
    scratch coupling.yaml (bed.yaml's key of the same name), or an option of the values
    derived here (then they are listed)."""
    text = stderr.split("\nusage:", 1)[0].strip().replace("tfdem-scene-check: ", "")
    if config in text:
        return re.sub(re.escape(config) + r"(:\d+:\d+)?", path, " ".join(text.split()))
    return (f"{path}: tfdem-scene-check refuses the values derived from it ({' '.join(text.split()) or 'no output'}): "
            f"k_n {stiffness:.3g} N/m, gas cells {cell:.3g} m, inflow {velocity:.3g} m/s; check particles.sizes, "
            "particles.density and the inflow against the solver's ranges")


def _hard_sphere_tangential(bed, stiffness, mass):
    """beta_0 of bed.yaml, or the soft contacts' (k_t = 2/7 k_n, eta_t = eta_n of the pair,
    the tangential mass 2/7 m_ab: seed 001 eq. 30; the same for every pair and the walls, as
    both scale with m_ab and k_n)."""
    given = bed["dem"]["tangential_restitution"]
    if given != "derived":
        return given
    e = bed["particles"]["restitution"]
    m_ab = _reduced(mass, mass)
    eta = -2 * math.log(e) * math.sqrt(m_ab * stiffness) / math.sqrt(math.pi ** 2 + math.log(e) ** 2)
    return restitution_of_damping(2 / 7 * stiffness, eta, 2 / 7 * m_ab)


def _fastest_inflow(bed):
    """The largest superficial inflow speed: the uniform inflow's or a jet's (m/s)."""
    return max([bed["inflow"]["velocity"]] + [j["velocity"] for j in bed["inflow"]["jets"]])


def windbox(bed):
    """Whether the case has an empty cell row below the bed (the floor one cell up): every bed
    fed through its whole bottom (uniform inflow, with or without a plate). Not under jets: an
    empty row would spread a jet under the bed."""
    return not bed["inflow"]["jets"]


def _closed_bottom(bed):
    """Whether the bottom outside the jets is a wall (jets and no background inflow)."""
    return bool(bed["inflow"]["jets"]) and bed["inflow"]["velocity"] == 0.0


def derive(bed, path="bed.yaml"):
    """Every value of the case, and a line per value saying what it is and why."""
    out = {"notes": []}
    for part in (_derive_depth, _derive_cells, _derive_jets, _derive_contacts, _derive_steps, _derive_bed,
                 _derive_inflow):
        part(bed, out, out["notes"].append, path)
    out["warnings"] = (_shallow_bed_warnings(bed, out) + _lifted_bed_warnings(bed, out)
                       + _untested_warnings(bed, out))
    return out


def _largest_diameter(bed):
    return bed["particles"]["sizes"][-1]["diameter"]


def _derive_depth(bed, out, note, path):
    """The bed's depth: one layer (seed 000's 2-D rule) or the box's."""
    box, d_large = bed["box"], _largest_diameter(bed)
    if box["width"] < d_large:
        raise BedError(f"{path}: box.width: {box['width']:g} m is narrower than a particle ({d_large:g} m)")
    one_layer = box["depth"] == ONE_LAYER
    depth = d_large if one_layer else box["depth"]
    if not one_layer and depth < d_large:
        raise BedError(f"{path}: box.depth: {depth:g} m is shallower than a particle ({d_large:g} m); "
                       f"use '{ONE_LAYER}' for a bed one particle deep")
    out["depth"], out["one_layer"] = depth, one_layer
    if one_layer:
        note(f"depth {depth:g} m: one diameter of the largest spheres (seed 000's 2-D rule), gas one cell deep")


def _derive_cells(bed, out, note, path):
    """The gas cells: square, a few diameters wide; one deep for one layer or a thin bed."""
    box, d_large = bed["box"], _largest_diameter(bed)
    one_layer, depth = out["one_layer"], out["depth"]
    cell = bed["mesh"]["cell_size"] or CELL_DIAMETERS * d_large
    nx = max(1, int(math.floor(box["width"] / cell + 1e-9)))
    dx = box["width"] / nx
    if dx < SMALLEST_CELL_DIAMETERS * d_large:
        raise BedError(f"{path}: box.width: {box['width']:g} m holds no gas cell of {SMALLEST_CELL_DIAMETERS:g} "
                       f"diameters ({SMALLEST_CELL_DIAMETERS * d_large:g} m), the smallest the centroid void fraction "
                       f"takes; widen the box (or mesh.cell_size below that needs another mapping)")
    ny = max(1, int(round(box["height"] / dx)))
    dy = box["height"] / ny
    nz = 1 if one_layer or depth < 2 * dx else int(round(depth / dx))
    if nx * ny * nz > LARGEST_COUNT:
        raise BedError(f"{path}: box: {box['width']:g} x {box['height']:g} x {depth:g} m makes {nx * ny * nz:.3g} gas "
                       f"cells ({nx:.3g} x {ny:.3g} x {nz:.3g}), more than OpenFOAM's 32-bit count holds "
                       f"({LARGEST_COUNT}): give a smaller box or a larger mesh.cell_size")
    out.update(nx=nx, ny=ny, nz=nz, dx=dx, dy=dy, dz=depth / nz)
    why = "mesh.cell_size" if bed["mesh"]["cell_size"] else f"{CELL_DIAMETERS:g} of the largest diameter, seed 000's uniform bed"
    note(f"gas cells {dx:.4g} x {dy:.4g} x {depth / nz:.4g} m ({nx} x {ny} x {nz}): {dx / d_large:.3g} d wide ({why}); "
         f"{_cell_shape(box, dx, dy, depth, nz)}")


def _derive_jets(bed, out, note, path):
    """Each jet as a patch of whole cell faces of the bottom."""
    dx = out["dx"]
    jets = []
    for i, jet in enumerate(bed["inflow"]["jets"]):
        lo, hi = jet["centre"] - jet["width"] / 2, jet["centre"] + jet["width"] / 2
        i0, i1 = lo / dx, hi / dx
        if abs(i0 - round(i0)) > 1e-6 or abs(i1 - round(i1)) > 1e-6 or round(i1) <= round(i0):
            suggestion = max(1, round(jet["width"] / dx)) * dx
            raise BedError(f"{path}: inflow.jets[{i}]: its edges x = {lo:g} and {hi:g} m are not on the gas cells' "
                           f"faces (cells {dx:g} m wide from x = 0): give a width of whole cells (e.g. {suggestion:g}) "
                           f"and a centre half a width from a face, or set mesh.cell_size")
        jets.append({"name": "jet" if i == 0 else f"jet_{i + 1}", "from": int(round(i0)), "to": int(round(i1)),
                     "velocity": jet["velocity"]})
    out["jets"] = jets


def _derive_contacts(bed, out, note, path):
    """U_mf and the contact stiffness of pairs and walls."""
    p = bed["particles"]
    d_small = p["sizes"][0]["diameter"]
    rho = p["density"]
    u_mf = wen_yu_minimum_fluidization(d_small, p["density"], bed["gas"]["density"], bed["gas"]["viscosity"], 9.81)
    out["u_mf"] = u_mf
    m_small = _mass(d_small, rho)
    stiffness = p["stiffness"] or _reduced(m_small, m_small) * (u_mf / (IMPACT_OVERLAP * d_small)) ** 2
    hard = bed["dem"]["engine"] == "hard_sphere"
    if not p["stiffness"] and not hard:
        note(f"k_n {stiffness:.4g} N/m: an impact at U_mf ({u_mf:.4g} m/s, Wen-Yu, smallest spheres) sinks "
             f"{IMPACT_OVERLAP:.0%} of d (seed 000's uniform bed: 5.7 %)")
    wall_stiffness = 2 * stiffness
    if not hard:
        note(f"wall k_n {wall_stiffness:.4g} N/m: twice the pairs', the same overlap and t_c for a wall's m_ab = m")
    out["stiffness"], out["wall_stiffness"] = stiffness, wall_stiffness


def _derive_steps(bed, out, note, path):
    """The scene check's numbers, the gas step, the DEM step and the coupling interval."""
    p, dy = bed["particles"], out["dy"]
    stiffness, wall_stiffness = out["stiffness"], out["wall_stiffness"]
    m_small = _mass(p["sizes"][0]["diameter"], p["density"])
    hard = bed["dem"]["engine"] == "hard_sphere"
    scene = scene_numbers(bed, stiffness, wall_stiffness, out["dx"], path)
    pair, wall = scene["pair"], scene["wall"]
    longest_dem_step = min(pair["recommended_time_step"], wall["recommended_time_step"])
    bound = min(GAS_STEP, INFLOW_COURANT * dy / _fastest_inflow(bed), 0.5 * scene["dense_drag_time"])
    gas_step = _round_down(bound)
    interval = max(1, int(math.ceil(gas_step / longest_dem_step - 1e-9)))
    dt = gas_step / interval
    out.update(dem_step=dt, coupling_interval=interval, gas_step=gas_step)
    if bed["run"]["end_time"] / gas_step > LARGEST_COUNT:
        raise BedError(f"{path}: run.end_time: {bed['run']['end_time']:g} s is {bed['run']['end_time'] / gas_step:.3g} "
                       f"gas steps of {gas_step:.3g} s, more than OpenFOAM's 32-bit time index holds "
                       f"({LARGEST_COUNT}): give a shorter end time (the gas step is at most {GAS_STEP:g} s, less for "
                       "a fast inflow: its Courant number)")
    for key in ("end_time", "write_interval"):
        steps = bed["run"][key] / gas_step
        if abs(steps - round(steps)) > 1e-6 * steps:
            raise BedError(f"{path}: run.{key}: {bed['run'][key]:g} s is not a whole number of gas steps of "
                           f"{gas_step:g} s (derived, below); use {max(1, round(steps)) * gas_step:g}")
    out["statistics_interval"] = max(1, round(min(0.01, bed["run"]["write_interval"]) / gas_step)) * gas_step
    note(f"gas step {gas_step:g} s: a round value below {bound:.4g} s, the least of {GAS_STEP:g} s (the bubbling "
         f"bed's measured front), the inflow's Courant number U dt/dy <= {INFLOW_COURANT:g} and half the packed "
         f"bed's drag response time {scene['dense_drag_time']:.3g} s")
    if hard:
        out["tangential_restitution"] = _hard_sphere_tangential(bed, stiffness, m_small)
        given = bed["dem"]["tangential_restitution"] != "derived"
        note(f"hard-sphere engine (seed 001 section 3.3, eqs. 11-21): binary collisions with e_n "
             f"{p['restitution']:g}, beta_0 {out['tangential_restitution']:.4g}"
             + (" (bed.yaml)" if given else " (the soft contacts' that tfdem new writes for LIGGGHTS: k_t = 2/7 k_n, "
                "eta_t = eta_n, seed 001 eq. 30)")
             + f" and mu {p['friction']:g}, the walls' e_n {p['wall']['restitution']:g} and mu "
             f"{p['wall']['friction']:g}; no stiffness and no DEM step: the flight between flow steps is event "
             "driven; one rank")
    else:
        note(f"DEM step {dt:.4g} s = gas step / {interval}: at most t_c/{pair['steps_per_contact']:.3g} = "
             f"{pair['recommended_time_step']:.4g} s with t_c = {pair['contact_time']:.4g} s (smallest pair, seed 000 "
             f"eq. 26), the scene check's rule for e_n = {p['restitution']:g}; walls t_c/{wall['contact_time'] / dt:.3g}")

    out["scene"] = scene


def _derive_bed(bed, out, note, path):
    """The bed's count, mass, packed height and weight per area; its floor and plate."""
    box, p, inflow = bed["box"], bed["particles"], bed["inflow"]
    rho, depth, dy, u_mf = p["density"], out["depth"], out["dy"], out["u_mf"]
    if "number" in p["sizes"][0]:
        numbers = [s["number"] for s in p["sizes"]]
        volumes = [n * math.pi * s["diameter"] ** 3 / 6 for n, s in zip(numbers, p["sizes"])]
        out["count"] = sum(numbers)
        fractions = [v / sum(volumes) for v in volumes]
    else:
        out["count"] = p["count"]
        fractions = [s["mass_fraction"] for s in p["sizes"]]
    out["mass_fractions"] = fractions
    mean_volume = 1 / sum(f / (math.pi * s["diameter"] ** 3 / 6) for f, s in zip(fractions, p["sizes"]))
    solid_volume = out["count"] * mean_volume
    out["bed_mass"] = rho * solid_volume
    plate = bool(inflow["plate"])
    floor = dy if windbox(bed) else 0.0
    out["floor"] = floor
    bed_height = solid_volume / (PACKED_SOLID_FRACTION * box["width"] * depth)
    out["bed_height"] = bed_height
    rests_on = (f", on a plate at y = {floor:g} m (one cell row of windbox)" if plate else
                f", on a floor at y = {floor:g} m above one empty cell row (a windbox: the gas enters below the "
                "bed, so the inlet's area-averaged p is the bed's bottom's; with the bed in the inlet's cells it "
                "leaves out the drop across their lower half: 17 % short on a 2.4 cm 3-D fixed bed of 8 mm cells, "
                "measured)" if floor else "")
    note(f"bed {out['count']} spheres, {out['bed_mass'] * 1000:.4g} g, about {bed_height * 100:.3g} cm deep packed "
         f"(solid fraction {PACKED_SOLID_FRACTION:g}){rests_on}")
    if box["height"] - floor < LID_OVER_BED * bed_height:
        raise BedError(f"{path}: box.height: {box['height']:g} m leaves the bed (about {bed_height:.3g} m packed) no "
                       f"room to expand or be poured; give at least {floor + LID_OVER_BED * bed_height:.3g} m")
    weight_per_area = (rho - bed["gas"]["density"]) * 9.81 * solid_volume / (box["width"] * depth)
    out["weight_per_area"] = weight_per_area
    if plate:
        fraction = inflow["plate"]["pressure_drop_fraction"]
        # Darcy: dp = mu d L U over the plate's cell row, fraction x weight/area at U_mf
        out["plate_darcy"] = fraction * weight_per_area / (bed["gas"]["viscosity"] * dy * u_mf)
        note(f"plate: Darcy d = {out['plate_darcy']:.4g} 1/m^2 over the cell row below it: {fraction:g} of the bed's "
             f"weight per area ({weight_per_area:.4g} Pa) at U_mf")


def _derive_inflow(bed, out, note, path):
    """The inflow against U_mf and the terminal velocity."""
    inflow, u_mf, scene = bed["inflow"], out["u_mf"], out["scene"]
    u_ratio = _fastest_inflow(bed) / u_mf
    note(f"inflow {_fastest_inflow(bed):g} m/s = {u_ratio:.3g} U_mf (Wen-Yu, smallest spheres); terminal velocity "
         f"{scene['terminal_velocity']:.3g} m/s")
    out["mean_inflow"] = mean_inflow(bed)
    if inflow["jets"]:
        across = " (each a slot over the whole depth)" if out["nz"] > 1 else ""
        note(f"jets{across} " + ", ".join(f"{j['velocity']:g} m/s = {j['velocity'] / u_mf:.3g} U_mf" for j in inflow["jets"])
             + "; the rest of the bottom " + (f"{inflow['velocity']:g} m/s = {inflow['velocity'] / u_mf:.3g} U_mf"
                                              if inflow["velocity"] > 0 else "closed"))
        note(f"mean superficial velocity over the whole bottom {out['mean_inflow']:.3g} m/s (the jets' flow and the "
             f"rest's over the width): {out['mean_inflow'] / u_mf:.3g} U_mf, "
             f"{out['mean_inflow'] / scene['terminal_velocity']:.2g} of the terminal velocity")


SHALLOW_BED_CELLS = 3.0  # a packed bed fewer gas cells deep than this is one or two cells to the gas


def _shallow_bed_warnings(bed, dv):
    """A bed one or a few gas cells deep: the gas resolves neither its bubbles nor its pressure
    profile. The suggestion: the count, the box or the cells that make it SHALLOW_BED_CELLS deep."""
    rows = dv["bed_height"] / dv["dy"]
    if rows >= SHALLOW_BED_CELLS:
        return []
    box, d = bed["box"], bed["particles"]["sizes"][-1]["diameter"]
    factor = SHALLOW_BED_CELLS / rows  # the cross-section shrinks, or the count grows, by this much
    if dv["nz"] > 1:
        narrower = (f"a box {box['width'] / math.sqrt(factor):.3g} x {dv['depth'] / math.sqrt(factor):.3g} m in "
                    "cross-section")
    else:
        narrower = f"a box {box['width'] / factor:.3g} m wide"
    finest = SMALLEST_CELL_DIAMETERS * d
    finer = (f"; cells of {finest:.3g} m (mesh.cell_size, {SMALLEST_CELL_DIAMETERS:g} d, the smallest the centroid "
             f"void fraction takes) make it {dv['bed_height'] / finest:.2g} cells deep" if finest < dv["dy"] else "")
    return [f"the bed is about {dv['bed_height'] * 100:.3g} cm deep packed: {rows:.2g} gas cells of "
            f"{dv['dy'] * 1000:.3g} mm, too few for the gas to resolve its bubbles or its pressure profile "
            f"(fewer than {SHALLOW_BED_CELLS:g}). For {SHALLOW_BED_CELLS:g} cells: {math.ceil(dv['count'] * factor)} "
            f"particles, or {narrower}{finer}"]


def mean_inflow(bed):
    """The mean superficial velocity over the whole bottom (m/s): the jets' flow and the rest of
    the bottom's (at inflow.velocity, or closed) over the width (every jet spans the depth)."""
    inflow, width = bed["inflow"], bed["box"]["width"]
    jets = inflow["jets"]
    jet_width = sum(j["width"] for j in jets)
    return (sum(j["velocity"] * j["width"] for j in jets) + inflow["velocity"] * (width - jet_width)) / width


def _lifted_bed_warnings(bed, dv):
    """A mean superficial velocity at or above the terminal velocity carries the whole bed up:
    it ends pinned under the lid (a DEM wall), not fluidized."""
    terminal, mean = dv["scene"]["terminal_velocity"], dv["mean_inflow"]
    if mean < terminal:
        return []
    source = "the jets' and the rest's flow" if bed["inflow"]["jets"] else "the inflow"
    return [f"{source} over the whole bottom is a mean superficial velocity of {mean:.3g} m/s = "
            f"{mean / dv['u_mf']:.3g} U_mf, at or above the terminal velocity {terminal:.3g} m/s of the smallest "
            "spheres: the gas carries the bed up as a whole and it ends pinned under the lid, not fluidized. Give "
            f"a mean below {terminal:.3g} m/s (slower or narrower jets, less background inflow, or a wider box)"]


# The ranges the project's coupled tests and measured tutorials cover (tests/integration/
# test_new_case.py, test_drivers_on_new_case.py, test_pressure_balance_3d.py, test_hard_sphere.py;
# tutorials/your_own_bed, studies/seed000, studies/bidisperse_segregation): (low, high, unit, where)
TESTED_RANGES = {
    "particle diameter": (0.001, 0.0025, "m", "1 mm (your_own_bed) to 2.5 mm (seed 000's beds)"),
    "particles.density": (2500.0, 2700.0, "kg/m^3", "glass 2500 to 2700"),
    "gas.density": (1.2, 1.2, "kg/m^3", "air only"),
    "gas.viscosity": (1.8e-5, 1.8e-5, "Pa s", "air only"),
    "particles.restitution": (0.8, 0.97, "", "e_n 0.8 (walls) to 0.97 (seed 000)"),
    "particles.friction": (0.1, 0.3, "", "your_own_bed's 0.1 to the jet and 3-D beds' 0.3"),
    "uniform inflow / U_mf": (0.37, 2.4, "", "fixed beds at 0.37-0.65 U_mf to bubbling at 2.4 U_mf"),
    "jet velocity / U_mf": (0.0, 18.1, "", "the jet bed of test_new_case.py, 18.1 U_mf"),
}


def _untested_warnings(bed, dv):
    """Each setting outside TESTED_RANGES: named, with the range the tests cover."""
    p, u_mf = bed["particles"], dv["u_mf"]
    values = {"particle diameter": [s["diameter"] for s in p["sizes"]],
              "particles.density": [p["density"]],
              "gas.density": [bed["gas"]["density"]],
              "gas.viscosity": [bed["gas"]["viscosity"]],
              "particles.restitution": [p["restitution"], p["wall"]["restitution"]],
              "particles.friction": [p["friction"], p["wall"]["friction"]],
              "uniform inflow / U_mf": [bed["inflow"]["velocity"] / u_mf] if not bed["inflow"]["jets"] else [],
              "jet velocity / U_mf": [j["velocity"] / u_mf for j in bed["inflow"]["jets"]]}
    out = []
    for name, given in values.items():
        low, high, unit, where = TESTED_RANGES[name]
        outside = sorted({v for v in given if not low * (1 - 1e-9) <= v <= high * (1 + 1e-9)})
        if outside:
            span = f"{low:g}" if low == high else f"{low:g} to {high:g}"
            out.append(f"{name} {', '.join(f'{v:.4g}' for v in outside)}{' ' + unit if unit else ''} is outside what "
                       f"the project's tests cover ({span}{' ' + unit if unit else ''}: {where}): the case runs, but "
                       "no test has checked results there; check a fixed bed against Ergun or a fluidization curve "
                       "(tutorials/your_own_bed) before trusting it")
    return out


def _foam_header(cls, obj):
    return ("FoamFile\n{\n    version     2.0;\n    format      ascii;\n"
            f"    class       {cls};\n    object      {obj};\n}}\n")


def _g(v):
    return f"{v:.10g}"


def block_mesh(bed, dv):
    """blockMeshDict: one block per span of x between jet edges and per row band (windbox)."""
    width, height, depth = bed["box"]["width"], bed["box"]["height"], dv["depth"]
    x_faces = sorted({0, dv["nx"]} | {j["from"] for j in dv["jets"]} | {j["to"] for j in dv["jets"]})
    y_faces = [0, 1, dv["ny"]] if windbox(bed) else [0, dv["ny"]]
    xs = [i * dv["dx"] for i in x_faces]
    xs[-1] = width
    ys = [j * dv["dy"] for j in y_faces]
    ys[-1] = height
    index = {}
    vertices = []
    for k, z in enumerate((0.0, depth)):
        for j, y in enumerate(ys):
            for i, x in enumerate(xs):
                index[i, j, k] = len(vertices)
                vertices.append(f"({_g(x)} {_g(y)} {_g(z)})")
    blocks, faces = [], {"inlet": [], "outlet": [], "walls": [], "frontAndBack": []}
    for jet in dv["jets"]:
        faces[jet["name"]] = []
    closed_bottom = _closed_bottom(bed)
    if closed_bottom:
        faces["bottom"] = faces.pop("inlet")
    for j in range(len(ys) - 1):
        for i in range(len(xs) - 1):
            v = lambda a, b, c: index[i + a, j + b, c]
            hexa = (v(0, 0, 0), v(1, 0, 0), v(1, 1, 0), v(0, 1, 0), v(0, 0, 1), v(1, 0, 1), v(1, 1, 1), v(0, 1, 1))
            zone = f" {PLATE_ZONE if bed['inflow']['plate'] else WINDBOX_ZONE}" if windbox(bed) and j == 0 else ""
            cells = (x_faces[i + 1] - x_faces[i], y_faces[j + 1] - y_faces[j], dv["nz"])
            blocks.append(f"    hex ({' '.join(map(str, hexa))}){zone} ({cells[0]} {cells[1]} {cells[2]}) "
                          "simpleGrading (1 1 1)")
            if j == 0:
                jet = next((t["name"] for t in dv["jets"] if t["from"] == x_faces[i]), None)
                faces[jet or ("bottom" if closed_bottom else "inlet")].append(
                    (v(0, 0, 0), v(1, 0, 0), v(1, 0, 1), v(0, 0, 1)))
            if j == len(ys) - 2:
                faces["outlet"].append((v(0, 1, 0), v(0, 1, 1), v(1, 1, 1), v(1, 1, 0)))
            if i == 0:
                faces["walls"].append((v(0, 0, 0), v(0, 0, 1), v(0, 1, 1), v(0, 1, 0)))
            if i == len(xs) - 2:
                faces["walls"].append((v(1, 0, 0), v(1, 1, 0), v(1, 1, 1), v(1, 0, 1)))
            side = "frontAndBack" if dv["nz"] == 1 else "walls"
            faces[side].append((v(0, 0, 0), v(0, 1, 0), v(1, 1, 0), v(1, 0, 0)))
            faces[side].append((v(0, 0, 1), v(1, 0, 1), v(1, 1, 1), v(0, 1, 1)))
    kinds = {"inlet": "patch", "outlet": "patch", "walls": "wall", "bottom": "wall", "frontAndBack": "empty"}
    patches = []
    for name, quads in faces.items():
        if not quads:
            continue
        listed = " ".join("(" + " ".join(map(str, q)) + ")" for q in quads)
        patches.append(f"    {name} {{ type {kinds.get(name, 'patch')}; faces ({listed}); }}")
    return (_foam_header("dictionary", "blockMeshDict") +
            f"\n// Generated by tfdem new: {width:g} x {height:g} x {depth:g} m, cells {dv['dx']:.4g} m "
            f"({dv['nx']} x {dv['ny']} x {dv['nz']}); a uniform grid (the coupler needs one).\n"
            "vertices\n(\n    " + "\n    ".join(vertices) + "\n);\nblocks\n(\n" + "\n".join(blocks) +
            "\n);\nboundary\n(\n" + "\n".join(patches) + "\n);\n")


def _patches(bed, dv):
    names = ["bottom" if _closed_bottom(bed) else "inlet"] + [j["name"] for j in dv["jets"]] + ["outlet", "walls"]
    return names + (["frontAndBack"] if dv["nz"] == 1 else [])


def initial_fields(bed, dv):
    """0/U, 0/p, 0/voidFraction: superficial inflow (eps = 1 on the inflow faces)."""
    u, p, eps = [], [], []
    jets = {j["name"]: j["velocity"] for j in dv["jets"]}
    for name in _patches(bed, dv):
        if name == "frontAndBack":
            u.append((name, "type empty;")); p.append((name, "type empty;")); eps.append((name, "type empty;"))
        elif name in jets or name == "inlet":
            speed = jets.get(name, bed["inflow"]["velocity"])
            u.append((name, f"type fixedValue; value uniform (0 {_g(speed)} 0);"))
            p.append((name, "type fixedFluxPressure; value uniform 101325;"))
            eps.append((name, "type fixedValue; value uniform 1;"))
        elif name == "outlet":
            u.append((name, "type pressureInletOutletVelocity; value uniform (0 0 0);"))
            p.append((name, "type fixedValue; value uniform 101325;"))
            eps.append((name, "type zeroGradient;"))
        else:
            u.append((name, "type noSlip;"))
            p.append((name, "type fixedFluxPressure; value uniform 101325;"))
            eps.append((name, "type zeroGradient;"))

    def field(cls, obj, dims, internal, entries, comment):
        body = "\n".join(f"    {n:<12} {{ {e} }}" for n, e in entries)
        return (_foam_header(cls, obj) + f"dimensions      {dims};\ninternalField   {internal};\n"
                f"boundaryField\n{{\n    // {comment}\n{body}\n}}\n")
    return {
        "U": field("volVectorField", "U", "[0 1 -1 0 0 0 0]", "uniform (0 0 0)", u,
                   "superficial inflow velocities of bed.yaml (eps = 1 on the inflow faces); gas at rest at t = 0"),
        "p": field("volScalarField", "p", "[1 -1 -2 0 0 0 0]", "uniform 101325", p,
                   "pressure in Pa; fixed at the outlet"),
        "voidFraction": field("volScalarField", "voidFraction", "[0 0 0 0 0 0 0]", "uniform 1", eps,
                              "gas enters with no particles in the way"),
    }


def _middle_centre(count, spacing):
    """The centre of the middle cell of `count` cells (of the one just past the middle when
    the count is even): a probe there samples one cell, never a face between two."""
    return (count // 2 + 0.5) * spacing


def _section_average(name, height, every, comment):
    """A function object writing the area average of p over the column's cross-section at
    `height` (a plane through a row of cell centres: each cell's own value, equal areas)."""
    return f"""
    // {comment}
    {name}
    {{
        type            surfaceFieldValue;
        libs            ("libfieldFunctionObjects.so");
        writeControl    timeStep;
        writeInterval   {every};
        log             false;
        writeFields     false;
        regionType      sampledSurface;
        name            {name}Plane;
        sampledSurfaceDict
        {{
            type            plane;
            planeType       pointAndNormal;
            pointAndNormalDict {{ point (0 {_g(height)} 0); normal (0 1 0); }}
            interpolate     false;
        }}
        operation       areaAverage;
        fields          (p);
    }}"""


def control_dict(bed, dv):
    height = bed["box"]["height"]
    x, z = _middle_centre(dv["nx"], dv["dx"]), _middle_centre(dv["nz"], dv["dz"])
    bottom_row = dv["floor"] + dv["dy"] / 2
    top = height - dv["dy"] / 2
    pressure_every = max(1, int(round(1e-3 / dv["gas_step"])))
    below = "below the plate: the windbox" if bed["inflow"]["plate"] else "below the windbox row" if dv["floor"] else ""
    inlet = "" if "inlet" not in _patches(bed, dv) else f"""
    // Mean pressure on the inlet ({below or 'the bottom'}), for the fluidization curve and
    // tfdem summary's Delta p
    inletPressure
    {{
        type            surfaceFieldValue;
        libs            ("libfieldFunctionObjects.so");
        writeControl    timeStep;
        writeInterval   {pressure_every};
        log             false;
        writeFields     false;
        regionType      patch;
        name            inlet;
        operation       areaAverage;
        fields          (p);
    }}"""
    return (_foam_header("dictionary", "controlDict") + f"""
application     tfdemFoam;
startFrom       startTime;
startTime       0;
stopAt          endTime;
endTime         {_g(bed['run']['end_time'])};
// gas step: a whole number of DEM steps ({dv['coupling_interval']} of in.bed's {dv['dem_step']:.4g} s)
deltaT          {dv['gas_step']!r};
writeControl    runTime;
writeInterval   {_g(bed['run']['write_interval'])};
purgeWrite      0;
writeFormat     ascii;
writePrecision  17;
writeCompression off;
timeFormat      general;
timePrecision   8;
runTimeModifiable false;
adjustTimeStep  no;

functions
{{
    // p every {pressure_every} gas steps: area averages over the cross-section (width and depth)
    // of the bed's bottom row of cells (the first above the floor) and of the top row, and
    // point values at mid-width and mid-depth on the same two rows
    pressure
    {{
        type            probes;
        libs            ("libsampling.so");
        writeControl    timeStep;
        writeInterval   {pressure_every};
        fields          (p);
        probeLocations  (({_g(x)} {_g(bottom_row)} {_g(z)}) ({_g(x)} {_g(top)} {_g(z)}));
    }}{_section_average("bedPressure", bottom_row, pressure_every,
                        "Mean pressure over the cross-section of the bed's bottom row of cells")}{
    _section_average("abovePressure", top, pressure_every,
                     "Mean pressure over the cross-section of the top row, for the fluidization curve")}{inlet}
}}
""")


def _dem_section(bed, dv):
    """coupling.yaml's dem: LIGGGHTS' script, or the hard-sphere engine and its collision laws."""
    if bed["dem"]["engine"] != "hard_sphere":
        return f"""dem:
  script: in.bed        # its timestep is the DEM step; the gas step (system/controlDict deltaT)
                        # is {dv['coupling_interval']} of them (the solver checks it is a whole number)"""
    p = bed["particles"]
    return f"""dem:
  engine: hard_sphere   # event-driven binary collisions (seed 001 section 3.3); one rank
  particles: bed.data   # tfdem pack pours it
  hard_sphere:          # seed 001 eqs. 11-21: e_n, beta_0 and mu of every pair, and of the walls
    restitution: {_g(p['restitution'])}
    tangential_restitution: {dv['tangential_restitution']:.6g}
    friction: {_g(p['friction'])}
    wall: {{restitution: {_g(p['wall']['restitution'])}, tangential_restitution: {dv['tangential_restitution']:.6g}, friction: {_g(p['wall']['friction'])}}}""" + "".join(
        f"\n    {key}: {_yaml_value(bed['dem'][key])}   # bed.yaml" for key in HARD_SPHERE_KEYS if bed["dem"][key] is not None)


def _yaml_value(value):
    """A value as coupling.yaml writes it: true/false, a whole number, or a number."""
    if isinstance(value, bool):
        return "true" if value else "false"
    return str(value) if isinstance(value, int) else _g(value)


def coupling_yaml(bed, dv):
    sizes = [s["diameter"] for s in bed["particles"]["sizes"]]
    diameter = _g(sizes[0]) if len(sizes) == 1 else "[" + ", ".join(_g(d) for d in sizes) + "]"
    return f"""# Generated by tfdem new from bed.yaml.
gas:
  density: {_g(bed['gas']['density'])}          # kg/m^3 (constant/transportProperties: the same)
  viscosity: {_g(bed['gas']['viscosity'])}     # Pa s
particles:
  diameter: {diameter}      # m
  density: {_g(bed['particles']['density'])}       # kg/m^3
{_dem_section(bed, dv)}
coupling:
  transfer: {bed['coupling']['transfer']}
  drag_law: {bed['coupling']['drag_law']}
  void_fraction:
    method: centroid    # cells {dv['dx'] / sizes[-1]:.3g} diameters wide
    two_dimensional: {'true' if dv['one_layer'] and len(sizes) == 1 else 'false'}{"   # one layer of two or more sizes: the 3-D volumes in cells one large diameter deep" if dv['one_layer'] and len(sizes) > 1 else ""}
    floor: 0.3
output:
  statistics_interval: {_g(dv['statistics_interval'])}   # s: N_c, mean height, ... (postProcessing/tfdemParticles/<start>/particles.dat)
  particles_vtk: true
"""


def packing_yaml(bed, dv):
    lines = ["# The packing `tfdem pack` pours (tfdem.packing): its count and mixture from bed.yaml",
             f"count: {dv['count']}"]
    if len(bed["particles"]["sizes"]) == 2:
        lines.append(f"mass_fraction_small: {dv['mass_fractions'][0]!r}")
    elif len(bed["particles"]["sizes"]) > 2:
        lines.append(f"mass_fractions: [{', '.join(repr(f) for f in dv['mass_fractions'])}]   # smallest size first")
    lines.append(f"floor: {_g(dv['floor'])}")
    return "\n".join(lines) + "\n"


def fv_options(bed, dv):
    d = _g(dv["plate_darcy"])
    return (_foam_header("dictionary", "fvOptions") + f"""
// The distributor plate's porous body (the cell row below the plate, cellZone distributor):
// Darcy dp = mu d L U, {bed['inflow']['plate']['pressure_drop_fraction']:g} of the bed's weight per area at U_mf (tfdem new).
distributor
{{
    type            explicitPorositySource;
    explicitPorositySourceCoeffs
    {{
        selectionMode   cellZone;
        cellZone        distributor;
        type            DarcyForchheimer;
        DarcyForchheimerCoeffs
        {{
            d   ({d} {d} {d});
            f   (0 0 0);
            coordinateSystem {{ origin (0 0 0); e1 (1 0 0); e2 (0 1 0); }}
        }}
    }}
}}
""")


ALLRUN = """#!/usr/bin/env bash
# Generated by tfdem new: packs the bed if there is none (tfdem pack), checks the packed bed is
# the one tfdem pack finished (its stamp), meshes, and runs tfdemFoam to the end time of
# system/controlDict; a case that holds a checkpoint carries on from the newest (tfdem resume:
# one a killed run left half-written is moved aside into incomplete/). Then tfdem summary
# writes summary.csv and summary.png.
# Stopped by Ctrl-C, `timeout` or a batch system's SIGTERM, the run writes a checkpoint and
# exits 75: Allrun again carries on from it, bit for bit as an unstopped run. To run longer, raise
# endTime in system/controlDict and ./Allrun again.
# Usage: ./Allrun [MPI ranks, default 1]. On several ranks the gas is whole on each or split
# (decomposePar, -parallel) as tfdem-gas-layout's measured rule has it for the mesh's cells;
# TFDEM_GAS_LAYOUT=whole or split chooses instead.
set -euo pipefail
cd "$(dirname "$0")"
. "{env}"
ranks=${{1:-1}}
case "$ranks" in ''|*[!0-9]*|0|00*) echo "$0: MPI ranks '$ranks': give a whole number of 1 or more" >&2; exit 2 ;; esac
[ -e bed.data ] || "$TFDEM_PYTHON" -m tfdem.packing . > log.pack
"$TFDEM_PYTHON" -m tfdem.packing --verify .
[ -f constant/polyMesh/owner ] || blockMesh > log.blockMesh 2>&1
"$TFDEM_PYTHON" -m tfdem.resume .
args=()
layout=whole
if [ "$ranks" -gt 1 ]; then
    cells=$(sed -n 's/.*nCells: *\\([0-9]*\\).*/\\1/p' constant/polyMesh/owner | head -n 1)
    layout=${{TFDEM_GAS_LAYOUT:-$(tfdem-gas-layout "$cells" "$ranks")}}
    case "$layout" in whole|split) ;; *) echo "TFDEM_GAS_LAYOUT=$layout: give whole or split" >&2; exit 2 ;; esac
fi
if [ "$layout" = split ]; then
    "$TFDEM_PYTHON" -m tfdem.run decompose . "$ranks" > log.decompose
    args=(-parallel)
else   # a checkpoint written split made whole
    "$TFDEM_PYTHON" -m tfdem.run reconstruct . > log.reconstruct
fi
[ -f log.tfdemFoam ] && mv log.tfdemFoam "log.tfdemFoam.$(date +%Y%m%d-%H%M%S)"
# Ctrl-C or SIGTERM (timeout, a batch system, kill) is passed to tfdem-solve, which has the run
# write a checkpoint and stop (the same signal sent to the whole group is passed on once); this
# script names the signal, waits for the stop and says how to carry on
TFDEM_STOP_NAMED=1 tfdem-solve log.tfdemFoam "$ranks" "${{args[@]}}" &
solver=$!
named=
stop() {{
    [ -n "$named" ] || echo "$0: $1 received: the run writes a checkpoint at the next gas step and stops (again to stop at once)" >&2
    named=1
    kill -TERM "$solver" 2>/dev/null
}}
trap 'stop "Ctrl-C (SIGINT)"' INT
trap 'stop SIGTERM' TERM
while kill -0 "$solver" 2>/dev/null; do
    wait "$solver" || true  # a signal ends the wait early: wait on for the solver's end
done
status=0
wait "$solver" || status=$?
[ "$status" -eq 75 ] && echo "$0: stopped at a checkpoint; $0 $ranks carries on from it"
"$TFDEM_PYTHON" -m tfdem.summary . || [ "$status" -ne 0 ] || status=$?
exit "$status"
"""

ALLCLEAN = """#!/usr/bin/env bash
# Removes what the run made; keeps the inputs and the packed bed (bed.data and its stamp
# bed.data.tfdem-packed; delete both to re-pour).
cd "$(dirname "$0")" || exit 1
rm -rf tfdem.lock *.tfdem-resume log.* [1-9]* 0.[0-9]* constant/polyMesh processor* incomplete \\
    postProcessing mean_height.txt forces.txt VTK in.bed.resumed summary.csv summary.png
"""
CASE_MARK = "derived.txt"   # a folder holding it is a case tfdem new wrote, which --force may replace
TEMPORARY = ".tfdem-new-"  # the case being built: .<name>.tfdem-new-<pid>-<random>


def case_files(bed, dv, source_text=None):
    """{path in the case: (text, executable)} of every file of the case."""
    files = {
        "system/blockMeshDict": block_mesh(bed, dv),
        "system/controlDict": control_dict(bed, dv),
        "constant/g": _foam_header("uniformDimensionedVectorField", "g") +
        "dimensions      [0 1 -2 0 0 0 0];\nvalue           (0 -9.81 0);\n",
        "constant/transportProperties": _foam_header("dictionary", "transportProperties") +
        f"// the gas of bed.yaml (coupling.yaml: the same)\nrho     {_g(bed['gas']['density'])};\n"
        f"nu      {_g(bed['gas']['viscosity'] / bed['gas']['density'])};\n",
        "coupling.yaml": coupling_yaml(bed, dv),
        "packing.yaml": packing_yaml(bed, dv),
        "derived.txt": "What tfdem new derived, and why:\n" + "".join(f"  {n}\n" for n in dv["notes"])
        + ("Warnings:\n" + "".join(f"  {w}\n" for w in dv["warnings"]) if dv["warnings"] else ""),
    }
    if bed["dem"]["engine"] != "hard_sphere":
        files["in.bed"] = bed_script(
            bed, dv, "" if bed["particles"]["stiffness"] else f" (an impact at U_mf sinks {IMPACT_OVERLAP:.0%} of d)")
    for name, text in initial_fields(bed, dv).items():
        files[f"0/{name}"] = text
    if bed["inflow"]["plate"]:
        files["constant/fvOptions"] = fv_options(bed, dv)
    for name in ("fvSchemes", "fvSolution"):
        with open(os.path.join(FIELDS_TEMPLATE, name)) as f:
            files[f"system/{name}"] = f.read()
    if source_text is not None:
        files["bed.yaml"] = source_text
    out = {name: (text, False) for name, text in files.items()}
    out["Allrun"] = (ALLRUN.format(env=os.path.join(SOURCE_DIR, "scripts", "tfdem-env.sh")), True)
    out["Allclean"] = (ALLCLEAN, True)
    return out


def check_destination(dest, force=False):
    """The names an existing `dest` holds that --force would replace ([] for a new or empty
    folder); BedError for an empty name, a file, a folder that is not empty (without force),
    and a folder --force must not replace (not a case, or one holding the current folder).
    bed.yaml may be inside it: it is read before the folder is replaced."""
    if not dest.strip():
        raise BedError(f"the case name {dest!r} is empty: give the new case's folder (an unset shell variable?)")
    if os.path.islink(dest) or (os.path.exists(dest) and not os.path.isdir(dest)):
        raise BedError(f"{dest}: exists and is not a folder: give a new folder for the case")
    above = os.path.dirname(os.path.abspath(dest))
    while not os.path.exists(above):
        above = os.path.dirname(above)
    if not os.path.isdir(above):
        raise BedError(f"{dest}: {above} is a file, not a folder: give a path of folders for the case")
    if not os.path.isdir(dest) or not os.listdir(dest):
        return []
    held = sorted(os.listdir(dest))
    if not force:
        raise BedError(f"{dest}: exists and is not empty ({_listing(held)}): give a new folder, or --force to "
                       "replace a case tfdem new wrote (nothing was written)")
    if CASE_MARK not in held:
        raise BedError(f"{dest}: --force replaces only a case tfdem new wrote (with its {CASE_MARK}), and this "
                       f"folder holds {_listing(held)}: give a new folder, or remove it yourself")
    here, top = os.getcwd(), os.path.abspath(dest)
    if here == top or here.startswith(top + os.sep):
        raise BedError(f"{dest}: --force would replace the folder you are in ({here}): run it from outside")
    return held


def _listing(names, shown_names=8):
    more = f", ... ({len(names)} entries)" if len(names) > shown_names else ""
    return ", ".join(names[:shown_names]) + more


def write_case(dest, bed, dv, source=None, force=False):
    """Write the case into `dest` whole or not at all: built in a temporary folder beside it,
    then renamed into place (a failure, a full disk, leaves what was there). `dest` must not
    exist or be an empty folder; with `force` a case tfdem new wrote there is replaced. Returns
    the names the replaced folder held ([] when there was none)."""
    held = check_destination(dest, force)
    source_text = None
    if source:
        with doing("reading", source), open(source, encoding="utf-8", errors="replace") as f:
            source_text = f.read()
    files = case_files(bed, dv, source_text)
    parent = os.path.dirname(os.path.abspath(dest))
    made = _make_parents(parent)
    temporary = None
    try:
        _remove_abandoned(parent, os.path.basename(os.path.abspath(dest)))
        with doing("making the case's folder in", parent):
            temporary = tempfile.mkdtemp(dir=parent, prefix=f".{os.path.basename(os.path.abspath(dest))}{TEMPORARY}"
                                         f"{os.getpid()}-")
            os.chmod(temporary, default_mode(executable=True))
        for name, (text, executable) in files.items():
            path = os.path.join(temporary, name)
            os.makedirs(os.path.dirname(path), exist_ok=True)
            with doing("writing", os.path.join(dest, name)):
                write_file_synced(path, text, default_mode(executable))
        _put_in_place(temporary, dest, held)
    except BaseException:
        if temporary and os.path.isdir(temporary):
            shutil.rmtree(temporary, ignore_errors=True)
        for folder in reversed(made):
            with contextlib.suppress(OSError):
                os.rmdir(folder)
        raise
    return held


def _make_parents(parent):
    """Make the missing folders of `parent`; returns those made, outermost first."""
    missing = []
    while parent and not os.path.isdir(parent):
        missing.append(parent)
        parent = os.path.dirname(parent)
    for folder in reversed(missing):
        os.mkdir(folder)
    return list(reversed(missing))


def _remove_abandoned(parent, name):
    """Remove the temporary folders of earlier runs for this case whose process is gone (a
    killed tfdem new)."""
    prefix = f".{name}{TEMPORARY}"
    for entry in os.listdir(parent):
        if not entry.startswith(prefix):
            continue
        pid = entry[len(prefix):].split("-", 1)[0]
        if pid.isdigit() and not _alive(int(pid)):
            shutil.rmtree(os.path.join(parent, entry), ignore_errors=True)


def _alive(pid):
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    except PermissionError:
        return True
    return True


def _put_in_place(temporary, dest, held):
    """Rename the built case to dest: over nothing; into an empty folder entry by entry (the
    folder stays, as someone may be in it); or, when it held files (--force), after moving the
    old one aside (moved back if the rename fails)."""
    if os.path.isdir(dest) and not held:
        _move_into(temporary, dest)
        return
    if not held:
        with doing("putting the case in place at", dest):
            os.rename(temporary, dest)
        _sync(os.path.dirname(os.path.abspath(dest)))
        return
    aside = temporary + ".replaced"
    with doing("moving aside the folder --force replaces,", dest):
        os.rename(dest, aside)
    try:
        os.rename(temporary, dest)
    except BaseException:
        os.rename(aside, dest)
        raise
    _sync(os.path.dirname(os.path.abspath(dest)))
    shutil.rmtree(aside, ignore_errors=True)


def _move_into(temporary, dest):
    """Move the built case's entries into the empty folder dest; on a failure the entries
    moved are taken out again, leaving it empty."""
    moved = []
    try:
        for name in sorted(os.listdir(temporary)):
            with doing("putting the case in place at", os.path.join(dest, name)):
                os.rename(os.path.join(temporary, name), os.path.join(dest, name))
            moved.append(name)
    except BaseException:
        for name in moved:
            path = os.path.join(dest, name)
            if os.path.isdir(path):
                shutil.rmtree(path, ignore_errors=True)
            else:
                with contextlib.suppress(OSError):
                    os.remove(path)
        raise
    os.rmdir(temporary)
    _sync(dest)


def _sync(folder):
    fd = os.open(folder, os.O_RDONLY)
    try:
        os.fsync(fd)
    except OSError:
        pass
    finally:
        os.close(fd)


def main(argv=None):
    return run_command("tfdem new", _new, argv)


def _new(argv):
    parser = argparse.ArgumentParser(prog="tfdem new", description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("case", help="the new case's folder (must not exist, or be empty)")
    parser.add_argument("--from", dest="source", required=True, help="the bed's YAML")
    parser.add_argument("--force", action="store_true",
                        help="replace CASE when it is a case tfdem new wrote (it says what the folder held)")
    add_debug_option(parser)
    args = parser.parse_args(argv)
    check_destination(args.case, args.force)
    with doing("reading", args.source):
        bed = load_bed(args.source)
    with doing("deriving the case from", args.source):
        dv = derive(bed, args.source)
    with doing("writing the case", args.case):
        held = write_case(args.case, bed, dv, args.source, force=args.force)
    if held:
        print(f"tfdem new: --force: replaced {args.case}, which held {_listing(held)}")
    print(f"tfdem new: wrote {args.case}. What it derived, and why (also in {args.case}/derived.txt):")
    for line in dv["notes"]:
        print(f"  {line}")
    for line in dv["warnings"]:
        print(f"tfdem new: warning: {line}")
    print(f"Next: tfdem pack {args.case} (pours the bed), then {args.case}/Allrun")
    return 0


if __name__ == "__main__":
    sys.exit(main())
