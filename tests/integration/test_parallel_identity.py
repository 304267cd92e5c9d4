"""Coupled runs on 1, 2, 3 and 4 MPI ranks give the same numbers (deterministic cases to 1e-8).

On N ranks (oversubscribed beyond this machine's cores) the gas mesh is split in y
(decomposePar, simple 1 N 1) and LIGGGHTS in x (`processors N 1 1`), so particles sit in
cells another rank owns; the run must report cell records exchanged between ranks. Each runs
on N ranks a second time with the gas whole on every rank (`mpirun -np N tfdemFoam`, no
decomposition): the ranks' per-cell particle sums are then added on rank 0 and broadcast,
and each rank solves the same gas. Compared:
  - settling sphere: its velocity every 0.01 s over 0.5 s (it falls from the upper gas
    subdomain into the lower one while staying on one DEM rank), relative to u_t;
  - packed bed at U = 0.6 m/s: the probe pressures below and above the bed, relative to the
    pressure drop.
1e-8 allows for the parallel linear solvers (a decomposed preconditioner converging to the
same tolerance); everything else is the same arithmetic in a different order. Measured
(2026-12-04, also at 8 ranks with TFDEM_IDENTITY_RANKS=8): split 6e-15 to 1.3e-13 (the
decomposed solvers' sums); whole bitwise for the one settling sphere, 1e-14 to 3e-14 for the
packed bed (each cell's sums added over the ranks' particles in another order than 1 rank's).
By hand, 24 ranks (the packed bed's 960 spheres in 24 LIGGGHTS slabs of 2.55 mm, thinner than
a particle with its skin, the gas whole; the split layout refuses more ranks than its 20 rows):
p within 3.2e-12 Pa of 1 rank's (of 184 Pa), U within 1.2e-14 m/s, the void fraction bitwise,
after 3 gas steps (2026-12-04).
"""
import os

from tfdem import TUTORIALS
from tfdem.case import Case
from tfdem.fixed_bed import FixedBed
from tfdem.outputs import dump_track, log_numbers
from tfdem.physics import SettlingSphere
from tfdem_testlib import Checks, copy_case, fail, run, write_decompose_dict

TOLERANCE = 1e-8
# The rank counts compared with 1 rank; TFDEM_IDENTITY_RANKS=8 (or 2,8) for more on demand
RANKS = tuple(int(n) for n in os.environ.get("TFDEM_IDENTITY_RANKS", "2,3,4").split(","))


def split_dem_in_x(case, ranks):
    """Put `processors N 1 1` before create_box in the case's DEM script."""
    path = Case(case).dem_script()
    text = open(path).read()
    if "create_box" not in text:
        fail(f"{path}: no create_box line to put 'processors' before")
    open(path, "w").write(text.replace("create_box", f"processors      {ranks} 1 1\ncreate_box", 1))


def run_case(source, name, ranks, edit=None, gas="y_split"):
    """Copy, mesh and run a tutorial case on `ranks` ranks, the gas split in y or `whole` on
    every rank; return the case dir."""
    case = copy_case(source, name)
    if edit:
        edit(case)
    run(["blockMesh"], case, "log.blockMesh")
    if ranks == 1:
        run(["tfdemFoam"], case, "log.tfdemFoam")
        return case
    split_dem_in_x(case, ranks)
    if gas == "whole":
        run(["tfdemFoam"], case, "log.tfdemFoam", ranks=ranks)
        return case
    write_decompose_dict(case, (1, ranks, 1))
    run(["decomposePar"], case, "log.decomposePar")
    run(["tfdemFoam", "-parallel"], case, "log.tfdemFoam", ranks=ranks)
    return case


def remote_records(case):
    found = log_numbers(os.path.join(case, "log.tfdemFoam"),
                        r"TFDEM parallel: (\S+) cell records received from particles on other ranks")
    return found[0] if found else 0.0


def gas_whole(case, ranks):
    return f"TFDEM parallel: the gas whole on each of {ranks} ranks" in open(os.path.join(case, "log.tfdemFoam")).read()


def main():
    checks = Checks()
    source = os.path.join(TUTORIALS, "settling_particle")
    serial = run_case(source, "identity_settling_1", 1)
    one = dump_track(serial, "vy")
    terminal = SettlingSphere.from_case(Case(source)).terminal_velocity()

    def same_track(label, case):
        two = dump_track(case, "vy")
        checks.true(f"{label}: same samples", len(one) == len(two) == 51, f"({len(one)}, {len(two)})")
        worst = max(abs(a[1] - b[1]) for a, b in zip(one, two)) / terminal
        checks.within(f"{label}: max |v_1 - v_N| / u_t", worst, 0.0, TOLERANCE)
    for ranks in RANKS:
        parallel = run_case(source, f"identity_settling_{ranks}", ranks)
        checks.true(f"settling, {ranks} ranks: particle in cells of another rank", remote_records(parallel) > 0,
                    f"({remote_records(parallel):g} remote cell records)")
        same_track(f"settling, {ranks} ranks", parallel)
        whole = run_case(source, f"identity_settling_{ranks}_whole", ranks, gas="whole")
        checks.true(f"settling, gas whole on each of {ranks} ranks: reported", gas_whole(whole, ranks))
        same_track(f"settling, gas whole on each of {ranks} ranks", whole)

    source = os.path.join(TUTORIALS, "packed_bed_ergun")
    bed = FixedBed(source)

    def edit(case):
        Case(case).set_patch_value("U", "inlet", (0, 0.6, 0))
    serial = run_case(source, "identity_packed_1", 1, edit)
    dp_one = bed.measured_pressure_drop(serial)
    checks.close("packed bed: pressure drop on 1 rank vs Ergun (Pa)", dp_one, bed.expected_pressure_drop(0.6), 0.03)
    for ranks in RANKS:
        parallel = run_case(source, f"identity_packed_{ranks}", ranks, edit)
        checks.true(f"packed bed, {ranks} ranks: particles in cells of another rank", remote_records(parallel) > 0,
                    f"({remote_records(parallel):g} remote cell records)")
        checks.close(f"packed bed: pressure drop on {ranks} ranks vs 1 (Pa)",
                     bed.measured_pressure_drop(parallel), dp_one, TOLERANCE)
        whole = run_case(source, f"identity_packed_{ranks}_whole", ranks, edit, gas="whole")
        checks.true(f"packed bed, gas whole on each of {ranks} ranks: reported", gas_whole(whole, ranks))
        checks.close(f"packed bed, gas whole on each of {ranks} ranks: pressure drop vs 1 rank (Pa)",
                     bed.measured_pressure_drop(whole), dp_one, TOLERANCE)
    checks.finish()


if __name__ == "__main__":
    main()
