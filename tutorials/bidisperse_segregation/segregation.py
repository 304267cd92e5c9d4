"""Goldschmidt's bidisperse segregation (seed 001 §5, eq. 49, Fig. 11) under two drag laws.

    segregation.py run [--end-time 60] [--jobs 2] [--ranks 1] [--variants polydisperse standard]
    segregation.py report

`run` pours the mixed bed once (bed.data, tfdem.packing from packing.yaml) and runs each law
in runs/<law>/ from it, `jobs` runs at a time on `ranks` ranks each; a run that was stopped
resumes from its last checkpoint (every write interval) when run again, a finished one is
skipped, and one given a later end time carries on from its last checkpoint. `report` prints
the degree of segregation s(t) (the coupler's particle statistics, every 0.1 s) at the times
the runs reached, beside the seed's, draws segregation.png and keeps each run's s(t) in
results/<run>.csv (the README's numbers are read from these).

The laws (coupling.yaml gives the polydisperse one):
- polydisperse: Beetstra et al.'s (2007) monodisperse law (seed 001 eq. 6) at the local Sauter
  mean with their polydisperse correction (coupling.polydisperse_drag: beetstra_2007);
- standard: seed 001 eq. 3-4 (Ergun, Wen-Yu) at each particle's own diameter.
Each also with seed 001's hard spheres (<law>_hard_sphere, not run by default): the same bed
and gas, dem.engine: hard_sphere with the LIGGGHTS contacts' e_n, beta_0 and mu
(tfdem.engines.hard_sphere_laws).
"""
import os
import sys

from tfdem import outputs
from tfdem.batch import VariantRun, clock, variants_command_line
from tfdem.engines import HARD_SPHERE, convert_to_hard_sphere, with_hard_sphere
from tfdem.stats import value_at

HERE = os.path.dirname(os.path.abspath(__file__))
LAWS = {
    "polydisperse": {"coupling.drag_law": "beetstra", "coupling.polydisperse_drag": "beetstra_2007"},
    "standard": {"coupling.drag_law": "ergun_wen_yu_review", "coupling.polydisperse_drag": "own_diameter"},
}
# Seed 001 §5 and Fig. 11 at 60 s: s = 0.65 with the polydisperse law, "almost completely
# segregated" with the standard one, 0.64 in Goldschmidt's experiment.
VARIANTS = with_hard_sphere(LAWS)
DEFAULT_VARIANTS = tuple(LAWS)
SEED_AT_60_S = {"polydisperse": 0.65, "experiment": 0.64}
REPORT_TIMES = (1, 2, 5, 10, 20, 30, 60)
LATE_SPAN = 10.0  # s: the span before the end whose samples' spread report prints


class HardSphereVariant(VariantRun):
    """A law's run with the hard-sphere engine on the poured bed (one rank)."""

    def prepare_mesh(self):
        convert_to_hard_sphere(self.case)


def segregation_run(name, ranks, root=HERE):
    """The run `name` (a key of VARIANTS) under root/runs/<name>/."""
    if name.endswith(HARD_SPHERE):
        return HardSphereVariant(name, VARIANTS[name], 1, root)
    return VariantRun(name, VARIANTS[name], ranks, root)


def segregation_series(law, root=HERE):
    """(t, s) of a run's particle statistics, joined over its segments, and where they came
    from: the run itself, else the s(t) an earlier report kept in results/<law>.csv (a run
    whose directory is gone); empty before its first sample."""
    path = os.path.join(root, "runs", law)
    try:
        stats = outputs.particle_statistics(path)
        return stats["t"], stats.get("segregation", []), "run"
    except outputs.OutputError:
        pass
    kept = os.path.join(root, "results", f"{law}.csv")
    if not os.path.isfile(kept):
        return [], [], None
    rows = [line.split(",") for line in open(kept) if line.strip() and not line.startswith("#")]
    return [float(t) for t, _ in rows], [float(s) for _, s in rows], "kept"


def write_series(path, t, s):
    """A run's s(t), a row per sample."""
    os.makedirs(os.path.dirname(path), exist_ok=True)
    with open(path, "w") as f:
        f.write("# t (s), degree of segregation s (seed 001 eq. 49)\n")
        f.writelines(f"{ti:.6g},{si:.6g}\n" for ti, si in zip(t, s))


def late_statistics(t, s, span=LATE_SPAN):
    """The mean and standard deviation of s over the last `span` seconds reached, when the run
    reached 60 s: the 0.1 s samples swing with the bubbles, so s(60 s) alone is one draw."""
    late = [si for ti, si in zip(t, s) if ti >= t[-1] - span - 1e-9]
    if t[-1] < REPORT_TIMES[-1] - 1e-9 or len(late) < 2:
        return ""
    mean = sum(late) / len(late)
    std = (sum((x - mean) ** 2 for x in late) / (len(late) - 1)) ** 0.5
    return f"; over {t[-1] - span:g}-{t[-1]:g} s: {mean:.3f} mean, {std:.3f} standard deviation of the samples"


def report(root=HERE):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, (whole, reached_axes) = plt.subplots(1, 2, figsize=(9, 3.5))
    reached_end = 0.0
    styles = {"polydisperse": "k-", "standard": "k--"}
    for law in VARIANTS:
        t, s, source = segregation_series(law, root)
        if not t:
            if law in DEFAULT_VARIANTS:
                print(f"{law}: no samples yet")
            continue
        hard = law.endswith(HARD_SPHERE)
        style = styles[law[:-len(HARD_SPHERE)] if hard else law].replace("k", "C1" if hard else "k")
        if source == "run":
            write_series(os.path.join(root, "results", f"{law}.csv"), t, s)
            cost = f"{clock(segregation_run(law, 1, root).cpu_seconds())} processor time"
        else:
            cost = f"from results/{law}.csv, the run's directory gone"
        reached = ", ".join(f"s({x:g} s) = {value_at(t, s, x):.3f}" for x in REPORT_TIMES if x <= t[-1] + 1e-9)
        print(f"{law}: t = {t[-1]:g} s reached ({cost}); {reached}{late_statistics(t, s)}")
        for ax in (whole, reached_axes):
            ax.plot(t, s, style, label=f"TFDEM, {law.replace(HARD_SPHERE, '')} drag" + (", hard spheres" if hard else ""))
        reached_end = max(reached_end, t[-1])
    whole.plot([60], [SEED_AT_60_S["polydisperse"]], "ks", mfc="none", label="seed 001, polydisperse drag (60 s)")
    whole.plot([60], [SEED_AT_60_S["experiment"]], "ko", label="experiment (60 s)")
    print(f"seed 001 at 60 s: polydisperse {SEED_AT_60_S['polydisperse']}, experiment {SEED_AT_60_S['experiment']},"
          " standard drag almost fully segregated")
    whole.set_xlim(0, 62)
    whole.set_ylim(-0.1, 1.0)
    whole.set_title("Fig. 11's span", fontsize=9)
    whole.legend(fontsize=7)
    reached_axes.set_xlim(0, max(reached_end, 0.1))
    reached_axes.set_title("the span reached", fontsize=9)
    for ax in (whole, reached_axes):
        ax.set_xlabel("t (s)")
    whole.set_ylabel("degree of segregation s (seed 001 eq. 49)")
    fig.tight_layout()
    fig.savefig(os.path.join(root, "segregation.png"), dpi=120)
    print("wrote segregation.png")


def main(argv=None):
    return variants_command_line(__doc__, HERE, VARIANTS, segregation_run, report, 60.0, argv, DEFAULT_VARIANTS)


if __name__ == "__main__":
    sys.exit(main())
