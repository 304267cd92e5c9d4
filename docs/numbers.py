"""Every measured number the docs and READMEs state, traced to the committed file it comes from.

A page states a measured number followed by a marker, invisible once rendered:

    the bed stands 9.39<!-- n:main_job_height --> cm

and docs/numbers.yaml says how the number is computed from a committed file (a small CSV or
JSON a committed script wrote from a run at the committed settings), and how it is printed:

    main_job_height:
      value: mean(column("tutorials/bubbling_bed/results/main_job.csv", "height_cm", since=1))
      format: "{:.2f}"

`python3 docs/numbers.py` (and the suite's python.docs_numbers) checks each marker's number
against its entry, and that every entry is used and every marker has one; it prints each
mismatch with the page, the number written and the number the file gives.
"""
import csv
import glob
import json
import os
import re
import sys

import yaml

ROOT = os.path.normpath(os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
REGISTRY = os.path.join(ROOT, "docs", "numbers.yaml")
MARKER = re.compile(r"(-?[0-9][0-9,]*(?:\.[0-9]+)?(?:e[-+]?[0-9]+)?)<!-- n:([A-Za-z0-9_.-]+) -->")
PAGES = ("README.md", "docs/src/**/*.md", "tutorials/*/README.md", "studies/*/README.md", "studies/*/*.md",
         "bench/README.md", "bench/*/README.md")


# Helpers the registry's expressions use: each reads a committed file under the repository ------
def path_of(relative):
    return os.path.join(ROOT, relative)


def load_json(relative):
    with open(path_of(relative)) as f:
        return json.load(f)


def column(relative, name, since=None, until=None, time="t"):
    """A CSV column (header row of names; '#' lines skipped) as floats, its rows with `time`
    within [since, until] when given."""
    with open(path_of(relative)) as f:
        rows = list(csv.DictReader(line for line in f if not line.startswith("#")))
    kept = [r for r in rows if (since is None or float(r[time]) >= since) and (until is None or float(r[time]) <= until)]
    return [float(r[name]) for r in kept]


def series(relative, since=None, until=None):
    """The second column of a CSV of (t, value) rows under '#' comment lines (no row of names),
    its rows with t within [since, until] when given."""
    with open(path_of(relative)) as f:
        rows = [line.split(",") for line in f if line.strip() and not line.startswith("#")]
    return [float(v) for t, v in rows if (since is None or float(t) >= since) and (until is None or float(t) <= until)]


def mean(values):
    values = list(values)
    return sum(values) / len(values)


def stdev(values):
    """The sample standard deviation (n - 1)."""
    values = list(values)
    m = mean(values)
    return (sum((v - m) ** 2 for v in values) / (len(values) - 1)) ** 0.5


HELPERS = {"json": load_json, "column": column, "series": series, "mean": mean, "stdev": stdev, "min": min, "max": max, "abs": abs,
           "len": len}


def markers(pages=PAGES):
    """(page, number as written, key) of every marker."""
    found = []
    for pattern in pages:
        for path in sorted(glob.glob(os.path.join(ROOT, pattern), recursive=True)):
            with open(path) as f:
                for m in MARKER.finditer(f.read()):
                    found.append((os.path.relpath(path, ROOT), m.group(1), m.group(2)))
    return found


def registry():
    with open(REGISTRY) as f:
        return yaml.safe_load(f) or {}


def expected(entry):
    """The number an entry gives, printed by its format."""
    # the registry is committed code; the helpers as globals, so that a comprehension sees them
    value = eval(entry["value"], {"__builtins__": {}, **HELPERS})
    return entry.get("format", "{:g}").format(value)


def problems():
    entries = registry()
    out, used = [], set()
    for page, written, key in markers():
        used.add(key)
        if key not in entries:
            out.append(f"{page}: {written}<!-- n:{key} -->: no entry '{key}' in docs/numbers.yaml")
            continue
        try:
            should = expected(entries[key])
        except (OSError, KeyError, ValueError, ZeroDivisionError) as e:
            out.append(f"docs/numbers.yaml: {key}: cannot be computed ({type(e).__name__}: {e})")
            continue
        if should != written:
            out.append(f"{page}: {key}: the page says {written}, {entries[key]['value']} gives {should}")
    out += [f"docs/numbers.yaml: {key}: no page states it (remove the entry)" for key in entries if key not in used]
    return out


def main():
    found = problems()
    for p in found:
        print(p, file=sys.stderr)
    print(f"{len(markers())} numbers checked, {len(found)} problems")
    return 1 if found else 0


if __name__ == "__main__":
    sys.exit(main())
