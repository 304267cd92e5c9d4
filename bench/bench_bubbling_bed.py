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

Usage (the tfdem package on PYTHONPATH, as scripts/tfdem-env.sh sets it):
    . scripts/tfdem-env.sh
    "$TFDEM_PYTHON" bench/bench_bubbling_bed.py [--time 0.25] [--ranks 1 2] [--interval 100] [--repeat 3]
"""
import argparse
import os
import shutil
import sys

from tfdem import BUILD_DIR, TUTORIALS
from tfdem.case import Case
from tfdem.outputs import OutputError, log_numbers, solver_timing
from tfdem.run import RunError, run as run_program

TUTORIAL = os.path.join(TUTORIALS, "bubbling_bed")
PACKING = os.path.join(TUTORIALS, "bubbling_bed_packing")
REPLAY = os.path.join(BUILD_DIR, "bench", "tfdem-dem-replay")


def run(args, cwd, log, ranks=1):
    """Run (under mpirun for ranks > 1; the gas whole on every rank) with the package's
    environment, output to cwd/log. Stops on failure."""
    try:
        run_program(args, cwd, log, ranks)
    except RunError as e:
        sys.exit(str(e))
    return os.path.join(cwd, log)


def tutorial_interval():
    return int(Case(TUTORIAL).coupling_value("dem.coupling_interval"))


def dem_step():
    return Case(TUTORIAL).dem_time_step()


def set_interval(case, interval):
    """coupling_interval and the gas step (interval x the DEM step) of the case."""
    case.set_time_steps(gas=interval * case.dem_time_step())


def prepare(path, end_time, ranks, interval):
    case = Case(TUTORIAL).copy_to(path)
    packed = Case(PACKING).file("bed.data")
    if not os.path.exists(packed):
        run([os.path.join(PACKING, "Allrun")], path, "log.packing")
    shutil.copy(packed, case.file(os.path.basename(case.dem().read_data())))
    case.set_control(endTime=end_time, writeInterval=end_time)
    set_interval(case, interval)
    run(["blockMesh"], path, "log.blockMesh")


def number(pattern, log):
    """Floats of the last match of pattern in the log file; stops when missing."""
    found = log_numbers(log, pattern)
    if found is None:
        sys.exit(f"{log}: no match for {pattern!r}")
    return found


def coupled_and_replay(case, ranks, interval, intervals):
    """One coupled run and its DEM-only replay: (coupled split dict, replay DEM seconds)."""
    solver = ["tfdemFoam", "-recordForces", "forces.bin"]
    log = run(solver, case, "log.tfdemFoam", ranks)
    try:
        timing = solver_timing(log)
    except OutputError as e:
        sys.exit(str(e))
    coupled_positions = number(r"TFDEM positions: sum of x, y, z over particles = (\S+) (\S+) (\S+)", log)
    script = os.path.basename(Case(case).dem_script())
    replay_log = run([REPLAY, script, "forces.bin", str(interval), str(intervals)], case, "log.replay.out", ranks)
    replay_dem = number(r"TFDEM replay: DEM (\S+) s", replay_log)[0]
    replay_positions = number(r"TFDEM positions: sum of x, y, z over particles = (\S+) (\S+) (\S+)", replay_log)
    same = max(abs(a - b) / abs(a) for a, b in zip(coupled_positions, replay_positions))
    if same > 1e-12:
        sys.exit(f"{case}: the replay ends {same:.1e} (relative) away from the coupled run's particle"
                 " coordinates: not the same steps and contacts")
    split = {part: timing[part] for part in ("DEM", "locate+map", "forces", "gas")}
    return split, replay_dem


def bench(end_time, ranks, interval, repeat):
    """Coupled and DEM-only runs alternated `repeat` times (so a drift of the machine's speed
    hits both); the ratio of the fastest of each is the figure, noise only adds time."""
    case = os.path.join(BUILD_DIR, "bench-runs", f"bubbling_bed_np{ranks}")
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
