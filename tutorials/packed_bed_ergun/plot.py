"""Run the fixed bed at three superficial velocities and compare with Ergun; ergun.png.

The bed, gas, gravity and probes come from the case's own files (tfdem.fixed_bed.FixedBed);
each run is a copy of the case in runs/U<velocity>.
"""
import os

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

from tfdem.fixed_bed import VELOCITIES, FixedBed  # noqa: E402


def main():
    here = os.path.dirname(os.path.abspath(__file__))
    bed = FixedBed(here)
    print(f"bed: {bed.particles} spheres of {1e3 * bed.d:g} mm, eps = {bed.eps:.4f}, height {100 * bed.height:.2f} cm")
    measured = []
    for u in VELOCITIES:
        dp = bed.run(os.path.join(here, "runs", f"U{u}"), u)
        expected = bed.expected_pressure_drop(u)
        measured.append(dp)
        print(f"U = {u} m/s: dp = {dp:.2f} Pa, Ergun {expected:.2f} Pa, error {100 * (dp / expected - 1):+.2f} %")
    us = [0.05 * k for k in range(1, 23)]
    plt.figure(figsize=(4, 3))
    plt.plot(us, [bed.expected_pressure_drop(u) for u in us], "k-", label="Ergun")
    plt.plot(VELOCITIES, measured, "o", label="tfdemFoam, fixed bed")
    plt.xlabel("superficial velocity (m/s)")
    plt.ylabel("pressure drop (Pa)")
    plt.legend(fontsize=8)
    plt.tight_layout()
    plt.savefig(os.path.join(here, "ergun.png"), dpi=120)
    print("wrote ergun.png")


if __name__ == "__main__":
    main()
