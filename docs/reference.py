"""The reference pages of the docs, written from the code's own declarations so they cannot
drift from it:

- reference/coupling-yaml.md: every key coupling.yaml takes (tfdem-config-reference, from the
  solver's readers and every registered engine's);
- reference/bed-yaml.md: every key of tfdem new's bed.yaml (tfdem.newcase.SCHEMA with its
  defaults and BED_KEYS with units and descriptions);
- reference/commands.md: every command's --help as the command prints it.

    python3 docs/reference.py [--check]

writes them into docs/src/reference/; --check writes nothing and exits 1 naming every page
that differs from what would be written (the suite runs it: python.docs_reference).
"""
import argparse
import os
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "python"))

from tfdem import SOURCE_DIR, TUTORIALS  # noqa: E402
from tfdem.newcase import BED_KEYS, REQUIRED, SCHEMA  # noqa: E402
from tfdem.run import environment  # noqa: E402

PAGES = os.path.join(HERE, "src", "reference")
PYTHON = os.environ.get("TFDEM_PYTHON", "/usr/bin/python3")  # Debian's, with numpy (scripts/setup.sh)

# (title, command): every command a user runs, as it prints its help
COMMANDS = [
    ("tfdem", [os.path.join(SOURCE_DIR, "tfdem"), "help"]),
    ("tfdem new", [PYTHON, "-m", "tfdem.newcase", "--help"]),
    ("tfdem pack", [PYTHON, "-m", "tfdem.packing", "--help"]),
    ("tfdem resume", [PYTHON, "-m", "tfdem.resume", "--help"]),
    ("tfdem summary", [PYTHON, "-m", "tfdem.summary", "--help"]),
    ("tfdem stats", [PYTHON, "-m", "tfdem.bedstats", "--help"]),
    ("tfdem pareto", [PYTHON, os.path.join(SOURCE_DIR, "bench", "pareto", "pareto.py"), "--help"]),
    ("fluidization.py (tutorials/fluidization_curve)",
     [PYTHON, os.path.join(TUTORIALS, "fluidization_curve", "fluidization.py"), "--help"]),
    ("tfdem-solve", ["tfdem-solve"]),
    ("tfdem-scene-check", ["tfdem-scene-check"]),
    ("tfdem-gas-layout", ["tfdem-gas-layout"]),
    ("tfdemFoam", ["tfdemFoam", "-help"]),
]


def command_help(args):
    """What a command prints for its help (stdout and stderr; a usage on a missing argument)."""
    env = dict(environment(), COLUMNS="100")  # argparse wraps its help to the terminal's width
    done = subprocess.run(args, capture_output=True, text=True, env=env, cwd=SOURCE_DIR)
    text = (done.stdout + done.stderr).replace(SOURCE_DIR, "<tfdem>")
    return "\n".join(line.rstrip() for line in text.strip().splitlines())


def commands_page():
    lines = ["# Commands", "",
             "Every command a user runs, with the help it prints (written by `docs/reference.py` from the "
             "commands themselves). Each one refuses bad input with the key or option, the value and the fix "
             "(exit 2), and ends a run stopped by Ctrl-C at a checkpoint.", ""]
    for title, args in COMMANDS:
        lines += [f"## {title}", "", "```text", command_help(args), "```", ""]
    return "\n".join(lines)


def flat_schema(schema, prefix=""):
    """(dotted key, default) of every key of SCHEMA, nested mappings walked; the sub-keys of
    lists and optional mappings come from BED_KEYS."""
    out = []
    for key, default in schema.items():
        path = prefix + key
        out.append((path, default))
        if isinstance(default, dict) and default:
            out += flat_schema(default, path + ".")
    return out


def default_text(value):
    if value is REQUIRED:
        return "required"
    if isinstance(value, dict) and value:
        return "(a section)"
    if value is None or value == {} or value == [] or value == 0 or value == 0.0:
        return "none" if value is None or value in ({}, []) else "derived"
    return str(value)


def bed_page():
    defaults = dict(flat_schema(SCHEMA))
    lines = ["# bed.yaml (`tfdem new`)", "",
             "`tfdem new CASE --from bed.yaml` writes a whole case from what you know about a bed; everything "
             "else is derived and printed with its reason (also in `CASE/derived.txt`). This page is written by "
             "`docs/reference.py` from `tfdem.newcase`'s own table of keys. Numbers take the solver's syntax "
             "(1e-3 is a number), a key given twice or unknown is refused with the nearest valid name, counts "
             "must be whole.", "",
             "| key | unit | default | what it sets |", "|---|---|---|---|"]
    for key, (unit, doc) in BED_KEYS.items():
        lines.append(f"| `{key}` | {unit or ' '} | {default_text(defaults.get(key, ''))} | {doc} |")
    return "\n".join(lines) + "\n"


def undocumented_bed_keys():
    """SCHEMA's keys with no line in BED_KEYS (each is a test failure)."""
    return [key for key, _ in flat_schema(SCHEMA) if key not in BED_KEYS]


def coupling_page():
    return command_help(["tfdem-config-reference"]) + "\n"


def pages():
    return {"coupling-yaml.md": coupling_page(), "bed-yaml.md": bed_page(), "commands.md": commands_page() + "\n"}


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--check", action="store_true", help="write nothing; exit 1 when a page differs")
    args = parser.parse_args(argv)
    missing = undocumented_bed_keys()
    if missing:
        print(f"docs/reference.py: bed.yaml keys without a line in tfdem.newcase.BED_KEYS: {', '.join(missing)}",
              file=sys.stderr)
        return 1
    stale = []
    for name, text in pages().items():
        path = os.path.join(PAGES, name)
        now = open(path).read() if os.path.isfile(path) else None
        if now == text:
            continue
        if args.check:
            stale.append(name)
        else:
            os.makedirs(PAGES, exist_ok=True)
            with open(path, "w") as f:
                f.write(text)
            print(f"wrote docs/src/reference/{name}")
    if stale:
        print(f"docs/reference.py --check: {', '.join(stale)} differ from what the code declares: run "
              "python3 docs/reference.py and commit them", file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
