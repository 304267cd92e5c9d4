"""Outputs of a case, joined over restarts.

A resumed run writes its OpenFOAM-style series under postProcessing/<name>/<start time>/; the
rows an interrupted run wrote after the time it was resumed from are superseded. LIGGGHTS
fix-print files and dumps are appended to on a resume: a time that comes again rewinds them.
"""
import glob
import os
import re

from tfdem.errors import Reported


class OutputError(Reported):
    """An expected output is missing or malformed; the message names the file."""


def _number(token):
    try:
        return float(token)
    except ValueError:
        return token


def _numbers(line):
    """Values of a row: floats, vectors '(x y z)' as tuples, names as text."""
    tokens = line.replace("(", " ( ").replace(")", " ) ").split()
    values, i = [], 0
    while i < len(tokens):
        if tokens[i] == "(":
            end = tokens.index(")", i)
            values.append(tuple(float(t) for t in tokens[i + 1:end]))
            i = end + 1
        else:
            values.append(_number(tokens[i]))
            i += 1
    return values


def _rows(path):
    with open(path) as f:
        return [_numbers(line) for line in f if line.strip() and not line.lstrip().startswith("#")]


def joined_series(case_path, name, filename):
    """(t, [values]) rows of postProcessing/<name>/<start>/<filename> over every start time,
    in time order; rows of a segment after the next segment's start are superseded."""
    folders = glob.glob(os.path.join(case_path, "postProcessing", name, "*", filename))
    if not folders:
        raise OutputError(f"{os.path.join(case_path, 'postProcessing', name)}: no */{filename}")
    segments = sorted(((float(p.split(os.sep)[-2]), p) for p in folders))
    stem, ext = os.path.splitext(filename)
    for _, path in segments:
        pattern = re.compile(rf"{re.escape(stem)}_[0-9][0-9.e+-]*{re.escape(ext)}$")
        stale = [n for n in os.listdir(os.path.dirname(path)) if pattern.match(n)]
        if stale:
            raise OutputError(f"{os.path.dirname(path)} holds {filename} beside {stale[0]}: "
                              "OpenFOAM renames a second run's file when the first one's is still there, so "
                              "this folder mixes two runs. Clean the case (its Allclean, or remove "
                              "postProcessing) and run again")
    rows = []
    for k, (_, path) in enumerate(segments):
        until = segments[k + 1][0] if k + 1 < len(segments) else float("inf")
        rows.extend((r[0], r[1:]) for r in _rows(path) if r[0] <= until * (1 + 1e-12) + 1e-15)
    return rows


def probes(case_path, name="pressure", field="p"):
    """(t, [value at each probe]) of an OpenFOAM probes function object, joined."""
    return joined_series(case_path, name, field)


def pressure_series(case_path, name):
    """(t, p) of a pressure function object, joined: a surfaceFieldValue's area average (its
    surfaceFieldValue.dat), or the mean of a probes object's probes."""
    if glob.glob(os.path.join(case_path, "postProcessing", name, "*", "surfaceFieldValue.dat")):
        return [(t, values[0]) for t, values in joined_series(case_path, name, "surfaceFieldValue.dat")]
    return [(t, sum(values) / len(values)) for t, values in probes(case_path, name, "p")]


def probe_locations(case_path, name="pressure", field="p"):
    """Probe locations from the header of the first segment."""
    path = sorted(glob.glob(os.path.join(case_path, "postProcessing", name, "*", field)))[0]
    with open(path) as f:
        return [tuple(float(v) for v in m.group(1).split())
                for m in (re.match(r"#\s*Probe\s+\d+\s*\(([^)]*)\)", line) for line in f) if m]


def particle_statistics(case_path):
    """Columns of the coupler's particle statistics (postProcessing/tfdemParticles): dict of
    lists t, particles, mass, mean_height, bulk_coordination, multicontact, and for a
    bidisperse bed segregation (seed 001 eq. 49)."""
    rows = joined_series(case_path, "tfdemParticles", "particles.dat")
    keys = ("particles", "mass", "mean_height", "bulk_coordination", "multicontact", "segregation")
    out = {"t": [r[0] for r in rows]}
    for k, key in enumerate(keys):
        if rows and len(rows[0][1]) > k:
            out[key] = [r[1][k] for r in rows]
    return out


def fix_print(path):
    """(t, [values]) rows of a LIGGGHTS `fix print` file (or of a `fix ave/time` file, whose
    first column is the step); a time that comes again (a resumed run appending) replaces the
    rows from it on."""
    out = []
    for row in _rows(path):
        while out and out[-1][0] >= row[0]:
            out.pop()
        out.append((row[0], row[1:]))
    return out


def dump_frames(path):
    """{timestep: (column names, rows)} of a LIGGGHTS custom dump; a timestep written again
    (a resumed run appending) replaces the earlier frames from it on."""
    frames = {}
    with open(path) as f:
        lines = f.read().splitlines()
    i = 0
    while i < len(lines):
        if lines[i].startswith("ITEM: TIMESTEP"):
            step = int(lines[i + 1])
            count = int(lines[i + 3])
            columns = lines[i + 8].split()[2:]
            rows = [[float(v) for v in line.split()] for line in lines[i + 9:i + 9 + count]]
            for later in [s for s in frames if s >= step]:
                del frames[later]
            frames[step] = (columns, rows)
            i += 9 + count
        else:
            i += 1
    return frames


