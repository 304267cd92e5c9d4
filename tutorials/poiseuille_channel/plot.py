"""Plot the computed velocity profile across the channel (the `profile` set of
system/controlDict) against the Poiseuille parabola.

Writes profile.png and prints centreline velocity and pressure drop errors. The channel height
(system/blockMeshDict), mean velocity (0/U inlet), gas (constant/transportProperties) and probe
positions (system/controlDict) come from the case's own files.
"""
import re

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

from tfdem import outputs  # noqa: E402
from tfdem.case import Case, vector  # noqa: E402
from tfdem.physics import PlanePoiseuille  # noqa: E402


def main(case_path="."):
    case = Case(case_path)
    flow = PlanePoiseuille(case)
    upstream, downstream = case.probe_locations("centreline")[:2]
    probe_dx = downstream[0] - upstream[0]
    rows = outputs.latest_set(case_path, "profile", "outletProfile_U.xy")
    y = [r[0] for r in rows]
    u = [r[1] for r in rows]
    yy = [flow.y0 + flow.h * i / 200 for i in range(201)]
    exact = [flow.velocity(v) for v in yy]
    _, p = outputs.probes(case_path, "centreline", "p")[-1]
    dp = p[0] - p[1]
    dp_exact = flow.pressure_drop(probe_dx)
    u_c, u_c_exact = u[len(u) // 2], flow.centreline_velocity()
    print(f"centreline velocity {u_c:.6g} m/s, analytic {u_c_exact:.6g} m/s, "
          f"error {100 * (u_c / u_c_exact - 1):+.3f} %")
    print(f"pressure drop over {probe_dx:.6g} m: {dp:.6g} Pa, analytic {dp_exact:.6g} Pa, "
          f"error {100 * (dp / dp_exact - 1):+.3f} %")
    x_profile = vector(re.search(r"start\s*(\([^()]*\))", case.function_body("profile")).group(1))[0]
    plt.figure(figsize=(4, 3.2))
    plt.plot(exact, [v * 1e3 for v in yy], "k-", label="analytic parabola")
    plt.plot(u, [v * 1e3 for v in y], "o", ms=3, label=f"tfdemFoam, x = {100 * x_profile:.0f} cm")
    plt.xlabel("U (m/s)")
    plt.ylabel("y (mm)")
    plt.legend(fontsize=8)
    plt.tight_layout()
    plt.savefig("profile.png", dpi=120)
    print("wrote profile.png")


if __name__ == "__main__":
    main()
