"""Plot the computed velocity profile at x = 0.09 m against the Poiseuille parabola.

Writes profile.png and prints centreline velocity and pressure drop errors.
"""
import glob
import os

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

H = 0.01          # channel height (m), system/blockMeshDict
U_MEAN = 0.015    # mean velocity (m/s), 0/U
RHO, NU = 1.2, 1.5e-5
PROBE_DX = 0.04   # distance between the two centreline probes (m)


def latest(pattern):
    files = sorted(glob.glob(pattern), key=lambda f: float(f.split(os.sep)[-2]))
    return files[-1]


def main():
    rows = [list(map(float, line.split())) for line in open(latest("postProcessing/profile/*/outletProfile_U.xy"))]
    y = [r[0] for r in rows]
    u = [r[1] for r in rows]
    yy = [H * i / 200 for i in range(201)]
    exact = [6 * U_MEAN * v * (H - v) / H**2 for v in yy]
    p_rows = [line.split() for line in open(latest("postProcessing/centreline/*/p")) if not line.startswith("#")]
    dp = float(p_rows[-1][1]) - float(p_rows[-1][2])
    dp_exact = 12 * RHO * NU * U_MEAN * PROBE_DX / H**2
    u_c = u[len(u) // 2]
    print(f"centreline velocity {u_c:.6g} m/s, analytic {1.5 * U_MEAN:.6g} m/s, "
          f"error {100 * (u_c / (1.5 * U_MEAN) - 1):+.3f} %")
    print(f"pressure drop over {PROBE_DX} m: {dp:.6g} Pa, analytic {dp_exact:.6g} Pa, "
          f"error {100 * (dp / dp_exact - 1):+.3f} %")
    plt.figure(figsize=(4, 3.2))
    plt.plot(exact, [v * 1e3 for v in yy], "k-", label="analytic parabola")
    plt.plot(u, [v * 1e3 for v in y], "o", ms=3, label="tfdemFoam, x = 9 cm")
    plt.xlabel("U (m/s)")
    plt.ylabel("y (mm)")
    plt.legend(fontsize=8)
    plt.tight_layout()
    plt.savefig("profile.png", dpi=120)
    print("wrote profile.png")


if __name__ == "__main__":
    main()
