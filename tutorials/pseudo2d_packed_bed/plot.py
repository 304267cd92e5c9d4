"""Pour the bed when bed.data is missing, run gas through it (one cell deep and the 3-D
variant, tfdem.fixed_bed.poured_bed_runs) and compare the pressure drop between the probe rows
with Ergun at the slab's measured solid fraction; ergun.png (with the bed's eps profile)."""
import os

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

from tfdem.fixed_bed import PouredBed, poured_bed_runs  # noqa: E402
from tfdem.packing import pour_case  # noqa: E402
from tfdem.physics import slab_solid_fraction  # noqa: E402

HERE = os.path.dirname(os.path.abspath(__file__))


def main():
    if not os.path.exists(os.path.join(HERE, "bed.data")):
        print(pour_case(HERE))
    bed = PouredBed(HERE)
    print(f"slab {100 * bed.below:g}-{100 * bed.above:g} cm: eps = {bed.eps:.4f}")
    results = poured_bed_runs(HERE, os.path.join(HERE, "runs"))
    for (name, u), (dp, expected) in results.items():
        print(f"{name:12s} U = {u} m/s: dp = {dp:.2f} Pa, Ergun {expected:.2f} Pa, error {100 * (dp / expected - 1):+.2f} %")

    particles = bed.case.particles()
    area = bed.width * bed.depth
    layer = 0.005
    heights = [layer * (k + 0.5) for k in range(int(0.15 / layer))]
    profile = [1 - slab_solid_fraction(particles, y - layer / 2, y + layer / 2, area) for y in heights]
    fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(8, 3))
    us = [0.05 * k for k in range(1, 23)]
    ax1.plot(us, [bed.expected_pressure_drop(u) for u in us], "k-", label=f"Ergun, eps = {bed.eps:.3f}")
    for name, marker in (("one_cell", "o"), ("deep_noslip", "s"), ("deep_slip", "^")):
        points = sorted((u, dp) for (n, u), (dp, _) in results.items() if n == name)
        ax1.plot([u for u, _ in points], [dp for _, dp in points], marker, mfc="none", label=name)
    ax1.set_xlabel("superficial velocity (m/s)")
    ax1.set_ylabel(f"p({100 * bed.below:g} cm) - p({100 * bed.above:g} cm) (Pa)")
    ax1.legend(fontsize=7)
    ax2.plot(profile, [100 * y for y in heights], "k.-")
    ax2.axhspan(100 * bed.below, 100 * bed.above, color="0.9")
    ax2.set_xlabel("gas fraction of 5 mm layers")
    ax2.set_ylabel("height (cm)")
    fig.tight_layout()
    fig.savefig(os.path.join(HERE, "ergun.png"), dpi=120)
    print("wrote ergun.png")


if __name__ == "__main__":
    main()
