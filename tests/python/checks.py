"""The python tests' checks: each prints PASS or FAIL with its name; finish() exits 1 if any
failed. A test script imports it from its own folder (the script's folder leads sys.path)."""
import sys

failures = []


def check(name, condition, detail=""):
    print(("PASS " if condition else "FAIL ") + name + (f" {detail}" if detail else ""))
    if not condition:
        failures.append(name)


def close(name, value, expected, tol=1e-7):
    """|value - expected| within tol, relative to |expected| where that exceeds 1."""
    check(name, abs(value - expected) <= tol * max(1.0, abs(expected)), f"{value!r} vs {expected!r}")


def finish():
    print(f"{len(failures)} failed" if failures else "all passed")
    sys.exit(1 if failures else 0)
