#!/usr/bin/env python3
"""Speed of the coupled solver on the uniform-inflow bubbling bed (seed 000 Table 1), against
the DEM alone with the same particles, steps, contacts and ranks.

For each rank count it runs tutorials/bubbling_bed (its packed bed, mesh and inputs) for
`--time` simulated seconds with `tfdemFoam -recordForces`, then `tfdem-dem-replay`, which
runs the same DEM script the way the coupler does with the recorded fluid forces and no gas.
The replay must end with the same particle coordinates (same steps and contacts). The pair is
run `--repeat` times, alternated, so that a drift of the machine's speed hits both. Prints the
fastest coupled run's wall-time split per coupling interval (DEM / locate+map / forces / gas),
each pair's coupled time loop / DEM-only time loop and the ratio of the fastest of each (noise
only adds time). A benchmark, not a test: it prints figures.

`--interval N` runs the bed with N DEM steps per gas step (gas step N x the DEM step) instead
of the tutorial's coupling_interval, for speed against the coupling interval.

Usage: bench/bench_bubbling_bed.py [--time 0.25] [--ranks 1 2] [--interval 100] [--repeat 3]
"""
import argparse
import os
import re
import shutil
import subprocess
import sys

SOURCE = os.path.abspath(os.path.join(os.path.dirname(__file__), ".."))
BUILD = os.environ.get("TFDEM_BUILD", os.path.join(SOURCE, "build"))
TUTORIAL = os.path.join(SOURCE, "tutorials", "bubbling_bed")
sys.path.insert(0, os.path.join(SOURCE, "tests", "integration"))
import tfdem_testlib  # noqa: E402
sys.path.insert(0, os.path.join(SOURCE, "tutorials"))
from case_copy import copy_case  # noqa: E402


def environment():
    """The integration tests' environment, with bench/ on PATH for tfdem-dem-replay."""
    env = tfdem_testlib.environment()
    env["PATH"] = os.pathsep.join([os.path.join(BUILD, "bench"), env["PATH"]])
    return env


def run(args, cwd, log, ranks=1):
    """Run (under mpirun for ranks > 1); return its output. Stops on failure."""
    if ranks > 1:
        args = ["mpirun", "-np", str(ranks)] + args
    proc = subprocess.run(args, cwd=cwd, env=environment(), stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                          text=True, errors="replace")
    open(os.path.join(cwd, log), "w").write(proc.stdout)
    if proc.returncode != 0:
        sys.exit(f"'{' '.join(args)}' failed in {cwd}:\n{proc.stdout[-3000:]}")
    return proc.stdout


def setting(pattern, path):
    """The first group of pattern in the file at path (a number); stops when missing."""
    match = re.search(pattern, open(path).read(), re.M)
    if not match:
        sys.exit(f"{path}: no match for {pattern!r}")
    return float(match.group(1))


def tutorial_interval():
    return int(setting(r"^\s*coupling_interval:\s*(\d+)", os.path.join(TUTORIAL, "coupling.yaml")))


def dem_step():
    return setting(r"^timestep\s+(\S+)", os.path.join(TUTORIAL, "in.bed"))


def set_interval(case, interval):
    """coupling_interval and the gas step (interval x the DEM step) of the case."""
    path = os.path.join(case, "coupling.yaml")
    text = re.sub(r"(?m)^(\s*coupling_interval:\s*)\d+", rf"\g<1>{interval}", open(path).read())
    open(path, "w").write(text)
    path = os.path.join(case, "system", "controlDict")
    text = re.sub(r"(?m)^deltaT .*$", f"deltaT          {interval * dem_step():.12g};", open(path).read())
    open(path, "w").write(text)


def prepare(case, end_time, ranks, interval):
    copy_case(TUTORIAL, case, ("coupling.yaml", "in.bed"))
    packed = os.path.join(SOURCE, "tutorials", "bubbling_bed_packing", "bed.data")
    if not os.path.exists(packed):
        run([os.path.join(SOURCE, "tutorials", "bubbling_bed_packing", "Allrun")], case, "log.packing")
    shutil.copy(packed, case)
    control = os.path.join(case, "system", "controlDict")
    text = open(control).read()
    text = re.sub(r"(?m)^endTime .*$", f"endTime         {end_time};", text)
    text = re.sub(r"(?m)^writeInterval .*$", f"writeInterval   {end_time};", text)
    open(control, "w").write(text)
    set_interval(case, interval)
    run(["blockMesh"], case, "log.blockMesh")
    if ranks > 1:
        # Gas split like LIGGGHTS' `processors * 1 1` in in.bed: side by side in x.
        tfdem_testlib.write_decompose_dict(case, (ranks, 1, 1))
        run(["decomposePar"], case, "log.decomposePar")


