"""Bad input to the coupled solver stops it with a message naming file, key, value and what is
expected; exit code non-zero; no crash. Each case is the settling tutorial with one fault."""
import os
import re

from tfdem_testlib import SOURCE_DIR, Checks, copy_case, run, write_decompose_dict

TUTORIAL = os.path.join(SOURCE_DIR, "tutorials", "settling_particle")


def edit(path, old, new):
    text = open(path).read()
    assert old in text, (path, old)
    open(path, "w").write(text.replace(old, new))


def expect_failure(checks, name, fault, must_contain, ranks=1):
    case = copy_case(TUTORIAL, "coupled_bad_" + re.sub(r"\W+", "_", name))
    fault(case)
    run(["blockMesh"], case, "log.blockMesh")
    solver = ["tfdemFoam"]
    if ranks > 1:
        write_decompose_dict(case, (1, 2, 1))
        run(["decomposePar"], case, "log.decomposePar")
        solver.append("-parallel")
    code, output = run(solver, case, "log.tfdemFoam", ranks=ranks, expect_success=False)
    checks.true(f"{name}: non-zero exit", code > 0, f"(exit code {code})")
    checks.true(f"{name}: no crash", "Segmentation fault" not in output and "sigsegv" not in output.lower())
    for text in must_contain:
        checks.true(f"{name}: message contains {text!r}", text in output)


def main():
    checks = Checks()
    expect_failure(checks, "misspelt key in coupling.yaml",
                   lambda c: edit(os.path.join(c, "coupling.yaml"), "  transfer:", "  transfr:"),
                   ["coupling.yaml:12:3: coupling.transfr: unknown key (did you mean 'transfer'?)"])
    expect_failure(checks, "DEM script not found",
                   lambda c: edit(os.path.join(c, "coupling.yaml"), "script: in.settling", "script: in.missing"),
                   ["dem.script: DEM input script", "in.missing' not found"])
    expect_failure(checks, "coupling interval does not divide the gas step",
                   lambda c: edit(os.path.join(c, "system", "controlDict"), "deltaT          1e-3;", "deltaT          1.5e-3;"),
                   ["deltaT = 0.0015 s must equal dem.coupling_interval x DEM timestep = 10 x 0.0001 = 0.001 s"])
    expect_failure(checks, "mesh depth is not d_p under the 2-D rule",
                   lambda c: edit(os.path.join(c, "coupling.yaml"), "    method: centroid",
                                  "    method: centroid\n    two_dimensional: true"),
                   ["coupling.void_fraction.two_dimensional is true", "depth = particles.diameter = 0.0001 m",
                    "1 cell(s) of depth 0.02 m"])
    expect_failure(checks, "particle outside the mesh",
                   lambda c: edit(os.path.join(c, "system", "blockMeshDict"), "0.4", "0.3"),
                   ["particle 0 at (0.03, 0.35, 0.01) m is outside the mesh"])
    # On 2 ranks the particle is held by one rank only; every rank must stop with its message.
    expect_failure(checks, "particle outside the mesh on 2 ranks",
                   lambda c: edit(os.path.join(c, "system", "blockMeshDict"), "0.4", "0.3"),
                   ["[0] at t = 0 s: particle 0 at (0.03, 0.35, 0.01) m is outside the mesh",
                    "[1] at t = 0 s: particle 0 at (0.03, 0.35, 0.01) m is outside the mesh"], ranks=2)
    expect_failure(checks, "gas properties disagree",
                   lambda c: edit(os.path.join(c, "coupling.yaml"), "density: 1.2 ", "density: 1.25 "),
                   ["gas properties disagree", "gas.density = 1.25"])
    # k_n = 1000 N/m for 100 um spheres: t_c = 2.5e-6 s, so a 1e-4 s step is far above t_c/10.
    expect_failure(checks, "DEM step above t_c/10",
                   lambda c: edit(os.path.join(c, "in.settling"), "kn peratomtypepair 1 1e-3", "kn peratomtypepair 1 1e3"),
                   ["contact of atom types 1 and 1", "DEM step dt = 0.0001 s is above t_c/10", "use dt <= t_c/50"])
    checks.finish()


if __name__ == "__main__":
    main()
