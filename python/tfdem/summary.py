"""A run's own outputs as one table and one picture, from a finished or stopped run, joined over
resumed segments (no simulation):

    tfdem summary CASE        (python3 -m tfdem.summary CASE; a generated Allrun calls it)

CASE/summary.csv: a row at each sample of the coupler's particle statistics
(postProcessing/tfdemParticles/*/particles.dat, every coupling.yaml output.statistics_interval):
t; Delta p (its mean over the samples since the previous row) between the inlet (area average of p on the inlet patch; a bed without one, under
jets through a closed bottom: the bed's bottom row) and the height of the case's upper
pressure function (its top row: `abovePressure`, an area average over the cross-section, or a
probe in older cases); the mean particle height; the rest of the
particle statistics (particles, mass, bulk coordination number, multicontact ratio, and for
two sizes the segregation degree); and for a LIGGGHTS case the vertical forces on the particles
over the sample's interval (forces.txt, as fractions of the bed's weight: the gas, the floor,
the walls beside the bed, the lid). The header line names every column's unit.

CASE/summary.png: Delta p and the mean particle height against time, and the particles at the
last time a particle file was written (VTK/particles_<t>.vtk; before the first one, the bed
the run started from), drawn to scale and coloured by diameter: a bed up to 4 largest diameters deep seen from the
front (x against y), a deeper one as a slice 2 largest diameters thick at mid-depth.

A warning is printed when the bed is pinned under the lid: the lid carrying more than 5 % of
its weight over the run's second half (LIGGGHTS), or more than 5 % of the particles less than
half a diameter from it in the last particle file (hard spheres).

The two paths are printed as the last lines.
"""
import argparse
import glob
import math
import os

import numpy

from tfdem.case import Case, CaseError
from tfdem.frontdoor import add_debug_option, doing, run_command, save_figure_atomic, write_text_atomic
from tfdem.outputs import OutputError, fix_print, particle_statistics, pressure_series, vtk_particles

TABLE, FIGURE = "summary.csv", "summary.png"
UPPER = "abovePressure"                         # the top row's pressure (tfdem new)
LOWER = ("inletPressure", "bedPressure")        # the inlet's, else the bed's bottom row's
STATISTICS = (("particles", "particles"), ("mass", "mass (kg)"), ("bulk_coordination", "bulk coordination number"),
              ("multicontact", "multicontact ratio"), ("segregation", "segregation degree"))
FORCES = ("gas force / weight", "floor force / weight", "wall force / weight", "lid force / weight")
SAME_TIME = 1e-9  # s: two function objects' samples of one gas step (printed at different precisions)


def _has_plate(case):
    """Whether the case has a distributor plate (tfdem new writes it as constant/fvOptions)."""
    return os.path.isfile(case.file("constant", "fvOptions"))


class Pressure:
    """Delta p between the case's lower and upper pressure functions, by time."""

    def __init__(self, case):
        functions = [name for name in LOWER if _has_function(case, name)]
        if _has_plate(case) and "bedPressure" in functions:  # the inlet's Delta p holds the plate's drop too
            functions = ["bedPressure"]
        if not functions or not _has_function(case, UPPER):
            raise OutputError(f"{case.path}/system/controlDict: no {' or '.join(LOWER)} and {UPPER} function "
                              "objects, so no Delta p: a case tfdem new writes has them")
        self.lower = functions[0]
        self.height = case.pressure_height(UPPER)
        lower = {round(t, 9): p for t, p in pressure_series(case.path, self.lower)}
        self.samples = {t: [lower[t] - p] for t, p in
                        ((round(t, 9), p) for t, p in pressure_series(case.path, UPPER)) if t in lower}
        where = "the inlet (area average)" if self.lower == "inletPressure" else \
            f"the bed's bottom row (y = {case.pressure_height(self.lower):.4g} m, cross-section average" + \
            (", above the distributor plate)" if _has_plate(case) else ")")
        self.label = f"dp (Pa) = p at {where} - p at y = {self.height:.4g} m (mean since the previous row)"


def _has_function(case, name):
    try:
        case.function_body(name)
    except CaseError:
        return False
    return True


def wall_forces(case, weight):
    """{t: [gas, floor, walls, lid] as fractions of `weight`} of a LIGGGHTS case's forces.txt
    (its forces_out fix, 1 ms averages), or None (the hard-sphere engine, or no file)."""
    if case.hard_sphere():
        return None
    dem = case.dem()
    try:
        path = case.file(dem.fix_file("forces_out"))
    except CaseError:
        return None
    if not os.path.isfile(path):
        return None
    step = dem.time_step()
    out = {}
    for n, values in fix_print(path):
        walls = values[2] + values[3] + (values[5] + values[6] if len(values) >= 7 else 0.0)
        out[n * step] = [values[0] / weight, values[1] / weight, walls / weight, values[4] / weight]
    return out


