"""The LIGGGHTS engine's files, the one Python module that knows their syntax: input scripts,
read through the engine's own reader (tfdem-liggghts-script, engines/liggghts/dem_script.cpp:
comments, '&' continuations and includes as LIGGGHTS takes them) and evaluated here (variables,
contact tables, walls); data files of atom style granular, read and written; and the in.bed
that tfdem new writes.
"""
import json
import math
import os
import re
import subprocess

from tfdem import BUILD_DIR
from tfdem.inputs import CaseError, read_text as _read

SCRIPT_READER = os.path.join(BUILD_DIR, "engines", "liggghts", "tfdem-liggghts-script")
CONTACT_PROPERTIES = ("kn", "kt", "gamman_abs", "gammat_abs", "coefficientFriction")


class ScriptError(CaseError):
    """A DEM script that cannot be read, or lacks what is asked of it, named."""


def _g(v):
    return f"{v:.10g}"


def script_commands(path):
    """The commands of the LIGGGHTS script at `path` as the engine reads them: a list of
    {"file", "line", "words"} (includes followed, relative to the script's folder)."""
    if not os.path.isfile(SCRIPT_READER):
        raise ScriptError(f"{path}: the script reader {SCRIPT_READER} is not built: run ./tfdem setup")
    if not os.path.isfile(path):
        raise ScriptError(f"{path}: cannot read (no such file)")
    done = subprocess.run([SCRIPT_READER, path], capture_output=True, text=True)
    if done.returncode != 0:
        raise ScriptError(done.stderr.strip() or f"{path}: tfdem-liggghts-script failed ({done.returncode})")
    return [json.loads(line) for line in done.stdout.splitlines()]


class DemScript:
    """A LIGGGHTS input script read command by command (comments dropped). Values can name
    the script's own variables (${name}) and be simple arithmetic $(...) of numbers."""

    def __init__(self, path):
        self.path = os.path.abspath(path)
        self.lines = [command["words"] for command in script_commands(self.path)]

    def commands(self, name):
        """Words of every `name` command, in order."""
        return [words for words in self.lines if words and words[0] == name]

    def command(self, name, *leading):
        """Words of the first `name` command whose next words are `leading` (e.g.
        command('fix', 'grav')); CaseError when there is none."""
        for words in self.commands(name):
            if list(words[1:1 + len(leading)]) == list(leading):
                return words
        raise ScriptError(f"{self.path}: no '{' '.join((name,) + leading)}' command")

    def variables(self):
        """{name: value text} of the script's `variable NAME equal|index|string VALUE` lines
        (the first definition counts, as for LIGGGHTS' index variables; quotes removed)."""
        out = {}
        for words in self.commands("variable"):
            if len(words) >= 4 and words[2] in ("equal", "index", "string") and words[1] not in out:
                out[words[1]] = " ".join(words[3:]).strip('"')
        return out

    def variable(self, name):
        value = self.variables().get(name)
        if value is None:
            raise ScriptError(f"{self.path}: no 'variable {name}'")
        return value

    def value(self, text):
        """A number of a command: a literal, ${variable}, v_variable or $(arithmetic); an
        equal-style variable's expression is evaluated as LIGGGHTS does (numbers, other
        variables, + - * / ^, PI, sqrt, ln, exp)."""
        expression = re.fullmatch(r"\$\((.*)\)", text)
        return self._evaluate(expression.group(1) if expression else text, set())

    def _evaluate(self, text, seen):
        variables = self.variables()

        def variable(name):
            if name not in variables or name in seen:
                raise ScriptError(f"{self.path}: '{text}' names {'no' if name not in variables else 'circular'} "
                                f"variable '{name}'")
            return repr(self._evaluate(variables[name], seen | {name}))

        python = re.sub(r"\$\{(\w+)\}|v_(\w+)", lambda m: variable(m.group(1) or m.group(2)), text)
        try:
            return float(python)
        except ValueError:
            pass
        if not re.fullmatch(r"(?:[\d.eE+\-*/()^ ,]|PI|sqrt|ln|exp)+", python):
            raise ScriptError(f"{self.path}: '{text}' is not a number")
        try:
            return float(eval(python.replace("^", "**"), {"__builtins__": {}},
                              {"PI": math.pi, "sqrt": math.sqrt, "ln": math.log, "exp": math.exp}))
        except (SyntaxError, TypeError, ValueError, ZeroDivisionError) as e:
            raise ScriptError(f"{self.path}: cannot evaluate '{text}': {e}") from None

    def time_step(self):
        return self.value(self.command("timestep")[1])

    def read_data(self):
        """Path of the data file of the script's read_data command."""
        return os.path.join(os.path.dirname(self.path), self.command("read_data")[1])

    def gravity(self):
        """(x, y, z) of the first `fix ID group gravity MAGNITUDE vector x y z`."""
        for words in self.commands("fix"):
            if len(words) >= 9 and words[3] == "gravity" and words[5] == "vector":
                magnitude = self.value(words[4])
                return tuple(magnitude * self.value(w) for w in words[6:9])
        raise ScriptError(f"{self.path}: no 'fix ... gravity ... vector x y z'")

    def region(self, name):
        """((x0, y0, z0), (x1, y1, z1)) of `region NAME block x0 x1 y0 y1 z0 z1`."""
        words = self.command("region", name)
        if len(words) < 9 or words[2] != "block":
            raise ScriptError(f"{self.path}: region '{name}' is not a block")
        bounds = [self.value(w) for w in words[3:9]]
        return tuple(bounds[0::2]), tuple(bounds[1::2])

    def lattice(self):
        """(spacing, (ox, oy, oz)) of the script's `lattice sc SPACING [origin ox oy oz]`."""
        words = self.command("lattice")
        if words[1] != "sc":
            raise ScriptError(f"{self.path}: lattice {words[1]}: only 'sc' is read")
        origin = (0.0, 0.0, 0.0)
        if "origin" in words:
            k = words.index("origin")
            origin = tuple(self.value(w) for w in words[k + 1:k + 4])
        return self.value(words[2]), origin

    def lattice_sites(self, region):
        """Centres [(x, y, z)] that `create_atoms TYPE region REGION` puts on the script's sc
        lattice inside a block region (sites on the region's faces count, as in LIGGGHTS)."""
        spacing, origin = self.lattice()
        lo, hi = self.region(region)
        axes = []
        for a in range(3):
            first = math.ceil(lo[a] / spacing - origin[a] - 1e-9)
            last = math.floor(hi[a] / spacing - origin[a] + 1e-9)
            axes.append([(i + origin[a]) * spacing for i in range(first, last + 1)])
        return [(x, y, z) for z in axes[2] for y in axes[1] for x in axes[0]]

    def fix_file(self, fix_id):
        """File name a fix writes (the word after `file` in `fix ID ...`), beside the script."""
        words = self.command("fix", fix_id)
        if "file" not in words:
            raise ScriptError(f"{self.path}: fix {fix_id} writes no file")
        return words[words.index("file") + 1]


