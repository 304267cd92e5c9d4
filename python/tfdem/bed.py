"""A fluidized bed's measured signals, the same for every run that compares beds (the seed 000
study, the speed-against-error sweeps, `tfdem stats`): the solids fraction at every cell
centre, p at two fixed heights, the bed's floor (the inlet, or the top of a distributor
plate's cell zone) and DP_HEIGHT above it (Delta p at 20 cm above the inlet, seed 000 Fig. 3;
another height for another column), and the coupler's particle statistics.

write_bed_probes() adds the function objects to a case's controlDict; BedOutputs reads what
they wrote, joined over resumes, as arrays. Any layout: one layer, a few cells deep or 3-D.
The maps are sampled at every cell centre and averaged over the depth (the z cells of each
x, y column). p is sampled at every cell centre of the rows either side of each fixed height
(across the width and the depth); p at the height is the linear interpolation of those rows'
cross-section means (level_weights), so Delta p is taken between the same heights on every
grid.
"""
import itertools
import re

import numpy

from tfdem.case import CaseError
from tfdem.outputs import OutputError, joined_series, particle_statistics, probe_locations

DP_HEIGHT = 0.2  # m: Delta p between the bed's floor and this far above it
# Where Delta p's lower level is: the bed's floor (the inlet or a plate's top; seed 000 Fig. 3,
# "20 cm above the inlet boundary"), or the centre of the bed's first row of cells, the upper
# level dp_height above that (as the seed 000 study measured before 2026-12-07: a run compared
# with such a record must be measured the same way)
DP_FROM = ("inlet", "bottom_row")
FIELDS = "studyFields"
PRESSURE = "studyPressure"
COUPLED_FIELDS = ("voidFraction", "contactForceByWeight", "dragForceByWeight", "granularTemperature")
TFM_FIELDS = ("alpha.particles", "Theta.particles")
# The granular temperature per cell, Theta = <|v - v_sm|^2> / 3 (seed 000 eq. 6): the coupled
# solver's from the particles (TfdemStatistics), the TFM's transported field
GRANULAR_TEMPERATURE = {False: "granularTemperature", True: "Theta.particles"}


# The cell zones below a bed (tfdem new): a distributor plate's porous rows, an empty windbox row
ZONES_BELOW_BED = ("distributor", "windbox")


def _row_span(case):
    """(floor, first, highest): the bed's floor (the top of the plate's or the windbox's cell
    zone, when the case has one, else the mesh's bottom) and the heights of the bed's first row
    of cell centres above it and of the column's highest row."""
    grid = case.grid()
    floor = grid.origin[1]
    for zone in ZONES_BELOW_BED:
        try:
            floor = case.block_bounds(zone)[1][1]
            break
        except CaseError:
            continue
    return floor, floor + 0.5 * grid.spacing[1], grid.origin[1] + (grid.counts[1] - 0.5) * grid.spacing[1]


def pressure_levels(case, dp_height=DP_HEIGHT, dp_from="inlet"):
    """(bottom, top): the heights (m) Delta p is taken between: the bed's floor (seed 000 Fig. 3:
    "at 20 cm above the inlet boundary"; the same heights on every grid), or with dp_from
    "bottom_row" the centre of its first row of cells, and dp_height above it. CaseError when
    the upper one is above the column's highest row of cell centres."""
    if dp_from not in DP_FROM:
        raise ValueError(f"dp_from {dp_from!r}: one of {', '.join(DP_FROM)}")
    floor, first, highest = _row_span(case)
    bottom = floor if dp_from == "inlet" else first
    if not 0 < dp_height <= highest - bottom + 1e-9:
        raise CaseError(f"{case.path}: a Delta p height of {dp_height:g} m puts its upper level outside the column "
                        f"(its lower level is at y = {bottom:g} m, the highest row of cell centres at {highest:g} m); "
                        f"give a height above 0 and up to {highest - bottom:g} m")
    return bottom, bottom + dp_height


def default_dp_height(case):
    """DP_HEIGHT (seed 000's 20 cm) when the column has room for it, else the column's whole
    height from the bed's floor to its highest row of cell centres (the whole bed's Delta p)."""
    floor, _, highest = _row_span(case)
    return min(DP_HEIGHT, highest - floor)