def interval_means(series, times):
    """The mean of `series` ({t: values}) over each interval (previous time, t] of `times`."""
    keys = numpy.array(sorted(series))
    values = numpy.array([series[k] for k in keys])
    means, previous = [], -math.inf
    for t in times:
        pick = (keys > previous + SAME_TIME) & (keys <= t + SAME_TIME)
        means.append(values[pick].mean(axis=0) if pick.any() else numpy.full(values.shape[1], math.nan))
        previous = t
    return means


def bed_weight(case):
    """(weight in N, buoyant weight per cross-section area in Pa) of the bed the run started
    from (its data file)."""
    atoms = case.particles()
    rho_gas, _ = case.gas()
    g = case.gravity_magnitude()
    lo, hi = case.mesh_bounds()
    volume = math.fsum(math.pi * d ** 3 / 6 for d in atoms["diameter"])
    mass = math.fsum(rho * math.pi * d ** 3 / 6 for rho, d in zip(atoms["density"], atoms["diameter"]))
    return mass * g, (mass - rho_gas * volume) * g / ((hi[0] - lo[0]) * (hi[2] - lo[2]))


def table(case):
    """(header, rows) of summary.csv."""
    statistics = particle_statistics(case.path)
    if not statistics["t"]:
        raise OutputError(f"{case.path}/postProcessing/tfdemParticles: no particle statistics yet (the run stopped "
                          "before its first sample)")
    pressure = Pressure(case)
    weight, _ = bed_weight(case)
    header = ["t (s)", pressure.label, "mean particle height (m)"]
    columns = [k for k, _ in STATISTICS if k in statistics]
    header += [name for k, name in STATISTICS if k in statistics]
    forces = wall_forces(case, weight)
    times = statistics["t"]
    dp = interval_means(pressure.samples, times) if pressure.samples else [[math.nan]] * len(times)
    rows = [[t, dp[i][0], statistics["mean_height"][i]] + [statistics[k][i] for k in columns]
            for i, t in enumerate(times)]
    if forces:
        header += [f"{name} (mean since the previous row)" for name in FORCES]
        for row, means in zip(rows, interval_means(forces, times)):
            row += list(means)
    return header, rows


def csv_text(header, rows):
    def cell(v):
        return "" if isinstance(v, float) and math.isnan(v) else f"{v:.10g}"
    quoted = [f'"{h}"' if "," in h else h for h in header]
    return ",".join(quoted) + "\n" + "".join(",".join(cell(v) for v in row) + "\n" for row in rows)


def last_particles(case):
    """(t, {position, diameter}) of the last particle file (VTK/particles_<t>.vtk), or (None,
    the data file's) before the first one was written."""
    files = glob.glob(case.file("VTK", "particles_*.vtk"))
    if not files:
        atoms = case.particles()
        return None, {"position": list(zip(atoms["x"], atoms["y"], atoms["z"])), "diameter": atoms["diameter"]}
    time_of = lambda path: float(os.path.basename(path)[len("particles_"):-len(".vtk")])
    path = max(files, key=time_of)
    return time_of(path), vtk_particles(path)


SLAB_DIAMETERS = 2.0  # a bed deeper than twice this is drawn as a mid-depth slice this many d thick


def mid_depth_slab(particles, z_lo, z_hi):
    """(positions, diameters, slab) of the particles to draw: in a bed deeper than 2 SLAB_DIAMETERS
    largest diameters, those whose centres lie in a slice SLAB_DIAMETERS thick at mid-depth
    (a projection of the whole depth hides jets, spouts and bubbles), slab = (mid-depth, thickness);
    in a shallower bed all of them, slab = None."""
    position = numpy.array(particles["position"], dtype=float).reshape(-1, 3)
    d = numpy.array(particles["diameter"], dtype=float)
    thickness = SLAB_DIAMETERS * (d.max() if len(d) else 0.0)
    if not len(d) or z_hi - z_lo <= 2 * thickness:
        return position, d, None
    middle = 0.5 * (z_lo + z_hi)
    inside = numpy.abs(position[:, 2] - middle) <= 0.5 * thickness
    return position[inside], d[inside], (middle, thickness)


LID_SHARE = 0.05  # the lid carrying more of the weight than this, on average, is a pinned bed


