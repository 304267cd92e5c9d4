"""Fluidization curve of a finished run: table, plateau, U_mf, fluidization_curve.png.

    plot.py [LEVELS] [--case DIR]    (LEVELS default DIR/levels.yaml, DIR default .)
"""
import argparse
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

from tfdem import fluidization  # noqa: E402
from tfdem.frontdoor import add_debug_option, run_command, save_figure_atomic  # noqa: E402


def report(case, schedule):
    """Print the table and the figures of the run in `case`; write fluidization_curve.png there."""
    s = fluidization.summary(case, schedule)
    for line in fluidization.report(s, schedule):
        print(line)
    result, weight = s["levels"], s["weight"]
    plt.figure(figsize=(5, 3.5))
    up, down = schedule.rising(result), schedule.falling(result)
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
    save_figure_atomic(plt.gcf(), os.path.join(case, "fluidization_curve.png"), dpi=120)
    plt.close()
    print("wrote fluidization_curve.png")


def main(argv=None):
    return run_command("plot.py", _plot, argv, known=(ValueError,))


def _plot(argv):
    parser = argparse.ArgumentParser(prog="plot.py", description=__doc__.splitlines()[0])
    parser.add_argument("levels", nargs="?", help="YAML file of levels (default: CASE/levels.yaml)")
    parser.add_argument("--case", default=".", help="case directory of the finished run (default: .)")
    add_debug_option(parser)
    args = parser.parse_args(argv)
    report(args.case, fluidization.Schedule.load(args.levels or os.path.join(args.case, "levels.yaml")))
    return 0


if __name__ == "__main__":
    sys.exit(main())
