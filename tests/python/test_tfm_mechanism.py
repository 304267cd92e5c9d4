"""tfm_mechanism.py's measures (studies/seed000) on hand-made fields with answers by hand, and
its committed table against its committed measures:

- the lateral std of alpha_s: rows (0.5, 0.3) and (0.4, 0.4) give (0.1 + 0) / 2 = 0.05;
- the departure from each cell's time mean is 0 for a steady lateral profile and for layers
  that move as one (each row uniform, its value changing in time), and 0.1 for a row that
  swaps (0.5, 0.3) and (0.3, 0.5) between two writes;
- the bed's rows: those whose initial mean is at least half the densest row's;
- the alpha-weighted Theta over the bed's rows;
- the second-half summary of a hand-made series, the Δp std from the intervals' means and
  spreads (the law of total variance);
- the inlet perturbation: one velocity per inlet face, the mean inflow kept;
- the jet bed's cells, numbered block by block, put in rows by their heights;
- results/tfm_mechanism.md is what report_text() makes of results/tfm_mechanism/*.csv;
- tfm_README's count of changes that leave the bed in layers is the measures';
- a snapshot file of alpha_s read back as written.
"""
import csv
import math
import os
import re
import sys
import tempfile

import checks
from checks import check, finish
from tfdem import STUDIES

sys.path.insert(0, os.path.join(STUDIES, "seed000"))
import tfm_mechanism as mechanism  # noqa: E402


def close(name, value, expected, tol=1e-12):
    checks.close(name, value, expected, tol)


close("lateral std, rows (0.5, 0.3) and (0.4, 0.4)", mechanism.lateral_std([0.5, 0.3, 0.4, 0.4], 2, [0, 1]), 0.05)

steady = [[0.5, 0.3], [0.5, 0.3]]
layers = [[0.5, 0.5], [0.3, 0.3]]
swapping = [[0.5, 0.3], [0.3, 0.5]]
for name, writes, expected in (("a steady profile", steady, 0.0), ("layers moving as one", layers, 0.0),
                               ("a row that swaps", swapping, 0.1)):
    mean = [sum(w[k] for w in writes) / len(writes) for k in range(2)]
    departures = [mechanism.lateral_std([a - m for a, m in zip(w, mean)], 2, [0]) for w in writes]
    close(f"departure from the cell's mean, {name}", sum(departures) / len(departures), expected)

check("bed rows: initial means 0.6, 0.6, 0.33, 0.1, 0", mechanism.bed_rows([0.6, 0.6, 0.6, 0.6, 0.33, 0.33,
                                                                           0.1, 0.1, 0, 0], 2) == [0, 1, 2])
close("bed Theta, alpha-weighted", mechanism.bed_theta([0.6, 0.2, 0.0, 0.0], [1.0, 5.0, 9.0, 9.0], 2, [0]),
      (0.6 * 1 + 0.2 * 5) / 0.8)

rows = [(1, 0.1, 0.1, 0.5, 0.01, 100, 0, 0.9), (2, 0.2, 0.2, 0.4, 0.02, 110, 3, 0.8),
        (3, 0.3, 0.4, 0.3, 0.03, 130, 4, 0.7), (4, 0.5, 0.6, 0.2, 0.05, 90, 0, 0.6)]
with tempfile.TemporaryDirectory() as folder:
    mechanism.RESULTS = folder
    with open(os.path.join(folder, "hand.csv"), "w", newline="") as f:
        out = csv.writer(f)
        out.writerow(["header"] * 8)
        out.writerows(rows)
    s = mechanism.summary("hand")
close("summary: from half the end time", s["from"], 2.0)
close("summary: lateral std over t = 2-4 s", s["lateral_std"], (0.2 + 0.3 + 0.5) / 3)
close("summary: departure over t = 2-4 s", s["departure_std"], (0.2 + 0.4 + 0.6) / 3)
close("summary: least alpha_s", s["min_alpha"], 0.2)
close("summary: Δp mean", s["dp_mean"], 110.0)
close("summary: Δp std, total variance of (110 ± 3), (130 ± 4), (90 ± 0)", s["dp_std"],
      math.sqrt((9 + 0 + 16 + 400 + 0 + 400) / 3))
close("summary: whole-bed support", s["support"], (0.8 + 0.7 + 0.6) / 3)

