"""tutorials/single_bubble/tfm.py's measures on hand-made maps, answers by hand:

- the mixing of Fig. 9 as a TFM field gives it: the fraction of the coloured solids above the
  median height of all the solids, each cell's solids spread evenly over its height. Layers
  apart give 0; colour everywhere in the same share as the solids gives 0.5; rows of solids
  0.6, 0.6, 0.3, 0 with colour 0.6, 0.15, 0, 0 put the median a quarter into the second row
  (0.75 of 1.5 reached at 0.6 + 0.25 x 0.6) and 0.15 x 0.75 / 0.75 = 0.15 of the colour above it;
- the packed bed's height: 72,600 spheres of 2.5 mm in 0.30 x 0.015 m at solids fraction 0.6
  stand 72600 x 8.1812e-9 m^3 / (0.0045 m^2 x 0.6) = 0.21998 m (by hand);
- the initial layer of a cell row straddling the top: 0.6 x its share below the top;
- --refine 2 doubles each block's cells along x and y and leaves the grading alone;
- --solids peer sets Jenkins & Zhang's effective restitution of in.bed's e_n 0.97 and friction
  0.1, 0.97 - 1.5 x 0.1 x exp(-0.3) = 0.858877 (by hand), selects kineticTheoryConservative
  with its coefficients, loads the library and writes Koch & Sangani's slip production.
"""
import os
import re
import shutil
import sys
import tempfile

import numpy

from tfdem import TUTORIALS, tfm_models
from tfdem.case import Case

sys.path.insert(0, os.path.join(TUTORIALS, "single_bubble"))
import tfm  # noqa: E402

failures = []


def close(name, value, expected, tol=1e-12):
    ok = abs(value - expected) <= tol
    print(("PASS " if ok else "FAIL ") + f"{name}: {value!r} vs {expected!r}")
    if not ok:
        failures.append(name)


column = lambda *v: numpy.array([[x] for x in v])  # noqa: E731
dy = 0.0125
median, above = tfm.median_and_coloured_above(column(0.6, 0.6, 0.6, 0.6), column(0.6, 0.6, 0, 0), dy)
close("layers apart: median height", median, 2 * dy)
close("layers apart: coloured above", above, 0.0)
_, above = tfm.median_and_coloured_above(column(0.6, 0.5, 0.2, 0.1), column(0.3, 0.25, 0.1, 0.05), dy)
close("colour in the solids' share everywhere: coloured above", above, 0.5)
median, above = tfm.median_and_coloured_above(column(0.6, 0.6, 0.3, 0), column(0.6, 0.15, 0, 0), dy)
close("median a quarter into the second row", median, 1.25 * dy)
close("coloured above it", above, 0.15)

here = os.path.join(TUTORIALS, "single_bubble")
close("packed bed height (m)", tfm.bed_height(Case(here), Case(os.path.join(here, "tfm"))), 0.21998, 5e-5)
close("a row straddling the top (0.2125-0.225 m, top 0.22 m)", tfm.layer([(0, 0.21875, 0)], 0.0125, 0.22)[0], 0.6 * 0.6, 1e-12)

with tempfile.NamedTemporaryFile("w", suffix="blockMeshDict", delete=False) as f:
    f.write("blocks\n(\n    hex (0 1 5 4 8 9 13 12) (19 80 1) simpleGrading (1 1 1)\n"
            "    hex (1 2 6 5 9 10 14 13) (2 80 1) simpleGrading (1 1 1)\n);\n")
tfm.refine_blocks(f.name, 2)
refined = open(f.name).read()
os.unlink(f.name)
ok = "(38 160 1) simpleGrading (1 1 1)" in refined and "(4 160 1) simpleGrading (1 1 1)" in refined
print(("PASS " if ok else "FAIL ") + "refine 2: (19 80 1) and (2 80 1) become (38 160 1) and (4 160 1), grading kept")
if not ok:
    failures.append("refine")

with tempfile.TemporaryDirectory() as scratch:
    peer = os.path.join(scratch, "tfm")
    shutil.copytree(os.path.join(here, "tfm"), peer)
    tfm.make_peer(Case(here), Case(peer))
    kinetic = open(os.path.join(peer, "constant", "turbulenceProperties.particles")).read()
    control = open(os.path.join(peer, "system", "controlDict")).read()
    options = open(os.path.join(peer, "constant", "fvOptions")).read()
    for what, ok in (("peer: e 0.8589", re.search(r"\n\s*e\s+0\.8589;", kinetic) is not None),
                     ("peer: RASModel kineticTheoryConservative", "RASModel        kineticTheoryConservative;" in kinetic),
                     ("peer: its coefficients renamed", "kineticTheoryConservativeCoeffs" in kinetic
                      and "kineticTheoryCoeffs" not in kinetic),
                     ("peer: the library loaded", tfm_models.library_entry() in control),
                     ("peer: Koch & Sangani's slip production", "production      KochSangani;" in options)):
        print(("PASS " if ok else "FAIL ") + what)
        if not ok:
            failures.append(what)

print(f"{len(failures)} failed" if failures else "all passed")
sys.exit(1 if failures else 0)
