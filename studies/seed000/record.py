"""A run's small outputs, kept in the repository (results/<run>/) so that every number of the
report can be traced to a file and made again without the run folders (meshes, fields and
particle files stay out of the repository):

    run.json       the run's grid (uniform cells), cost (and the coupled solver's split of it,
                   `TFDEM timing`, when its segments printed one) and the map windows kept
    pressure.csv   t, Delta p at 20 cm (every statistics interval); its header names the
                   lower level (DP_HEADERS: the inlet, or the bed's bottom row of cells)
    particles.csv  t, mean particle height, bulk coordination number, multicontact ratio,
                   particle count (TFM: t, the solids' mean height)
    maps.csv       the time-averaged maps (solids fraction; TF-DEM also the contact and drag
                   force per cell; the granular temperature when the run sampled it) over each
                   window the report uses, one row of cells a line

report.py writes a Record from every finished run and computes its numbers from the Record
read back, so the numbers from runs/ and from a clone holding only results/ are the same.
"""
import csv
import json
import os

import numpy

META, PRESSURE, PARTICLES, MAPS = "run.json", "pressure.csv", "particles.csv", "maps.csv"
PARTICLE_COLUMNS = ("mean_height", "bulk_coordination", "multicontact", "particles")
TFDEM_MAPS, TFM_MAPS = ("solids", "contact", "drag"), ("solids",)
# pressure.csv's Delta p column per tfdem.bed.DP_FROM: the header says where it was measured
DP_HEADERS = {"inlet": "dp 20 cm (Pa): p(inlet) - p(20 cm above it)",
              "bottom_row": "dp 20 cm (Pa): p(bottom row) - p(row 20 cm above)"}


class RecordError(Exception):
    """A run's record is missing or malformed, naming the run and the file."""


def window_key(start, end):
    return f"{start:g}-{end:g}"


class Record:
    """A run's series (p_t, dp; particles: t and PARTICLE_COLUMNS, or the TFM's height
    series), its window-averaged maps, grid and cost."""

    def __init__(self, name, meta, pressure, heights, maps):
        self.name, self.meta = name, meta
        self.tfm = bool(meta["tfm"])
        self.wall, self.cpu = meta["wall_seconds"], meta["cpu_seconds"]
        nx, ny = meta["grid"]["counts"]
        (x0, y0), (dx, dy) = meta["grid"]["origin"], meta["grid"]["spacing"]
        self.shape = (ny, nx)
        self.width = nx * dx
        self.x, self.y = numpy.meshgrid(x0 + dx * (numpy.arange(nx) + 0.5), y0 + dy * (numpy.arange(ny) + 0.5))
        self.p_t, self.dp = pressure
        self.dp_from = meta["dp_from"]
        self.particles = heights
        self.maps = maps

    # From a run folder ----------------------------------------------------------------------
    @classmethod
    def from_outputs(cls, d, windows):
        """The record of a finished run read as tfdem.bed.BedOutputs `d` (with name, tfm, wall,
        cpu), its maps averaged over each (start, end) of `windows`."""
        grid = d.grid
        meta = {"name": d.name, "tfm": d.tfm, "wall_seconds": d.wall, "cpu_seconds": d.cpu,
                "grid": {"counts": [grid.counts[0], grid.counts[1]], "origin": [grid.origin[0], grid.origin[1]],
                         "spacing": [grid.spacing[0], grid.spacing[1]]},
                "windows": [list(w) for w in windows], "dp_from": d.dp_from}
        if getattr(d, "timing", None):
            meta["timing"] = d.timing
        if d.tfm:
            t, h = d.mean_height()
            heights = {"t": numpy.asarray(t), "mean_height": numpy.asarray(h)}
        else:
            heights = {k: numpy.asarray(d.particles[k]) for k in ("t",) + PARTICLE_COLUMNS}
        fields = (TFM_MAPS if d.tfm else TFDEM_MAPS) + (("theta",) if d.theta is not None else ())
        maps = {window_key(*w): {f: d.field_average(getattr(d, f), *w) for f in fields} for w in windows}
        record = cls(d.name, meta, (numpy.asarray(d.p_t), numpy.asarray(d.dp)), heights, maps)
        centres = numpy.array([c[:2] for c in grid.centres()[:grid.counts[0] * grid.counts[1]]])  # the front layer: x, y
        if not numpy.allclose(centres[:, 0], record.x.ravel()) or not numpy.allclose(centres[:, 1], record.y.ravel()):
            raise RecordError(f"{d.name}: its grid is not uniform; a record keeps only counts, origin and spacing")
        return record

    # Files ------------------------------------------------------------------------------------
    def write(self, folder):
        os.makedirs(folder, exist_ok=True)
        with open(os.path.join(folder, META), "w") as f:  # dp_from: pressure.csv's header says it
            json.dump({k: v for k, v in self.meta.items() if k != "dp_from"}, f, indent=1)
        _write_csv(os.path.join(folder, PRESSURE), ["t (s)", DP_HEADERS[self.dp_from]],
                   zip(self.p_t, self.dp), ("{:.6g}", "{:.6g}"))
        if self.tfm:
            _write_csv(os.path.join(folder, PARTICLES), ["t (s)", "solids mean height (m)"],
                       zip(self.particles["t"], self.particles["mean_height"]), ("{:.6g}", "{:.6g}"))
        else:
            p = self.particles
            _write_csv(os.path.join(folder, PARTICLES),
                       ["t (s)", "mean particle height (m)", "bulk coordination number", "multicontact ratio",
                        "particles"], zip(p["t"], *(p[k] for k in PARTICLE_COLUMNS)),
                       ("{:.6g}", "{:.6g}", "{:.6g}", "{:.6g}", "{:.0f}"))
        rows = ([start, end, field, row] + list(values[row])
                for key, fields in self.maps.items() for start, end in [map(float, key.split("-"))]
                for field, values in fields.items() for row in range(values.shape[0]))
        header = ["window start (s)", "window end (s)", "field", "row"] + [f"x = {x:.4g} m" for x in self.x[0]]
        _write_csv(os.path.join(folder, MAPS), header, rows,
                   ("{:g}", "{:g}", "{}", "{}") + ("{:.5g}",) * self.shape[1])

    @classmethod
    def read(cls, folder, name):
        path = os.path.join(folder, META)
        try:
            with open(path) as f:
                meta = json.load(f)
        except OSError as e:
            raise RecordError(f"{name}: cannot read {path} ({e.strerror})") from None
        except ValueError as e:
            raise RecordError(f"{name}: {path} is not JSON ({e})") from None
        pressure = _read_columns(os.path.join(folder, PRESSURE), name, 2)
        meta["dp_from"] = _dp_from(os.path.join(folder, PRESSURE), name)
        columns = ("t", "mean_height") if meta["tfm"] else ("t",) + PARTICLE_COLUMNS
        heights = dict(zip(columns, _read_columns(os.path.join(folder, PARTICLES), name, len(columns))))
        return cls(name, meta, tuple(pressure), heights, _read_maps(os.path.join(folder, MAPS), name, meta))

    # What the report asks ---------------------------------------------------------------------
    @property
    def extent(self):
        """(left, right, bottom, top) of the grid in metres, as matplotlib's imshow takes it."""
        (x0, y0), (dx, dy) = self.meta["grid"]["origin"], self.meta["grid"]["spacing"]
        return x0, x0 + self.shape[1] * dx, y0, y0 + self.shape[0] * dy

    def mean_height(self):
        """(t, mean particle height in m; TFM: the solids' centroid height)."""
        return self.particles["t"], self.particles["mean_height"]

    def window_map(self, field, start, end):
        """The `field` map ("solids", "contact", "drag", "theta") averaged over [start, end] s, as (rows,
        columns); RecordError when the record does not keep that window or field."""
        key = window_key(start, end)
        if key not in self.maps or field not in self.maps[key]:
            raise RecordError(f"{self.name}: no {field} map over {key} s in its record (it keeps "
                              f"{', '.join(self.maps) or 'none'}); re-make it from the run folder")
        return self.maps[key][field]