def read_data_file(path):
    """The Atoms section of a LIGGGHTS data file of atom style granular (id type diameter
    density x y z)."""
    lines = _read(path).splitlines()
    try:
        start = next(i for i, line in enumerate(lines) if line.split()[:1] == ["Atoms"])
    except StopIteration:
        raise CaseError(f"{path}: no Atoms section") from None
    out = {k: [] for k in ("id", "type", "diameter", "density", "x", "y", "z")}
    for line in lines[start + 1:]:
        words = line.split("#", 1)[0].split()
        if not words:
            if out["id"]:
                break
            continue
        if not re.match(r"^-?\d", words[0]):
            break
        out["id"].append(int(words[0]))
        out["type"].append(int(words[1]))
        for key, w in zip(("diameter", "density", "x", "y", "z"), words[2:7]):
            out[key].append(float(w))
    return out


def read_data_box(path):
    """((xlo, ylo, zlo), (xhi, yhi, zhi)) of a LIGGGHTS data file's header."""
    bounds = {}
    for line in _read(path).splitlines():
        words = line.split()
        if len(words) == 4 and words[2:] in (["xlo", "xhi"], ["ylo", "yhi"], ["zlo", "zhi"]):
            bounds[words[2][0]] = (float(words[0]), float(words[1]))
        if words[:1] == ["Atoms"]:
            break
    if len(bounds) != 3:
        raise CaseError(f"{path}: no xlo xhi, ylo yhi and zlo zhi lines")
    return tuple(bounds[a][0] for a in "xyz"), tuple(bounds[a][1] for a in "xyz")


def write_data_file(path, lower, upper, diameters, densities, positions, velocities=None, types=None,
                    type_count=None, title="TFDEM particles"):
    """A LIGGGHTS data file (atom_style granular: id type diameter density x y z) of these
    particles in the box lower..upper, with a Velocities section when velocities are given."""
    n = len(positions)
    types = types or [1] * n
    lines = [title, "", f"{n} atoms", f"{type_count or max(types, default=1)} atom types", ""]
    lines += [f"{lower[a]!r} {upper[a]!r} {'xyz'[a]}lo {'xyz'[a]}hi" for a in range(3)]
    lines += ["", "Atoms # granular", ""]
    lines += [f"{k + 1} {types[k]} {diameters[k]!r} {densities[k]!r} {x!r} {y!r} {z!r}"
              for k, (x, y, z) in enumerate(positions)]
    if velocities:
        lines += ["", "Velocities", ""]
        lines += [f"{k + 1} {vx!r} {vy!r} {vz!r} 0 0 0" for k, (vx, vy, vz) in enumerate(velocities)]
    with open(path, "w") as f:
        f.write("\n".join(lines) + "\n")


