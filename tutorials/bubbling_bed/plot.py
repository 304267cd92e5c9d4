"""Bubbling bed results: pressure drop at 20 cm and mean particle height (seed 000 Fig. 3, 9).

Writes bubbling_bed.csv (t, dp_20cm, mean particle height) and bubbling_bed.png, and prints
time averages after the start-up (from 1 s on) beside the paper's values.
"""
import glob
import os

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

BED_WEIGHT_PER_AREA = 4000 * 2526 * 3.141592653589793 * 0.0025 ** 3 / 6 * 9.81 / (0.15 * 0.0025)
STARTUP = 1.0  # s, averages from here on


def pressure_drop():
    """(t, p_inlet - p_20cm) from the probes (first probe at the inlet cell, second at 20 cm)."""
    rows = []
    for path in sorted(glob.glob("postProcessing/pressure/*/p"), key=lambda f: float(f.split(os.sep)[-2])):
        for line in open(path):
            if line.startswith("#") or not line.strip():
                continue
            t, p_in, p_20 = map(float, line.split()[:3])
            rows.append((t, p_in - p_20))
    return rows


def mean_height():
    return [tuple(map(float, line.split())) for line in open("mean_height.txt") if not line.startswith("#")]


def value_at(series, t):
    """Last sample of `series` at or before t."""
    best = series[0][1]
    for ts, v in series:
        if ts > t + 1e-12:
            break
        best = v
    return best


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
