"""Bokkers' single bubble (tutorials/single_bubble), short: its own files with a tenth of the
particles (packing.yaml count / 10, a bed ~2 cm deep instead of ~22 cm) poured, then run
through the tutorial's driver to 0.14 s, 40 ms into the jet (which starts at 0.1 s by 0/U).

- The jet's window read from 0/U: 0.1 s to 0.25 s.
- The run ends and conserves the particles; every write (0.02 s) has its gas-fraction field and
  particle file.
- Before the jet the bed is at minimum fluidization: no region of eps_g > 0.8 inside it (a
  bubble found at 0.1 s would be a spurious one).
- 40 ms into the 20 m/s jet through a bed ~2 cm deep: the jet has blown a channel through the
  bed (the cells over the jet hold eps_g > 0.8 up to the freeboard) and thrown particles of
  the coloured lower half above the bed's median height.
"""
import os
import sys

from tfdem import TUTORIALS, bubble, outputs
from tfdem.batch import run_batch
from tfdem_testlib import Checks, poured_copy

TUTORIAL = os.path.join(TUTORIALS, "single_bubble")
sys.path.insert(0, TUTORIAL)
import bubble as driver  # noqa: E402  (the tutorial's bubble.py)


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
    mixed = driver.mixing(path, root)
    checks.true("coloured particles thrown above the bed's middle", mixed[-1][1] > 0,
                f"({100 * mixed[-1][1]:.2f} % at {mixed[-1][0]} s)")
    checks.finish()


if __name__ == "__main__":
    main()
