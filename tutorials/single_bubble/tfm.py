"""Bokkers' single bubble (seed 001 Fig. 8-9) with the two-fluid model, beside the DPM.

    tfm.py run [--refine 2] [--solids peer]      # the TFM case tfm/ in runs/tfm/ by Debian's twoPhaseEulerFoam
    tfm.py report [--refine 2] [--solids peer]   # the bubble and the coloured layer's mixing, results/tfm.csv

`--refine k` runs and reports the case on cells k times smaller each way (runs/tfm_refine<k>/,
results/tfm_refine<k>.csv): how much of the TFM's mixing is its grid's. `--solids peer` runs the
kinetic-theory peer of studies/seed000 instead of v1912's kinetic theory as shipped
(runs/tfm_peer/, results/tfm_peer.csv): Theta's production by gas slip as MFIX has it (Koch &
Sangani 1999; tfm_models/granularSlipProduction) and Jenkins & Zhang's (2002) effective
restitution of the DPM case's e_n and friction (in.bed), with the solids pressure force as
-grad P_s (tfm_models/kineticTheoryConservative).

The case (tfm/, OpenFOAM v1912's kinetic theory with seed 001's restitution 0.97, Ergun/Wen-Yu
drag) takes from this DPM case what they share, read from its files: the grid and its jet
(system/blockMeshDict), the background inflow and the jet's table (0/U), the end time and
write interval (system/controlDict), and the inventory (packing.yaml's count of 2.5 mm
spheres in the 0.30 x 0.015 m section), which `run` lays down as a packed bed at solids
fraction ALPHA_PACKED, its lower half coloured. The colour is a solids fraction of its own,
alpha.coloured, carried with the solids' velocity (a scalarTransport function object).

`report` measures both models the same way (tfdem.bubble): the bubble is the largest region
with gas fraction above 0.8 below the freeboard (its equivalent diameter, aspect ratio and
centroid height), and the mixing is the fraction of the coloured solids above the median
height of all the solids (0 while the layers stay apart, 0.5 once mixed): for the TFM the
solids are spread evenly over each cell's height, so the median and the fraction above it are
continuous in time.
"""
import argparse
import math
import os
import re
import shutil
import sys

from tfdem import bubble, outputs, tfm_models
from tfdem.case import Case
from tfdem.errors import Reported
from tfdem.packing import packing_settings
from tfdem.physics import jenkins_zhang_effective_restitution
from tfdem.run import run

HERE = os.path.dirname(os.path.abspath(__file__))
TEMPLATE = os.path.join(HERE, "tfm")


def paths(refine, solids="stock"):
    """(run folder, results file) of the case on cells `refine` times smaller, with `solids`."""
    name = "tfm" + ("" if solids == "stock" else f"_{solids}") + ("" if refine == 1 else f"_refine{refine}")
    return os.path.join(HERE, "runs", name), os.path.join(HERE, "results", name + ".csv")


def make_peer(dpm, tfm):
    """The kinetic-theory peer in the TFM case: MFIX's slip production (constant/fvOptions, the
    library in controlDict), the effective restitution of the DPM's e_n and friction and the
    solids pressure force as -grad P_s (kineticTheoryConservative)."""
    script = dpm.dem()
    restitution = jenkins_zhang_effective_restitution(script.value(script.variable("en")),
                                                      script.value(script.variable("mu")))
    kinetic, control = tfm.file("constant", "turbulenceProperties.particles"), tfm.file("system", "controlDict")
    edits = ([(kinetic, r"(\n\s*e\s+)[0-9.]+;", rf"\g<1>{restitution:.4f};")]
             + [(kinetic, *edit) for edit in tfm_models.CONSERVATIVE_PRESSURE_EDITS]
             + [(control, *tfm_models.load_library_edit())])
    for path, pattern, replacement in edits:
        text, count = re.subn(pattern, replacement, open(path).read())
        if count != 1:
            raise SystemExit(f"{path}: not one match of {pattern!r}")
        open(path, "w").write(text)
    with open(tfm.file("constant", "fvOptions"), "w") as f:
        f.write(tfm_models.slip_production_options("KochSangani"))
    print(f"tfm: the kinetic-theory peer, e {restitution:.4f}, Koch & Sangani's slip production, -grad P_s")
# The poured bed's solids fraction (packing.yaml's note), between the frictional stress's
# onset (0.58) and its packing limit (0.62): the bed starts packed and friction-supported
ALPHA_PACKED = 0.6


def jet_table(dpm):
    """The DPM case's 0/U jet entry, its `uniformValue table (...)` text."""
    text = open(dpm.file("0", "U")).read()
    found = re.search(r"\bjet\s*\{.*?(uniformValue\s+table\s*\(.*?\n\s*\);)", text, flags=re.S)
    if not found:
        raise SystemExit(f"{dpm.file('0', 'U')}: no jet table")
    return found.group(1)


def bed_height(dpm, tfm):
    """Height (m) of the packed bed holding packing.yaml's spheres in the DPM's section."""
    count = packing_settings(dpm)["count"]
    d = float(re.search(r"\n\s*d\s+([0-9.eE+-]+);", open(tfm.file("constant", "phaseProperties")).read()).group(1))
    grid = dpm.grid()
    width = grid.spacing[0] * grid.counts[0]
    depth = grid.spacing[2] * grid.counts[2]
    return count * math.pi * d ** 3 / 6 / (width * depth * ALPHA_PACKED)


