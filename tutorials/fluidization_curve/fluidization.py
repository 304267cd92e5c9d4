#!/usr/bin/env python3
"""Run a fluidization curve: the inflow velocity stepped through the levels of a YAML file,
then the table, the plateau, U_mf and fluidization_curve.png.

    fluidization.py [LEVELS] [--case DIR] [--set-end-time] [--report-only]

LEVELS (default DIR/levels.yaml) lists [velocity m/s, hold time s] pairs, the analysis settings
and the packing of the initial bed (this folder's levels.yaml is the tutorial's schedule and
says what each key means). The case DIR (default: the current directory) is run in place: it
is packed (when LEVELS has `packing`), its 0/U written, meshed and run with tfdemFoam; logs go
to DIR/log.*. For your own particles, copy this folder, change coupling.yaml's particles, the
DEM script (contacts, timestep; system/controlDict's deltaT = coupling_interval x timestep)
and the mesh as the coupler requires (depth d_p under the 2-D rule), write your levels and run
    . scripts/tfdem-env.sh && python3 fluidization.py my_levels.yaml --case my_case
What the case must have is listed in python/tfdem/fluidization.py.
"""
import argparse
import os
import sys

from tfdem import fluidization
from tfdem.case import CaseError
from tfdem.frontdoor import add_debug_option, doing, run_command

import plot


def main(argv=None):
    return run_command("fluidization.py", _fluidization, argv, known=(ValueError,))


def _fluidization(argv):
    parser = argparse.ArgumentParser(prog="fluidization.py", description=__doc__.splitlines()[0])
    parser.add_argument("levels", nargs="?", help="YAML file of levels (default: CASE/levels.yaml)")
    parser.add_argument("--case", default=".", help="case directory, run in place (default: .)")
    parser.add_argument("--set-end-time", action="store_true",
                        help="set system/controlDict's endTime to the sum of the hold times")
    parser.add_argument("--report-only", action="store_true",
                        help="do not run: report the finished run of the case")
    add_debug_option(parser)
    args = parser.parse_args(argv)
    if not os.path.isfile(os.path.join(args.case, "coupling.yaml")):
        raise CaseError(f"--case {args.case}: not a case folder (no coupling.yaml): give the case's folder")
    levels = args.levels or os.path.join(args.case, "levels.yaml")
    schedule = fluidization.Schedule.load(levels)
    if not args.report_only:
        print(f"{args.case}: {len(schedule.levels)} levels, {schedule.end_time():g} s simulated"
              f" (packing, blockMesh, tfdemFoam; logs in {os.path.join(args.case, 'log.*')})", flush=True)
        with doing("running the levels of", levels):
            fluidization.prepare_run(args.case, args.case, schedule, set_end_time=args.set_end_time)
    with doing("reporting the run of", args.case):
        plot.report(args.case, schedule)
    return 0


if __name__ == "__main__":
    sys.exit(main())
