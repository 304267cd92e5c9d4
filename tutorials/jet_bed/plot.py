"""Central-jet bed results: pressure drops, mean particle height, solids fraction, snapshots.

Writes jet_bed.csv (t; p(1 cm) - p(21 cm) on the jet axis, x = 7.5 cm, and in the side column
x = 1.5 cm, seed 000 Fig. 3; p(1 cm) - p(89 cm) on the axis and at the side, the whole bed;
mean particle height) and jet_bed.png (the pressure drops and the mean height against time,
the time-averaged solids fraction 1 - eps of the second half of the run, seed 000 Fig. 4 and
8b, and the particles at the end), and jet_bed_snapshots.png (the particles over the last
0.5 s). Prints averages over the second half of the run.
"""
import math
import os
import re
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
from matplotlib.collections import EllipseCollection  # noqa: E402

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
from tutorial_series import mean_height, pressure_probes, value_at  # noqa: E402

WIDTH, HEIGHT, DEPTH = 0.15, 0.90, 0.004  # m; depth = particle diameter (2-D rule)
PARTICLES, DIAMETER, DENSITY, G = 2400, 0.004, 2700.0, 9.81
PARTICLE_WEIGHT = DENSITY * math.pi * DIAMETER ** 3 / 6 * G
BED_WEIGHT_PER_AREA = PARTICLES * PARTICLE_WEIGHT / (WIDTH * DEPTH)  # Pa
SHOWN_HEIGHT = 0.45  # m, the paper's figures show the lower 45 cm
CELL_WIDTH, CELL_HEIGHT = 0.01, 0.02  # m, system/blockMeshDict
COLUMNS, ROWS = round(WIDTH / CELL_WIDTH), round(HEIGHT / CELL_HEIGHT)
DEM_STEP = 1e-5  # s, in.bed (dump steps to time)


def latest_time_dir():
    times = [d for d in os.listdir(".") if re.fullmatch(r"[0-9.e+-]+", d) and os.path.isdir(d) and float(d) > 0]
    return max(times, key=float) if times else None


def internal_field(path):
    """Values of an ascii field's internalField: a list of floats or of (x, y, z)."""
    text = open(path).read()
    start = text.index("internalField")
    head = text[start:start + 200]
    if "nonuniform" not in head:
        return None
    body = text[text.index("(", start) + 1:]
    if body.lstrip().startswith("("):  # vectors
        return [tuple(map(float, v.split())) for v in re.findall(r"\(([^()]*)\)", body.split("\n)\n")[0])]
    return [float(v) for v in body.split(")")[0].split()]


def solids_fraction_map(time_dir):
    """Time-averaged 1 - eps on the COLUMNS x ROWS grid (rows bottom to top), or None."""
    eps = internal_field(os.path.join(time_dir, "voidFractionMean"))
    centres = internal_field(os.path.join(time_dir, "C"))
    if eps is None or centres is None:
        return None
    grid = np.full((ROWS, COLUMNS), np.nan)
    for e, (x, y, _) in zip(eps, centres):
        grid[int(y / CELL_HEIGHT), int(x / CELL_WIDTH)] = 1 - e
    return grid


def read_dump(path="particles.dump"):
    """[(t step, array of (x, y, vx, vy))] from a LIGGGHTS custom dump (id x y vx vy)."""
    frames = []
    lines = open(path).read().splitlines()
    i = 0
    while i < len(lines):
        if lines[i].startswith("ITEM: TIMESTEP"):
            step = int(lines[i + 1])
            count = int(lines[i + 3])
            data = np.array([list(map(float, l.split()[1:5])) for l in lines[i + 9:i + 9 + count]])
            frames.append((step, data))
            i += 9 + count
        else:
            i += 1
    return frames


def draw_particles(ax, data, title):
    circles = EllipseCollection(DIAMETER, DIAMETER, 0, units="x", offsets=data[:, :2],
                                transOffset=ax.transData, cmap="viridis", linewidths=0)
    circles.set_array(np.hypot(data[:, 2], data[:, 3]))
    circles.set_clim(0, 2)
    ax.add_collection(circles)
    ax.set_xlim(0, WIDTH)
    ax.set_ylim(0, SHOWN_HEIGHT)
    ax.set_aspect("equal")
    ax.set_title(title, fontsize=8)
    ax.tick_params(labelsize=7)


def dominant_frequency(t, signal):
    """Frequency (Hz) of the largest peak of the spectrum of a uniformly sampled signal."""
    if len(signal) < 16:
        return float("nan")
    x = np.asarray(signal) - np.mean(signal)
    spectrum = np.abs(np.fft.rfft(x))
    freq = np.fft.rfftfreq(len(x), d=(t[-1] - t[0]) / (len(t) - 1))
    return freq[1 + int(np.argmax(spectrum[1:]))]


