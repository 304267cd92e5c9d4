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
(tfdem.engines.hard_sphere_laws). Further realizations of these, <law>_hard_sphere_r2 and _r3,
start from the same pour jiggled at JIGGLE m/s (tfdem.packing.jiggle, one seed each); and
<law>_hard_sphere_segregated from the same spheres poured apart, the large first and the small
on them (s = 1 at the start; bed_segregated.data, made once by segregated_bed()).
"""
import os
import shutil
import sys

from tfdem import outputs
from tfdem.batch import VariantRun, clock, variants_command_line
from tfdem.case import Case
from tfdem.engines import HARD_SPHERE, convert_to_hard_sphere, with_hard_sphere
from tfdem.frontdoor import save_figure_atomic
from tfdem.liggghts import read_data_box, read_data_file, write_data_file
from tfdem.packing import jiggle, pour, pour_case
from tfdem.stats import value_at

HERE = os.path.dirname(os.path.abspath(__file__))
LAWS = {
    "polydisperse": {"coupling.drag_law": "beetstra", "coupling.polydisperse_drag": "beetstra_2007"},
    "standard": {"coupling.drag_law": "ergun_wen_yu_review", "coupling.polydisperse_drag": "own_diameter"},
    # the other two of {Ergun/Wen-Yu, Beetstra} x {own diameter, polydisperse correction}: which
    # of the two differences between the laws above sets the standard law's plateau
    "beetstra_own": {"coupling.drag_law": "beetstra", "coupling.polydisperse_drag": "own_diameter"},
    "ergun_polydisperse": {"coupling.drag_law": "ergun_wen_yu_review", "coupling.polydisperse_drag": "beetstra_2007"},
}
# Seed 001 §5 and Fig. 11 at 60 s: s = 0.65 with the polydisperse law, "almost completely
# segregated" with the standard one, 0.64 in Goldschmidt's experiment.
HARD_SPHERE_LAWS = {law + HARD_SPHERE: settings for law, settings in LAWS.items()}
REALIZATIONS = ("_r2", "_r3")  # beside the first, from the pour as it is
SEGREGATED = "_segregated"
VARIANTS = {**with_hard_sphere(LAWS),
            **{name + r: settings for name, settings in HARD_SPHERE_LAWS.items() for r in REALIZATIONS},
            **{name + SEGREGATED: settings for name, settings in HARD_SPHERE_LAWS.items()}}
DEFAULT_VARIANTS = ("polydisperse", "standard")
JIGGLE = 1e-6  # m/s: the realizations' perturbation, far below the bed's motion
SEGREGATED_BED = "bed_segregated.data"
SEED_AT_60_S = {"polydisperse": 0.65, "experiment": 0.64}
REPORT_TIMES = (1, 2, 5, 10, 20, 30, 60)
LATE_SPAN = 10.0  # s: the span before the end whose samples' spread report prints


class HardSphereVariant(VariantRun):
    """A law's run with the hard-sphere engine (one rank) on the poured bed, jiggled with
    `seed` when one is given, or on `bed` (a data file of root) instead of the pour."""

    def __init__(self, name, settings, root, seed=None, bed=None):
        super().__init__(name, settings, 1, root)
        self.seed, self.bed = seed, bed

    def prepare_mesh(self):
        if self.bed:
            shutil.copy(os.path.join(self.root, self.bed), self.case.file("bed.data"))
        if self.seed is not None:
            jiggle(self.case.file("bed.data"), JIGGLE, self.seed)
        convert_to_hard_sphere(self.case)


def segregation_run(name, ranks, root=HERE):
    """The run `name` (a key of VARIANTS) under root/runs/<name>/."""
    if name.endswith(SEGREGATED):
        return HardSphereVariant(name, VARIANTS[name], root, bed=SEGREGATED_BED)
    for k, r in enumerate(REALIZATIONS):
        if name.endswith(r):
            return HardSphereVariant(name, VARIANTS[name], root, seed=15485863 + 2 * k)
    if name.endswith(HARD_SPHERE):
        return HardSphereVariant(name, VARIANTS[name], root)
    return VariantRun(name, VARIANTS[name], ranks, root)


def segregated_bed(root=HERE, ranks=1):
    """root/bed_segregated.data: the spheres of root's pour (bed.data), each size poured apart
    into the column, the large first and the small on them, at rest (tfdem.packing.pour, the
    pour's own contacts), atom types and box as in bed.data. Made once; returns its path."""
    path = os.path.join(root, SEGREGATED_BED)
    if os.path.isfile(path):
        return path
    mixed = read_data_file(os.path.join(root, "bed.data"))
    lower, upper = read_data_box(os.path.join(root, "bed.data"))
    sizes = sorted(set(mixed["diameter"]), reverse=True)
    spheres, floor = [], lower[1]
    for d in sizes:
        count = sum(1 for x in mixed["diameter"] if x == d)
        where = os.path.join(root, "runs", f"pour_{d:g}")
        case = Case(root).copy_to(where)
        case.set_coupling("particles.diameter", [d])
        print(f"pouring {count} spheres of {d:g} m onto {floor:g} m", flush=True)
        print(pour(case, count, ranks=ranks, floor=floor), flush=True)
        poured = read_data_file(case.file("bed.data"))
        spheres += list(zip(poured["diameter"], poured["density"], poured["x"], poured["y"], poured["z"]))
        floor = max(y + x / 2 for x, y in zip(poured["diameter"], poured["y"]))
        shutil.rmtree(where)
    small_first = sorted(set(mixed["diameter"]))
    type_count = int(next(line.split()[0] for line in open(os.path.join(root, "bed.data"))
                          if line.strip().endswith("atom types")))
    write_data_file(path + ".tmp", lower, upper, [d for d, *_ in spheres], [rho for _, rho, *_ in spheres],
                    [(x, y, z) for *_, x, y, z in spheres],
                    velocities=[(0, 0, 0)] * len(spheres), types=[1 + small_first.index(d) for d, *_ in spheres],
                    type_count=type_count, title="TFDEM: Goldschmidt's bed poured segregated, large below small")
    os.replace(path + ".tmp", path)
    return path


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


def describe(name):
    """(law, engine label, start) of a run's name: ('standard', 'hard spheres', 'realization 2')."""
    law = next(law for law in LAWS if name.startswith(law))
    rest = name[len(law):]
    engine = "hard spheres" if rest.startswith(HARD_SPHERE) else "LIGGGHTS"
    rest = rest[len(HARD_SPHERE):] if engine == "hard spheres" else rest
    start = {"": "from the pour", SEGREGATED: "from a segregated start"}.get(rest, f"realization {rest[2:]}")
    return law, engine, start


def band(series):
    """(t, mean, lowest, highest) of several s(t) sampled at the same times, over the span all
    of them reached."""
    n = min(len(t) for t, _ in series)
    t = series[0][0][:n]
    rows = list(zip(*(s[:n] for _, s in series)))
    return t, [sum(r) / len(r) for r in rows], [min(r) for r in rows], [max(r) for r in rows]


def report(root=HERE):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, (whole, reached_axes) = plt.subplots(1, 2, figsize=(9, 4.3))
    reached_end, highest = 0.0, 1.0
    dashes = {"polydisperse": "-", "standard": "--", "beetstra_own": ":", "ergun_polydisperse": "-."}
    realizations = {law: [] for law in LAWS}
    for name in VARIANTS:
        t, s, source = segregation_series(name, root)
        if not t:
            if name in DEFAULT_VARIANTS:
                print(f"{name}: no samples yet")
            continue
        law, engine, start = describe(name)
        if source == "run":
            write_series(os.path.join(root, "results", f"{name}.csv"), t, s)
            cost = f"{clock(segregation_run(name, 1, root).cpu_seconds())} processor time"
        else:
            cost = f"from results/{name}.csv, the run's directory gone"
        reached = ", ".join(f"s({x:g} s) = {value_at(t, s, x):.3f}" for x in REPORT_TIMES if x <= t[-1] + 1e-9)
        print(f"{name}: t = {t[-1]:g} s reached ({cost}); {reached}{late_statistics(t, s)}")
        if engine == "hard spheres" and start != "from a segregated start":
            realizations[law].append((t, s))
            continue
        colour = "k" if engine == "LIGGGHTS" else "C2"
        for ax in (whole, reached_axes):
            ax.plot(t, s, colour + dashes[law], lw=1, label=f"TFDEM, {law} drag, {engine}, {start}")
        reached_end = max(reached_end, t[-1])
        highest = max(highest, max(s))
    for law, series in realizations.items():
        if not series:
            continue
        t, mean, low, high = band(series)
        label = f"TFDEM, {law} drag, hard spheres" + (f", {len(series)} realizations" if len(series) > 1 else "")
        for ax in (whole, reached_axes):
            ax.fill_between(t, low, high, color="C1", alpha=0.3, lw=0)
            ax.plot(t, mean, "C1" + dashes[law], lw=1, label=label)
        reached_end = max(reached_end, t[-1])
        if len(series) > 1:
            print(f"{law} drag, hard spheres: {len(series)} realizations to {t[-1]:g} s; "
                  + ", ".join(f"s({x:g} s) = {value_at(t, mean, x):.3f} ({value_at(t, low, x):.3f} to "
                              f"{value_at(t, high, x):.3f})" for x in REPORT_TIMES if x <= t[-1] + 1e-9))
    whole.plot([60], [SEED_AT_60_S["polydisperse"]], "ks", mfc="none", label="seed 001, polydisperse drag (60 s)")
    whole.plot([60], [SEED_AT_60_S["experiment"]], "ko", label="experiment (60 s)")
    print(f"seed 001 at 60 s: polydisperse {SEED_AT_60_S['polydisperse']}, experiment {SEED_AT_60_S['experiment']},"
          " standard drag almost fully segregated")
    whole.set_xlim(0, 62)
    whole.set_ylim(-0.1, max(1.05, highest + 0.05))
    whole.set_title("Fig. 11's span", fontsize=9)
    handles, labels = whole.get_legend_handles_labels()
    fig.legend(handles, labels, loc="lower center", ncol=2, fontsize=7, frameon=False)
    reached_axes.set_xlim(0, max(reached_end, 0.1))
    reached_axes.set_title("the span reached", fontsize=9)
    for ax in (whole, reached_axes):
        ax.set_xlabel("t (s)")
    whole.set_ylabel("degree of segregation s (seed 001 eq. 49)")
    fig.tight_layout(rect=(0, 0.2, 1, 1))  # the legend below both panels, clear of the curves
    save_figure_atomic(fig, os.path.join(root, "segregation.png"), dpi=120)
    print("wrote segregation.png")


def main(argv=None):
    argv = sys.argv[1:] if argv is None else argv
    if "run" in argv and any(v.endswith(SEGREGATED) for v in argv):
        if not os.path.isfile(os.path.join(HERE, "bed.data")):
            print("pouring the bed (tfdem.packing, packing.yaml)", flush=True)
            print(pour_case(HERE), flush=True)
        segregated_bed()
    return variants_command_line(__doc__, HERE, VARIANTS, segregation_run, report, 60.0, argv, DEFAULT_VARIANTS)


if __name__ == "__main__":
    sys.exit(main())
