"""Bad input gives a clear message naming the file or argument and a non-zero exit, no crash."""
import os

from tfdem import SOURCE_DIR, TUTORIALS
from tfdem.case import Case, remove_dict_entry
from tfdem_testlib import Checks, copy_case, run, scratch

FREE_FALL = os.path.join(SOURCE_DIR, "tests", "cases", "dem_free_fall", "in.free_fall")
TUTORIAL = os.path.join(TUTORIALS, "poiseuille_channel")
DEM_VARS = ["-var", "steps", "10", "-var", "dumpfile", "dump.final", "-var", "weight_fraction", "1"]


def expect_error(checks, name, args, cwd, must_contain, ranks=1):
    log_name = "log." + "".join(c if c.isalnum() else "_" for c in name)
    code, output = run(args, cwd, log_name, ranks=ranks, expect_success=False)
    checks.true(f"{name}: non-zero exit", code > 0, f"(exit code {code}; negative = killed by a signal)")
    checks.true(f"{name}: no crash", "Segmentation fault" not in output and "signal" not in output.lower())
    for text in must_contain:
        checks.true(f"{name}: message contains {text!r}", text in output)


def edited_script(case, old, new):
    path = os.path.join(case, "in.edited")
    text = open(FREE_FALL).read()
    assert old in text
    open(path, "w").write(text.replace(old, new))
    return path


def main():
    checks = Checks()
    empty = scratch("bad_no_controlDict")
    expect_error(checks, "tfdemFoam without system/controlDict", ["tfdemFoam", "-case", empty], empty,
                 [os.path.join(empty, "system", "controlDict")])

    case = copy_case(TUTORIAL, "bad_transportProperties")
    run(["blockMesh"], case, "log.blockMesh")
    remove_dict_entry(Case(case).file("constant", "transportProperties"), "nu")
    expect_error(checks, "tfdemFoam with 'nu' missing", ["tfdemFoam"], case,
                 ["Entry 'nu' not found", "constant/transportProperties"])

    dem = scratch("bad_dem")
    expect_error(checks, "DEM script not found", ["tfdem-liggghts", "-in", "missing.in"], dem,
                 ["'missing.in' not found"])
    misspelt = edited_script(dem, "weight_fraction ${weight_fraction}", "wieght_fraction 0.5")
    expect_error(checks, "unknown fix argument", ["tfdem-liggghts", "-in", misspelt] + DEM_VARS, dem,
                 ["unknown argument 'wieght_fraction'", "did you mean 'weight_fraction'?"])
    not_number = edited_script(dem, "weight_fraction ${weight_fraction}", "weight_fraction abc")
    expect_error(checks, "non-numeric fix argument on 2 ranks", ["tfdem-liggghts", "-in", not_number] + DEM_VARS,
                 dem, ["'weight_fraction' must be a number, got 'abc'"], ranks=2)
    checks.finish()


if __name__ == "__main__":
    main()
