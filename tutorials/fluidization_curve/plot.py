"""Fluidization curve of the finished run: table, plateau, U_mf, fluidization_curve.png."""
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

import fluidization as f  # noqa: E402


def main():
    drops = f.level_pressure_drops(".")
    n_up = len(f.RISING)
    for k, (u, dp) in enumerate(drops):
        print(f"{'rising ' if k < n_up else 'falling'} U = {u:.2f} m/s: dp = {dp:7.1f} Pa")
    top, weight = f.plateau(drops), f.bed_weight_per_area()
    u_mf, wen_yu = f.minimum_fluidization(drops), f.wen_yu_minimum_fluidization()
    print(f"plateau {top:.1f} Pa, bed weight per area {weight:.1f} Pa ({100 * (top / weight - 1):+.1f} %)")
    print(f"U_mf (falling branch) {u_mf:.3f} m/s, Wen-Yu {wen_yu:.3f} m/s ({100 * (u_mf / wen_yu - 1):+.1f} %)")
    plt.figure(figsize=(4.5, 3.2))
    plt.plot([u for u, _ in drops[:n_up]], [dp for _, dp in drops[:n_up]], "o-", ms=3, label="rising")
    plt.plot([u for u, _ in drops[n_up - 1:]], [dp for _, dp in drops[n_up - 1:]], "s--", ms=3, label="falling")
    plt.axhline(weight, color="k", lw=0.8, label="bed weight / area")
    plt.axvline(wen_yu, color="gray", ls=":", lw=0.8, label="U_mf Wen-Yu")
    plt.xlabel("superficial velocity (m/s)")
    plt.ylabel("pressure drop (Pa)")
    plt.legend(fontsize=7)
    plt.tight_layout()
    plt.savefig("fluidization_curve.png", dpi=120)
    print("wrote fluidization_curve.png")


if __name__ == "__main__":
    main()
