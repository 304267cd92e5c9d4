"""Bad input to the coupled solver, one fault per case: each stops with exit code != 0 and a
message naming the file or key, the bad value and the fix (checked by its key words), with
no crash. The base case is the settling tutorial (one particle, 0.02 s) unless named; every
row is one fault a user has met or will meet.
"""
import os
import re
import shutil

from tfdem import SOURCE_DIR, TUTORIALS
from tfdem.case import Case
from tfdem_testlib import Checks, copy_case, run, write_decompose_dict

SETTLING = os.path.join(TUTORIALS, "settling_particle")
BLOWOUT = os.path.join(SOURCE_DIR, "tests", "cases", "blowout")


def edit(path, old, new):
    text = open(path).read()
    assert old in text, (path, old)
    open(path, "w").write(text.replace(old, new))


def append(path, text):
    with open(path, "a") as f:
        f.write(text)


def expect_failure(checks, name, fault, must_contain, ranks=1, base=SETTLING, end_time=0.02, gas="split",
                   on_each_rank=False):
    """The run stops non-zero, without a crash, with every text of must_contain in its output
    (on_each_rank: each text once per rank; the ranks' lines may interleave)."""
    case = copy_case(base, "coupled_bad_" + re.sub(r"\W+", "_", name))
    Case(case).set_control(endTime=end_time)
    run(["blockMesh"], case, "log.blockMesh")
    fault(case)
    command = ["tfdemFoam"]
    if ranks > 1 and gas == "split":
        write_decompose_dict(case, (1, 2, 1))
        run(["decomposePar", "-force"], case, "log.decomposePar")
        command.append("-parallel")
    code, output = run(command, case, "log.tfdemFoam", ranks=ranks, expect_success=False)
    checks.true(f"{name}: non-zero exit", code != 0, f"(exit code {code})")
    checks.true(f"{name}: no crash", "Segmentation fault" not in output and "sigsegv" not in output.lower()
                and "stack trace" not in output.lower())
    for text in must_contain:
        times = ranks if on_each_rank else 1
        checks.true(f"{name}: message contains {text!r}" + (f" {times} times" if on_each_rank else ""),
                    output.count(text) >= times, f"({output.count(text)})")


def in_case(relative, old, new):
    return lambda c: edit(os.path.join(c, relative), old, new)


def yaml(old, new):
    return in_case("coupling.yaml", old, new)


def dem(old, new):
    return in_case("in.settling", old, new)


def dem_append(text):
    return lambda c: append(os.path.join(c, "in.settling"), text)


def hertz(case):
    """The settling case's linear contact replaced by a Hertz one too stiff for its 1e-4 s step."""
    script = os.path.join(case, "in.settling")
    text = re.sub(r"(?m)^fix\s+m[1-4] .*\n", "", open(script).read())
    text = text.replace("hooke/stiffness", "hertz").replace(
        "fix             m5", "fix             m1 all property/global youngsModulus peratomtype 5e6\n"
        "fix             m2 all property/global poissonsRatio peratomtype 0.3\n"
        "fix             m3 all property/global coefficientRestitution peratomtypepair 1 0.9\n"
        "fix             m5").replace(" absolute_damping on", "")
    open(script, "w").write(text)


def start_later(case):
    shutil.copytree(os.path.join(case, "0"), os.path.join(case, "0.01"))
    Case(case).set_control(startFrom="latestTime")