def dump_track(case_path, column, dump_id=None, atom=0):
    """(t, value) of one atom (the `atom`-th row of each frame; sort the dump by id) in a
    LIGGGHTS custom dump of the case's DEM script: the first `dump` command, or dump_id; t =
    step x the script's timestep."""
    from tfdem.case import Case

    dem = Case(case_path).dem()
    words = dem.command("dump", dump_id) if dump_id else dem.command("dump")
    path = os.path.join(case_path, words[5])
    dt = dem.time_step()
    out = []
    for step, (columns, rows) in sorted(dump_frames(path).items()):
        if column not in columns:
            raise OutputError(f"{path}: no column '{column}' (has {' '.join(columns)})")
        out.append((step * dt, rows[atom][columns.index(column)]))
    return out


def vtk_particles(path):
    """Arrays of a particle file the coupler writes (VTK/particles_<time>.vtk): dict with
    'position' and every POINT_DATA field (vectors as (x, y, z) tuples)."""
    with open(path) as f:
        tokens = f.read().split()
    out, i = {}, 0
    n = None
    while i < len(tokens):
        word = tokens[i]
        if word == "POINTS":
            n = int(tokens[i + 1])
            values = [float(v) for v in tokens[i + 3:i + 3 + 3 * n]]
            out["position"] = [tuple(values[3 * k:3 * k + 3]) for k in range(n)]
            i += 3 + 3 * n
        elif word == "SCALARS":
            name, kind = tokens[i + 1], tokens[i + 2]
            start = tokens.index("LOOKUP_TABLE", i) + 2
            cast = int if kind == "int" else float
            out[name] = [cast(v) for v in tokens[start:start + n]]
            i = start + n
        elif word == "VECTORS":
            name = tokens[i + 1]
            values = [float(v) for v in tokens[i + 3:i + 3 + 3 * n]]
            out[name] = [tuple(values[3 * k:3 * k + 3]) for k in range(n)]
            i += 3 + 3 * n
        else:
            i += 1
    if n is None:
        raise OutputError(f"{path}: no POINTS")
    return out


def times(case_path):
    """Time directories of a case (numbers), sorted."""
    out = []
    for name in os.listdir(case_path):
        try:
            value = float(name)
        except ValueError:
            continue
        if os.path.isdir(os.path.join(case_path, name)):
            out.append((value, name))
    return [name for _, name in sorted(out)]


def field(case_path, time_name, name):
    """Internal values of an ASCII OpenFOAM volume field: a list of floats or of (x, y, z);
    a uniform field gives a one-element list."""
    path = os.path.join(case_path, time_name, name)
    with open(path) as f:
        text = f.read()
    uniform = re.search(r"internalField\s+uniform\s+([^;]+);", text)
    if uniform:
        value = uniform.group(1).strip()
        return [tuple(float(v) for v in value.strip("()").split())] if value.startswith("(") else [float(value)]
    found = re.search(r"internalField\s+nonuniform\s+List<(\w+)>\s*(\d+)\s*\(", text)
    if not found:
        raise OutputError(f"{path}: no internalField")
    count, body = int(found.group(2)), text[found.end():]
    if found.group(1) == "scalar":
        return [float(v) for v in body.split(None, count)[:count]]
    values = re.findall(r"\(([^()]*)\)", body)[:count]
    return [tuple(float(v) for v in value.split()) for value in values]


def boundary_values(case_path, time_name, name, patch):
    """Values of a patch of an ASCII OpenFOAM field (its `value` entry): a list of floats or of
    (x, y, z); a uniform value gives a one-element list."""
    path = os.path.join(case_path, time_name, name)
    with open(path) as f:
        text = f.read()
    found = re.search(rf"\n\s*{re.escape(patch)}\s*\{{(.*?)\n\s*\}}", text, flags=re.S)
    if not found:
        raise OutputError(f"{path}: no patch '{patch}'")
    body = found.group(1)
    uniform = re.search(r"value\s+uniform\s+([^;]+);", body)
    if uniform:
        value = uniform.group(1).strip()
        return [tuple(float(v) for v in value.strip("()").split())] if value.startswith("(") else [float(value)]
    listed = re.search(r"value\s+nonuniform\s+List<(\w+)>\s*(\d+)\s*\(", body)
    if not listed:
        raise OutputError(f"{path}: patch '{patch}' has no value")
    count, rest = int(listed.group(2)), body[listed.end():]
    if listed.group(1) == "scalar":
        return [float(v) for v in rest.replace(")", " ").split()[:count]]
    return [tuple(float(v) for v in value.split()) for value in re.findall(r"\(([^()]*)\)", rest)[:count]]


def latest_set(case_path, name, filename):
    """Rows (lists of floats) of a `sets` function object's raw file at its latest time,
    postProcessing/<name>/<time>/<filename>."""
    paths = glob.glob(os.path.join(case_path, "postProcessing", name, "*", filename))
    if not paths:
        raise OutputError(f"{os.path.join(case_path, 'postProcessing', name)}: no */{filename}")
    path = max(paths, key=lambda p: float(p.split(os.sep)[-2]))
    return [[float(v) for v in line.split()] for line in open(path)
            if line.strip() and not line.lstrip().startswith("#")]


def log_numbers(path, pattern):
    """Floats of the groups of the last match of a regular expression in a log, or None."""
    with open(path, errors="replace") as f:
        found = None
        for found in re.finditer(pattern, f.read()):
            pass
    return [float(g) for g in found.groups()] if found else None


TIMING_PARTS = ("DEM", "locate+map", "forces", "gas", "statistics", "checkpoints")


def solver_timing(log):
    """{part: seconds} of the solver's last `TFDEM timing:` line (the first rank's wall time in
    each part); OutputError when the log has none (the run did not finish)."""
    pattern = r"TFDEM timing: " + r", ".join(re.escape(p) + r" (\S+) s" for p in TIMING_PARTS)
    found = log_numbers(log, pattern)
    if found is None:
        raise OutputError(f"{log}: no 'TFDEM timing:' line (the run did not finish)")
    return dict(zip(TIMING_PARTS, found))
