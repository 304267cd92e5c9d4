"""Fluidization curve of the finished run: table, plateau, U_mf, fluidization_curve.png."""
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

import fluidization as f  # noqa: E402


def pct(value, reference):
    return f"{100 * (value / reference - 1):+.2f} %"


def main():
    s = f.summary(".")
    result = s["levels"]
    print(f"{s['particles']} particles; net bed weight / cross-section {s['weight']:.1f} Pa")
    print("branch   U (m/s)  dp (Pa)   eps    Ergun(eps) (Pa)  force on particles / weight:"
          " gas  plate  side walls")
    for k, r in enumerate(result):
        branch = "rising " if k < f.RISING_COUNT else "falling"
        print(f"{branch}  {r['u']:5.2f}  {r['dp']:7.1f}  {r['eps']:.3f}  {r['ergun']:9.1f}"
              f"            {r['gas']:.3f}  {r['plate']:.3f}  {r['side']:+.3f}")
    top, weight = s["plateau"], s["weight"]
    print(f"plateau (U >= {f.FLUIDIZED} m/s) {top:.1f} Pa vs bed weight {weight:.1f} Pa: {pct(top, weight)}"
          f" +- {100 * s['plateau_error'] / weight:.2f} % (standard error of {s['plateau_batches']}"
          f" {f.BATCH} s batch means)  [gas carries {s['gas_share']:.3f}, plate {s['plate_share']:.3f},"
          f" side walls {s['side_share']:+.3f} of the weight]")
    print(f"U_mf (falling branch, Ergun-form fit of {len(s['fitted'])} fixed-bed levels x plateau)"
          f" {s['u_mf']:.3f} m/s vs Wen-Yu {s['wen_yu']:.3f} m/s: {pct(s['u_mf'], s['wen_yu'])};"
          f" vs Ergun at the bed's eps_mf = {s['eps_mf']:.3f}: {s['ergun_u_mf']:.3f} m/s,"
          f" {pct(s['u_mf'], s['ergun_u_mf'])}")
    print(f"U_mf (rising branch, same method) {s['u_mf_rising']:.3f} m/s: {pct(s['u_mf_rising'], s['wen_yu'])} on Wen-Yu")
    r1 = s["fixed_bed_1"]
    print(f"fixed bed at 1.0 m/s (falling): {r1['dp']:.1f} Pa vs Ergun {r1['ergun']:.1f} Pa at eps = {r1['eps']:.3f},"
          f" H = {100 * r1['height']:.2f} cm: {pct(r1['dp'], r1['ergun'])}")

    plt.figure(figsize=(5, 3.5))
    up, down = f.rising(result), f.falling(result)
    plt.plot([r["u"] for r in up], [r["dp"] for r in up], "o-", ms=3, label="rising")
    plt.plot([r["u"] for r in down], [r["dp"] for r in down], "s--", ms=3, label="falling")
    a, b = s["fit"]
    us = [0.02 * k for k in range(int(s["u_mf"] / 0.02) + 1)]
    plt.plot(us, [a * u + b * u * u for u in us], "k:", lw=0.8, label="fixed-bed fit (falling)")
    plt.axhline(weight, color="k", lw=0.8, label="bed weight / area")
    plt.axvline(s["wen_yu"], color="gray", ls="-.", lw=0.8, label="U_mf Wen-Yu")
    plt.axvline(s["u_mf"], color="C3", ls=":", lw=0.8, label="U_mf measured")
    plt.ylim(0, 1.12 * weight)
    plt.xlabel("superficial velocity (m/s)")
    plt.ylabel("pressure drop (Pa)")
    plt.legend(fontsize=7)
    plt.tight_layout()
    plt.savefig("fluidization_curve.png", dpi=120)
    print("wrote fluidization_curve.png")


if __name__ == "__main__":
    main()