CONFIG = [
    ("misspelt key in coupling.yaml", yaml("  transfer:", "  transfr:"),
     ["coupling.yaml:12:3: coupling.transfr: unknown key (did you mean 'transfer'?)"]),
    ("malformed YAML", yaml("density: 1.2 ", "density: [1.2 "), ["malformed YAML"]),
    ("duplicate YAML key", yaml("  coupling_interval: 10\n", "  coupling_interval: 10\n  coupling_interval: 20\n"),
     ["dem.coupling_interval: given twice (first at", "keep one"]),
    ("missing dem.script", yaml("  script: in.settling\n", ""), ["dem.script: missing (required)"]),
    ("non-numeric coupling interval", yaml("coupling_interval: 10", "coupling_interval: ten"),
     ["dem.coupling_interval: must be a whole number, got 'ten'"]),
    ("zero coupling interval", yaml("coupling_interval: 10", "coupling_interval: 0"),
     ["dem.coupling_interval: value 0 is out of range [1, 1000000]"]),
    ("unknown drag law", yaml("drag_law: ergun_wen_yu", "drag_law: wen_yu"),
     ["coupling.drag_law: unknown value 'wen_yu'", "'ergun_wen_yu'"]),
    ("unknown transfer method", yaml("transfer: per_particle", "transfer: perparticle"),
     ["coupling.transfer: unknown value 'perparticle' (did you mean 'per_particle'?)"]),
    ("unknown void fraction method", yaml("method: centroid", "method: centroids"),
     ["coupling.void_fraction.method: unknown value 'centroids' (did you mean 'centroid'?)"]),
    ("porous cube factor below the sphere's volume", yaml("method: centroid", "method: porous_cube\n    cube_factor: 0.7"),
     ["coupling.void_fraction.cube_factor: value 0.7 is out of range [0.805996"]),
    ("void fraction floor 1", yaml("method: centroid", "method: centroid\n    floor: 1"),
     ["coupling.void_fraction.floor: value 1 leaves no room for particles"]),
    ("interpolated gas velocity with the averaged transfer",
     yaml("transfer: per_particle", "transfer: averaged\n  gas_velocity_at_particle: interpolated"),
     ["'interpolated' applies to the per-particle transfers"]),
    ("misspelt output key", lambda c: append(os.path.join(c, "coupling.yaml"), "output:\n  statistic_interval: 0.01\n"),
     ["output.statistic_interval: unknown key (did you mean 'statistics_interval'?)"]),
    ("statistics interval not a whole number of gas steps",
     lambda c: append(os.path.join(c, "coupling.yaml"), "output:\n  statistics_interval: 0.0015\n"),
     ["output.statistics_interval = 0.0015 s is not a whole number of gas steps of 0.001 s"]),
    ("outlet patch misspelt", yaml("  coupling_interval: 10\n", "  coupling_interval: 10\n  outlets: [topp]\n"),
     ["dem.outlets: no patch 'topp' (did you mean 'top'?)"]),
    ("gas properties disagree", yaml("density: 1.2 ", "density: 1.25 "), ["gas properties disagree", "gas.density = 1.25"]),
    ("particle diameter disagrees with coupling.yaml", yaml("diameter: 1.0e-4", "diameter: 1.2e-4"),
     ["particles disagree", "diameters 0.0001 to 0.0001 m", "particles.diameter = 0.00012 m"]),
    ("particle density disagrees with coupling.yaml", yaml("density: 2500 ", "density: 2600 "),
     ["particles disagree", "densities 2500 to 2500 kg/m^3", "particles.density = 2600 kg/m^3"]),
]

DEM = [
    ("DEM script not found", yaml("script: in.settling", "script: in.missing"),
     ["dem.script: DEM input script", "in.missing' not found"]),
    ("DEM script syntax error on the terminal", dem("timestep        1e-4", "timestep        1e-4 extra"),
     ["[DEM rank 0] LIGGGHTS ERROR: Illegal timestep command", "full LIGGGHTS output:", "log.liggghts.screen"]),
    ("DEM data file missing", lambda c: None, ["[DEM rank 0] LIGGGHTS ERROR on proc 0: Cannot open file bed.data", "log.liggghts.screen"], 1,
     os.path.join(TUTORIALS, "bubbling_bed")),
    ("run in the DEM script", dem_append("run 10\n"),
     ["in.settling:31: 'run' in a coupled DEM script", "remove the command"]),
    ("clear in the DEM script", dem_append("clear\n"), ["'clear' drops TFDEM's fix styles"]),
    ("two coupling fixes", dem_append("fix fluid2 all tfdem/coupling\n"),
     ["2 'fix ... tfdem/coupling' (in.settling:26, in.settling:31)", "keep exactly one"]),
    ("no coupling fix", dem("fix             fluid all tfdem/coupling", ""), ["no 'fix ID all tfdem/coupling'"]),
    ("gravity disagrees with constant/g", dem("gravity 9.81 vector 0 -1 0", "gravity 9.7 vector 0 -1 0"),
     ["gravity disagrees", "(0 -9.7 0)"]),
    ("particle of diameter 0", dem("diameter 1.0e-4 density 2500", "diameter 0 density 2500"),
     ["has diameter 0 m; every DEM particle needs a positive diameter"]),
    ("DEM step above t_c/10", dem("kn peratomtypepair 1 1e-3", "kn peratomtypepair 1 1e3"),
     ["contact of atom types 1 and 1", "DEM step dt = 0.0001 s is above t_c/10", "use dt <= t_c/57"]),  # e_n ~1: the finer end of the rule
    ("overdamped contact", dem("gamman_abs peratomtypepair 1 1e-8", "gamman_abs peratomtypepair 1 1e-3"),
     ["the contact is overdamped", "e_n is undefined"]),
    ("Hertz contact too stiff for the DEM step", hertz, ["Hertz, E* =", "is above t_c/10"]),
    ("particles lost in the DEM (box smaller than the mesh)",
     dem("region          box block 0 0.06 0 0.4 0 0.02", "region          box block 0 0.06 0.3499 0.4 0 0.02"),
     ["particles were lost in the DEM between t =", "id 1 at (0.03 ", "dem.outlets"], 1, SETTLING, 0.05),
    ("processors 1 1 1 on 2 ranks", dem("units           si", "units           si\nprocessors      1 1 1"),
     ["[DEM rank 0] LIGGGHTS ERROR: Specified processors != physical processors"], 2),
]

