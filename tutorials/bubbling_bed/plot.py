"""Bubbling bed results: pressure drop over the probes and mean particle height (seed 000
Fig. 3, 9).

Writes bubbling_bed.csv (t, p(first probe) - p(second probe), mean particle height) and
bubbling_bed.png, and prints time averages after the start-up (from 1 s on) beside the paper's
values. The probes (system/controlDict `pressure`: the inlet cell and 20 cm above it), the
particles (the DEM script's data file), gravity and the cross-section come from the case.
"""
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

from tfdem import outputs  # noqa: E402
from tfdem.case import Case  # noqa: E402
from tfdem.physics import sphere_volume  # noqa: E402
from tfdem.stats import value_at  # noqa: E402

STARTUP = 1.0  # s, averages from here on


def bed_weight_per_area(case):
    """Weight of the particles of the DEM script's data file per cross-section (Pa)."""
    particles = case.particles(case.dem().read_data())
    mass = sum(rho * sphere_volume(d) for d, rho in zip(particles["diameter"], particles["density"]))
    lo, hi = case.mesh_bounds()
    return mass * case.gravity_magnitude() / ((hi[0] - lo[0]) * (hi[2] - lo[2]))


def main(case_path="."):
    case = Case(case_path)
    below, above = case.probe_locations("pressure")[:2]
    gap = f"{100 * (above[1] - below[1]):.0f}"  # cm
    weight = bed_weight_per_area(case)
    dp = [(t, p[0] - p[1]) for t, p in outputs.probes(case_path, "pressure", "p")]
    height = outputs.fix_print(case.file(case.dem().fix_file("height_out")))
    t_h, h = [t for t, _ in height], [v[0] for _, v in height]
    with open("bubbling_bed.csv", "w") as out:
        out.write(f"t_s,dp_{gap}cm_Pa,mean_particle_height_m\n")
        for t, d in dp:
            out.write(f"{t:.6g},{d:.6g},{value_at(t_h, h, t):.6g}\n")
    late_dp = [d for t, d in dp if t >= STARTUP]
    late_h = [v for t, v in zip(t_h, h) if t >= STARTUP]
    if late_dp and late_h:
        print(f"from {STARTUP} s to {dp[-1][0]:.3g} s: mean dp(inlet - {gap} cm) {sum(late_dp) / len(late_dp):.0f} Pa "
              f"(bed weight / area {weight:.0f} Pa); mean particle height "
              f"{100 * sum(late_h) / len(late_h):.2f} cm (seed 000, averaged 5-10 s: 8.9 cm TF-DEM, 9.16 cm TFM, "
              f"11.4 cm experiment)")
    fig, (a, b) = plt.subplots(2, 1, figsize=(6, 5), sharex=True)
    a.plot([t for t, _ in dp], [d for _, d in dp], lw=0.8)
    a.axhline(weight, color="k", ls="--", lw=0.8, label="bed weight / area")
    a.set_ylabel(f"p(inlet) - p({gap} cm) (Pa)")
    a.legend(fontsize=8)
    b.plot(t_h, [100 * v for v in h], lw=0.8)
    b.set_ylabel("mean particle height (cm)")
    b.set_xlabel("t (s)")
    fig.tight_layout()
    fig.savefig("bubbling_bed.png", dpi=120)
    print("wrote bubbling_bed.csv and bubbling_bed.png")


if __name__ == "__main__":
    main()