def level_weights(case, level):
    """[(row height, weight)]: p at the fixed height `level` (m) as a combination of the
    cross-section means of rows of cell centres, linear in y: a level on a row is that row; one
    between two rows, their linear interpolation; one between the bed's floor and its first
    row, the linear extrapolation of the first two rows above the floor (a plate's rows below
    it are not used: its resistance would enter). CaseError when the level is outside the
    rows, or the bed has one row only."""
    grid = case.grid()
    floor, first, highest = _row_span(case)
    h = grid.spacing[1]
    tolerance = 1e-9 * max(1.0, abs(level))
    if not floor - tolerance <= level <= highest + tolerance:
        raise CaseError(f"{case.path}: p at y = {level:g} m: outside the bed's rows of cell centres (floor {floor:g} m, "
                        f"highest row {highest:g} m)")
    if highest - first < 0.5 * h:
        raise CaseError(f"{case.path}: the bed has one row of cells above its floor: p at a fixed height needs two")
    rows = (level - first) / h  # rows above the first
    below = min(max(int(numpy.floor(rows + 1e-9)), 0), int(round((highest - first) / h)) - 1)
    fraction = rows - below
    if abs(fraction) <= 1e-9:
        return [(first + below * h, 1.0)]
    if abs(fraction - 1) <= 1e-9:
        return [(first + (below + 1) * h, 1.0)]
    return [(first + below * h, 1.0 - fraction), (first + (below + 1) * h, fraction)]


def section_points(grid, height):
    """The cell centres of the row at `height` across the width and the depth (x fastest, then
    z): the points whose mean is the row's cross-section average."""
    return [(grid.origin[0] + (i + 0.5) * grid.spacing[0], height, grid.origin[2] + (k + 0.5) * grid.spacing[2])
            for k in range(grid.counts[2]) for i in range(grid.counts[0])]


def _points_block(points):
    return "\n".join(f"            ({x:.10g} {y:.10g} {z:.10g})" for x, y, z in points)


def pressure_rows(case, dp_height=DP_HEIGHT, dp_from="inlet"):
    """The heights of the rows of cell centres whose p gives p at both levels (pressure_levels,
    level_weights), lowest first."""
    heights = {round(y, 12) for level in pressure_levels(case, dp_height, dp_from)
               for y, _ in level_weights(case, level)}
    return sorted(heights)


def write_bed_probes(case, field_interval, pressure_interval, tfm=False, dp_height=DP_HEIGHT, dp_from="inlet"):
    """Replace the functions of `case`'s controlDict by the bed probes: every field of the maps
    at every cell centre (every depth's) every field_interval, p at every cell centre of the
    rows either side of the two levels (pressure_rows) every pressure_interval (s). The coupled
    solver samples every so many gas steps; twoPhaseEulerFoam (adjustable step) at run times."""
    grid = case.grid()
    levels = pressure_levels(case, dp_height, dp_from)
    rows = [point for y in pressure_rows(case, dp_height, dp_from) for point in section_points(grid, y)]
    fields = TFM_FIELDS if tfm else COUPLED_FIELDS
    if tfm:
        control = lambda dt: f"writeControl adjustableRunTime; writeInterval {dt:.10g};"
    else:
        steps = lambda dt: max(1, int(round(dt / case.delta_t())))
        control = lambda dt: f"writeControl timeStep; writeInterval {steps(dt)};"
    across = "" if grid.counts[2] == 1 else f" (each across its {grid.counts[2]} cells of depth)"
    block = (
        "functions\n{\n"
        f"    // tfdem.bed: every cell centre (maps); the rows of cells either side of y = {levels[0]:g} and "
        f"{levels[1]:g} m{across} (Delta p)\n"
        f"    {FIELDS}\n    {{\n        type probes; libs (\"libsampling.so\");\n"
        f"        {control(field_interval)}\n        fields ({' '.join(fields)});\n"
        f"        probeLocations\n        (\n{_points_block(grid.centres())}\n        );\n    }}\n"
        f"    {PRESSURE}\n    {{\n        type probes; libs (\"libsampling.so\");\n"
        f"        {control(pressure_interval)}\n        fields (p);\n"
        f"        probeLocations\n        (\n{_points_block(rows)}\n        );\n    }}\n"
        "}\n")
    path = case.file("system", "controlDict")
    text = open(path).read()
    start = re.search(r"(?m)^functions\s*\n?\s*\{", text)
    text = (text[:start.start()] if start else text) + block
    open(path, "w").write(text)


