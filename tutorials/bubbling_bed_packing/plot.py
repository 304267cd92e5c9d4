"""Summarise and draw the packed bed written by in.pack (LIGGGHTS data file bed.data).

Prints the particle count, mean particle height, bed height (highest particle top) and the
solid fraction of the bed slab, and draws the particles to packing.png.
"""
import math
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from matplotlib.collections import EllipseCollection  # noqa: E402

WIDTH = 0.15  # m, box width (in.pack)


def read_atoms(path):
    lines = open(path).read().splitlines()
    start = lines.index("Atoms") + 2
    atoms = []
    for line in lines[start:]:
        if not line.strip():
            break
        _, _, diameter, density, x, y, z = map(float, line.split()[:7])
        atoms.append((diameter, density, x, y, z))
    return atoms


def main(path="bed.data"):
    atoms = read_atoms(path)
    d = atoms[0][0]
    mean_height = sum(a[3] for a in atoms) / len(atoms)
    bed_height = max(a[3] + a[0] / 2 for a in atoms)
    solid_volume = sum(math.pi * a[0] ** 3 / 6 for a in atoms)
    off_plane = max(abs(a[4] - d / 2) for a in atoms)
    print(f"particles: {len(atoms)}")
    print(f"mean particle height: {100 * mean_height:.2f} cm")
    print(f"bed height (top of highest particle): {100 * bed_height:.2f} cm (seed 000 Table 1: 15 cm)")
    print(f"solid fraction of the bed slab (depth d_p): {solid_volume / (WIDTH * bed_height * d):.3f}")
    print(f"largest distance of a centre from the mid-plane z = d_p/2: {off_plane:.1e} m")
    fig, ax = plt.subplots(figsize=(3, 5))
    ax.add_collection(EllipseCollection([a[0] for a in atoms], [a[0] for a in atoms], 0, units="x",
                                        offsets=[(a[2], a[3]) for a in atoms], transOffset=ax.transData,
                                        facecolors="tab:orange", edgecolors="k", linewidths=0.2))
    ax.set_xlim(0, WIDTH)
    ax.set_ylim(0, 0.2)
    ax.set_aspect("equal")
    ax.set_xlabel("x (m)")
    ax.set_ylabel("y (m)")
    ax.set_title(f"{len(atoms)} particles, bed {100 * bed_height:.1f} cm", fontsize=9)
    fig.tight_layout()
    fig.savefig("packing.png", dpi=150)
    print("wrote packing.png")


if __name__ == "__main__":
    main(*sys.argv[1:])
