"""tfm_dissipation.py (studies/seed000) on hand-made particles, with the answers worked by hand:

- the power of gas and gravity on two spheres of d = 1 cm, rho 1000 kg/m^3 (m = 5.236e-4 kg),
  g = 10 m/s^2: one at v (1, 2, 0) under F (3, 4, 0), one at v (0, -1, 0) under no force:
  3 + (4 - 10 m) 2 + 10 m = 10.994764 W;
- kinetic theory's dissipation scale of one cell of 0.1 x 0.1 x 0.01 m holding two spheres of
  d = 2 cm (alpha 0.0837758, Carnahan-Starling g0 1.2456931) at v (+-1, 0, 0): Theta = 2 / 3
  (n - 1 = 1), S = 12 g0 rho alpha^2 Theta^1.5 V / (d sqrt(pi)) = 0.16109709 W; with the 2-D
  temperature (Theta = 1) 0.29595425 W; a third sphere alone in another cell adds nothing;
- the effective restitution of D = 0.75 S is 0.5;
- a run folder without particle files is refused with a message, exit 1.
"""
import os
import sys
import tempfile

from checks import check, close, finish
from tfdem import STUDIES
from tfdem.case import Grid

sys.path.insert(0, os.path.join(STUDIES, "seed000"))
import tfm_dissipation as dissipation  # noqa: E402

pair = {"diameter": [0.01, 0.01], "velocity": [(1, 2, 0), (0, -1, 0)], "fluidForce": [(3, 4, 0), (0, 0, 0)]}
close("power of gas and gravity on two spheres", dissipation.input_power(pair, 1000.0, 10.0), 10.994764012)

grid = Grid((0, 0, 0), (0.1, 0.1, 0.01), (2, 1, 1))
cell = {"position": [(0.05, 0.05, 0.005), (0.06, 0.04, 0.005), (0.15, 0.05, 0.005)],
        "diameter": [0.02, 0.02, 0.02], "velocity": [(1, 0, 0), (-1, 0, 0), (5, 5, 0)]}
close("kinetic theory's dissipation scale, one cell of two spheres",
      dissipation.dissipation_scale(cell, grid, 1000.0), 0.161097088)
close("the same with the 2-D temperature", dissipation.dissipation_scale(cell, grid, 1000.0, components=2),
      0.295954248)
close("effective restitution of D = 0.75 S", dissipation.effective(0.75, 1.0), 0.5, 1e-12)

with tempfile.TemporaryDirectory() as folder:
    code = dissipation.main([folder, "--csv", os.path.join(folder, "out.csv")])
    check("a run without particle files: exit 1", code == 1)

finish()