GAS = [
    ("coupling interval does not divide the gas step",
     in_case(os.path.join("system", "controlDict"), "deltaT          1e-3;", "deltaT          1.5e-3;"),
     ["deltaT = 0.0015 s must equal dem.coupling_interval x DEM timestep = 10 x 0.0001 = 0.001 s"]),
    ("adjustable time step", lambda c: Case(c).set_control(adjustTimeStep="yes"), ["adjustTimeStep must be 'no'"]),
    ("mesh depth is not d_p under the 2-D rule", yaml("    method: centroid", "    method: centroid\n    two_dimensional: true"),
     ["coupling.void_fraction.two_dimensional is true", "depth = particles.diameter = 0.0001 m", "1 cell(s) of depth 0.02 m"]),
    ("graded mesh", lambda c: (edit(os.path.join(c, "system", "blockMeshDict"), "simpleGrading (1 1 1)",
                                    "simpleGrading (1 2 1)"), run(["blockMesh"], c, "log.blockMesh")),
     ["needs a uniform Cartesian mesh"]),
    ("particle outside the mesh", lambda c: (edit(os.path.join(c, "system", "blockMeshDict"), "0.4", "0.3"),
                                             run(["blockMesh"], c, "log.blockMesh")),
     ["particle 0 at (0.03, 0.35, 0.01) m is outside the mesh"]),
    ("particle outside the mesh on 2 ranks", lambda c: (edit(os.path.join(c, "system", "blockMeshDict"), "0.4", "0.3"),
                                                        run(["blockMesh"], c, "log.blockMesh")),
     ["at t = 0 s: particle 0 at (0.03, 0.35, 0.01) m is outside the mesh"], 2, SETTLING, 0.02, "split", True),
    ("particle outside the mesh on 2 ranks, the gas whole on each",
     lambda c: (edit(os.path.join(c, "system", "blockMeshDict"), "0.4", "0.3"), run(["blockMesh"], c, "log.blockMesh")),
     ["at t = 0 s: particle 0 at (0.03, 0.35, 0.01) m is outside the mesh"], 2, SETTLING, 0.02, "whole"),
    ("re-read controlDict with the gas whole on 2 ranks", lambda c: Case(c).set_control(runTimeModifiable="true"),
     ["the gas is solved whole on each of 2 ranks", "runTimeModifiable true", "Fix: runTimeModifiable false"],
     2, SETTLING, 0.02, "whole"),
    ("later start time without a checkpoint", start_later,
     ["the gas starts at t = 0.01 s but", "has no TFDEM checkpoint", "startFrom latestTime"]),
    ("inlet without 0/voidFraction", lambda c: os.remove(os.path.join(c, "0", "voidFraction")),
     ["gas flows in through patch 'inlet'", '"0/voidFraction"', "fixedValue; value uniform 1;"], 1, BLOWOUT),
]


def main():
    checks = Checks()
    for table in (CONFIG, DEM, GAS):
        for row in table:
            name, fault, words = row[:3]
            expect_failure(checks, name, fault, words, *row[3:])
    checks.finish()


if __name__ == "__main__":
    main()
