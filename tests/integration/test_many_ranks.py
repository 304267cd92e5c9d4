"""Particles that cross between ranks all the time lose nothing: seed 000's jet bed on 4 ranks.

The jet bed (2400 spheres of 4 mm, a 39 m/s jet on the axis) runs 0.3 s on 4 ranks with the
gas split in x (decomposePar, 4 parts) and LIGGGHTS splitting x by the template's
`processors * 1 1`: the ranks' boundaries lie at x = 3.75, 7.5 and 11.25 cm, one on the jet's
axis, so the spheres the jet throws up and the bed's circulation take them from one rank to
another. A dump per rank (LIGGGHTS' `%` in the file name: each rank writes its own spheres)
every 50 DEM steps tells each sphere's rank, and so counts the crossings: the test shows they
happen. Expected, exactly: the data file's 2400 spheres in every statistics sample and in
every snapshot, each owned by one rank, and the bed's mass unchanged. Measured: ~900
crossings, in ~9 of 10 intervals of 1 ms. The start reports LIGGGHTS' grid (4 x 1 x 1) and
the particles per rank, without advice; the same bed cut `* * 1` on 2 ranks (LIGGGHTS halves
the 90 cm column in y, above the 14 cm bed) is advised to cut across the bed instead.
"""
import os
import re
import shutil

from tfdem import SOURCE_DIR, TUTORIALS
from tfdem.case import Case
from tfdem.fixed_bed import data_file_of
from tfdem.outputs import particle_statistics
from tfdem.run import decompose, run
from tfdem_testlib import Checks, scratch

RANKS, END_TIME, DUMP_EVERY = 4, 0.3, 50


def jet_bed_on_ranks():
    source = Case(os.path.join(TUTORIALS, "jet_bed"))
    case = source.copy_to(scratch("many_ranks_jet"))
    shutil.copy(source.file("Allpack"), case.file("Allpack"))
    run(["env", f"TFDEM_ROOT={SOURCE_DIR}", "bash", "Allpack"], case.path, "log.Allpack")
    case.set_control(endTime=END_TIME, writeInterval=END_TIME)
    case.set_coupling("output.statistics_interval", 0.01)
    with open(case.dem_script(), "a") as f:
        f.write(f"dump            ranks all custom {DUMP_EVERY} ranks%.dump id\n")
    run(["blockMesh"], case.path, "log.blockMesh")
    decompose(case.path, RANKS)
    _, output = run(["tfdemFoam"], case.path, "log.tfdemFoam", RANKS, gas="split")
    return case, output


def cut_in_y(case, _cache={}):
    """The start of the same bed on 2 ranks with `processors * * 1` (two gas steps)."""
    if "output" not in _cache:
        copy = Case(case.path).copy_to(scratch("many_ranks_jet_cut_in_y"), extra=data_file_of(case))
        path = copy.dem_script()
        text = re.sub(r"(?m)^processors[ \t]+.*$", "processors      * * 1", open(path).read())
        open(path, "w").write(text)
        copy.set_control(endTime=2 * float(copy.control("deltaT")), writeInterval=1.0)
        run(["blockMesh"], copy.path, "log.blockMesh")
        _cache["output"] = run(["tfdemFoam"], copy.path, "log.tfdemFoam", 2, gas="whole")[1]
    return _cache["output"]


def rank_frames(case):
    """[{id: rank}], one per snapshot, from the per-rank dumps ranks<r>.dump (each holds the
    IDs of the spheres rank r owned at every snapshot)."""
    frames = {}
    for rank in range(RANKS):
        lines = open(case.file(f"ranks{rank}.dump")).read().splitlines()
        k = 0
        while k < len(lines):
            if lines[k].startswith("ITEM: TIMESTEP"):
                step = int(lines[k + 1])
                count = int(lines[k + 3])
                k = next(j for j in range(k, len(lines)) if lines[j].startswith("ITEM: ATOMS")) + 1
                frame = frames.setdefault(step, {})
                for line in lines[k:k + count]:
                    atom = int(line.split()[0])
                    frame[atom] = -1 if atom in frame else rank  # -1: owned twice
                k += count
            else:
                k += 1
    return [frames[step] for step in sorted(frames)]


def data_file_ids(path):
    lines = open(path).read().splitlines()
    start = next(k for k, line in enumerate(lines) if line.strip().startswith("Atoms")) + 1
    ids = []
    for line in lines[start:]:
        words = line.split()
        if not words:
            if ids:
                break
            continue
        if not words[0].isdigit():
            break
        ids.append(int(words[0]))
    return ids


def main():
    checks = Checks()
    case, output = jet_bed_on_ranks()
    ids = set(data_file_ids(case.file(data_file_of(case)[0])))
    checks.true("the packing holds 2400 spheres", len(ids) == 2400, f"({len(ids)})")
    stats = particle_statistics(case.path)
    checks.true("every statistics sample counts all the spheres",
                len(stats["t"]) >= 30 and all(n == len(ids) for n in stats["particles"]),
                f"({len(stats['t'])} samples, counts {min(stats['particles'])} to {max(stats['particles'])})")
    checks.within("mass, last sample over first", stats["mass"][-1] / stats["mass"][0], 1.0, 1e-12)
    frames = rank_frames(case)
    checks.true("every snapshot holds the packing's IDs", len(frames) == 301 and all(set(f) == ids for f in frames),
                f"({len(frames)} snapshots, {min(len(f) for f in frames)} to {max(len(f) for f in frames)} IDs)")
    checks.true("each sphere owned by one rank in every snapshot", all(r >= 0 for f in frames for r in f.values()))
    crossings = [sum(a[i] != b[i] for i in a) for a, b in zip(frames, frames[1:])]
    frames_with = sum(c > 0 for c in crossings)
    checks.true("spheres cross between ranks (owner changed between dumps 1 ms apart)",
                sum(crossings) > 0,
                f"({sum(crossings)} crossings, in {frames_with} of {len(crossings)} intervals, at most"
                f" {max(crossings)} in one)")
    checks.true("the run reports cell records exchanged between ranks",
                "cell records received from particles on other ranks" in output)
    grid = re.search(r"LIGGGHTS' processor grid (\d+) x (\d+) x (\d+) \(even cuts of the box\): particles per rank"
                     r" (\S+) to (\S+), mean (\S+)", output)
    checks.true("the start reports the DEM grid 4 x 1 x 1 and 600 particles a rank on average, no advice",
                grid is not None and grid.group(1, 2, 3) == ("4", "1", "1") and float(grid.group(6)) == 600
                and "the fullest rank holds" not in output, grid.group(0) if grid else "(no line)")
    checks.true("cut * * 1 on 2 ranks: the empty upper rank is named and the fix given",
                "the fullest rank holds 2 times the mean" in cut_in_y(case) and "processors * 1 1" in cut_in_y(case))
    checks.finish()


if __name__ == "__main__":
    main()