def map_columns(grid, locations):
    """The (row, column) map index, row * nx + column, of the cell under each probe location
    (x, y, z): probes at any depth fall on their x, y column."""
    def index(value, axis):
        return min(max(int((value - grid.origin[axis]) // grid.spacing[axis]), 0), grid.counts[axis] - 1)
    return numpy.array([index(y, 1) * grid.counts[0] + index(x, 0) for x, y, _ in locations])


def depth_average(values, columns, cells):
    """(samples, cells) map from (samples, probes) values: the mean over the probes that fall
    on each (row, column) cell (`columns`, from map_columns), i.e. over the depth. ValueError
    when a cell has no probe."""
    values = numpy.asarray(values, dtype=float)
    if values.ndim != 2 or values.shape[1] != len(columns):
        raise ValueError(f"map samples of shape {values.shape}: expected (samples, {len(columns)}), one value a probe")
    counts = numpy.bincount(columns, minlength=cells)
    if counts.size != cells or not counts.all():
        missing = int((counts[:cells] == 0).sum())
        raise ValueError(f"{missing} of the {cells} map cells have no probe: the probes do not cover the grid")
    sums = numpy.zeros((values.shape[0], cells))
    numpy.add.at(sums.T, columns, values.T)
    return sums / counts


def section_pressure_drop(p, heights, levels):
    """Delta p from samples (samples, probes) of p on rows of cells: `heights` (one a probe)
    names each probe's row, `levels` the (bottom, top) levels as level_weights; p at each
    level is its rows' cross-section means so weighted, Delta p the bottom's less the top's.
    ValueError naming the row a level needs and the run did not probe."""
    p, heights = numpy.asarray(p, dtype=float), numpy.asarray(heights, dtype=float)
    if p.ndim != 2 or p.shape[1] != heights.size:
        raise ValueError(f"pressure samples of shape {p.shape}: expected (samples, {heights.size}), one value a probe")
    at_level = []
    for weights in levels:
        value = numpy.zeros(p.shape[0])
        for row, weight in weights:
            on_row = numpy.abs(heights - row) <= 1e-9 * max(1.0, abs(row))
            if not on_row.any():
                raise ValueError(f"no pressure probe on the row at y = {row:g} m (probed: "
                                 f"{', '.join(f'{y:g}' for y in sorted(set(heights.round(12))))} m): the run probed "
                                 "other rows than its Delta p levels need (runs prepared before 2026-12-07 probed "
                                 "the bed's first row of cell centres and the row 20 cm above it); prepare and run "
                                 "it again")
            value += weight * p[:, on_row].mean(axis=1)
        at_level.append(value)
    return at_level[0] - at_level[1]


class BedOutputs:
    """What a bed run wrote, as arrays: field_t and solids (samples x map cells, each map cell an
    x, y column averaged over the depth), p_t and dp (p at the floor, or with dp_from
    "bottom_row" at the first row of cell centres, less p dp_height above it, default
    default_dp_height; levels: the two heights), theta
    (the granular temperature per map cell; None when the run did not sample it), and for the
    coupled solver the contact and drag force maps and the particle statistics. depth_cells:
    the cells across the depth the maps average (1 for a bed one cell deep)."""

    def __init__(self, case, tfm=False, dp_height=None, dp_from="inlet"):
        self.case, self.tfm = case, tfm
        self.grid = case.grid()
        nx, ny = self.grid.counts[0], self.grid.counts[1]
        self.shape = (ny, nx)
        self.depth_cells = self.grid.counts[2]
        self.y = numpy.array([c[1] for c in self.grid.centres()[:nx * ny]]).reshape(self.shape)
        path = case.path
        first = TFM_FIELDS[0] if tfm else COUPLED_FIELDS[0]
        columns = map_columns(self.grid, probe_locations(path, FIELDS, first))
        rows = joined_series(path, FIELDS, first)
        self.field_t = numpy.array([r[0] for r in rows])

        def field_map(name):
            return depth_average([r[1] for r in joined_series(path, FIELDS, name)], columns, nx * ny)

        values = depth_average([r[1] for r in rows], columns, nx * ny)
        self.solids = values if tfm else 1.0 - values
        if not tfm:
            self.contact = field_map("contactForceByWeight")
            self.drag = field_map("dragForceByWeight")
            self.particles = particle_statistics(path)
        try:  # runs prepared before the field was sampled have none
            self.theta = field_map(GRANULAR_TEMPERATURE[tfm])
        except OutputError:
            self.theta = None
        p = joined_series(path, PRESSURE, "p")
        heights = [location[1] for location in probe_locations(path, PRESSURE)]
        self.p_t = numpy.array([r[0] for r in p])
        self.dp_from = dp_from
        self.levels = pressure_levels(case, dp_height or default_dp_height(case), dp_from)
        self.dp = section_pressure_drop([r[1] for r in p], heights, [level_weights(case, y) for y in self.levels])

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


def mirror_mean(field):
    """A (rows, columns) map averaged with its mirror image about the vertical mid-plane (which
    side a jet leans to left out)."""
    return 0.5 * (field + field[:, ::-1])


def l1_difference(a, b, rows=None):
    """Mean |a - b| over the cells of two maps on one grid (after to_grid), over the first
    `rows` rows when given (e.g. the bed, not the empty freeboard)."""
    if rows is not None:
        a, b = a[:rows], b[:rows]
    return float(numpy.abs(a - b).mean())


def pairwise_l1(maps, rows=None):
    """l1_difference of every pair (i < j) of maps, in the order (0, 1), (0, 2), ... (1, 2), ..."""
    return [l1_difference(maps[i], maps[j], rows) for i in range(len(maps)) for j in range(i + 1, len(maps))]


def cross_l1(maps_a, maps_b, rows=None):
    """l1_difference of every map of one set against every map of another (len(a) * len(b)
    values): two configurations' realizations compared pair by pair."""
    return [l1_difference(a, b, rows) for a in maps_a for b in maps_b]


def l1_noise_floor(maps, rows=None):
    """The L1 two maps of one configuration differ by from chance alone: the realizations'
    time-averaged maps (independent initial states, the same time window) compared pair by
    pair (pairwise_l1). Against it, an L1 between two configurations' single realizations is
    resolved only when it stands clear of these. Returns {"mean", "min", "max", "pairs"};
    ValueError with fewer than two maps."""
    values = pairwise_l1(maps, rows)
    if not values:
        raise ValueError(f"{len(maps)} map(s): a noise floor needs two realizations")
    return {"mean": float(numpy.mean(values)), "min": float(min(values)), "max": float(max(values)),
            "pairs": len(values)}


def _cross_minus_within(maps, first, rows):
    """Mean L1 between the maps of `first` (indices) and the rest, minus the mean L1 within
    each of the two groups."""
    second = [k for k in range(len(maps)) if k not in first]
    a, b = [maps[k] for k in first], [maps[k] for k in second]
    return float(numpy.mean(cross_l1(a, b, rows)) - numpy.mean(pairwise_l1(a, rows) + pairwise_l1(b, rows)))


def l1_permutation_test(maps_a, maps_b, rows=None):
    """Are two configurations' maps further apart than their realizations are from each
    other? The statistic is the mean L1 across the configurations (cross_l1) minus the mean
    L1 within them (pairwise_l1); under the null hypothesis (one configuration) the
    realizations are exchangeable, so its p-value is the share of all C(n_a + n_b, n_a)
    relabellings into groups of n_a and n_b whose statistic is at least the observed one (an
    exact permutation test; with 4 + 4 maps the smallest p is 2/70 = 0.029). Returns
    {"statistic", "p", "relabellings"}."""
    if len(maps_a) < 2 or len(maps_b) < 2:
        raise ValueError(f"{len(maps_a)} and {len(maps_b)} maps: a permutation test needs two of each")
    maps = list(maps_a) + list(maps_b)
    observed = _cross_minus_within(maps, list(range(len(maps_a))), rows)
    values = [_cross_minus_within(maps, list(c), rows) for c in itertools.combinations(range(len(maps)), len(maps_a))]
    extreme = sum(1 for v in values if v >= observed - 1e-12 * max(1.0, abs(observed)))
    return {"statistic": observed, "p": extreme / len(values), "relabellings": len(values)}
