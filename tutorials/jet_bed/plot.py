"""Central-jet bed results: pressure drops, mean particle height, solids fraction, snapshots.

Writes jet_bed.csv (t; p(1 cm) - p(21 cm) on the jet axis, x = 7.5 cm, and in the side column
x = 1.5 cm, seed 000 Fig. 3; p(1 cm) - p(89 cm) on the axis and at the side, the whole bed;
mean particle height) and jet_bed.png (the pressure drops and the mean height against time,
the time-averaged solids fraction 1 - eps of the second half of the run, seed 000 Fig. 4 and
8b, and the particles at the end), and jet_bed_snapshots.png (the particles over the last
0.5 s). Prints averages over the second half of the run. The probes (system/controlDict
`pressure`: axis bottom and 20 cm up, side bottom and 20 cm up, axis top), the grid, the
particles, gravity and the DEM step come from the case's own files.
"""
import os

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
from matplotlib.collections import EllipseCollection  # noqa: E402

from tfdem import outputs, stats  # noqa: E402
from tfdem.case import Case  # noqa: E402
from tfdem.physics import sphere_volume  # noqa: E402

SHOWN_HEIGHT = 0.45  # m, the paper's figures show the lower 45 cm


class Bed:
    """What the plots need of the case."""

    def __init__(self, case):
        lo, hi = case.mesh_bounds()
        self.width, self.height, self.depth = (hi[a] - lo[a] for a in range(3))
        grid = case.grid()
        self.cell_width, self.cell_height = grid.spacing[0], grid.spacing[1]
        self.columns, self.rows = grid.counts[0], grid.counts[1]
        self.diameter = case.particle_properties()[0]
        dem = case.dem()
        particles = case.particles(dem.read_data())
        mass = sum(rho * sphere_volume(d) for d, rho in zip(particles["diameter"], particles["density"]))
        self.weight_per_area = mass * case.gravity_magnitude() / (self.width * self.depth)  # Pa
        self.dem_step = dem.time_step()
        self.dump = case.file(dem.command("dump", "snapshots")[5])
        self.height_file = case.file(dem.fix_file("height_out"))
        self.probes = case.probe_locations("pressure")


def latest_time_dir(case_path):
    times = [name for name in outputs.times(case_path) if float(name) > 0]
    return os.path.join(case_path, times[-1]) if times else None


def solids_fraction_map(bed, time_dir):
    """Time-averaged 1 - eps on the columns x rows grid (rows bottom to top), or None."""
    case_path, time_name = os.path.split(time_dir)
    try:
        eps = outputs.field(case_path, time_name, "voidFractionMean")
        centres = outputs.field(case_path, time_name, "C")
    except (OSError, outputs.OutputError):
        return None
    if len(eps) != bed.columns * bed.rows or len(centres) != len(eps):
        return None
    grid = np.full((bed.rows, bed.columns), np.nan)
    for e, (x, y, _) in zip(eps, centres):
        grid[int(y / bed.cell_height), int(x / bed.cell_width)] = 1 - e
    return grid


def read_dump(path):
    """[(step, array of (x, y, vx, vy))] of the DEM script's snapshot dump, in step order."""
    frames = []
    for step, (columns, rows) in sorted(outputs.dump_frames(path).items()):
        index = [columns.index(c) for c in ("x", "y", "vx", "vy")]
        frames.append((step, np.array([[row[k] for k in index] for row in rows])))
    return frames


def draw_particles(ax, bed, data, title):
    circles = EllipseCollection(bed.diameter, bed.diameter, 0, units="x", offsets=data[:, :2],
                                transOffset=ax.transData, cmap="viridis", linewidths=0)
    circles.set_array(np.hypot(data[:, 2], data[:, 3]))
    circles.set_clim(0, 2)
    ax.add_collection(circles)
    ax.set_xlim(0, bed.width)
    ax.set_ylim(0, SHOWN_HEIGHT)
    ax.set_aspect("equal")
    ax.set_title(title, fontsize=8)
    ax.tick_params(labelsize=7)


def dominant_frequency(t, signal):
    """Frequency (Hz) of the largest spectral peak (tfdem.stats); nan below 16 samples."""
    return stats.dominant_frequency(t, signal) if len(signal) >= 16 else float("nan")


def cm(value):
    return f"{100 * value:.3g} cm"