def number(pattern, text):
    match = re.search(pattern, text)
    if not match:
        sys.exit(f"no match for {pattern!r}")
    return [float(g) for g in match.groups()]


def coupled_and_replay(case, ranks, interval, intervals):
    """One coupled run and its DEM-only replay: (coupled split dict, replay DEM seconds)."""
    solver = ["tfdemFoam", "-recordForces", "forces.bin"] + (["-parallel"] if ranks > 1 else [])
    log = run(solver, case, "log.tfdemFoam", ranks)
    dem, mapping, forces, gas = number(r"TFDEM timing: DEM (\S+) s, locate\+map (\S+) s, forces (\S+) s, gas (\S+) s", log)
    coupled_positions = number(r"TFDEM positions: sum of x, y, z over particles = (\S+) (\S+) (\S+)", log)
    replay_log = run(["tfdem-dem-replay", "in.bed", "forces.bin", str(interval), str(intervals)],
                     case, "log.replay.out", ranks)
    replay_dem = number(r"TFDEM replay: DEM (\S+) s", replay_log)[0]
    replay_positions = number(r"TFDEM positions: sum of x, y, z over particles = (\S+) (\S+) (\S+)", replay_log)
    same = max(abs(a - b) / abs(a) for a, b in zip(coupled_positions, replay_positions))
    if same > 1e-12:
        sys.exit(f"{case}: the replay ends {same:.1e} (relative) away from the coupled run's particle"
                 " coordinates: not the same steps and contacts")
    split = {"DEM": dem, "locate+map": mapping, "forces": forces, "gas": gas}
    return split, replay_dem


def bench(end_time, ranks, interval, repeat):
    """Coupled and DEM-only runs alternated `repeat` times (so a drift of the machine's speed
    hits both); the ratio of the fastest of each is the figure, noise only adds time."""
    case = os.path.join(BUILD, "bench-runs", f"bubbling_bed_np{ranks}")
    prepare(case, end_time, ranks, interval)
    intervals = round(end_time / (interval * dem_step()))
    pairs = [coupled_and_replay(case, ranks, interval, intervals) for _ in range(repeat)]
    loops = [sum(split.values()) for split, _ in pairs]
    replays = [replay for _, replay in pairs]
    fastest = pairs[loops.index(min(loops))][0]
    per = 1e3 / intervals
    print(f"\n{ranks} rank(s), {end_time} s simulated, {intervals} coupling intervals of {interval} DEM steps,"
          f" {repeat} coupled and {repeat} DEM-only runs alternated (replays end at the coupled"
          " particle coordinates)")
    print("  per interval (ms, rank 0, fastest coupled run): "
          + ", ".join(f"{name} {seconds * per:.3f}" for name, seconds in fastest.items()))
    print("  coupled time loops (s): " + " ".join(f"{t:.2f}" for t in loops))
    print("  DEM-only replays (s):   " + " ".join(f"{t:.2f}" for t in replays))
    print("  coupled / DEM-only, run by run: " + " ".join(f"{a / b:.3f}" for a, b in zip(loops, replays)))
    print(f"  coupled / DEM-only, fastest of each: {min(loops) / min(replays):.3f}")
    return min(loops) / min(replays)


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--time", type=float, default=0.25, help="simulated seconds (default 0.25)")
    parser.add_argument("--ranks", type=int, nargs="+", default=[1, 2], help="rank counts (default 1 2)")
    parser.add_argument("--interval", type=int, default=tutorial_interval(),
                        help="DEM steps per gas step (default: the tutorial's coupling_interval)")
    parser.add_argument("--repeat", type=int, default=3,
                        help="coupled and DEM-only runs, alternated (default 3)")
    args = parser.parse_args()
    if args.interval < 1:
        parser.error(f"--interval {args.interval}: expected a positive number of DEM steps")
    if args.repeat < 1:
        parser.error(f"--repeat {args.repeat}: expected a positive number of runs")
    for ranks in args.ranks:
        bench(args.time, ranks, args.interval, args.repeat)


if __name__ == "__main__":
    main()
