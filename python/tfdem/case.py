"""A case read from its own files, copied and edited: the one place a case's numbers come from.

OpenFOAM dictionaries are read and edited entry by entry (``key value;`` lines), coupling.yaml
with python3-yaml (edited line by line so its comments stay), the mesh from blockMeshDict,
the particles from the DEM script's ``read_data`` file.
"""
import math
import os
import re
import shutil

import yaml

from tfdem.frontdoor import write_text_atomic
from tfdem.inputs import CaseError, Source, parse_yaml, read_text as _read
from tfdem.liggghts import DemScript, read_data_file


def _write(path, text):
    write_text_atomic(path, text)


def _strip_comments(text):
    text = re.sub(r"/\*.*?\*/", "", text, flags=re.S)
    return re.sub(r"//[^\n]*", "", text)


def dict_entry(path, key):
    """Text of the top-level ``key value;`` entry of an OpenFOAM dictionary file."""
    found = re.search(rf"(?m)^\s*{re.escape(key)}\s+([^;]*);", _strip_comments(_read(path)))
    if not found:
        raise CaseError(f"{path}: no entry '{key}'")
    return found.group(1).strip()


def set_dict_entries(path, **entries):
    """Set top-level ``key value;`` entries of an OpenFOAM dictionary (added when absent)."""
    text = _read(path)
    for key, value in entries.items():
        line = f"{key:<15} {value};"
        text, n = re.subn(rf"(?m)^{re.escape(key)}\s+[^;]*;", line.replace("\\", r"\\"), text)
        if n == 0:
            text += f"\n{line}\n"
    _write(path, text)


def number(text):
    """The last number of an OpenFOAM entry value, e.g. '[1 -3 0 0 0 0 0] 1.2' or '1.2'."""
    return float(text.split()[-1])


def vector(text):
    """(x y z) of an entry value such as '[0 1 -2 0 0 0 0] (0 -9.81 0)'."""
    found = re.search(r"\(([^()]*)\)\s*$", text)
    if not found:
        raise CaseError(f"not a vector: {text!r}")
    return tuple(float(v) for v in found.group(1).split())


def remove_dict_entry(path, key):
    """Remove the top-level ``key value;`` entry of an OpenFOAM dictionary (CaseError when absent)."""
    text = _read(path)
    text, n = re.subn(rf"(?m)^\s*{re.escape(key)}\s+[^;]*;[^\n]*\n?", "", text, count=1)
    if n == 0:
        raise CaseError(f"{path}: no entry '{key}'")
    _write(path, text)


def _sub_dict_span(text, name, path, start=0, end=None):
    """(first, last) index of the body (between the braces) of the first sub-dictionary
    ``name { ... }`` of text[start:end], nested braces included."""
    end = len(text) if end is None else end
    found = re.compile(rf"(?<![\w.]){re.escape(name)}\s*\{{").search(text, start, end)
    if not found:
        raise CaseError(f"{path}: no sub-dictionary '{name}'")
    depth = 1
    for i in range(found.end(), end):
        if text[i] == "{":
            depth += 1
        elif text[i] == "}":
            depth -= 1
            if depth == 0:
                return found.end(), i
    raise CaseError(f"{path}: sub-dictionary '{name}' is not closed")


def sub_dict(text, name, path="dictionary"):
    """Body (between the braces) of the first sub-dictionary ``name { ... }`` of OpenFOAM text
    (comments removed), nested braces included."""
    text = _strip_comments(text)
    first, last = _sub_dict_span(text, name, path)
    return text[first:last]


def set_sub_dict_entry(path, dotted, value):
    """Set entry `a.b.c` of an OpenFOAM dictionary file in place (sub-dictionaries a, then b;
    entry c, which must exist), keeping the rest of the text."""
    *parents, key = dotted.split(".")
    text = _read(path)
    start, end = 0, len(text)
    for name in parents:
        start, end = _sub_dict_span(text, name, f"{path} ('{dotted}')", start, end)
    entry = re.compile(rf"(?<![\w$.]){re.escape(key)}\s+[^;{{}}]*;").search(text, start, end)
    if not entry:
        raise CaseError(f"{path}: no entry '{dotted}'")
    _write(path, text[:entry.start()] + f"{key} {value};" + text[entry.end():])


