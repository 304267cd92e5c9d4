"""Hard cases that must run to the end with every particle accounted for, or stop clearly.

Each runs briefly from seed 000's beds (the packing is made once). Expected: the run ends,
with the particles' number and mass at the end equal to those at the start (nothing lost),
or -- where the scene cannot be simulated -- a message naming the cause and the fix:
- central jet at 42 and 80 m/s (Table 1: 39 m/s), 0.1 s;
- uniform bed with e_n = 1 (eta_n = 0) and e_n = 0.01 (eta_n = 0.15 N s/m by seed 001
  eq. 27), 0.1 s;
- cells smaller than the particles (2 mm cells, 2.5 mm spheres): centroid mapping stops with
  the cell and its particles; porous-cube mapping (cube side d_p) runs;
- a gas Courant number above 1 (25 m/s through 1 cm cells in 1 ms steps) is warned about.
The refused cases (DEM step above t_c/10, overdamped contact) are in coupled.bad_input; zero
particles in coupled.zero_particles; particles leaving through an outlet in coupled.blowout.
"""
import math
import os
import re

from tfdem import SOURCE_DIR, TUTORIALS
from tfdem.case import Case
from tfdem.outputs import particle_statistics
from tfdem_testlib import Checks, copy_case, run, scratch

BED = os.path.join(TUTORIALS, "bubbling_bed")
JET = os.path.join(TUTORIALS, "jet_bed")
BLOWOUT = os.path.join(SOURCE_DIR, "tests", "cases", "blowout")


def pack(name, variables):
    where = scratch(name)
    run(["tfdem-liggghts", "-in", os.path.join(TUTORIALS, "bubbling_bed_packing", "in.pack")] + variables
        + ["-log", "log.liggghts"], where, "log.screen")
    return where


def prepared(name, template, data, end_time):
    case = Case(copy_case(template, name))
    os.symlink(data, case.file(os.path.basename(data)))
    case.set_control(endTime=end_time, writeInterval=end_time)
    case.set_coupling("output.statistics_interval", end_time / 10)
    return case


def run_to_end(checks, name, case, particle_mass):
    run(["blockMesh"], case.path, "log.blockMesh")
    code, output = run(["tfdemFoam"], case.path, "log.tfdemFoam", expect_success=False)
    checks.true(f"{name}: ran to the end", code == 0 and re.search(r"(?m)^End$", output), f"(exit code {code})")
    if code != 0:
        print("\n".join(output.splitlines()[-20:]))
        return output
    start = int(re.search(r"TFDEM coupling: (\d+) particles", output).group(1))
    stats = particle_statistics(case.path)
    checks.true(f"{name}: every particle still there", stats["particles"][-1] == start,
                f"({stats['particles'][-1]:g} of {start})")
    checks.close(f"{name}: particle mass conserved", stats["mass"][-1], start * particle_mass, 1e-12)
    return output


def replace_in(path, old, new):
    text = open(path).read()
    assert old in text, (path, old)
    with open(path, "w") as f:
        f.write(text.replace(old, new))


def set_damping(case, particles, walls):
    script = case.file("in.bed")
    text = open(script).read()
    for prop in ("gamman_abs", "gammat_abs"):
        text = re.sub(rf"(fix\s+m\d all property/global {prop} peratomtypepair 2) \S+ \S+ \S+ \S+",
                      rf"\1 {particles} {walls} {walls} {walls}", text)
    open(script, "w").write(text)


def main():
    checks = Checks()
    bed = os.path.join(pack("stability_bed", ["-var", "steps", "20000", "-var", "out", "bed.data"]), "bed.data")
    jet = os.path.join(pack("stability_jet", ["-var", "dp", "0.004", "-var", "rho", "2700", "-var", "mu", "0.2",
                                              "-var", "spacing", "0.005", "-var", "width", "0.15", "-var", "height",
                                              "0.9", "-var", "fill_top", "0.41", "-var", "steps", "30000",
                                              "-var", "out", "packed_bed.data"]), "packed_bed.data")
    bed_mass = 2526 * math.pi * 0.0025 ** 3 / 6
    jet_mass = 2700 * math.pi * 0.004 ** 3 / 6

    for speed in (42, 80):
        case = prepared(f"stability_jet_{speed}", JET, jet, 0.1)
        replace_in(case.file("0", "U"), "value uniform (0 39 0)", f"value uniform (0 {speed} 0)")
        run_to_end(checks, f"jet at {speed} m/s", case, jet_mass)

    for label, particles, walls in (("e_n = 1", 0, 0), ("e_n = 0.01", 0.15, 0.15)):
        case = prepared("stability_" + re.sub(r"\W+", "_", label), BED, bed, 0.1)
        set_damping(case, particles, walls)
        run_to_end(checks, f"uniform bed with {label}", case, bed_mass)

    for method in ("centroid", "porous_cube"):
        case = prepared(f"stability_small_cells_{method}", BED, bed, 0.02)
        case.scale_cells(0, 5)  # 1 cm -> 2 mm
        case.scale_cells(1, 5)
        case.set_coupling("coupling.void_fraction.method", method)
        if method == "centroid":
            run(["blockMesh"], case.path, "log.blockMesh")
            code, output = run(["tfdemFoam"], case.path, "log.tfdemFoam", expect_success=False)
            checks.true("cells smaller than particles, centroid: stopped", code != 0, f"(exit code {code})")
            for words in ("fill it: gas fraction", "before any floor", "Particles with a share in it",
                          "divided or porous_cube"):
                checks.true(f"cells smaller than particles, centroid: message contains {words!r}", words in output)
        else:
            run_to_end(checks, "cells smaller than particles, porous cube", case, bed_mass)

    case = Case(copy_case(BLOWOUT, "stability_courant"))
    case.set_control(endTime=0.01, writeInterval=5)
    # 50 m/s through 1 cm cells at 1 ms: Courant >= 5, above the measured 3.2 (scene_check.h)
    replace_in(case.file("0", "U"), "value uniform (0 5 0)", "value uniform (0 50 0)")
    run(["blockMesh"], case.path, "log.blockMesh")
    _, output = run(["tfdemFoam"], case.path, "log.tfdemFoam", expect_success=False)
    checks.true("gas Courant number above the measured 3.2 is warned about",
                "TFDEM warning: the gas Courant number reached" in output and "(> 3.2" in output)
    checks.finish()


if __name__ == "__main__":
    main()
