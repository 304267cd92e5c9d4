"""Shared helpers of TFDEM's integration tests: run programs, copy cases, read outputs."""
import os
import shutil
import subprocess
import sys

SOURCE_DIR = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))
sys.path.insert(0, os.path.join(SOURCE_DIR, "tutorials"))
import case_copy  # noqa: E402

BUILD_DIR = os.environ.get("TFDEM_BUILD", os.path.join(SOURCE_DIR, "build"))


def environment():
    """Environment with build/ on PATH and what Debian's OpenFOAM and Open MPI need."""
    env = dict(os.environ)
    env["WM_PROJECT_DIR"] = "/usr/share/openfoam"
    env["PATH"] = os.pathsep.join([os.path.join(BUILD_DIR, "openfoam_solver"),
                                   os.path.join(BUILD_DIR, "liggghts_fixes"), env.get("PATH", "")])
    if os.geteuid() == 0:
        env["OMPI_ALLOW_RUN_AS_ROOT"] = "1"
        env["OMPI_ALLOW_RUN_AS_ROOT_CONFIRM"] = "1"
    env["OMPI_MCA_rmaps_base_oversubscribe"] = "1"
    return env


def scratch(name):
    """A fresh, empty directory for one test run under build/test-runs/."""
    path = os.path.join(BUILD_DIR, "test-runs", name)
    shutil.rmtree(path, ignore_errors=True)
    os.makedirs(path)
    return path


def copy_case(source, name):
    """Copy a case's 0/, constant/, system/ and, for coupled cases, coupling.yaml and the
    DEM input (in.*) into a fresh scratch directory."""
    dest = os.path.join(BUILD_DIR, "test-runs", name)
    names = [entry for entry in os.listdir(source) if entry == "coupling.yaml" or entry.startswith("in.")]
    case_copy.copy_case(source, dest, names)
    return dest


def write_decompose_dict(case, split):
    """system/decomposeParDict of `case`: simple decomposition into split = (nx, ny, nz)."""
    nx, ny, nz = split
    with open(os.path.join(case, "system", "decomposeParDict"), "w") as out:
        out.write("FoamFile { version 2.0; format ascii; class dictionary; object decomposeParDict; }\n"
                  f"numberOfSubdomains {nx * ny * nz};\nmethod          simple;\n"
                  f"coeffs          {{ n ({nx} {ny} {nz}); }}\n")


def run(args, cwd, log_name, ranks=1, expect_success=True):
    """Run a command (under mpirun when ranks > 1); return (exit code, combined output)."""
    if ranks > 1:
        args = ["mpirun", "-np", str(ranks)] + args
    # errors="replace": LIGGGHTS 3.8.0, aborting on 2 ranks, sometimes echoes an error line
    # from a freed buffer (bytes that are not UTF-8) on the second rank.
    proc = subprocess.run(args, cwd=cwd, env=environment(), stdout=subprocess.PIPE,
                          stderr=subprocess.STDOUT, text=True, errors="replace")
    with open(os.path.join(cwd, log_name), "w") as log:
        log.write(proc.stdout)
    if expect_success and proc.returncode != 0:
        print(proc.stdout[-4000:])
        fail(f"'{' '.join(args)}' exited with {proc.returncode} (log: {os.path.join(cwd, log_name)})")
    return proc.returncode, proc.stdout


def read_probe(case, field, function="centreline"):
    """Last row of an OpenFOAM probes file: (time, [values]); vectors come as tuples."""
    times = sorted(os.listdir(os.path.join(case, "postProcessing", function)), key=float)
    path = os.path.join(case, "postProcessing", function, times[-1], field)
    rows = [line for line in open(path) if line.strip() and not line.startswith("#")]
    tokens = rows[-1].replace("(", " ( ").replace(")", " ) ").split()
    time, values, i = float(tokens[0]), [], 1
    while i < len(tokens):
        if tokens[i] == "(":
            end = tokens.index(")", i)
            values.append(tuple(float(t) for t in tokens[i + 1:end]))
            i = end + 1
        else:
            values.append(float(tokens[i]))
            i += 1
    return time, values


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
