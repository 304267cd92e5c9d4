"""Bubbling bed results: pressure drop at 20 cm and mean particle height (seed 000 Fig. 3, 9).

Writes bubbling_bed.csv (t, dp_20cm, mean particle height) and bubbling_bed.png, and prints
time averages after the start-up (from 1 s on) beside the paper's values.
"""
import math
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
from tutorial_series import mean_height, pressure_probes, value_at  # noqa: E402

BED_WEIGHT_PER_AREA = 4000 * 2526 * math.pi * 0.0025 ** 3 / 6 * 9.81 / (0.15 * 0.0025)
STARTUP = 1.0  # s, averages from here on


def pressure_drop():
    """(t, p_inlet - p_20cm) from the probes (first probe at the inlet cell, second at 20 cm)."""
    return [(t, p[0] - p[1]) for t, p in pressure_probes()]


def main():
    dp = pressure_drop()
    height = mean_height()
    with open("bubbling_bed.csv", "w") as out:
        out.write("t_s,dp_20cm_Pa,mean_particle_height_m\n")
        for t, d in dp:
            out.write(f"{t:.6g},{d:.6g},{value_at(height, t):.6g}\n")
    late_dp = [d for t, d in dp if t >= STARTUP]
    late_h = [h for t, h in height if t >= STARTUP]
    if late_dp and late_h:
        print(f"from {STARTUP} s to {dp[-1][0]:.3g} s: mean dp(inlet - 20 cm) {sum(late_dp) / len(late_dp):.0f} Pa "
              f"(bed weight / area {BED_WEIGHT_PER_AREA:.0f} Pa); mean particle height "
              f"{100 * sum(late_h) / len(late_h):.2f} cm (seed 000, averaged 5-10 s: 8.9 cm TF-DEM, 9.16 cm TFM, "
              f"11.4 cm experiment)")
    fig, (a, b) = plt.subplots(2, 1, figsize=(6, 5), sharex=True)
    a.plot([t for t, _ in dp], [d for _, d in dp], lw=0.8)
    a.axhline(BED_WEIGHT_PER_AREA, color="k", ls="--", lw=0.8, label="bed weight / area")
    a.set_ylabel("p(inlet) - p(20 cm) (Pa)")
    a.legend(fontsize=8)
    b.plot([t for t, _ in height], [100 * h for _, h in height], lw=0.8)
    b.set_ylabel("mean particle height (cm)")
    b.set_xlabel("t (s)")
    fig.tight_layout()
    fig.savefig("bubbling_bed.png", dpi=120)
    print("wrote bubbling_bed.csv and bubbling_bed.png")


if __name__ == "__main__":
    main()
