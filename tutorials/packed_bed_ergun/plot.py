"""Run the fixed bed at three superficial velocities and compare with Ergun; ergun.png."""
import os

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

import ergun  # noqa: E402


def main():
    here = os.path.dirname(os.path.abspath(__file__))
    measured = []
    for u in ergun.VELOCITIES:
        dp = ergun.prepare_run(here, os.path.join(here, "runs", f"U{u}"), u, ergun.run_locally)
        expected = ergun.ergun_pressure_drop(u)
        measured.append(dp)
        print(f"U = {u} m/s: dp = {dp:.2f} Pa, Ergun {expected:.2f} Pa, error {100 * (dp / expected - 1):+.2f} %")
    us = [0.05 * k for k in range(1, 23)]
    plt.figure(figsize=(4, 3))
    plt.plot(us, [ergun.ergun_pressure_drop(u) for u in us], "k-", label="Ergun")
    plt.plot(ergun.VELOCITIES, measured, "o", label="tfdemFoam, fixed bed")
    plt.xlabel("superficial velocity (m/s)")
    plt.ylabel("pressure drop (Pa)")
    plt.legend(fontsize=8)
    plt.tight_layout()
    plt.savefig(os.path.join(here, "ergun.png"), dpi=120)
    print("wrote ergun.png")


if __name__ == "__main__":
    main()
