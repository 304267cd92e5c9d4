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


class CaseError(Exception):
    """A case file lacks what is asked of it; the message names the file and the entry."""


def _read(path):
    try:
        with open(path) as f:
            return f.read()
    except OSError as e:
        raise CaseError(f"{path}: cannot read ({e.strerror})") from None


def _write(path, text):
    with open(path, "w") as f:
        f.write(text)


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


def _expand_variables(text):
    """Top-level ``name value;`` entries substituted for ``$name`` (blockMeshDict macros)."""
    values = dict(re.findall(r"(?m)^\s*([A-Za-z]\w*)\s+([-+.\w]+)\s*;", text))
    return re.sub(r"\$(\w+)", lambda m: values.get(m.group(1), m.group(0)), text)


def _blocks(text):
    """[(vertex indices, (nx, ny, nz))] of a blockMeshDict's hex blocks."""
    return [([int(v) for v in m.group(1).split()], tuple(int(n) for n in m.group(2).split()))
            for m in re.finditer(r"hex\s*\(([\d\s]+)\)\s*\(([\d\s]+)\)", text)]


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
        first, cells = blocks[0]
        lo = [min(points[v][a] for v in first) for a in range(3)]
        hi = [max(points[v][a] for v in first) for a in range(3)]
        spacing = [(hi[a] - lo[a]) / cells[a] for a in range(3)]
        origin = [min(p[a] for p in points) for a in range(3)]
        top = [max(p[a] for p in points) for a in range(3)]
        return Grid(origin, spacing, [round((top[a] - origin[a]) / spacing[a]) for a in range(3)])

    def scale_cells(self, axis, factor):
        """Multiply every block's cell count along axis (0, 1, 2) by factor (refine the grid)."""
        path = self.file("system", "blockMeshDict")

        text = _read(path)
        if re.search(r"hex\s*\([\d\s]+\)\s*\(\s*\$", text):
            raise CaseError(f"{path}: cell counts are macros; set them with set_dict_entries")

        def refine(m):
            counts = [int(n) for n in m.group(2).split()]
            counts[axis] = int(round(counts[axis] * factor))
            return f"hex ({m.group(1)}) ({' '.join(map(str, counts))})"

        _write(path, re.sub(r"hex\s*\(([\d\s]+)\)\s*\(([\d\s]+)\)", refine, text))

    # coupling.yaml ------------------------------------------------------------------------
    def coupling(self):
        """coupling.yaml as nested dicts."""
        return yaml.safe_load(_read(self.file("coupling.yaml"))) or {}

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

    # DEM -----------------------------------------------------------------------------------
    def dem_script(self):
        return self.file(self.coupling_value("dem.script"))

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

    def particles(self, data_file=None):
        """Particles of the DEM script's read_data file (atom style granular): dict of lists
        id, type, diameter, density, x, y, z."""
        path = data_file or self.file(self.dem_command("read_data")[1])
        return read_data_file(path)

    def particle_count(self):
        return len(self.particles()["id"])


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
            break
        start = found + 1
        end = next((i for i in range(start, len(lines))
                    if lines[i].strip() and not lines[i].startswith("  " * (level + 1))
                    and not lines[i].lstrip().startswith("#")), len(lines))
    _write(path, "\n".join(lines) + "\n")
