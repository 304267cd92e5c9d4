"""The hard-sphere engine against Smallenburg's event-driven code (EDMD, 2022) on the same
elastic periodic gas, side by side (issue 51).

    bench.py --edmd PATH [--pairs 3] [--collisions 1e7]

PATH is a checkout of https://github.com/FSmallenburg/EDMD (not part of TFDEM). Its `Single`
program keeps its settings in global variables; bench.py copies mdSingle.c to
build/bench-runs/hard_sphere_gas/, sets them there and compiles it with the flags CMake builds
TFDEM's Release with (read from build/CMakeCache.txt; EDMD's own Makefile has -Ofast
-funroll-loops -march=native), so both codes have the same compiler and flags. For each gas
of STATES (EDMD's face-centred start, N = 4 n^3 spheres of diameter 1 at solids fraction
phi): EDMD melts the crystal for MELT_TIME with its thermostat and writes the snapshot; then
both codes fly the same snapshot, without thermostat, at kT = 1 and unit mass (fresh
Maxwellian velocities), for the time that makes about `--collisions` collisions at the
Enskog rate, in `--pairs` alternated pairs (EDMD first, then ours). Each run's wall time
(the whole process, its set-up included) over its collisions is its microseconds per
collision. Writes results/hard_sphere_gas.json and prints the table of README.md.
"""
import argparse
import json
import math
import os
import re
import shutil
import statistics
import subprocess
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))
BUILD = os.environ.get("TFDEM_BUILD", os.path.join(ROOT, "build"))
WORK = os.path.join(BUILD, "bench-runs", "hard_sphere_gas")
OURS = os.path.join(BUILD, "bench", "tfdem-hard-sphere-gas")
STATES = ((11, 0.30), (11, 0.45), (22, 0.30), (22, 0.45))  # (n, phi): N = 4 n^3 = 5324, 42592
MELT_TIME = 20.0  # time units (EDMD's): the crystal melts and the gas relaxes


def enskog_collisions_per_time(count, phi):
    """N nu / 2: collisions per unit time of N unit spheres at kT = 1 (Enskog, Carnahan-Starling
    g0): nu = 4 n g0 sqrt(pi), n = 6 phi / pi."""
    g0 = (1 - phi / 2) / (1 - phi) ** 3
    return count * 4 * (6 * phi / math.pi) * g0 * math.sqrt(math.pi) / 2


def release_flags():
    cache = open(os.path.join(BUILD, "CMakeCache.txt")).read()
    flags = [re.search(rf"^{key}:\w+=(.*)$", cache, flags=re.M) for key in ("CMAKE_CXX_FLAGS", "CMAKE_CXX_FLAGS_RELEASE")]
    return " ".join(f.group(1) for f in flags if f).split()


def edmd_program(edmd, name, settings, flags):
    """EDMD's Single program with `settings` (global name -> value) set, compiled as `name`."""
    source = open(os.path.join(edmd, "Single", "mdSingle.c")).read()
    for key, value in settings.items():
        source, n = re.subn(rf"^((?:const )?(?:int|double) {key}\s*=\s*)[^;]*;", rf"\g<1>{value};", source,
                            count=1, flags=re.M)
        if n != 1:
            raise SystemExit(f"{edmd}/Single/mdSingle.c: no global '{key}' (another EDMD version?)")
    folder = os.path.join(WORK, name)
    os.makedirs(folder, exist_ok=True)
    for extra in ("mdSingle.h", "mt19937ar.c"):
        shutil.copy(os.path.join(edmd, "Single", extra), folder)
    with open(os.path.join(folder, "mdSingle.c"), "w") as f:
        f.write(source)
    subprocess.run(["gcc", *flags, "mdSingle.c", "-o", "md", "-lm"], cwd=folder, check=True)
    return folder


def timed(command, cwd):
    start = time.perf_counter()
    out = subprocess.run(command, cwd=cwd, check=True, capture_output=True, text=True).stdout
    return time.perf_counter() - start, out


def edmd_collisions(out):
    return int(re.findall(r"Collisions: (\d+)", out)[-1])


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--edmd", required=True, help="a checkout of Smallenburg's EDMD")
    parser.add_argument("--pairs", type=int, default=3)
    parser.add_argument("--collisions", type=float, default=1e7)
    args = parser.parse_args(argv)
    if not os.path.exists(OURS):
        raise SystemExit(f"{OURS} missing: build TFDEM first (./tfdem setup)")
    flags = release_flags()
    print(f"compiler flags, both codes: {' '.join(flags)}")
    results = {"flags": flags, "compiler": subprocess.run(["gcc", "--version"], capture_output=True, text=True)
               .stdout.splitlines()[0], "states": []}
    for n, phi in STATES:
        count = 4 * n ** 3
        fly_time = round(args.collisions / enskog_collisions_per_time(count, phi), 1)
        melt = edmd_program(args.edmd, f"melt_{count}_{phi}", {"initialconfig": 1, "N": count, "packfrac": phi,
                                                             "maxtime": MELT_TIME, "writeinterval": MELT_TIME}, flags)
        subprocess.run(["./md"], cwd=melt, check=True, capture_output=True)
        flight = edmd_program(args.edmd, f"fly_{count}_{phi}", {"initialconfig": 0, "maxtime": fly_time,
                                                              "writeinterval": fly_time, "usethermostat": 0}, flags)
        snapshot = os.path.join(flight, "init.sph")
        shutil.copy(os.path.join(melt, "snapshot_end.sph"), snapshot)
        edmd_rates, our_rates = [], []
        for pair in range(args.pairs):
            seconds, out = timed(["./md"], flight)
            edmd_rates.append(1e6 * seconds / edmd_collisions(out))
            seconds, out = timed([OURS, snapshot, str(fly_time), str(15485863 + pair)], flight)
            our_rates.append(1e6 * seconds / int(re.search(r"collisions (\d+)", out).group(1)))
        state = {"spheres": count, "solids_fraction": phi, "time": fly_time,
                 "edmd_us_per_collision": edmd_rates, "tfdem_us_per_collision": our_rates,
                 "edmd_median": statistics.median(edmd_rates), "tfdem_median": statistics.median(our_rates)}
        state["ratio"] = state["tfdem_median"] / state["edmd_median"]
        results["states"].append(state)
        print(f"{count} spheres, phi {phi}: EDMD {state['edmd_median']:.3f} us/collision, TFDEM "
              f"{state['tfdem_median']:.3f} ({state['ratio']:.2f}x), {args.pairs} pairs", flush=True)
    os.makedirs(os.path.join(HERE, "results"), exist_ok=True)
    with open(os.path.join(HERE, "results", "hard_sphere_gas.json"), "w") as f:
        json.dump(results, f, indent=1)
    return 0


if __name__ == "__main__":
    sys.exit(main())
