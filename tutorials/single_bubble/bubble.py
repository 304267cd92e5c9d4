"""Bokkers' single bubble (seed 001 §5, Fig. 8-9) under two drag laws.

    bubble.py run [--jobs 2] [--ranks 1] [--variants beetstra ergun_wen_yu]
    bubble.py report

Each law also with seed 001's hard spheres (--variants beetstra_hard_sphere ...; one rank,
not run by default): the same bed, dem.engine hard_sphere with the contacts' e_n, beta_0 and
mu (tfdem.engines.convert_to_hard_sphere).

`run` pours the bed once (bed.data, tfdem.packing from packing.yaml) and runs each law in
runs/<law>/ (resumable: a stopped run resumes from its last write, a finished one is
skipped). `report` finds the bubble in every written gas-fraction field (tfdem.bubble: the
largest region with eps_g > 0.8 below the freeboard), prints its equivalent diameter, aspect
ratio and rise velocity, the mixing of the coloured lower half of the bed (the fraction of its
particles above the bed's median height), keeps both at every write in results/<law>.csv (as
tfm.py keeps the two-fluid model's in results/tfm.csv), and draws snapshots.png (particles and the eps_g = 0.8
contour 0.1, 0.2 and 0.4 s after injection, as Fig. 8 and 9) and bubble.png (size, shape and
height against time). The jet's start and end come from the case's 0/U.
"""
import os
import re
import statistics
import sys

import numpy

from tfdem import bubble, outputs
from tfdem.batch import VariantRun, clock, variants_command_line
from tfdem.case import Case, CaseError
from tfdem.engines import HARD_SPHERE, convert_to_hard_sphere, with_hard_sphere
from tfdem.run import run

HERE = os.path.dirname(os.path.abspath(__file__))
# coupling.yaml gives Beetstra et al.'s law (seed 001 eq. 6, lattice-Boltzmann); the standard
# one is seed 001 eq. 3-4 (Ergun below eps_g = 0.8, Wen-Yu above).
LAWS = {"beetstra": {"coupling.drag_law": "beetstra"},
        "ergun_wen_yu": {"coupling.drag_law": "ergun_wen_yu_review"}}
VARIANTS = with_hard_sphere(LAWS)
AFTER_INJECTION = (0.1, 0.2, 0.4)  # s, seed 001 Fig. 8
# the two-fluid model's results beside the DPM's in bubble.png (tfm.py)
TFM_RESULTS = {"tfm": "TFM (v1912 kinetic theory)", "tfm_refine2": "TFM, cells halved",
               "tfm_peer": "TFM peer (MFIX slip production, effective e)"}


class BubbleRun(VariantRun):
    """The run of `law` (a key of VARIANTS: a law, or a law with the hard spheres, one rank)
    under root/runs/<law>/, with the cell centres the bubble's map needs."""

    def __init__(self, law, ranks, root=HERE):
        hard = law.endswith(HARD_SPHERE)
        super().__init__(law, VARIANTS[law], 1 if hard else ranks, root)
        self.hard_sphere = hard

    def prepare_mesh(self):
        run(["postProcess", "-func", "writeCellCentres", "-time", "0"], self.case.path, "log.writeCellCentres")
        if self.hard_sphere:
            convert_to_hard_sphere(self.case)


def jet_window(case):
    """(start, end) of the jet: the times of the 0/U jet table where its velocity starts to
    rise from the background's (the inlet's) and where it starts to fall back."""
    path = case.file("0", "U")
    background = case.patch_value("U", "inlet")[1]
    body = re.search(r"\bjet\s*\{(.*?)\n\s*\}", open(path).read(), flags=re.S)
    rows = re.findall(r"\(\s*([-\d.eE+]+)\s*\(\s*\S+\s+([-\d.eE+]+)\s+\S+\s*\)\s*\)", body.group(1) if body else "")
    table = [(float(t), float(v)) for t, v in rows]
    on = [k for k, (_, v) in enumerate(table) if v > background]
    if not on or on[0] == 0:
        raise CaseError(f"{path}: the jet's table must start at the background {background} m/s and rise above it")
    return table[on[0] - 1][0], table[on[-1]][0]


def bubble_history(case_path, root=HERE):
    """[(t, bubble or None)] over the run's written times (after 0)."""
    return bubble.bubble_history(case_path, Case(root).grid(), "voidFraction")


def rise_velocity(history, start, end):
    """Least-squares slope of the bubble centroid's height over [start, end] (m/s)."""
    points = [(t, b["y"]) for t, b in history if b is not None and start <= t <= end]
    if len(points) < 3:
        return None
    return float(numpy.polyfit([t for t, _ in points], [y for _, y in points], 1)[0])


def coloured_layer(root=HERE):
    """({id: initial height}, interface): the lower half of the poured bed (by count) is the
    coloured layer, below the interface (its median height)."""
    start = Case(root).particles()
    return dict(zip(start["id"], start["y"])), statistics.median(start["y"])


def mixing(case_path, root=HERE):
    """[(t, coloured fraction above the bed's middle)] from the particle files: the middle is
    the median particle height at t, so a bubble that lifts the whole bed does not count as
    mixing: 0 while the layers stay apart, 0.5 once they are mixed."""
    initial, interface = coloured_layer(root)
    out = []
    for path in sorted(os.listdir(os.path.join(case_path, "VTK")),
                       key=lambda n: float(n[len("particles_"):-len(".vtk")])):
        t = float(path[len("particles_"):-len(".vtk")])
        p = outputs.vtk_particles(os.path.join(case_path, "VTK", path))
        heights = [x[1] for x in p["position"]]
        out.append((t, bubble.coloured_above(initial, p["id"], heights, interface, statistics.median(heights))))
    return out


