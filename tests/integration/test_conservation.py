"""Conservation in a coupled bubbling bed (seed 000's uniform-inflow bed, first 0.05 s).

Every coupling step the solver compares sum_c (1 - eps_c) V_c with sum_i V_i (steps where the
void-fraction floor is unused) and the gas momentum sink with the particle drags; it prints
the largest relative mismatches at the end. Expected: both below 1e-10 for the porous-cube
mapping with the conservative per-particle transfer, and for centroid with the averaged
transfer (round-off: ~1e-13 over ~4000 particles).
"""
import os
import re
import shutil

from tfdem_testlib import SOURCE_DIR, Checks, copy_case, run, scratch

BED = os.path.join(SOURCE_DIR, "tutorials", "bubbling_bed")
PACKING = os.path.join(SOURCE_DIR, "tutorials", "bubbling_bed_packing", "in.pack")
REPORT = re.compile(r"TFDEM conservation: max \|sum \(1-eps\) V_cell - sum V_p\| / sum V_p = (\S+) "
                    r"over (\d+) steps without floor; max \|momentum imbalance\| / sum \|drag\| = (\S+)")
END_TIME = 0.05


def coupling_steps():
    """Coupling steps of the run: END_TIME over the bed's gas step, plus the initial coupling."""
    control = open(os.path.join(BED, "system", "controlDict")).read()
    return round(END_TIME / float(re.search(r"(?m)^deltaT\s+([^;\s]+);", control).group(1))) + 1


def packed_bed():
    where = scratch("conservation_packing")
    run(["tfdem-liggghts", "-in", PACKING, "-var", "steps", "20000", "-var", "out", "bed.data",
         "-log", "log.liggghts"], where, "log.screen")
    return os.path.join(where, "bed.data")


def coupled_run(name, bed, transfer, method, cube_factor):
    case = copy_case(BED, name)
    shutil.copy(bed, case)
    config = os.path.join(case, "coupling.yaml")
    text = open(config).read()
    text = re.sub(r"transfer: \w+", f"transfer: {transfer}", text)
    text = re.sub(r"method: \w+", f"method: {method}\n    cube_factor: {cube_factor}", text)
    open(config, "w").write(text)
    control = os.path.join(case, "system", "controlDict")
    text = re.sub(r"endTime\s+\S+;", f"endTime {END_TIME};", open(control).read())
    open(control, "w").write(text)
    run(["blockMesh"], case, "log.blockMesh")
    _, output = run(["tfdemFoam"], case, "log.tfdemFoam")
    found = REPORT.search(output)
    return (float(found.group(1)), int(found.group(2)), float(found.group(3))) if found else (None, 0, None)


def main():
    checks = Checks()
    bed = packed_bed()
    expected_steps = coupling_steps()
    for transfer, method in (("per_particle_conservative", "porous_cube"), ("averaged", "centroid")):
        volume, steps, momentum = coupled_run(f"conservation_{transfer}", bed, transfer, method, 1.0)
        checks.true(f"{transfer} + {method}: conservation report printed", volume is not None)
        # centroid over-fills a few dense cells in some steps; the floor is used there instead
        checks.true(f"{transfer} + {method}: volume checked in most steps", steps >= expected_steps // 2,
                    f"({steps} of {expected_steps})")
        if volume is not None:
            checks.within(f"{transfer} + {method}: volume mismatch", volume, 0.0, 1e-10)
            checks.within(f"{transfer} + {method}: momentum imbalance", momentum, 0.0, 1e-10)
    checks.finish()


if __name__ == "__main__":
    main()
