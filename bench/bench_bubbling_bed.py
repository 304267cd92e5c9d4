#!/usr/bin/env python3
"""Speed of the coupled solver on the uniform-inflow bubbling bed (seed 000 Table 1), against
the DEM alone with the same particles, steps, contacts and ranks.

For each rank count it runs tutorials/bubbling_bed (its packed bed, mesh and inputs) for
`--time` simulated seconds with `tfdemFoam -recordForces`, then `tfdem-dem-replay`, which
runs the same DEM script the way the coupler does with the recorded fluid forces and no gas.
The replay must end with the same particle coordinates (same steps and contacts). Prints the
coupled run's wall-time split per coupling interval (DEM / locate+map / forces / gas) and
coupled wall time / DEM-only wall time. A benchmark, not a test: it prints figures.

Usage: bench/bench_bubbling_bed.py [--time 0.25] [--ranks 1 2]
"""
import argparse
import os
import re
import shutil
import subprocess
import sys
import time

SOURCE = os.path.abspath(os.path.join(os.path.dirname(__file__), ".."))
BUILD = os.environ.get("TFDEM_BUILD", os.path.join(SOURCE, "build"))
TUTORIAL = os.path.join(SOURCE, "tutorials", "bubbling_bed")
sys.path.insert(0, os.path.join(SOURCE, "tests", "integration"))
import tfdem_testlib  # noqa: E402

INTERVAL = 50  # dem.coupling_interval of the tutorial's coupling.yaml
GAS_STEP = 2.5e-4  # its deltaT


def environment():
    """The integration tests' environment, with bench/ on PATH for tfdem-dem-replay."""
    env = tfdem_testlib.environment()
    env["PATH"] = os.pathsep.join([os.path.join(BUILD, "bench"), env["PATH"]])
    return env


def run(args, cwd, log, ranks=1):
    """Run (under mpirun for ranks > 1); return (wall seconds, output). Stops on failure."""
    if ranks > 1:
        args = ["mpirun", "-np", str(ranks)] + args
    start = time.monotonic()
    proc = subprocess.run(args, cwd=cwd, env=environment(), stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                          text=True, errors="replace")
    wall = time.monotonic() - start
    open(os.path.join(cwd, log), "w").write(proc.stdout)
    if proc.returncode != 0:
        sys.exit(f"'{' '.join(args)}' failed in {cwd}:\n{proc.stdout[-3000:]}")
    return wall, proc.stdout


def prepare(case, end_time, ranks):
    shutil.rmtree(case, ignore_errors=True)
    os.makedirs(case)
    for sub in ("0", "constant", "system"):
        shutil.copytree(os.path.join(TUTORIAL, sub), os.path.join(case, sub), ignore=shutil.ignore_patterns("polyMesh"))
    for name in ("coupling.yaml", "in.bed"):
        shutil.copy(os.path.join(TUTORIAL, name), case)
    packed = os.path.join(SOURCE, "tutorials", "bubbling_bed_packing", "bed.data")
    if not os.path.exists(packed):
        run([os.path.join(SOURCE, "tutorials", "bubbling_bed_packing", "Allrun")], case, "log.packing")
    shutil.copy(packed, case)
    control = os.path.join(case, "system", "controlDict")
    text = open(control).read()
    text = re.sub(r"(?m)^endTime .*$", f"endTime         {end_time};", text)
    text = re.sub(r"(?m)^writeInterval .*$", f"writeInterval   {end_time};", text)
    open(control, "w").write(text)
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


def bench(end_time, ranks):
    case = os.path.join(BUILD, "bench-runs", f"bubbling_bed_np{ranks}")
    prepare(case, end_time, ranks)
    solver = ["tfdemFoam", "-recordForces", "forces.bin"] + (["-parallel"] if ranks > 1 else [])
    coupled_wall, log = run(solver, case, "log.tfdemFoam", ranks)
    dem, mapping, forces, gas = number(r"TFDEM timing: DEM (\S+) s, locate\+map (\S+) s, forces (\S+) s, gas (\S+) s", log)
    record = number(r"TFDEM record: forces written in (\S+) s", log)[0]
    coupled_positions = number(r"TFDEM positions: sum of x, y, z over particles = (\S+) (\S+) (\S+)", log)
    intervals = round(end_time / GAS_STEP)
    replay_wall, replay_log = run(["tfdem-dem-replay", "in.bed", "forces.bin", str(INTERVAL), str(intervals)],
                                  case, "log.replay.out", ranks)
    replay_dem = number(r"TFDEM replay: DEM (\S+) s", replay_log)[0]
    replay_positions = number(r"TFDEM positions: sum of x, y, z over particles = (\S+) (\S+) (\S+)", replay_log)
    same = max(abs(a - b) / abs(a) for a, b in zip(coupled_positions, replay_positions))
    coupled_loop = dem + mapping + forces + gas
    per = 1e3 / intervals
    print(f"\n{ranks} rank(s), {end_time} s simulated, {intervals} coupling intervals of {INTERVAL} DEM steps")
    print(f"  per interval (ms, rank 0): DEM {dem * per:.2f}, locate+map {mapping * per:.3f}, "
          f"forces {forces * per:.3f}, gas {gas * per:.2f}")
    print(f"  coupled time loop {coupled_loop:.2f} s (+ {record:.2f} s writing the force record); "
          f"DEM-only replay {replay_dem:.2f} s")
    print(f"  coupled / DEM-only, time loops: {coupled_loop / replay_dem:.3f}")
    print(f"  coupled / DEM-only, whole programs: {coupled_wall:.1f} s / {replay_wall:.1f} s = "
          f"{(coupled_wall - record) / replay_wall:.3f} (record writing excluded)")
    print(f"  replay ends at the coupled run's particle coordinates to {same:.1e} relative")
    return coupled_loop / replay_dem


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--time", type=float, default=0.25, help="simulated seconds (default 0.25)")
    parser.add_argument("--ranks", type=int, nargs="+", default=[1, 2], help="rank counts (default 1 2)")
    args = parser.parse_args()
    for ranks in args.ranks:
        bench(args.time, ranks)


if __name__ == "__main__":
    main()