def report(root=HERE):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    case = Case(root)
    t_jet, t_off = jet_window(case)
    print(f"jet from {t_jet:g} s to {t_off:g} s")
    histories = {}
    for law in VARIANTS:
        path = os.path.join(root, "runs", law)
        if not os.path.isdir(path):
            continue
        history = bubble_history(path, root)
        histories[law] = history
        run_ = BubbleRun(law, 1, root)
        print(f"{law}: {clock(run_.cpu_seconds())} processor time")
        for after in AFTER_INJECTION:
            found = [b for t, b in history if abs(t - (t_jet + after)) < 1e-6]
            if found and found[0]:
                b = found[0]
                print(f"  {after:g} s after injection: D = {100 * b['diameter']:.1f} cm, aspect {b['aspect']:.2f},"
                      f" centroid {100 * b['y']:.1f} cm")
            elif found:
                print(f"  {after:g} s after injection: no bubble below the freeboard")
        u = rise_velocity(history, t_off, t_jet + max(AFTER_INJECTION))
        print(f"  rise velocity after the jet: {u:.2f} m/s" if u is not None else "  rise velocity: too few samples")
        mixed = dict(mixing(path, root)) if os.path.isdir(os.path.join(path, "VTK")) else {}
        if mixed:
            last = max(mixed)
            print(f"  coloured lower half above the bed's median height at {last:g} s:"
                  f" {100 * mixed[last]:.2f} % (0: layers apart, 50: mixed)")
        bubble.write_history(os.path.join(root, "results", law + ".csv"), history, mixed)
    if not histories:
        print("no runs yet")
        return
    fig, axes = plt.subplots(1, 4, figsize=(13, 3))
    for name in [law for law in VARIANTS if law in histories] + [n for n in TFM_RESULTS if n not in histories]:
        path = os.path.join(root, "results", name + ".csv")
        if not os.path.exists(path):
            continue
        rows = [line.split(",") for line in open(path).read().splitlines()[1:]]
        for ax, k, scale in zip(axes, (1, 2, 3, 4), (100, 1, 100, 1)):
            points = [(float(r[0]) - t_jet, scale * float(r[k])) for r in rows if r[k] and float(r[0]) >= t_jet]
            ax.plot([t for t, _ in points], [v for _, v in points], ".-", label=TFM_RESULTS.get(name, name))
    for ax, label in zip(axes, ("equivalent diameter (cm)", "aspect ratio (height/width)", "centroid height (cm)",
                                "coloured share above the median height")):
        ax.set_xlabel("t after injection (s)")
        ax.set_ylabel(label)
    axes[0].legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(os.path.join(root, "bubble.png"), dpi=120)
    draw_snapshots(root, histories, t_jet, plt)
    print("wrote bubble.png, snapshots.png")


def draw_snapshots(root, histories, t_jet, plt):
    """Particles (coloured lower half dark) and the eps_g = 0.8 contour at the Fig. 8 times."""
    case = Case(root)
    grid = case.grid()
    initial, interface = coloured_layer(root)
    coloured = {i for i, y in initial.items() if y < interface}
    fig, axes = plt.subplots(len(histories), len(AFTER_INJECTION), figsize=(3 * len(AFTER_INJECTION), 3.2 * len(histories)),
                             squeeze=False)
    for row, law in enumerate(histories):
        path = os.path.join(root, "runs", law)
        cells = bubble.cell_rows_columns(path, grid)
        for col, after in enumerate(AFTER_INJECTION):
            ax = axes[row][col]
            name = f"{t_jet + after:g}"
            vtk = os.path.join(path, "VTK", f"particles_{name}.vtk")
            if os.path.exists(vtk):
                p = outputs.vtk_particles(vtk)
                dark = [i in coloured for i in p["id"]]
                xs, ys = [x[0] for x in p["position"]], [x[1] for x in p["position"]]
                ax.scatter([x for x, d in zip(xs, dark) if not d], [y for y, d in zip(ys, dark) if not d], s=0.05, c="0.75")
                ax.scatter([x for x, d in zip(xs, dark) if d], [y for y, d in zip(ys, dark) if d], s=0.05, c="k")
            if os.path.exists(os.path.join(path, name, "voidFraction")):
                eps = bubble.to_map(outputs.field(path, name, "voidFraction"), cells, (grid.counts[1], grid.counts[0]))
                x = [grid.origin[0] + (c + 0.5) * grid.spacing[0] for c in range(grid.counts[0])]
                y = [grid.origin[1] + (r + 0.5) * grid.spacing[1] for r in range(grid.counts[1])]
                ax.contour(x, y, eps, levels=[bubble.BUBBLE_GAS_FRACTION], colors="r", linewidths=0.8)
            ax.set_xlim(0, grid.origin[0] + grid.counts[0] * grid.spacing[0])
            ax.set_ylim(0, 0.45)
            ax.set_aspect("equal")
            ax.set_title(f"{law}, {after:g} s", fontsize=8)
    fig.tight_layout()
    fig.savefig(os.path.join(root, "snapshots.png"), dpi=130)


def main(argv=None):
    end_time = float(Case(HERE).control("endTime"))
    return variants_command_line(__doc__, HERE, VARIANTS, BubbleRun, report, end_time, argv,
                                 default_variants=LAWS)


if __name__ == "__main__":
    sys.exit(main())
