"""What only TFDEM's integration tests need on top of the tfdem package: named checks that fail
the test at the end, scratch folders, and running a program as a test step (a failure ends
the test with the program's output)."""
import os
import re
import shutil
import sys

import tfdem.run
from tfdem import BUILD_DIR, SOURCE_DIR  # noqa: F401  (re-exported for the tests)
from tfdem import STUDIES, TUTORIALS, tfm_models
from tfdem.case import Case
from tfdem.fixed_bed import FixedBed
from tfdem.outputs import probes
from tfdem.run import write_decompose_dict  # noqa: F401


def scratch(name):
    """A fresh, empty directory for one test run under build/test-runs/."""
    path = os.path.join(BUILD_DIR, "test-runs", name)
    shutil.rmtree(path, ignore_errors=True)
    os.makedirs(path)
    return path


PACKED_BED = FixedBed(os.path.join(TUTORIALS, "packed_bed_ergun"))


def packed_bed_copy(name, end_time, mesh=True):
    """PACKED_BED at 0.6 m/s under build/test-runs/name, to end_time, writing every 0.2 s;
    meshed unless `mesh` is False. Steady, so round-off does not grow: runs that differ in
    layout or rank count end at the same pressure drop to ~1e-13."""
    case = PACKED_BED.case.copy_to(scratch(name), extra=PACKED_BED.extra_files())
    case.set_patch_value("U", "inlet", (0, 0.6, 0))
    case.set_control(endTime=end_time, writeInterval=0.2)
    if mesh:
        run(["blockMesh"], case.path, "log.blockMesh")
    return case


def copy_case(source, name):
    """A fresh copy of a case (fields, dictionaries, coupling.yaml, DEM scripts) under
    build/test-runs/name; returns its path."""
    return Case(source).copy_to(os.path.join(BUILD_DIR, "test-runs", name)).path


def poured_copy(tutorial, name, fraction, extra=()):
    """A copy of a poured-bed tutorial under build/test-runs/name with `fraction` of its
    packing.yaml count, poured there (its bed.data); returns (the copy, the count)."""
    from tfdem.case import set_yaml_value
    from tfdem.packing import packing_settings, pour_case
    case = Case(tutorial).copy_to(scratch(name), extra=("packing.yaml",) + tuple(extra))
    count = int(packing_settings(case)["count"] * fraction)
    set_yaml_value(case.file("packing.yaml"), "count", count)
    print(pour_case(case, runner=lambda *a, **k: run(*a[:3])))
    return case, count


def run(args, cwd, log_name, ranks=1, expect_success=True, **options):
    """Run a command (under mpirun when ranks > 1; a split gas needs -parallel in args, the
    whole gas none; `options` as tfdem.run.run's); return (exit code, combined output); a
    failure ends the test."""
    try:
        return tfdem.run.run(args, cwd, log_name, ranks, expect_success, **options)
    except tfdem.run.RunError as e:
        print(e)
        fail(str(e).splitlines()[0])


def read_probe(case, field, function="centreline"):
    """Last row of an OpenFOAM probes function object: (time, [values])."""
    return probes(case, function, field)[-1]


class Checks:
    """Collects named comparisons, prints each, and fails the test at the end if any failed."""

    def __init__(self):
        self.failed = 0
        self.passed = 0

    def close(self, name, value, expected, rel_tol):
        error = abs(value - expected) / abs(expected)
        ok = error <= rel_tol
        self._report(ok, f"{name}: {value:.12g} vs {expected:.12g}, relative error {error:.3e} "
                         f"(tolerance {rel_tol:g})")

    def within(self, name, value, expected, abs_tol):
        ok = abs(value - expected) <= abs_tol
        self._report(ok, f"{name}: {value:.12g} vs {expected:.12g}, |difference| "
                         f"{abs(value - expected):.3e} (tolerance {abs_tol:g})")

    def true(self, name, condition, detail=""):
        self._report(bool(condition), f"{name} {detail}".rstrip())

    def _report(self, ok, text):
        print(("PASS " if ok else "FAIL ") + text)
        if ok:
            self.passed += 1
        else:
            self.failed += 1

    def finish(self):
        print(f"{self.passed} passed, {self.failed} failed")
        sys.exit(1 if self.failed or not self.passed else 0)


def fail(message):
    print("FAIL " + message)
    sys.exit(1)


def edit_once(path, pattern, replacement):
    """The file's one match of `pattern` replaced (a test's case edit); fails on 0 or 2+ matches."""
    with open(path) as f:
        text = f.read()
    new, count = re.subn(pattern, replacement, text)
    if count != 1:
        fail(f"{path}: {pattern!r} matched {count} times")
    with open(path, "w") as f:
        f.write(new)


def dict_number(path, key):
    """The number of an OpenFOAM dictionary's `key value;` entry (comments left out)."""
    with open(path) as f:
        text = re.sub(r"//.*", "", f.read())
    return float(re.search(rf"\n\s*{key}\s+([-+0-9.eE]+)\s*;", text).group(1))


def tfm_column(name, cells, step):
    """studies/seed000's TFM template (tfm_bubbling_bed) as a column one cell wide and `cells`
    tall under build/test-runs/name, set to run one step of `step` seconds written at 15
    digits; its path (not yet prepared)."""
    template = os.path.join(STUDIES, "seed000", "tfm_bubbling_bed")
    path = Case(template).copy_to(scratch(name), extra=("Allprepare", "0.orig")).path
    edit_once(os.path.join(path, "system/blockMeshDict"), r"\nnx\s+15;", "\nnx      1;")
    edit_once(os.path.join(path, "system/blockMeshDict"), r"\nny\s+45;", f"\nny      {cells};")
    control = os.path.join(path, "system/controlDict")
    edit_once(control, r"\ndeltaT\s[^;]*;", f"\ndeltaT          {step:g};")
    edit_once(control, r"\nendTime\s[^;]*;", f"\nendTime {step:g};")
    edit_once(control, r"\nwriteInterval\s[^;]*;", f"\nwriteInterval {step:g};")
    edit_once(control, r"\nwritePrecision\s[^;]*;", "\nwritePrecision  15;")
    edit_once(control, r"\nadjustTimeStep\s[^;]*;", "\nadjustTimeStep  no;")
    return path


def set_internal_field(path, value):
    """A field file's internalField set to `value` (e.g. "uniform 0.4")."""
    edit_once(path, r"internalField\s+[^;]*;", f"internalField   {value};")


def require_tfm_models():
    """Fail unless tfm_models/'s library is built; its path."""
    try:
        tfm_models.check_library()
    except tfm_models.TfmModelsError as error:
        fail(str(error))
    return tfm_models.LIBRARY