def _points(text):
    """(x y z) tuples of a list text such as '((0 1 2) (3 4 5))'."""
    return [tuple(float(v) for v in m.group(1).split()) for m in re.finditer(r"\(([^()]*)\)", text)]


class Grid:
    """The uniform Cartesian grid of a blockMeshDict: origin, spacing and cell counts."""

    def __init__(self, origin, spacing, counts):
        self.origin, self.spacing, self.counts = tuple(origin), tuple(spacing), tuple(counts)

    @property
    def cell_count(self):
        return self.counts[0] * self.counts[1] * self.counts[2]

    def centres(self):
        """Cell centres in OpenFOAM's blockMesh order for one block: x fastest, then y, z."""
        return [tuple(self.origin[a] + (ijk[a] + 0.5) * self.spacing[a] for a in range(3))
                for ijk in ((i, j, k) for k in range(self.counts[2]) for j in range(self.counts[1])
                            for i in range(self.counts[0]))]

    def upper(self, axis):
        return self.origin[axis] + self.spacing[axis] * self.counts[axis]

    def centre_of_cell_at(self, axis, x):
        """The centre coordinate, along axis, of the cell holding x (a probe samples its cell's
        value, so a gradient between probes is taken between their cells' centres)."""
        index = min(max(int((x - self.origin[axis]) // self.spacing[axis]), 0), self.counts[axis] - 1)
        return self.origin[axis] + (index + 0.5) * self.spacing[axis]


def _expand_variables(text):
    """Top-level ``name value;`` entries substituted for ``$name`` (blockMeshDict macros)."""
    values = dict(re.findall(r"(?m)^\s*([A-Za-z]\w*)\s+([-+.\w]+)\s*;", text))
    return re.sub(r"\$(\w+)", lambda m: values.get(m.group(1), m.group(0)), text)


_HEX = r"hex\s*\(([\d\s]+)\)\s*(\w*)\s*\(([\d\s]+)\)"


def _blocks(text):
    """[(vertex indices, (nx, ny, nz), zone name or '')] of a blockMeshDict's hex blocks."""
    return [([int(v) for v in m.group(1).split()], tuple(int(n) for n in m.group(3).split()), m.group(2))
            for m in re.finditer(_HEX, text)]


def _vertices(path, text):
    found = re.search(r"vertices\s*\((.*?)\)\s*;", text, flags=re.S)
    if not found:
        raise CaseError(f"{path}: no vertices")
    return [tuple(float(v) for v in m.group(1).split()) for m in re.finditer(r"\(([^()]*)\)", found.group(1))]


class Case:
    """An OpenFOAM/LIGGGHTS case directory."""

    def __init__(self, path):
        self.path = os.path.abspath(path)

    def __repr__(self):
        return f"Case({self.path!r})"

    def file(self, *parts):
        return os.path.join(self.path, *parts)

    # Copying -------------------------------------------------------------------------------
    def copy_to(self, dest, extra=()):
        """A fresh copy at dest: 0/, constant/ (without a mesh), system/, and coupling.yaml, the
        DEM input scripts (in.*) and the named extra files when present."""
        shutil.rmtree(dest, ignore_errors=True)
        os.makedirs(dest)
        for sub in ("0", "constant", "system"):
            if os.path.isdir(self.file(sub)):
                shutil.copytree(self.file(sub), os.path.join(dest, sub), ignore=shutil.ignore_patterns("polyMesh"))
        for name in os.listdir(self.path):
            if name == "coupling.yaml" or name.startswith("in.") or name in extra:
                if os.path.isdir(self.file(name)):
                    shutil.copytree(self.file(name), os.path.join(dest, name))
                else:
                    shutil.copy(self.file(name), dest)
        return Case(dest)

    # OpenFOAM dictionaries -----------------------------------------------------------------
    def control(self, key):
        return dict_entry(self.file("system", "controlDict"), key)

    def set_control(self, **entries):
        set_dict_entries(self.file("system", "controlDict"), **entries)

    def delta_t(self):
        return float(self.control("deltaT"))

    def end_time(self):
        return float(self.control("endTime"))

    def gas(self):
        """(rho, mu) of constant/transportProperties."""
        path = self.file("constant", "transportProperties")
        rho = number(dict_entry(path, "rho"))
        return rho, rho * number(dict_entry(path, "nu"))

    def gravity(self):
        return vector(dict_entry(self.file("constant", "g"), "value"))

    def gravity_magnitude(self):
        """|g| (m/s^2) of constant/g."""
        return math.sqrt(sum(c * c for c in self.gravity()))

    def function_body(self, function):
        """Text (between its braces, comments removed) of the function object `function` of
        system/controlDict."""
        path = self.file("system", "controlDict")
        return sub_dict(sub_dict(_read(path), "functions", path), function, path)

    def function_entry(self, function, key):
        """Text of entry `key` of the function object `function` in system/controlDict."""
        path = self.file("system", "controlDict")
        body = self.function_body(function)
        found = re.search(rf"(?m)^\s*{re.escape(key)}\s+(.*?);", body, flags=re.S)
        if not found:
            raise CaseError(f"{path}: function '{function}' has no entry '{key}'")
        return found.group(1).strip()

    def probe_locations(self, function):
        """[(x, y, z)] of a probes function object of system/controlDict."""
        return _points(self.function_entry(function, "probeLocations")[1:-1])

    def pressure_height(self, function):
        """The height y (m) a pressure function object of system/controlDict samples: a probes
        object's first location, or the point of a surfaceFieldValue's cutting plane."""
        body = self.function_body(function)
        if re.search(r"(?m)^\s*probeLocations\s", body):
            return self.probe_locations(function)[0][1]
        found = re.search(r"\bpoint\s*\(([^()]*)\)", body)
        if not found:
            raise CaseError(f"{self.file('system', 'controlDict')}: function '{function}' has neither probeLocations "
                            "nor a cutting plane's point")
        return vector(f"({found.group(1)})")[1]

    def set_probe_locations(self, function, points):
        """Replace the probeLocations of a probes function object of system/controlDict."""
        path = self.file("system", "controlDict")
        text = _read(path)
        old = self.function_entry(function, "probeLocations")
        start = text.find(old)
        if start < 0:
            raise CaseError(f"{path}: cannot rewrite the probeLocations of function '{function}'")
        written = "(" + " ".join(f"({' '.join(f'{v:g}' for v in p)})" for p in points) + ")"
        _write(path, text[:start] + written + text[start + len(old):])

    def patch_value(self, field, patch, time="0"):
        """The `value uniform ...` of a patch of a field file (e.g. 0/U inlet): a float or an
        (x, y, z) tuple."""
        path = self.file(time, field)
        body = sub_dict(sub_dict(_read(path), "boundaryField", path), patch, path)
        found = re.search(r"(?:^|\s)value\s+uniform\s+([^;]+);", body)
        if not found:
            raise CaseError(f"{path}: patch '{patch}' has no 'value uniform ...;'")
        value = found.group(1).strip()
        return vector(value) if value.startswith("(") else float(value)

    def _patch_span(self, field, patch, time):
        """(path, text, start, end) of a field file: its patch entry's body is text[start:end],
        between the braces."""
        path = self.file(time, field)
        text = _read(path)
        found = re.search(rf"(?m)^\s*{re.escape(patch)}\s*\{{", text)
        if not found:
            raise CaseError(f"{path}: no patch '{patch}'")
        depth, end = 1, found.end()
        while depth and end < len(text):
            depth += {"{": 1, "}": -1}.get(text[end], 0)
            end += 1
        return path, text, found.end(), end - 1

    def set_patch_value(self, field, patch, value, time="0"):
        """Set the `value uniform ...` of a patch of a field file; value a float or a tuple."""
        path, text, start, end = self._patch_span(field, patch, time)
        written = f"({' '.join(f'{v:g}' for v in value)})" if isinstance(value, (tuple, list)) else f"{value:g}"
        body, n = re.subn(r"(\bvalue\s+uniform\s+)[^;]+;", lambda m: f"{m.group(1)}{written};",
                          text[start:end], count=1)
        if n == 0:
            raise CaseError(f"{path}: patch '{patch}' has no 'value uniform ...;'")
        _write(path, text[:start] + body + text[end:])

    def set_patch_condition(self, field, patch, body, time="0"):
        """Replace a patch's whole entry in a field file with `body` (e.g. 'type noSlip;')."""
        path, text, start, end = self._patch_span(field, patch, time)
        _write(path, text[:start] + f" {body} " + text[end:])

    def porosity(self, name=None):
        """A Darcy-Forchheimer porous zone of the case's fvOptions (constant/ or system/):
        dict with 'zone' (its cellZone), 'd' (1/m^2) and 'f' (1/m) as (x, y, z); the first
        explicitPorositySource unless name is given; None when the case has no fvOptions."""
        paths = [p for p in (self.file("constant", "fvOptions"), self.file("system", "fvOptions"))
                 if os.path.exists(p)]
        if not paths:
            return None
        path = paths[0]
        text = _strip_comments(_read(path))
        if name is None:
            found = re.search(r"(?m)^\s*(\w+)\s*\{\s*type\s+explicitPorositySource\s*;", text)
            if not found:
                raise CaseError(f"{path}: no explicitPorositySource")
            name = found.group(1)
        body = sub_dict(text, name, path)
        coeffs = sub_dict(body, "DarcyForchheimerCoeffs", path)
        zone = re.search(r"cellZone\s+(\w+)\s*;", body)
        out = {"zone": zone.group(1) if zone else None}
        for key in ("d", "f"):
            found = re.search(rf"(?m)^\s*{key}\s+(\([^()]*\))\s*;", coeffs)
            if not found:
                raise CaseError(f"{path}: {name} has no '{key} (x y z);'")
            out[key] = vector(found.group(1))
        return out

    def grid(self):
        """The uniform grid of system/blockMeshDict (spacing of the first block; all blocks
        must share it, as the coupler requires)."""
        path = self.file("system", "blockMeshDict")
        text = _expand_variables(_strip_comments(_read(path)))
        scale = float(re.search(r"(?m)^\s*(?:convertToMeters|scale)\s+([^;]+);", text).group(1)) \
            if re.search(r"(?m)^\s*(?:convertToMeters|scale)\s", text) else 1.0
        points = [tuple(scale * c for c in p) for p in _vertices(path, text)]
        blocks = _blocks(text)
        if not blocks:
            raise CaseError(f"{path}: no hex blocks")
        first, cells, _ = blocks[0]
        lo = [min(points[v][a] for v in first) for a in range(3)]
        hi = [max(points[v][a] for v in first) for a in range(3)]
        spacing = [(hi[a] - lo[a]) / cells[a] for a in range(3)]
        origin = [min(p[a] for p in points) for a in range(3)]
        top = [max(p[a] for p in points) for a in range(3)]
        return Grid(origin, spacing, [round((top[a] - origin[a]) / spacing[a]) for a in range(3)])

    def _mesh_points(self):
        path = self.file("system", "blockMeshDict")
        text = _expand_variables(_strip_comments(_read(path)))
        scale = float(re.search(r"(?m)^\s*(?:convertToMeters|scale)\s+([^;]+);", text).group(1)) \
            if re.search(r"(?m)^\s*(?:convertToMeters|scale)\s", text) else 1.0
        return path, text, [tuple(scale * c for c in p) for p in _vertices(path, text)]

    def mesh_bounds(self):
        """((x, y, z) lowest, (x, y, z) highest) corner of system/blockMeshDict's vertices."""
        _, _, points = self._mesh_points()
        return (tuple(min(p[a] for p in points) for a in range(3)),
                tuple(max(p[a] for p in points) for a in range(3)))

    def block_bounds(self, zone):
        """(lowest, highest) corner of the blockMeshDict block that makes cellZone `zone`."""
        path, text, points = self._mesh_points()
        for vertices, _, name in _blocks(text):
            if name == zone:
                return (tuple(min(points[v][a] for v in vertices) for a in range(3)),
                        tuple(max(points[v][a] for v in vertices) for a in range(3)))
        raise CaseError(f"{path}: no block of zone '{zone}'")

    def scale_cells(self, axis, factor):
        """Multiply every block's cell count along axis (0, 1, 2) by factor (refine the grid)."""
        path = self.file("system", "blockMeshDict")

        text = _read(path)
        if re.search(r"hex\s*\([\d\s]+\)\s*\w*\s*\(\s*\$", text):
            raise CaseError(f"{path}: cell counts are macros; set them with set_dict_entries")

        def refine(m):
            counts = [int(n) for n in m.group(3).split()]
            counts[axis] = int(round(counts[axis] * factor))
            zone = f"{m.group(2)} " if m.group(2) else ""
            return f"hex ({m.group(1)}) {zone}({' '.join(map(str, counts))})"

        _write(path, re.sub(_HEX, refine, text))

    # coupling.yaml ------------------------------------------------------------------------
    def coupling(self):
        """coupling.yaml as nested dicts."""
        path = self.file("coupling.yaml")
        return parse_yaml(_read(path), path, CaseError) or {}

    def coupling_value(self, dotted, default=None):
        node = self.coupling()
        for key in dotted.split("."):
            if not isinstance(node, dict) or key not in node:
                return default
            node = node[key]
        return node

    def set_coupling(self, dotted, value):
        """Set coupling.yaml's key (e.g. 'coupling.void_fraction.method'), keeping comments;
        missing sections are added."""
        set_yaml_value(self.file("coupling.yaml"), dotted, value)

    # Particles of coupling.yaml ------------------------------------------------------------
    def particle_diameters(self):
        """The particle sizes of coupling.yaml's particles.diameter (a number or a list), ascending."""
        d = self.coupling_value("particles.diameter")
        if d is None:
            raise CaseError(f"{self.file('coupling.yaml')}: no particles.diameter")
        source = Source(self.file("coupling.yaml"), CaseError)
        return sorted(source.number("particles.diameter", x, 0.0, low_open=True, what="a diameter in m above 0")
                      for x in (d if isinstance(d, list) else [d]))

    def particle_density(self):
        """coupling.yaml's particles.density (kg/m^3)."""
        return Source(self.file("coupling.yaml"), CaseError).number(
            "particles.density", self.coupling_value("particles.density"), 0.0, low_open=True,
            what="a density in kg/m^3 above 0")

    def particle_properties(self):
        """(diameter, density) of a monodisperse case's coupling.yaml particles section."""
        diameters = self.particle_diameters()
        if self.coupling_value("particles.density") is None:
            raise CaseError(f"{self.file('coupling.yaml')}: no particles.density")
        if len(diameters) != 1:
            raise CaseError(f"{self.file('coupling.yaml')}: particles.diameter lists {len(diameters)} sizes;"
                            " this needs a monodisperse case")
        return diameters[0], self.particle_density()

    # DEM -----------------------------------------------------------------------------------
    def dem_script(self):
        script = self.coupling_value("dem.script")
        if script is None:
            raise CaseError(f"{self.file('coupling.yaml')}: no dem.script"
                            + (": the hard-sphere engine (dem.engine: hard_sphere) runs without a LIGGGHTS script"
                               if self.hard_sphere() else ""))
        return self.file(script)

    def dem(self):
        """The case's DEM script (coupling.yaml dem.script) as a DemScript."""
        return DemScript(self.dem_script())

    def dem_command(self, name, script=None):
        """Words of the first `name` command of the DEM script."""
        path = script or self.dem_script()
        for line in _read(path).splitlines():
            words = line.split("#", 1)[0].split()
            if words and words[0] == name:
                return words
        raise CaseError(f"{path}: no '{name}' command")

    def dem_time_step(self):
        return float(self.dem_command("timestep")[1])

    def set_time_steps(self, dem=None, gas=None):
        """DEM step (the DEM script's `timestep`) and gas step (controlDict deltaT), each kept
        when None; the coupling interval (dem.coupling_interval, when the case states it) is
        their ratio, which must be a whole number. The hard-sphere engine has no DEM step: only
        the gas step is set."""
        if self.hard_sphere():
            if dem is not None:
                raise CaseError(f"{self.path}: a DEM step of {dem:g} s for the hard-sphere engine, which has none "
                                "(its flight between flow steps is event driven): give the gas step only")
            if gas is not None:
                if not float(gas) > 0:
                    raise CaseError(f"{self.path}: gas step {gas:g} s must be positive")
                self.set_control(deltaT=f"{float(gas):.12g}")
            return
        dem = self.dem_time_step() if dem is None else float(dem)
        gas = self.delta_t() if gas is None else float(gas)
        if not (dem > 0 and gas > 0):
            raise CaseError(f"{self.path}: DEM step {dem:g} s and gas step {gas:g} s must both be positive")
        interval = gas / dem
        if abs(interval - round(interval)) > 1e-6 * interval or round(interval) < 1:
            raise CaseError(f"{self.path}: gas step {gas:g} s is not a whole number of DEM steps {dem:g} s "
                            f"({interval:.6g}); choose steps whose ratio is whole")
        script = self.dem_script()
        text, n = re.subn(r"(?m)^timestep\s+\S+", f"timestep        {dem:.12g}", _read(script))
        if n != 1:
            raise CaseError(f"{script}: expected one 'timestep' command, found {n}")
        _write(script, text)
        if self.coupling_value("dem.coupling_interval") is not None:  # left out, the solver derives it
            self.set_coupling("dem.coupling_interval", int(round(interval)))
        self.set_control(deltaT=f"{gas:.12g}")

    def hard_sphere(self):
        """Whether coupling.yaml runs the hard-sphere engine (dem.engine: hard_sphere)."""
        return self.coupling_value("dem.engine", "liggghts") == "hard_sphere"

    def particles_file(self):
        """The data file the particle engine starts from, relative to the case: the DEM
        script's read_data, or the hard-sphere engine's dem.particles."""
        if self.hard_sphere():
            return self.coupling_value("dem.particles")
        return self.dem_command("read_data")[1]

    def particles(self, data_file=None):
        """Particles of the engine's data file (atom style granular): dict of lists id, type,
        diameter, density, x, y, z."""
        return read_data_file(data_file or self.file(self.particles_file()))

    def particle_count(self):
        return len(self.particles()["id"])


def sphere_volume(d):
    return math.pi * d ** 3 / 6.0


def set_yaml_value(path, dotted, value):
    """Set a key of a block-style YAML file (two-space indents) in place, keeping comments."""
    keys = dotted.split(".")
    lines = _read(path).splitlines()
    text_value = yaml.safe_dump(value, default_flow_style=True).strip()
    if text_value.endswith("\n..."):
        text_value = text_value[:-4].strip()
    start, end = 0, len(lines)
    for level, key in enumerate(keys):
        indent = "  " * level
        pattern = re.compile(rf"^{indent}{re.escape(key)}:(\s|$)")
        found = next((i for i in range(start, end) if pattern.match(lines[i])), None)
        last = level == len(keys) - 1
        if found is None:
            new = [f"{'  ' * (level + k)}{keys[level + k]}:" for k in range(len(keys) - level)]
            new[-1] += f" {text_value}"
            lines[end:end] = new
            break
        if last:
            comment = re.search(r"\s+#.*$", lines[found])
            lines[found] = f"{indent}{key}: {text_value}" + (comment.group(0) if comment else "")
            # the old value's own lines (a block list or mapping under the key) go with it
            rest = found + 1
            while rest < len(lines) and lines[rest].strip() and (
                    lines[rest].startswith(indent + " ") or lines[rest].startswith(indent + "- ")):
                del lines[rest]
            break
        start = found + 1
        end = next((i for i in range(start, len(lines))
                    if lines[i].strip() and not lines[i].startswith("  " * (level + 1))
                    and not lines[i].lstrip().startswith("#")), len(lines))
    _write(path, "\n".join(lines) + "\n")