def contact_properties(script):
    """A LIGGGHTS script's (a DemScript) `fix ... property/global <name> peratomtypepair n
    <values>` for the linear spring-dashpot (CONTACT_PROPERTIES) as n x n matrices; refuses a
    script without them (a Hertz or restitution-based contact) by name."""
    tables = {}
    for words in script.commands("fix"):
        if len(words) > 6 and words[3] == "property/global" and words[5] == "peratomtypepair":
            n = int(words[6])
            numbers = [script.value(w) for w in words[7:]]
            if len(numbers) != n * n:
                raise ScriptError(f"{script.path}: property/global {words[4]} gives {len(numbers)} values for "
                                  f"{n} x {n} types")
            tables[words[4]] = [numbers[i * n:(i + 1) * n] for i in range(n)]
    missing = [p for p in CONTACT_PROPERTIES if p not in tables]
    if missing:
        raise ScriptError(f"{script.path}: no property/global {', '.join(missing)} peratomtypepair: the hard-sphere "
                          "laws are derived from a linear spring-dashpot with absolute damping (hooke/stiffness)")
    return tables


def wall_type(script, type_count):
    """The atom type (1-based) of a LIGGGHTS script's walls: the `type` of its `fix ...
    wall/gran` commands (one for all), else the last of the contact tables' type_count."""
    found = {int(w[w.index("type") + 1]) for w in script.commands("fix")
             if len(w) > 3 and w[2] == "wall/gran" and "type" in w[3:-1]}
    if len(found) > 1:
        raise ScriptError(f"{script.path}: its walls are of atom types {sorted(found)}: the hard-sphere laws take "
                          "one wall law per particle type")
    return found.pop() if found else type_count


