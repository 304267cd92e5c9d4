"""Summarise and draw the packed bed written by in.pack (LIGGGHTS data file bed.data).

Prints the particle count, mean particle height, bed height (highest particle top) and the
solid fraction of the bed slab, and draws the particles to packing.png. The box width comes
from the data file's header.
"""
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from matplotlib.collections import EllipseCollection  # noqa: E402

from tfdem.liggghts import read_data_box, read_data_file  # noqa: E402
from tfdem.physics import sphere_volume  # noqa: E402

SHOWN_HEIGHT = 0.2  # m, the picture's height (the bed is about 15 cm)


def main(path="bed.data"):
    atoms = read_data_file(path)
    (xlo, _, _), (xhi, _, _) = read_data_box(path)
    width = xhi - xlo
    diameters, x, y, z = atoms["diameter"], atoms["x"], atoms["y"], atoms["z"]
    d = diameters[0]
    count = len(diameters)
    mean_height = sum(y) / count
    bed_height = max(yi + di / 2 for yi, di in zip(y, diameters))
    solid_volume = sum(sphere_volume(di) for di in diameters)
    off_plane = max(abs(zi - d / 2) for zi in z)
    print(f"particles: {count}")
    print(f"mean particle height: {100 * mean_height:.2f} cm")
    print(f"bed height (top of highest particle): {100 * bed_height:.2f} cm (seed 000 Table 1: 15 cm)")
    print(f"solid fraction of the bed slab (depth d_p): {solid_volume / (width * bed_height * d):.3f}")
    print(f"largest distance of a centre from the mid-plane z = d_p/2: {off_plane:.1e} m")
    fig, ax = plt.subplots(figsize=(3, 5))
    ax.add_collection(EllipseCollection(diameters, diameters, 0, units="x",
                                        offsets=list(zip(x, y)), transOffset=ax.transData,
                                        facecolors="tab:orange", edgecolors="k", linewidths=0.2))
    ax.set_xlim(xlo, xhi)
    ax.set_ylim(0, max(SHOWN_HEIGHT, 1.1 * bed_height))
    ax.set_aspect("equal")
    ax.set_xlabel("x (m)")
    ax.set_ylabel("y (m)")
    ax.set_title(f"{count} particles, bed {100 * bed_height:.1f} cm", fontsize=9)
    fig.tight_layout()
    fig.savefig("packing.png", dpi=150)
    print("wrote packing.png")


if __name__ == "__main__":
    main(*sys.argv[1:])
