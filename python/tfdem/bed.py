"""A fluidized bed's measured signals, the same for every run that compares beds (the seed 000
study, the speed-against-error sweeps): the solids fraction at every cell centre, p on the
bottom row of cells and on the row 20 cm above it (Delta p at 20 cm, seed 000 Fig. 3), and
the coupler's particle statistics.

write_bed_probes() adds the function objects to a case's controlDict; BedOutputs reads what
they wrote, joined over resumes, as arrays.
"""
import re

import numpy

from tfdem.outputs import joined_series, particle_statistics

DP_HEIGHT = 0.2  # m: Delta p between the bottom row of cells and the row this far above it
FIELDS = "studyFields"
PRESSURE = "studyPressure"
COUPLED_FIELDS = ("voidFraction", "contactForceByWeight", "dragForceByWeight")
TFM_FIELDS = ("alpha.particles",)


def write_bed_probes(case, field_interval, pressure_interval, tfm=False):
    """Replace the functions of `case`'s controlDict by the bed probes: every field of the maps
    at every cell centre every field_interval, p on the two rows every pressure_interval (s).
    The coupled solver samples every so many gas steps; twoPhaseEulerFoam (adjustable step)
    at run times."""
    grid = case.grid()
    centres = grid.centres()
    z = grid.origin[2] + 0.5 * grid.spacing[2]
    bottom = grid.origin[1] + 0.5 * grid.spacing[1]
    rows = [(x, y) for y in (bottom, bottom + DP_HEIGHT) for x, _, _ in centres[:grid.counts[0]]]
    fields = TFM_FIELDS if tfm else COUPLED_FIELDS
    if tfm:
        control = lambda dt: f"writeControl adjustableRunTime; writeInterval {dt:.10g};"
    else:
        steps = lambda dt: max(1, int(round(dt / case.delta_t())))
        control = lambda dt: f"writeControl timeStep; writeInterval {steps(dt)};"
    points = "\n".join(f"            ({x:.10g} {y:.10g} {z:.10g})" for x, y, _ in centres)
    row_points = "\n".join(f"            ({x:.10g} {y:.10g} {z:.10g})" for x, y in rows)
    block = (
        "functions\n{\n"
        "    // tfdem.bed: every cell centre (maps) and two rows of cells (Delta p at 20 cm)\n"
        f"    {FIELDS}\n    {{\n        type probes; libs (\"libsampling.so\");\n"
        f"        {control(field_interval)}\n        fields ({' '.join(fields)});\n"
        f"        probeLocations\n        (\n{points}\n        );\n    }}\n"
        f"    {PRESSURE}\n    {{\n        type probes; libs (\"libsampling.so\");\n"
        f"        {control(pressure_interval)}\n        fields (p);\n"
        f"        probeLocations\n        (\n{row_points}\n        );\n    }}\n"
        "}\n")
    path = case.file("system", "controlDict")
    text = open(path).read()
    start = re.search(r"(?m)^functions\s*\n?\s*\{", text)
    text = (text[:start.start()] if start else text) + block
    open(path, "w").write(text)


class BedOutputs:
    """What a bed run wrote, as arrays: field_t and solids (samples x cells), p_t and dp, and
    for the coupled solver the contact and drag force maps and the particle statistics."""

    def __init__(self, case, tfm=False):
        self.case, self.tfm = case, tfm
        self.grid = case.grid()
        nx, ny = self.grid.counts[0], self.grid.counts[1]
        self.shape = (ny, nx)
        self.y = numpy.array([c[1] for c in self.grid.centres()]).reshape(self.shape)
        path = case.path
        rows = joined_series(path, FIELDS, TFM_FIELDS[0] if tfm else COUPLED_FIELDS[0])
        self.field_t = numpy.array([r[0] for r in rows])
        values = numpy.array([r[1] for r in rows])
        self.solids = values if tfm else 1.0 - values
        if not tfm:
            self.contact = numpy.array([r[1] for r in joined_series(path, FIELDS, "contactForceByWeight")])
            self.drag = numpy.array([r[1] for r in joined_series(path, FIELDS, "dragForceByWeight")])
            self.particles = particle_statistics(path)
        p = joined_series(path, PRESSURE, "p")
        self.p_t = numpy.array([r[0] for r in p])
        rows_p = numpy.array([r[1] for r in p])
        self.dp = rows_p[:, :nx].mean(axis=1) - rows_p[:, nx:].mean(axis=1)

    def mean_height(self):
        """(t, mean particle height in m): the particles' (coupled) or the solids' centroid
        height sum(y alpha_s) / sum(alpha_s) on the cells (TFM, as Ref. 26 of seed 000)."""
        if not self.tfm:
            return numpy.array(self.particles["t"]), numpy.array(self.particles["mean_height"])
        weights = self.solids
        return self.field_t, (weights * self.y.ravel()).sum(axis=1) / weights.sum(axis=1)

    def field_average(self, values, start, end):
        """Time average over [start, end] s of a sampled map, as (rows, columns)."""
        pick = (self.field_t >= start - 1e-9) & (self.field_t <= end + 1e-9)
        if not pick.any():
            raise ValueError(f"{self.case.path}: no field samples in [{start}, {end}] s")
        return values[pick].mean(axis=0).reshape(self.shape)

    def field_at(self, values, t):
        """The sampled map nearest to time t, as (rows, columns)."""
        return values[int(numpy.argmin(numpy.abs(self.field_t - t)))].reshape(self.shape)


def to_grid(field, shape):
    """A (rows, columns) map averaged in blocks onto a coarser (rows, columns) shape whose
    counts divide it (a refined run's map on the coarse grid)."""
    ry, rx = field.shape[0] // shape[0], field.shape[1] // shape[1]
    if ry * shape[0] != field.shape[0] or rx * shape[1] != field.shape[1]:
        raise ValueError(f"a {field.shape} map does not divide into {shape} blocks")
    return field.reshape(shape[0], ry, shape[1], rx).mean(axis=(1, 3))


def l1_difference(a, b, rows=None):
    """Mean |a - b| over the cells of two maps on one grid (after to_grid), over the first
    `rows` rows when given (e.g. the bed, not the empty freeboard)."""
    if rows is not None:
        a, b = a[:rows], b[:rows]
    return float(numpy.abs(a - b).mean())