def main(case_path="."):
    case = Case(case_path)
    bed = Bed(case)
    axis_low, axis_up, side_low, side_up, top = bed.probes[:5]
    probes = outputs.probes(case_path, "pressure", "p")
    height = outputs.fix_print(bed.height_file)
    t_h, h = [th for th, _ in height], [v[0] for _, v in height]
    t = np.array([r[0] for r in probes])
    p = np.array([r[1] for r in probes])
    dp_axis, dp_side = p[:, 0] - p[:, 1], p[:, 2] - p[:, 3]
    bed_axis, bed_side = p[:, 0] - p[:, 4], p[:, 2] - p[:, 4]
    gap = f"{100 * (axis_up[1] - axis_low[1]):.0f}cm"
    with open("jet_bed.csv", "w") as out:
        out.write(f"t_s,dp_{gap}_axis_Pa,dp_{gap}_side_Pa,dp_bed_axis_Pa,dp_bed_side_Pa,mean_particle_height_m\n")
        for row in zip(t, dp_axis, dp_side, bed_axis, bed_side):
            out.write(",".join(f"{v:.6g}" for v in row) + f",{stats.value_at(t_h, h, row[0]):.6g}\n")

    end = t[-1]
    start = end / 2
    late = t >= start
    late_h = [v for th, v in zip(t_h, h) if th >= start]
    weight = bed.weight_per_area
    low, up, tip = cm(axis_low[1]), cm(axis_up[1]), cm(top[1])
    side = f"side x = {cm(side_low[0])}"
    print(f"averages over {start:.3g}-{end:.3g} s (bed weight / area {weight:.0f} Pa):")
    for name, series in ((f"p({low}) - p({up}), jet axis", dp_axis), (f"p({low}) - p({up}), {side}", dp_side),
                         (f"p({low}) - p({tip}), jet axis", bed_axis), (f"p({low}) - p({tip}), {side}", bed_side)):
        s = series[late]
        print(f"  {name}: mean {s.mean():.0f} Pa ({s.mean() / weight:.2f} of bed weight / area), "
              f"std {s.std():.0f} Pa, dominant frequency {dominant_frequency(t[late], s):.2f} Hz")
    if late_h:
        print(f"  mean particle height {100 * np.mean(late_h):.2f} cm (initial {100 * h[0]:.2f} cm)")

    time_dir = latest_time_dir(case_path)
    solids = solids_fraction_map(bed, time_dir) if time_dir else None
    if solids is not None:
        shown = [j for j in (0, 2, 4, 6, 8, 10, 12, 15) if j < bed.rows]
        axis = solids[:, bed.columns // 2]
        rows = ", ".join(f"{100 * (bed.cell_height * (j + 0.5)):.0f} cm {axis[j]:.2f}" for j in shown)
        print(f"  time-averaged solids fraction on the jet axis: {rows}")
        walls = np.nanmean(solids[:, [0, 1, bed.columns - 2, bed.columns - 1]], axis=1)
        rows = ", ".join(f"{100 * (bed.cell_height * (j + 0.5)):.0f} cm {walls[j]:.2f}" for j in shown)
        print(f"  time-averaged solids fraction at the walls (2 columns each side): {rows}")
    frames = read_dump(bed.dump) if os.path.exists(bed.dump) else []

    fig = plt.figure(figsize=(10, 6))
    a = fig.add_subplot(2, 2, 1)
    a.plot(t, dp_axis, lw=0.5, label=f"p({low}) - p({up}), axis")
    a.plot(t, dp_side, lw=0.5, label=f"p({low}) - p({up}), side")
    a.plot(t, bed_side, lw=0.5, label=f"p({low}) - p({tip}), side")
    a.axhline(weight, color="k", ls="--", lw=0.8, label="bed weight / area")
    a.set_ylabel("pressure drop (Pa)")
    a.legend(fontsize=6, loc="upper right", ncol=2)
    b = fig.add_subplot(2, 2, 3, sharex=a)
    b.plot(t_h, [100 * v for v in h], lw=0.8)
    b.set_ylabel("mean particle height (cm)")
    b.set_xlabel("t (s)")
    if solids is not None:
        c = fig.add_subplot(1, 4, 3)
        image = c.imshow(solids, origin="lower", extent=(0, bed.width, 0, bed.height), vmin=0, vmax=0.6,
                         cmap="viridis")
        c.set_ylim(0, SHOWN_HEIGHT)
        c.set_title(f"1 - eps, mean {start:.3g}-{end:.3g} s", fontsize=8)
        c.tick_params(labelsize=7)
        fig.colorbar(image, ax=c, fraction=0.08)
    if frames:
        step, data = frames[-1]
        draw_particles(fig.add_subplot(1, 4, 4), bed, data,
                       f"particles at {step * bed.dem_step:.3g} s\n(colour: speed 0-2 m/s)")
    fig.tight_layout()
    fig.savefig("jet_bed.png", dpi=120)
    written = ["jet_bed.csv", "jet_bed.png"]
    if len(frames) >= 6:
        fig, axes = plt.subplots(1, 6, figsize=(10, 5), sharey=True)
        for ax, (step, data) in zip(axes, frames[-6:]):
            draw_particles(ax, bed, data, f"{step * bed.dem_step:.3g} s")
        fig.tight_layout()
        fig.savefig("jet_bed_snapshots.png", dpi=120)
        written.append("jet_bed_snapshots.png")
    print("wrote " + ", ".join(written))


if __name__ == "__main__":
    main()