def _write_csv(path, header, rows, formats):
    with open(path, "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(header)
        for row in rows:
            w.writerow([fmt.format(v) for fmt, v in zip(formats, row)])


def _dp_from(path, name):
    """Where the record's Delta p was measured from (a DP_HEADERS key), read from its header."""
    with open(path, newline="") as f:
        header = next(csv.reader(f), [])
    found = [key for key, text in DP_HEADERS.items() if header[1:2] == [text]]
    if not found:
        raise RecordError(f"{name}: {path}: Delta p column {header[1:2]} is none of "
                          + "; ".join(repr(t) for t in DP_HEADERS.values()))
    return found[0]


def _read_columns(path, name, count):
    try:
        with open(path, newline="") as f:
            rows = list(csv.reader(f))[1:]
    except OSError as e:
        raise RecordError(f"{name}: cannot read {path} ({e.strerror})") from None
    try:
        values = numpy.array(rows, dtype=float)
    except ValueError as e:
        raise RecordError(f"{name}: {path}: not a table of numbers ({e})") from None
    if values.ndim != 2 or values.shape[1] != count or values.shape[0] == 0:
        raise RecordError(f"{name}: {path}: expected rows of {count} numbers, got shape {values.shape}")
    return list(values.T)


def _read_maps(path, name, meta):
    nx, ny = meta["grid"]["counts"]
    try:
        with open(path, newline="") as f:
            rows = list(csv.reader(f))[1:]
    except OSError as e:
        raise RecordError(f"{name}: cannot read {path} ({e.strerror})") from None
    maps = {}
    for line, row in enumerate(rows, 2):
        if len(row) != 4 + nx:
            raise RecordError(f"{name}: {path} line {line}: {len(row)} columns, expected {4 + nx}")
        fields = maps.setdefault(window_key(float(row[0]), float(row[1])), {})
        fields.setdefault(row[2], numpy.full((ny, nx), numpy.nan))[int(row[3])] = [float(v) for v in row[4:]]
    holes = [f"{key} {field}" for key, fields in maps.items() for field, v in fields.items() if numpy.isnan(v).any()]
    if holes:
        raise RecordError(f"{name}: {path}: rows missing in the maps {', '.join(holes)}")
    return maps