def main():
    probes = pressure_probes()
    height = mean_height()
    t = np.array([r[0] for r in probes])
    p = np.array([r[1] for r in probes])
    dp_axis, dp_side = p[:, 0] - p[:, 1], p[:, 2] - p[:, 3]
    bed_axis, bed_side = p[:, 0] - p[:, 4], p[:, 2] - p[:, 4]
    with open("jet_bed.csv", "w") as out:
        out.write("t_s,dp_20cm_axis_Pa,dp_20cm_side_Pa,dp_bed_axis_Pa,dp_bed_side_Pa,mean_particle_height_m\n")
        for row in zip(t, dp_axis, dp_side, bed_axis, bed_side):
            out.write(",".join(f"{v:.6g}" for v in row) + f",{value_at(height, row[0]):.6g}\n")

    end = t[-1]
    start = end / 2
    late = t >= start
    late_h = [h for th, h in height if th >= start]
    print(f"averages over {start:.3g}-{end:.3g} s (bed weight / area {BED_WEIGHT_PER_AREA:.0f} Pa):")
    for name, series in (("p(1 cm) - p(21 cm), jet axis", dp_axis), ("p(1 cm) - p(21 cm), side x = 1.5 cm", dp_side),
                         ("p(1 cm) - p(89 cm), jet axis", bed_axis), ("p(1 cm) - p(89 cm), side x = 1.5 cm", bed_side)):
        s = series[late]
        print(f"  {name}: mean {s.mean():.0f} Pa ({s.mean() / BED_WEIGHT_PER_AREA:.2f} of bed weight / area), "
              f"std {s.std():.0f} Pa, dominant frequency {dominant_frequency(t[late], s):.2f} Hz")
    if late_h:
        print(f"  mean particle height {100 * np.mean(late_h):.2f} cm (initial {100 * height[0][1]:.2f} cm)")

    time_dir = latest_time_dir()
    solids = solids_fraction_map(time_dir) if time_dir else None
    if solids is not None:
        axis = solids[:, COLUMNS // 2]
        rows = ", ".join(f"{100 * (CELL_HEIGHT * (j + 0.5)):.0f} cm {axis[j]:.2f}" for j in (0, 2, 4, 6, 8, 10, 12, 15))
        print(f"  time-averaged solids fraction on the jet axis: {rows}")
        side = np.nanmean(solids[:, [0, 1, COLUMNS - 2, COLUMNS - 1]], axis=1)
        rows = ", ".join(f"{100 * (CELL_HEIGHT * (j + 0.5)):.0f} cm {side[j]:.2f}" for j in (0, 2, 4, 6, 8, 10, 12, 15))
        print(f"  time-averaged solids fraction at the walls (2 columns each side): {rows}")
    frames = read_dump() if os.path.exists("particles.dump") else []

    fig = plt.figure(figsize=(10, 6))
    a = fig.add_subplot(2, 2, 1)
    a.plot(t, dp_axis, lw=0.5, label="p(1 cm) - p(21 cm), axis")
    a.plot(t, dp_side, lw=0.5, label="p(1 cm) - p(21 cm), side")
    a.plot(t, bed_side, lw=0.5, label="p(1 cm) - p(89 cm), side")
    a.axhline(BED_WEIGHT_PER_AREA, color="k", ls="--", lw=0.8, label="bed weight / area")
    a.set_ylabel("pressure drop (Pa)")
    a.legend(fontsize=6, loc="upper right", ncol=2)
    b = fig.add_subplot(2, 2, 3, sharex=a)
    b.plot([th for th, _ in height], [100 * h for _, h in height], lw=0.8)
    b.set_ylabel("mean particle height (cm)")
    b.set_xlabel("t (s)")
    if solids is not None:
        c = fig.add_subplot(1, 4, 3)
        image = c.imshow(solids, origin="lower", extent=(0, WIDTH, 0, HEIGHT), vmin=0, vmax=0.6, cmap="viridis")
        c.set_ylim(0, SHOWN_HEIGHT)
        c.set_title(f"1 - eps, mean {start:.3g}-{end:.3g} s", fontsize=8)
        c.tick_params(labelsize=7)
        fig.colorbar(image, ax=c, fraction=0.08)
    if frames:
        step, data = frames[-1]
        draw_particles(fig.add_subplot(1, 4, 4), data, f"particles at {step * DEM_STEP:.3g} s\n(colour: speed 0-2 m/s)")
    fig.tight_layout()
    fig.savefig("jet_bed.png", dpi=120)
    written = ["jet_bed.csv", "jet_bed.png"]
    if len(frames) >= 6:
        fig, axes = plt.subplots(1, 6, figsize=(10, 5), sharey=True)
        for ax, (step, data) in zip(axes, frames[-6:]):
            draw_particles(ax, data, f"{step * DEM_STEP:.3g} s")
        fig.tight_layout()
        fig.savefig("jet_bed_snapshots.png", dpi=120)
        written.append("jet_bed_snapshots.png")
    print("wrote " + ", ".join(written))


if __name__ == "__main__":
    main()
