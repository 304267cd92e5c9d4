"""Plot the settling particle's velocity against the ODE reference; print the errors."""
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

import settling_ode  # noqa: E402


def main():
    track = settling_ode.read_track("particle.dump")
    times = [t for t, _ in track]
    dem = [-v for _, v in track]
    reference = [-v for v in settling_ode.velocity(times)]
    u_t = settling_ode.terminal_velocity()
    print(f"terminal velocity: tfdemFoam {dem[-1]:.6g} m/s, drag law {u_t:.6g} m/s, "
          f"error {100 * (dem[-1] / u_t - 1):+.4f} %")
    print(f"largest velocity error over the run: {100 * max(abs(a - b) for a, b in zip(dem, reference)) / u_t:.3f} % of u_t")
    plt.figure(figsize=(4, 3))
    plt.plot(times, reference, "k-", label="ODE, seed 000 eq. 29-31")
    plt.plot(times, dem, "o", ms=3, label="tfdemFoam + LIGGGHTS")
    plt.xlabel("t (s)")
    plt.ylabel("settling speed (m/s)")
    plt.legend(fontsize=8)
    plt.tight_layout()
    plt.savefig("settling.png", dpi=120)
    print("wrote settling.png")


if __name__ == "__main__":
    main()