def bed_script(bed, dv, stiffness_note=""):
    """tfdem new's in.bed for a bed (its YAML, tfdem.newcase) and its derived values `dv`:
    e_n, k_n and friction stated once as variables, every pair's damping from them;
    `stiffness_note` says where k_n came from."""
    p, box = bed["particles"], bed["box"]
    sizes = [s["diameter"] for s in p["sizes"]]
    types = len(sizes) + 1
    wall_type = types
    kinds = {1: "Monodisperse", 2: "Bidisperse"}
    spheres = {1: "1 the spheres", 2: "1 the small, 2 the large spheres"}
    lines = [f"# {kinds.get(len(sizes), f'{len(sizes)}-size')} bed generated by tfdem new (edit freely: each value "
             "is stated once, below, and the rest follows from it).",
             f"# Atom types: {spheres.get(len(sizes), f'1 to {len(sizes)} the sizes, smallest first')}, "
             f"{wall_type} the walls. Linear spring-dashpot contacts with absolute damping from e_n",
             "# (seed 001 eq. 27) for each pair's reduced mass (seed 001 eq. 16; a wall: m_ab = m).",
             f"variable        width equal {_g(box['width'])}",
             f"variable        height equal {_g(box['height'])}",
             f"variable        depth equal {_g(dv['depth'])}",
             f"variable        floor equal {_g(dv['floor'])}" + (("   # the distributor plate" if bed["inflow"]["plate"]
                                                                      else "   # above the windbox row") if dv["floor"] else ""),
             f"variable        rho equal {_g(p['density'])}"]
    for i, d in enumerate(sizes, 1):
        lines.append(f"variable        d{i} equal {_g(d)}")
        lines.append(f"variable        mass{i} equal v_rho*PI*v_d{i}^3/6")
    lines += [f"variable        en equal {_g(p['restitution'])}          # e_n, particle pairs",
              f"variable        en_wall equal {_g(p['wall']['restitution'])}     # e_n, particle-wall",
              f"variable        mu equal {_g(p['friction'])}",
              f"variable        mu_wall equal {_g(p['wall']['friction'])}",
              f"variable        kn equal {dv['stiffness']:.6g}          # N/m" + stiffness_note,
              "variable        kn_wall equal 2*v_kn   # the pairs' overlap and t_c for a wall's m_ab = m",
              "variable        kt equal 2/7*v_kn",
              "variable        kt_wall equal 2/7*v_kn_wall"]

    def pair(i, j):
        return f"v_mass{i}*v_mass{j}/(v_mass{i}+v_mass{j})" if j else f"v_mass{i}"

    for i in range(1, len(sizes) + 1):
        for j in list(range(i, len(sizes) + 1)) + [0]:
            name = f"eta{i}{j}" if j else f"eta{i}w"
            e, k = ("v_en", "v_kn") if j else ("v_en_wall", "v_kn_wall")
            lines.append(f"variable        {name} equal -2*ln({e})*sqrt(({pair(i, j)})*{k})/sqrt(PI^2+ln({e})^2)")

    def matrix(entry):
        rows = []
        for a in range(1, types + 1):
            for b in range(1, types + 1):
                rows.append(entry(min(a, b), max(a, b)))
        return " ".join(rows)

    def is_wall(a, b):  # a <= b: the wall type is the last
        return b == wall_type

    def eta(a, b):
        if a == wall_type:
            return f"${{eta{len(sizes)}w}}"
        return f"${{eta{a}w}}" if is_wall(a, b) else f"${{eta{a}{b}}}"

    kn = matrix(lambda a, b: "${kn_wall}" if is_wall(a, b) else "${kn}")
    kt = matrix(lambda a, b: "${kt_wall}" if is_wall(a, b) else "${kt}")
    damping = matrix(eta)
    friction = matrix(lambda a, b: "${mu_wall}" if is_wall(a, b) else "${mu}")
    walls = [("wall_x0", "xplane 0"), ("wall_x1", "xplane ${width}"), ("plate", "yplane ${floor}"),
             ("lid", "yplane ${height}")]
    if not dv["one_layer"]:
        walls += [("wall_z0", "zplane 0"), ("wall_z1", "zplane ${depth}")]
    lines += ["atom_style      granular",
              "atom_modify     map array sort 0 0",
              "boundary        f f f",
              "newton          off",
              "communicate     single vel yes",
              "units           si",
              # LIGGGHTS cuts across the bed only, never along gravity (y): cuts in y leave the
              # upper ranks in the freeboard and one rank with the whole bed
              "processors      " + ("* 1 1" if dv["one_layer"] else "* 1 *"),
              "read_data       bed.data",
              f"neighbor        {_g(0.2 * sizes[-1])} bin",
              "neigh_modify    delay 0",
              "",
              f"fix             m1 all property/global kn peratomtypepair {types} {kn}",
              f"fix             m2 all property/global kt peratomtypepair {types} {kt}",
              f"fix             m3 all property/global gamman_abs peratomtypepair {types} {damping}",
              f"fix             m4 all property/global gammat_abs peratomtypepair {types} {damping}",
              f"fix             m5 all property/global coefficientFriction peratomtypepair {types} {friction}",
              "pair_style      gran model hooke/stiffness tangential history absolute_damping on",
              "pair_coeff      * *",
              "# store_force: each wall's force on the particles (forces.txt below)"]
    for name, plane in walls:
        lines.append(f"fix             {name} all wall/gran model hooke/stiffness tangential history primitive "
                     f"type {wall_type} {plane} store_force yes absolute_damping on")
    lines += ["",
              f"# The scene check's rule (tfdem-scene-check): t_c/{dv['scene']['pair']['steps_per_contact']:.3g} of the "
              "smallest pair; the gas step (system/controlDict deltaT) is a whole number of these",
              f"timestep        {dv['dem_step']!r}",
              "fix             grav all gravity 9.81 vector 0 -1 0",
              "fix             fluid all tfdem/coupling",
              "fix             integr all nve/sphere",
              "",
              "compute         height all reduce ave y",
              "thermo_style    custom step atoms ke c_height",
              f"thermo          {max(1, int(round(0.1 / dv['dem_step'])))}",
              "",
              "# Mean particle height every 1 ms",
              "variable        t equal step*dt",
              "variable        h equal c_height",
              f"fix             height_out all print {max(1, int(round(1e-3 / dv['dem_step'])))} \"${{t}} ${{h}}\" "
              "file mean_height.txt screen no title \"# t (s)  mean particle height (m)\"",
              "# Where the bed's weight goes: vertical force on all particles from the gas, the plate, the",
              "# side walls (x), the lid" + ("" if dv["one_layer"] else " and the front and back walls (z)")
              + ", averaged over 1 ms",
              "compute         f_gas all reduce sum f_fluid[2]",
              "compute         f_plate all reduce sum f_force_plate[2]",
              "compute         f_side all reduce sum f_force_wall_x0[2] f_force_wall_x1[2]",
              "compute         f_lid all reduce sum f_force_lid[2]"]
    depth_walls = ""
    if not dv["one_layer"]:
        lines.append("compute         f_depth all reduce sum f_force_wall_z0[2] f_force_wall_z1[2]")
        depth_walls = " c_f_depth[1] c_f_depth[2]"
    every = max(1, int(round(1e-3 / dv["dem_step"])))
    lines.append(f"fix             forces_out all ave/time 1 {every} {every} c_f_gas c_f_plate c_f_side[1] "
                 f"c_f_side[2] c_f_lid{depth_walls} file forces.txt")
    return "\n".join(lines) + "\n"
