"""Plot the settling particle's velocity against the ODE reference; print the errors.

Run in the case directory after the run: the sphere, gas, gravity and cell come from the case's
files (tfdem.physics.SettlingSphere.from_case), the track from the DEM script's dump.
"""
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

from tfdem.case import Case  # noqa: E402
from tfdem.outputs import dump_track  # noqa: E402
from tfdem.physics import SettlingSphere  # noqa: E402


def main(case_path="."):
    sphere = SettlingSphere.from_case(Case(case_path))
    track = dump_track(case_path, "vy")
    times = [t for t, _ in track]
    dem = [-v for _, v in track]
    reference = [-v for v in sphere.velocity(times)]
    u_t = sphere.terminal_velocity()
    print(f"terminal velocity: tfdemFoam {dem[-1]:.6g} m/s, drag law {u_t:.6g} m/s, "
          f"error {100 * (dem[-1] / u_t - 1):+.4f} %")
    print(f"largest velocity error over the run: {100 * max(abs(a - b) for a, b in zip(dem, reference)) / u_t:.3f} % of u_t")
    plt.figure(figsize=(4, 3))
    plt.plot(times, reference, "k-", label="ODE, seed 000 eq. 28-31")
    plt.plot(times, dem, "o", ms=3, label="tfdemFoam + LIGGGHTS")
    plt.xlabel("t (s)")
    plt.ylabel("settling speed (m/s)")
    plt.legend(fontsize=8)
    plt.tight_layout()
    plt.savefig("settling.png", dpi=120)
    print("wrote settling.png")


if __name__ == "__main__":
    main()