def layer(centres, dy, top):
    """Per cell (the case's order, from its centres): ALPHA_PACKED times the fraction of the
    cell's height below `top`."""
    return [ALPHA_PACKED * min(max((top - (y - dy / 2)) / dy, 0.0), 1.0) for _, y, _ in centres]


def write_internal(path, values):
    text = open(path).read()
    body = f"nonuniform List<scalar>\n{len(values)}\n(\n" + "\n".join(f"{v:.9g}" for v in values) + "\n)"
    text, n = re.subn(r"internalField\s+[^;]*;", f"internalField   {body};", text, count=1)
    if n != 1:
        raise SystemExit(f"{path}: no internalField")
    open(path, "w").write(text)


def refine_blocks(path, factor):
    """The blockMeshDict's cell counts times `factor` along x and y."""
    text = open(path).read()
    text, count = re.subn(r"(hex\s*\([^)]*\)\s*)\((\d+)\s+(\d+)\s+1\)",
                          lambda m: f"{m.group(1)}({int(m.group(2)) * factor} {int(m.group(3)) * factor} 1)", text)
    if count == 0:
        raise SystemExit(f"{path}: no one-cell-deep hex block to refine")
    open(path, "w").write(text)


def prepare(run_path, refine=1, solids="stock"):
    if solids == "peer":
        tfm_models.check_library()  # before the earlier run is removed
    dpm = Case(HERE)
    shutil.rmtree(run_path, ignore_errors=True)
    shutil.copytree(TEMPLATE, run_path)
    tfm = Case(run_path)
    if solids == "peer":
        make_peer(dpm, tfm)
    if refine > 1:
        refine_blocks(tfm.file("system", "blockMeshDict"), refine)
    air = tfm.file("0.orig", "U.air")
    text = open(air).read()
    text = re.sub(r"uniformValue\s+table\s*\([^;]*\);", jet_table(dpm).replace("\\", "\\\\"), text, count=1)
    background = f"uniform (0 {dpm.patch_value('U', 'inlet')[1]:g} 0)"
    text = re.sub(r"(internalField|inletVelocity)(\s+)uniform \([^)]*\)", rf"\g<1>\g<2>{background}", text)
    open(air, "w").write(text)
    tfm.set_control(endTime=dpm.control("endTime"), writeInterval=dpm.control("writeInterval"))
    run(["blockMesh"], run_path, "log.blockMesh")
    shutil.copytree(tfm.file("0.orig"), tfm.file("0"))
    run(["postProcess", "-func", "writeCellCentres", "-time", "0"], run_path, "log.writeCellCentres")
    centres, dy = outputs.field(run_path, "0", "C"), tfm.grid().spacing[1]
    height = bed_height(dpm, tfm)
    write_internal(tfm.file("0", "alpha.particles"), layer(centres, dy, height))
    write_internal(tfm.file("0", "alpha.coloured"), layer(centres, dy, height / 2))
    print(f"tfm: bed {height:.4f} m at solids fraction {ALPHA_PACKED}, the lower {height / 2:.4f} m coloured")


def median_and_coloured_above(solids, coloured, dy):
    """(median height of the solids, fraction of the coloured solids above it) of two (rows,
    columns) maps of a uniform grid with rows dy high; each cell's solids spread evenly over
    its height."""
    rows, colour = [float(r.sum()) for r in solids], [float(r.sum()) for r in coloured]
    half, below = sum(rows) / 2, 0.0
    for j, row in enumerate(rows):
        if below + row >= half:
            f = (half - below) / row  # the share of row j below the median
            above = sum(colour[j + 1:]) + colour[j] * (1 - f)
            return (j + f) * dy, above / sum(colour)
        below += row
    raise ValueError("no solids")


def history(path):
    """([(t, bubble or None)], {t: mixing}) over the written times after 0."""
    grid = Case(path).grid()
    bubbles = bubble.bubble_history(path, grid, "alpha.air")
    cells = bubble.cell_rows_columns(path, grid)
    shape = (grid.counts[1], grid.counts[0])
    written = {float(name): name for name in outputs.times(path)}
    mixing = {}
    for t, _ in bubbles:
        solids, coloured = (bubble.to_map(outputs.field(path, written[t], f), cells, shape)
                            for f in ("alpha.particles", "alpha.coloured"))
        mixing[t] = median_and_coloured_above(solids, coloured, grid.spacing[1])[1]
    return bubbles, mixing


def report(run_path, results):
    bubbles, mixing = history(run_path)
    bubble.write_history(results, bubbles, mixing)
    for t, b in bubbles:
        print(f"t = {t:5.2f} s  " + (f"bubble {100 * b['diameter']:5.1f} cm, aspect {b['aspect']:.2f}, at "
                                      f"{100 * b['y']:5.1f} cm" if b else "no bubble") + f"; mixing {mixing[t]:.3f}")
    print(f"wrote {os.path.relpath(results, HERE)}")


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("command", choices=("run", "report"))
    parser.add_argument("--refine", type=int, default=1, help="cells this many times smaller each way")
    parser.add_argument("--solids", choices=("stock", "peer"), default="stock",
                        help="v1912's kinetic theory as shipped, or the peer of studies/seed000 (default stock)")
    args = parser.parse_args(argv)
    if args.refine < 1:
        parser.error(f"--refine must be a whole number of 1 or more, got {args.refine}")
    run_path, results = paths(args.refine, args.solids)
    try:
        if args.command == "run":
            prepare(run_path, args.refine, args.solids)
            run(["twoPhaseEulerFoam"], run_path, "log.twoPhaseEulerFoam")
        report(run_path, results)
    except Reported as error:
        print(f"tfm.py: {error}", file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