# the inlet perturbation on a hand-made case of 3 inlet faces: 3 values, mean 2 m/s kept,
# each within +-10 % (times the mean's rescaling) of it, not all equal
with tempfile.TemporaryDirectory() as case:
    os.makedirs(os.path.join(case, "system"))
    os.makedirs(os.path.join(case, "0.orig"))
    with open(os.path.join(case, "system", "blockMeshDict"), "w") as f:
        f.write("convertToMeters 1;\nvertices\n(\n    (0 0 0) (0.03 0 0) (0.03 0.3 0) (0 0.3 0)\n"
                "    (0 0 0.01) (0.03 0 0.01) (0.03 0.3 0.01) (0 0.3 0.01)\n);\n"
                "blocks\n(\n    hex (0 1 2 3 4 5 6 7) (3 3 1) simpleGrading (1 1 1)\n);\n")
    with open(os.path.join(case, "0.orig", "U.air"), "w") as f:
        f.write("inlet\n{\n    inletVelocity   uniform (0 2 0);\n}\n")
    mechanism.perturb_inlet(case)
    text = open(os.path.join(case, "0.orig", "U.air")).read()
    values = [float(v) for v in re.findall(r"\(0 (\S+) 0\)", text)]
    check("inlet perturbation: one value per inlet face", "nonuniform List<vector> 3" in text and len(values) == 3,
          text)
    close("inlet perturbation: the mean inflow kept", sum(values) / 3, 2.0, 1e-8)
    check("inlet perturbation: within +-10 % (rescaled) and not uniform",
          all(abs(v / 2 - 1) < 0.1 / 0.9 + 1e-9 for v in values) and max(values) - min(values) > 1e-3, str(values))

# the jet bed's mesh: three blocks side by side (2, 1 and 2 cells wide, 2 rows) numbered block
# by block; row by row, left to right, that is cells 0 1 | 4 | 6 7, then 2 3 | 5 | 8 9
with tempfile.TemporaryDirectory() as case:
    os.makedirs(os.path.join(case, "0"))
    heights = [0.5, 0.5, 1.5, 1.5, 0.5, 1.5, 0.5, 0.5, 1.5, 1.5]
    with open(os.path.join(case, "0", "Cy"), "w") as f:
        f.write("internalField   nonuniform List<scalar> 10\n(\n" + "\n".join(map(str, heights)) + "\n)\n;\n")
    order = mechanism.row_major(case)
    check("three blocks' cells in rows, left to right", order == [0, 1, 4, 6, 7, 2, 3, 5, 8, 9], str(order))
    check("a case without 0/Cy keeps its cells' order", mechanism.row_major(os.path.join(case, "none")) is None)

# snapshots: a hand-written file of two writes of a 2 x 2 grid of 5 mm x 1 cm cells read back
with tempfile.TemporaryDirectory() as folder:
    mechanism.SNAPSHOTS = folder
    with open(os.path.join(folder, "hand.csv"), "w") as f:
        f.write("t (s),row,alpha_s of the row's 2 cells, left to right; cells 0.5 x 1 cm\n"
                "1,0,0.6,0.5\n1,1,0.1,0.2\n2,0,0.55,0.45\n2,1,0.3,0\n")
    frames, cell = mechanism.read_snapshots("hand")
check("snapshots: two writes, each two rows, bottom first",
      frames == {"1": [[0.6, 0.5], [0.1, 0.2]], "2": [[0.55, 0.45], [0.3, 0.0]]}, str(frames))
check("snapshots: the cell size from the header", cell == (0.5, 1.0), str(cell))

mechanism.RESULTS = os.path.join(STUDIES, "seed000", "results", "tfm_mechanism")
text, missing = mechanism.report_text()
with open(os.path.join(STUDIES, "seed000", "results", "tfm_mechanism.md")) as f:
    check("results/tfm_mechanism.md is the report of the committed measures", f.read() == text,
          "run tfm_mechanism.py report")
check("every variant's measures are committed", not missing, " ".join(missing))

# tfm_README's count of the uniform bed's changes that stay below the bound, from the measures
changes = [n for n in mechanism.SEED000_VARIANTS if n != "template"]
layered = [n for n in changes if mechanism.summary(n)["departure_std"] <= mechanism.BUBBLING]
with open(os.path.join(STUDIES, "seed000", "tfm_README.md")) as f:
    stated = re.search(r"Over (\d+) of the (\d+) changes", f.read())
check("tfm_README's count of changes that leave layers", stated is not None and
      (int(stated.group(1)), int(stated.group(2))) == (len(layered), len(changes)),
      f"stated {stated.groups() if stated else None}, measured {len(layered)} of {len(changes)}")

finish()
