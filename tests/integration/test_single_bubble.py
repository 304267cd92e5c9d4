"""Bokkers' single bubble (tutorials/single_bubble), short: its own files with a tenth of the
particles (packing.yaml count / 10, a bed ~2 cm deep instead of ~22 cm) poured, then run
through the tutorial's driver to 0.14 s, 40 ms into the jet (which starts at 0.1 s by 0/U).

- The jet's window read from 0/U: 0.1 s to 0.25 s.
- The run ends and conserves the particles; every write (0.02 s) has its gas-fraction field and
  particle file.
- Before the jet the bed is at minimum fluidization: no region of eps_g > 0.8 inside it (a
  bubble found at 0.1 s would be a spurious one).
- 40 ms into the 20 m/s jet through a bed ~2 cm deep: the jet has blown a channel through the
  bed (the cells over the jet hold eps_g > 0.8 up to the freeboard).
- Mixing of the coloured lower half (its particles above the bed's median height), resolved by
  where each particle started: before the jet the layers stay apart (< 0.5 % above the median:
  the measure reads no mixing at rest); 40 ms into the jet nearly every coloured particle that
  started over the 15 mm opening is above the median (>= 90 %: 20 m/s is 1.6x the terminal
  speed of a 2.5 mm glass sphere in air, sqrt(4 g d rho_p / (3 0.44 rho_g)) = 12.5 m/s, and
  the bed's drag at eps_g ~ 0.4 is far larger than a lone sphere's), while those that started
  more than two jet widths from its axis have not moved up (< 2 %): the mixing is the jet's.
"""
import math
import os
import statistics
import sys

from tfdem import TUTORIALS, bubble, outputs
from tfdem.batch import run_batch
from tfdem_testlib import Checks, poured_copy

TUTORIAL = os.path.join(TUTORIALS, "single_bubble")
sys.path.insert(0, TUTORIAL)
import bubble as driver  # noqa: E402  (the tutorial's bubble.py)


def coloured_above_by_origin(path, root, time_name, start_x, region):
    """Fraction of the coloured particles whose start x (start_x: id -> x) is in region(x) that
    are above the bed's median height at time_name, and how many there are."""
    initial, interface = driver.coloured_layer(root)
    now = outputs.vtk_particles(os.path.join(path, "VTK", f"particles_{time_name}.vtk"))
    heights = [x[1] for x in now["position"]]
    middle = statistics.median(heights)
    chosen = [h for i, h in zip(now["id"], heights) if initial.get(i, math.inf) < interface and region(start_x[i])]
    return sum(h > middle for h in chosen) / len(chosen), len(chosen)


def check_mixing_by_origin(checks, path, root, jet_lower, jet_upper):
    first = outputs.vtk_particles(os.path.join(path, "VTK", "particles_0.02.vtk"))
    start_x = {i: x[0] for i, x in zip(first["id"], first["position"])}
    axis, width = (jet_lower + jet_upper) / 2, jet_upper - jet_lower
    everywhere, _ = coloured_above_by_origin(path, root, "0.1", start_x, lambda x: True)
    checks.true("no mixing before the jet", everywhere < 0.005, f"({100 * everywhere:.2f} % above the median at 0.1 s)")
    over, n_over = coloured_above_by_origin(path, root, "0.14", start_x, lambda x: jet_lower <= x <= jet_upper)
    checks.true("the jet threw up the coloured particles over its opening", over >= 0.9,
                f"({100 * over:.1f} % of {n_over} above the median at 0.14 s)")
    far, n_far = coloured_above_by_origin(path, root, "0.14", start_x, lambda x: abs(x - axis) > 2 * width)
    checks.true("those far from the jet stayed down", far < 0.02,
                f"({100 * far:.2f} % of {n_far} more than {2 * width:g} m from the axis above the median at 0.14 s)")


def main():
    checks = Checks()
    case, count = poured_copy(TUTORIAL, "single_bubble", 0.1)
    root = case.path
    start, end = driver.jet_window(case)
    checks.true("jet window from 0/U", (start, end) == (0.1, 0.25), f"({start}, {end})")

    beetstra = driver.BubbleRun("beetstra", 1, root=root)
    checks.true("run finished", run_batch([beetstra], 0.14, 1))
    path = beetstra.case.path
    stats = outputs.particle_statistics(path)
    checks.true("particles conserved", all(n == count for n in stats["particles"]), f"({set(stats['particles'])})")
    written = [t for t in outputs.times(path) if float(t) > 0]
    checks.true("fields and particle files at every write", written == ["0.02", "0.04", "0.06", "0.08", "0.1", "0.12", "0.14"]
                and all(os.path.exists(os.path.join(path, "VTK", f"particles_{t}.vtk")) for t in written), f"({written})")

    history = dict(driver.bubble_history(path, root))
    checks.true("no bubble before the jet", history[0.1] is None, f"({history[0.1]})")
    grid = case.grid()
    eps = bubble.to_map(outputs.field(path, "0.14", "voidFraction"), bubble.cell_rows_columns(path, grid),
                        (grid.counts[1], grid.counts[0]))
    middle = grid.counts[0] // 2
    bed_rows = int(0.03 // grid.spacing[1]) + 1
    channel = [min(eps[r, middle - 1], eps[r, middle]) for r in range(bed_rows)]
    checks.true("the jet blew a channel through the bed", min(channel) > bubble.BUBBLE_GAS_FRACTION,
                f"(eps over the jet, lowest {bed_rows} rows: {[round(e, 3) for e in channel]})")
    jet_lower, jet_upper = (grid.origin[0] + c * grid.spacing[0] for c in (middle - 1, middle + 1))
    check_mixing_by_origin(checks, path, root, jet_lower, jet_upper)
    checks.finish()


if __name__ == "__main__":
    main()