def lid_warnings(case, header, rows, snapshot=None):
    """A bed pressed against the lid is not fluidized: a warning with the lid's mean share of the
    weight over the run's second half (LIGGGHTS' forces.txt, in summary.csv), or, without it,
    the share of the particles touching the lid in the last particle file (`snapshot`, as
    last_particles gives it; read when not given)."""
    column = next((i for i, h in enumerate(header) if h.startswith(FORCES[3])), None)
    fix = ("a taller box (box.height) or a slower inflow (inflow.velocity, the jets' velocity): a packed bed started at "
           "the full inflow first rises as a plug, which can reach a lid close above it")
    if column is not None:
        t_end = rows[-1][0]
        late = [abs(r[column]) for r in rows if r[0] >= 0.5 * t_end and not math.isnan(r[column])]
        share = sum(late) / len(late) if late else 0.0
        if share > LID_SHARE:
            return [f"the lid carries {share:.2f} of the bed's weight on average over t = {0.5 * t_end:g} to "
                    f"{t_end:g} s (summary.csv, its lid column): particles are pinned under the lid and the bed is "
                    f"not fluidized as meant. Fix: {fix}"]
        return []
    _, particles = snapshot or last_particles(case)
    _, hi = case.mesh_bounds()
    position = numpy.array(particles["position"], dtype=float).reshape(-1, 3)
    d = numpy.array(particles["diameter"], dtype=float)
    touching = int(numpy.count_nonzero(position[:, 1] + d >= hi[1])) if len(d) else 0  # gaps under d/2
    if len(d) and touching > LID_SHARE * len(d):
        return [f"{touching} of the {len(d)} particles ({touching / len(d):.0%}) are less than half a diameter from the lid in "
                f"the last particle file: the bed is pinned under the lid, not fluidized as meant. Fix: {fix}"]
    return []


def plot(case, header, rows, path, snapshot):
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from matplotlib.collections import EllipseCollection

    _, weight_per_area = bed_weight(case)
    t = [r[0] for r in rows]
    fig, axes = plt.subplots(1, 3, figsize=(12, 4), gridspec_kw={"width_ratios": [2, 2, 1.2]})
    axes[0].plot(t, [r[1] for r in rows], lw=0.8)
    axes[0].axhline(weight_per_area, color="k", ls="--", lw=0.8, label=f"bed's buoyant weight / area {weight_per_area:.4g} Pa")
    axes[0].set_xlabel("t (s)")
    axes[0].set_ylabel("Δp (Pa)")
    axes[0].set_title(header[1].replace("dp (Pa) = ", ""), fontsize=7)
    axes[0].legend(fontsize=7)
    axes[1].plot(t, [100 * r[2] for r in rows], lw=0.8)
    axes[1].set_xlabel("t (s)")
    axes[1].set_ylabel("mean particle height (cm)")
    snapshot_time, particles = snapshot
    lo, hi = case.mesh_bounds()
    position, d, slab = mid_depth_slab(particles, lo[2], hi[2])
    xy = position[:, :2]
    front = numpy.argsort(-position[:, 2])  # the front (small z) drawn last
    sizes = sorted(set(numpy.round(d, 12)))
    colour = numpy.searchsorted(sizes, numpy.round(d, 12)) / max(1, len(sizes) - 1)
    circles = EllipseCollection(d[front], d[front], numpy.zeros(len(d)), units="xy", offsets=xy[front],
                                offset_transform=axes[2].transData, cmap="viridis", edgecolors="none")
    circles.set_array(colour[front])
    circles.set_clim(0, 1)
    axes[2].add_collection(circles)
    axes[2].set_xlim(lo[0], hi[0])
    axes[2].set_ylim(lo[1], hi[1])
    axes[2].set_aspect("equal")
    axes[2].set_xlabel("x (m)")
    when = f"t = {snapshot_time:g} s" if snapshot_time is not None else "the bed the run started from"
    seen = f"mid-depth slice {1000 * slab[1]:.3g} mm thick" if slab else "seen from the front"
    axes[2].set_title(f"particles at {when}\n{seen}\n" + ", ".join(f"{1000 * s:g}" for s in sizes[:9]) + " mm"
                      + (" (dark to light)" if len(sizes) > 1 else ""), fontsize=7)
    fig.tight_layout()
    save_figure_atomic(fig, path, dpi=110)
    plt.close(fig)


def summarize(case_path):
    """Write CASE/summary.csv and CASE/summary.png; returns their paths, the rows and the warnings."""
    case = Case(case_path)
    with doing("reading the run's outputs in", case.path):
        header, rows = table(case)
        snapshot = last_particles(case)
        warnings = lid_warnings(case, header, rows, snapshot)
    csv = case.file(TABLE)
    with doing("writing", csv):
        write_text_atomic(csv, csv_text(header, rows))
    figure = case.file(FIGURE)
    with doing("plotting", figure):
        plot(case, header, rows, figure, snapshot)
    return csv, figure, rows, warnings


def main(argv=None):
    return run_command("tfdem summary", _summary, argv)


def _summary(argv):
    parser = argparse.ArgumentParser(prog="tfdem summary", description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("case", help="the case's folder (a finished or stopped run)")
    add_debug_option(parser)
    args = parser.parse_args(argv)
    if not os.path.isfile(os.path.join(args.case, "coupling.yaml")):
        raise CaseError(f"{args.case}: not a case folder (no coupling.yaml): give the folder of a case that has run")
    csv, figure, rows, warnings = summarize(args.case)
    print(f"tfdem summary: {len(rows)} samples, t = {rows[0][0]:g} to {rows[-1][0]:g} s")
    for warning in warnings:
        print(f"tfdem summary: warning: {warning}")
    print(csv)
    print(figure)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
