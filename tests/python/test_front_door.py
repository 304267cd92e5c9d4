"""The front door's Python commands on bad input, bad options, bad paths and failing disks:
`tfdem new`, `tfdem pack` (and its --verify), `tfdem stats`, `pareto.py`, the fluidization
driver and `python3 -m tfdem.run`, each run in-process through its main(argv). No simulation:
the pour is a stand-in that writes a small data file, and the runs are refused before they
start.

Every case asserts the exit code (2 for a refusal, 130 for Ctrl-C, 1 for an internal error,
0 where the input is good), no traceback on stderr, that the message names the key (or the
option, or the path) and the bad value as the input gives them, and where files are at stake
that they are byte-identical afterwards (nothing half-written, no temporary file left). A
full disk and a read-only file system are simulated by making os.fsync, os.rename or
tempfile.mkdtemp raise OSError(ENOSPC, EROFS, EACCES) part way. The counts per class are
printed at the end.
"""
import contextlib
import errno
import importlib.util
import io
import os
import signal
import subprocess
import sys
import tempfile
import traceback

import tfdem.batch
import tfdem.bedstats
import tfdem.frontdoor
import tfdem.newcase
import tfdem.packing
import tfdem.run
from tfdem import SOURCE_DIR

HANG_SECONDS = 20  # a command that has not ended by then hangs

BED = """box: {width: 0.04, height: 0.12, depth: one_layer}
particles:
  density: 2500
  sizes: [{diameter: 0.001, number: 800}]
  restitution: 0.9
  friction: 0.1
gas: {density: 1.2, viscosity: 1.8e-5}
inflow: {velocity: 0.8, plate: {pressure_drop_fraction: 0.3}}
run: {end_time: 0.05, write_interval: 0.05}
"""
MIXTURE = BED.replace("sizes: [{diameter: 0.001, number: 800}]",
                      "sizes: [{diameter: 0.001, mass_fraction: 0.5}, {diameter: 0.0015, mass_fraction: 0.5}]\n"
                      "  count: 600")
SWEEP = """template: ./case
end_time: 0.2
window: [0.05, 0.2]
batch: 0.05
band: 0.01
field_interval: 0.01
statistics_interval: 0.002
reference: reference
points:
  reference: {gas_time_step: 2.5e-4}
  default: {}
"""
LEVELS = """levels:
  - [0.4, 0.2]
  - [1.8, 0.5]
  - [0.4, 0.2]
analysis: {fluidized: 1.8}
"""

results = {}  # class: [(name, ok, detail)]


def load_script(path, name):
    spec = importlib.util.spec_from_file_location(name, path)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


PARETO = load_script(os.path.join(SOURCE_DIR, "bench", "pareto", "pareto.py"), "pareto")
sys.path.insert(0, os.path.join(SOURCE_DIR, "tutorials", "fluidization_curve"))
FLUIDIZATION = load_script(os.path.join(SOURCE_DIR, "tutorials", "fluidization_curve", "fluidization.py"),
                           "fluidization_driver")

COMMANDS = {"new": tfdem.newcase.main, "pack": tfdem.packing.main, "stats": tfdem.bedstats.main,
            "pareto": PARETO.main, "fluidization": FLUIDIZATION.main, "run": tfdem.run.main}


# Running a command ------------------------------------------------------------------------------
class Outcome:
    def __init__(self, code, out, err, exception=None):
        self.code, self.out, self.err, self.exception = code, out, err, exception


class Hang(BaseException):
    pass


def _alarm(signum, frame):
    raise Hang()


def invoke(command, argv, cwd):
    """COMMANDS[command](argv) in cwd: its exit code, stdout and stderr; an exception that
    escapes is kept (with its traceback on stderr, as Python would print it)."""
    out, err = io.StringIO(), io.StringIO()
    previous = signal.signal(signal.SIGALRM, _alarm)
    signal.alarm(HANG_SECONDS)
    here = os.getcwd()
    exception, code = None, None
    try:
        os.chdir(cwd)
        with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
            code = COMMANDS[command](list(argv))
    except Hang:
        exception, code = "hang", "hang"
    except SystemExit as e:
        code = e.code if isinstance(e.code, int) else (0 if e.code is None else 1)
        if not isinstance(e.code, int) and e.code is not None:
            err.write(str(e.code))
    except BaseException as e:  # what a user would see as a traceback
        exception = e
        err.write("Traceback (most recent call last):\n" + traceback.format_exc())
    finally:
        signal.alarm(0)
        signal.signal(signal.SIGALRM, previous)
        os.chdir(here)
    return Outcome(code, out.getvalue(), err.getvalue(), exception)


def snapshot(path):
    """{relative path: bytes (None for a folder)} of everything under path (or the file)."""
    if os.path.isfile(path):
        with open(path, "rb") as f:
            return {"": f.read()}
    found = {}
    for folder, dirs, files in os.walk(path):
        for name in dirs:
            found[os.path.relpath(os.path.join(folder, name), path)] = None
        for name in files:
            with open(os.path.join(folder, name), "rb") as f:
                found[os.path.relpath(os.path.join(folder, name), path)] = f.read()
    return found


def record(kind, name, ok, detail=""):
    results.setdefault(kind, []).append((name, ok, detail))
    print(("PASS " if ok else "FAIL ") + f"[{kind}] {name}" + ("" if ok else f": {detail}"), flush=True)


def check(kind, name, command, argv, cwd, names=(), code=2, unchanged=(), absent=(), after=None):
    """Run a command and check its exit code, no traceback, that stderr holds each of `names`,
    that the paths in `unchanged` are byte-identical and those in `absent` missing afterwards;
    `after(outcome)` returns a further problem or None. Returns the outcome."""
    before = {p: snapshot(p) for p in unchanged}
    outcome = invoke(command, argv, cwd)
    problems = []
    if outcome.code != code:
        problems.append(f"exit {outcome.code}, expected {code}")
    if "Traceback" in outcome.err:
        problems.append("a traceback")
    problems += [f"{n!r} not in the message" for n in names if n not in outcome.err]
    problems += [f"{p} changed" for p in unchanged if snapshot(p) != before[p]]
    problems += [f"{p} exists" for p in absent if os.path.lexists(p)]
    if after is not None:
        extra = after(outcome)
        if extra:
            problems.append(extra)
    detail = "; ".join(problems) + f" | stderr: {outcome.err.strip()[-400:]}"
    record(kind, name, not problems, detail)
    return outcome


def write(path, text, mode="w"):
    os.makedirs(os.path.dirname(path), exist_ok=True)
    with open(path, mode) as f:
        f.write(text)
    return path


@contextlib.contextmanager
def failing(module, name, error, after_calls=0, when=None):
    """module.name raising `error` from its (after_calls + 1)-th call on (of those for which
    when(*args, **kwargs) holds, when given)."""
    original = getattr(module, name)
    calls = [0]

    def stand_in(*args, **kwargs):
        if when is None or when(*args, **kwargs):
            calls[0] += 1
            if calls[0] > after_calls:
                raise error
        return original(*args, **kwargs)

    setattr(module, name, stand_in)
    try:
        yield calls
    finally:
        setattr(module, name, original)


@contextlib.contextmanager
def replaced(module, name, value):
    original = getattr(module, name)
    setattr(module, name, value)
    try:
        yield
    finally:
        setattr(module, name, original)


def full_disk():
    return OSError(errno.ENOSPC, os.strerror(errno.ENOSPC))


# The pour's stand-in ----------------------------------------------------------------------------
def fake_pour(args, cwd, log_name, ranks=1, **_):
    """tfdem-liggghts' pour replaced: a data file (in.pour's -var out) of `count` spheres of
    dp_small on a square grid above the floor, in a box of in.pour's width, height and depth."""
    variables = {args[k + 1]: args[k + 2] for k in range(len(args) - 2) if args[k] == "-var"}
    width, height, depth = (float(variables[k]) for k in ("width", "height", "depth"))
    floor, d, count = float(variables["floor"]), float(variables["dp_small"]), int(variables["count"])
    across = int(width / (1.1 * d))
    atoms, velocities = [], []
    for k in range(count):
        x, y = (k % across + 0.5) * 1.1 * d, floor + (k // across + 0.5) * 1.1 * d
        atoms.append(f"{k + 1} 1 {d!r} 2500 {x!r} {y!r} {depth / 2!r} 0 0 0")
        velocities.append(f"{k + 1} 0.01 -0.02 0 0 0 3")
    text = (f"LAMMPS data file (stand-in)\n\n{count} atoms\n3 atom types\n0 {width!r} xlo xhi\n{floor!r} {height!r} "
            f"ylo yhi\n0 {depth!r} zlo zhi\n\nAtoms\n\n" + "\n".join(atoms) + "\n\nVelocities\n\n"
            + "\n".join(velocities) + "\n")
    write(os.path.join(cwd, variables["out"]), text)
    return 0, f"TFDEM packed bed: {count} particles (stand-in)\n"


def stand_in_pour():
    return replaced(tfdem.run, "run", fake_pour)


# The cases --------------------------------------------------------------------------------------
def bed_cases(root):
    """(class, name, bed.yaml text, names the message must hold)."""
    def edit(old, new, text=BED):
        assert old in text, old
        return text.replace(old, new, 1)

    return [
        ("malformed YAML", "an empty bed.yaml", "", ["bed.yaml", "empty"]),
        ("malformed YAML", "a bed.yaml of comments only", "# nothing yet\n", ["bed.yaml", "empty"]),
        ("malformed YAML", "a list where the mapping belongs", "- box\n- particles\n",
         ["bed.yaml", "expected a mapping"]),
        ("malformed YAML", "a bare word", "hello\n", ["bed.yaml", "'hello'"]),
        ("malformed YAML", "an unclosed bracket", edit("sizes: [{diameter: 0.001, number: 800}]",
                                                       "sizes: [{diameter: 0.001, number: 800}"),
         ["bed.yaml:", "not valid YAML"]),
        ("malformed YAML", "a tab in the indentation", edit("  density: 2500", "\tdensity: 2500"),
         ["bed.yaml:", "not valid YAML"]),
        ("malformed YAML", "bad indentation", edit("  restitution: 0.9", "    restitution: 0.9"),
         ["bed.yaml:", "not valid YAML"]),
        ("wrong type", "box as a list", edit("box: {width: 0.04, height: 0.12, depth: one_layer}",
                                             "box: [0.04, 0.12]"), ["box", "expected a mapping"]),
        ("wrong type", "sizes as a mapping", edit("sizes: [{diameter: 0.001, number: 800}]",
                                                  "sizes: {diameter: 0.001, number: 800}"),
         ["particles.sizes", "expected a list"]),
        ("wrong type", "a size as a number", edit("sizes: [{diameter: 0.001, number: 800}]", "sizes: [0.001]"),
         ["particles.sizes[0]", "0.001", "expected a mapping"]),
        ("wrong type", "a width in words", edit("width: 0.04", "width: abc"), ["box.width", "abc", "not a number"]),
        ("wrong type", "a density as a list", edit("density: 2500", "density: [2500, 2600]"),
         ["particles.density", "2500", "not a number"]),
        ("wrong type", "a count in words", edit("number: 800", "number: abc"),
         ["particles.sizes[0].number", "abc", "not a number"]),
        ("wrong type", "a count of true", edit("number: 800", "number: true"),
         ["particles.sizes[0].number", "true"]),
        ("wrong type", "jets as a mapping", edit("inflow: {velocity: 0.8, plate: {pressure_drop_fraction: 0.3}}",
                                                 "inflow: {jets: {centre: 0.02, width: 0.004, velocity: 20}}"),
         ["inflow.jets", "expected a list"]),
        ("wrong type", "a plate as a number", edit("plate: {pressure_drop_fraction: 0.3}", "plate: 0.3"),
         ["inflow.plate", "0.3", "expected a mapping"]),
        ("wrong type", "an empty end time", edit("end_time: 0.05", "end_time:"), ["run.end_time", "not a number"]),
        ("wrong type", "a drag law as a list", BED + "coupling: {drag_law: [ergun_wen_yu]}\n",
         ["coupling.drag_law", "ergun_wen_yu"]),
        ("wrong type", "an engine as a number", BED + "dem: {engine: 5}\n", ["dem.engine", "5"]),
        ("wrong type", "a cell size in words", BED + "mesh: {cell_size: fine}\n", ["mesh.cell_size", "fine"]),
        ("wrong type", "walls as a list", edit("friction: 0.1", "friction: 0.1\n  wall: [0.9, 0.1]"),
         ["particles.wall", "expected a mapping"]),
        ("wrong type", "a section left empty", edit("gas: {density: 1.2, viscosity: 1.8e-5}", "gas:"),
         ["gas", "expected a mapping"]),
        ("unknown key", "box.widht", edit("width: 0.04", "widht: 0.04"), ["box.widht", "did you mean 'width'"]),
        ("unknown key", "partciles", edit("particles:", "partciles:"), ["partciles", "did you mean 'particles'"]),
        ("unknown key", "sizes[0].diamter", edit("diameter: 0.001", "diamter: 0.001"),
         ["particles.sizes[0].diamter", "did you mean 'diameter'"]),
        ("unknown key", "inflow.jet", edit("inflow: {velocity: 0.8, plate: {pressure_drop_fraction: 0.3}}",
                                           "inflow: {jet: [{centre: 0.02, width: 0.004, velocity: 20}]}"),
         ["inflow.jet", "did you mean 'jets'"]),
        ("unknown key", "an engine misspelt", BED + "dem: {engine: hardsphere}\n",
         ["dem.engine", "hardsphere", "did you mean 'hard_sphere'"]),
        ("unknown key", "depth one_layr", edit("depth: one_layer", "depth: one_layr"),
         ["box.depth", "one_layr", "did you mean 'one_layer'"]),
        ("non-finite", "width .inf", edit("width: 0.04", "width: .inf"), ["box.width", ".inf", "finite"]),
        ("non-finite", "height .nan", edit("height: 0.12", "height: .nan"), ["box.height", ".nan", "finite"]),
        ("non-finite", "viscosity .NaN", edit("viscosity: 1.8e-5", "viscosity: .NaN"),
         ["gas.viscosity", "finite"]),
        ("non-finite", "velocity +.inf", edit("velocity: 0.8", "velocity: +.inf"), ["inflow.velocity", "finite"]),
        ("non-finite", "end time .inf", edit("end_time: 0.05", "end_time: .inf"), ["run.end_time", ".inf"]),
        ("non-finite", "friction -.inf", edit("friction: 0.1", "friction: -.inf"),
         ["particles.friction", "-.inf"]),
        ("non-finite", "a diameter .nan", edit("diameter: 0.001", "diameter: .nan"),
         ["particles.sizes[0].diameter", ".nan"]),
        ("out of range", "width 0", edit("width: 0.04", "width: 0"), ["box.width", "0"]),
        ("out of range", "width -0.04", edit("width: 0.04", "width: -0.04"), ["box.width", "-0.04"]),
        ("out of range", "particles lighter than the gas", edit("density: 2500", "density: 0.5"),
         ["particles.density", "0.5", "1.2"]),
        ("out of range", "no gas density", edit("density: 1.2", "density: 0"), ["gas.density", "0"]),
        ("out of range", "a viscosity above the solver's", edit("viscosity: 1.8e-5", "viscosity: 5000"),
         ["gas.viscosity", "5000"]),
        ("out of range", "a 2 m diameter", edit("diameter: 0.001", "diameter: 2"),
         ["particles.sizes[0].diameter", "2"]),
        ("out of range", "e_n 1.2", edit("restitution: 0.9", "restitution: 1.2"),
         ["particles.restitution", "1.2"]),
        ("out of range", "friction -0.1", edit("friction: 0.1", "friction: -0.1"), ["particles.friction", "-0.1"]),
        ("out of range", "write interval past the end", edit("write_interval: 0.05", "write_interval: 0.1"),
         ["run.write_interval", "0.1"]),
        ("out of range", "a plate of 0", edit("pressure_drop_fraction: 0.3", "pressure_drop_fraction: 0"),
         ["inflow.plate.pressure_drop_fraction", "0"]),
        ("out of range", "a plate without its fraction", edit("plate: {pressure_drop_fraction: 0.3}", "plate: {}"),
         ["inflow.plate.pressure_drop_fraction", "missing"]),
        ("out of range", "stiffness 0 given", edit("friction: 0.1", "friction: 0.1\n  stiffness: 0"),
         ["particles.stiffness", "0"]),
        ("out of range", "cell size 0 given", BED + "mesh: {cell_size: 0}\n", ["mesh.cell_size", "0"]),
        ("out of range", "cell size -0.004", BED + "mesh: {cell_size: -0.004}\n", ["mesh.cell_size", "-0.004"]),
        ("out of range", "mass fraction 1.5", edit("mass_fraction: 0.5}, {", "mass_fraction: 1.5}, {", MIXTURE),
         ["particles.sizes[0].mass_fraction", "1.5"]),
        ("out of range", "a jet of no speed", edit("inflow: {velocity: 0.8, plate: {pressure_drop_fraction: 0.3}}",
                                                   "inflow: {jets: [{centre: 0.02, width: 0.004, velocity: 0}]}"),
         ["inflow.jets[0].velocity", "0"]),
        ("out of range", "an inflow too fast for OpenFOAM's time index", edit("velocity: 0.8", "velocity: 1e300"),
         ["run.end_time", "0.05", "32-bit"]),
        ("out of range", "a box deeper than OpenFOAM can count cells", edit("depth: one_layer", "depth: 1e300"),
         ["box", "gas cells", "32-bit"]),
        ("out of range", "spheres of 1 nm (the scene check refuses k_n)",
         edit("diameter: 0.001", "diameter: 1e-9") + "mesh: {cell_size: 0.004}\n",
         ["bed.yaml", "tfdem-scene-check refuses", "k_n"]),
        ("ignored value", "a count beside numbers (ignored before)",
         edit("friction: 0.1", "friction: 0.1\n  count: 900"),
         ["particles.count", "900"]),
        ("fractional count", "number 800.7", edit("number: 800", "number: 800.7"),
         ["particles.sizes[0].number", "800.7", "whole number"]),
        ("fractional count", "number 800.5", edit("number: 800", "number: 800.5"),
         ["particles.sizes[0].number", "800.5"]),
        ("fractional count", "count 600.2 with mass fractions", edit("count: 600", "count: 600.2", MIXTURE),
         ["particles.count", "600.2"]),
        ("fractional count", "number 1e-1", edit("number: 800", "number: 1e-1"),
         ["particles.sizes[0].number", "0.1"]),
        ("duplicate key", "box given twice", BED + "box: {width: 0.05, height: 0.12, depth: one_layer}\n",
         ["bed.yaml:10", "box", "given twice", "line 1"]),
        ("duplicate key", "particles.density given twice",
         edit("  restitution: 0.9", "  density: 2600\n  restitution: 0.9"),
         ["density", "2500", "2600", "given twice"]),
        ("duplicate key", "a flow mapping's key twice", edit("gas: {density: 1.2, viscosity: 1.8e-5}",
                                                             "gas: {density: 1.2, density: 1.3}"),
         ["density", "1.2", "1.3", "given twice"]),
        ("number syntax", "0x10 is not a number", edit("number: 800", "number: 0x10"),
         ["particles.sizes[0].number", "0x10"]),
        ("number syntax", "1_000 is not a number", edit("number: 800", "number: 1_000"),
         ["particles.sizes[0].number", "1_000"]),
        ("number syntax", "017 is refused (octal or decimal?)", edit("number: 800", "number: 017"),
         ["particles.sizes[0].number", "017", "leading zero"]),
        ("number syntax", "1:30 is not a number", edit("end_time: 0.05", "end_time: 1:30"), ["run.end_time", "1:30"]),
    ]


def check_bed_refusals(root):
    inputs = os.path.join(root, "inputs")
    for kind, name, text, names in bed_cases(root):
        source = write(os.path.join(inputs, "bed.yaml"), text)
        dest = os.path.join(root, "refused_case")
        check(kind, f"tfdem new: {name}", "new", [dest, "--from", source], root, names, unchanged=[inputs],
              absent=[dest])
    bad = write(os.path.join(inputs, "latin1.yaml"), b"box: {width: 0.04}\nname: caf\xe9\n", "wb")
    check("malformed YAML", "tfdem new: a file that is not UTF-8", "new",
          [os.path.join(root, "refused_case"), "--from", bad], root, ["latin1.yaml", "not valid YAML"],
          absent=[os.path.join(root, "refused_case")])


def check_number_syntax(root):
    """1e-3, 1.0e4 and 8e2 are numbers (yaml-cpp's syntax), equal to 0.001, 10000 and 800: the
    case written from them is the case written from the plain decimals, byte for byte."""
    plain = BED.replace("density: 2500", "density: 2500.0")
    exponent = (plain.replace("diameter: 0.001", "diameter: 1e-3").replace("density: 2500.0", "density: 2.5e3")
                .replace("number: 800", "number: 8e2").replace("viscosity: 1.8e-5", "viscosity: 0.000018")
                .replace("width: 0.04", "width: 4.0e-2"))
    cases = {}
    for label, text in (("plain", plain), ("exponent", exponent)):
        folder = os.path.join(root, f"syntax_{label}")
        source = write(os.path.join(folder, "bed.yaml"), text)
        check("number syntax", f"tfdem new accepts the {label} spelling", "new",
              [os.path.join(folder, "case"), "--from", source], folder, code=0)
        files = snapshot(os.path.join(folder, "case"))
        files.pop("bed.yaml", None)
        cases[label] = files
    record("number syntax", "1e-3, 2.5e3, 8e2, 4.0e-2 and 0.000018 make the case 0.001, 2500.0, 800, 0.04 and 1.8e-5 "
           "make", cases["plain"] == cases["exponent"] and bool(cases["plain"]))
    from tfdem.inputs import parse_yaml
    values = parse_yaml("a: 1e-3\nb: 1.0e4\nc: 0.017\nd: 1E+2\ne: .5\nf: -0\n")
    record("number syntax", "1e-3 = 0.001, 1.0e4 = 10000, 0.017, 1E+2 = 100, .5 = 0.5, -0 = 0",
           values == {"a": 0.001, "b": 10000.0, "c": 0.017, "d": 100.0, "e": 0.5, "f": 0}, str(values))


def check_names_and_folders(root):
    """Empty names, existing folders, --force and what it replaces."""
    folder = os.path.join(root, "names")
    source = write(os.path.join(folder, "bed.yaml"), BED)
    own = {"coupling.yaml": "# the user's own coupling.yaml\n", "in.bed": "# the user's own in.bed\n"}
    for name, text in own.items():
        write(os.path.join(folder, name), text)
    for name in ("", "   ", "\t"):
        check("empty name", f"tfdem new {name!r}", "new", [name, "--from", source], folder,
              ["case name", repr(name), "empty"], unchanged=[folder])
    check("existing folder", "tfdem new . (the current folder, not empty)", "new", [".", "--from", source], folder,
          ["exists and is not empty", "coupling.yaml"], unchanged=[folder])
    check("existing folder", "tfdem new . --force (not a case: refused)", "new", [".", "--from", source, "--force"],
          folder, ["--force replaces only a case"], unchanged=[folder])
    user = os.path.join(root, "user_folder")
    write(os.path.join(user, "notes.txt"), "mine\n")
    check("existing folder", "tfdem new into a folder of the user's", "new", [user, "--from", source], root,
          [user, "exists and is not empty", "notes.txt"], unchanged=[user])
    check("existing folder", "... and with --force (not a case: refused)", "new", [user, "--from", source, "--force"],
          root, [user, "--force replaces only a case"], unchanged=[user])
    empty = os.path.join(root, "empty_folder")
    os.makedirs(empty)
    check("existing folder", "tfdem new into an empty folder writes the case", "new", [empty, "--from", source], root,
          code=0, after=lambda o: None if os.path.isfile(os.path.join(empty, "Allrun")) else "no Allrun")
    here = os.path.join(root, "empty_here")
    os.makedirs(here)
    inode = os.stat(here).st_ino
    with failing(os, "rename", OSError(errno.EROFS, os.strerror(errno.EROFS)), after_calls=2):
        check("read-only", "tfdem new . in an empty folder failing part way leaves it empty", "new",
              [".", "--from", source], here, ["read-only"], unchanged=[here])
    check("existing folder", "tfdem new . in an empty folder (you in it) keeps the folder itself", "new",
          [".", "--from", source], here, code=0,
          after=lambda o: None if os.stat(here).st_ino == inode and os.path.isfile(os.path.join(here, "Allrun"))
          else "the folder was replaced")
    case = os.path.join(root, "names_case")
    check("existing folder", "tfdem new writes a case", "new", [case, "--from", source], root, code=0)
    check("existing folder", "a second tfdem new into the case is refused", "new", [case, "--from", source], root,
          [case, "exists and is not empty", "--force"], unchanged=[case])
    write(os.path.join(case, "bed.data"), "an old bed\n")
    check("existing folder", "--force replaces a case and names what it held", "new",
          [case, "--from", source, "--force"], root, code=0,
          after=lambda o: None if ("replaced" in o.out and "bed.data" in o.out
                                   and not os.path.exists(os.path.join(case, "bed.data"))) else f"out: {o.out[:300]}")
    inner = write(os.path.join(case, "bed.yaml"), BED.replace("velocity: 0.8", "velocity: 0.9"))
    check("existing folder", "--force from the case's own bed.yaml", "new", [case, "--from", inner, "--force"], root,
          code=0, after=lambda o: None if "velocity: 0.9" in open(inner).read() else "bed.yaml lost")
    check("existing folder", "--force on the folder you are in is refused", "new", [".", "--from", inner, "--force"],
          case, ["the folder you are in"], unchanged=[case])
    a_file = write(os.path.join(root, "a_file"), "x\n")
    check("paths", "tfdem new CASE where CASE is a file", "new", [a_file, "--from", source], root,
          [a_file, "not a folder"], unchanged=[a_file])
    check("paths", "tfdem new CASE under a file", "new", [os.path.join(a_file, "case"), "--from", source], root,
          [a_file], unchanged=[a_file])
    check("paths", "tfdem new --from a missing file", "new", [os.path.join(root, "c_missing"), "--from",
                                                              os.path.join(root, "nowhere.yaml")], root,
          ["nowhere.yaml", "cannot read"], absent=[os.path.join(root, "c_missing")])
    check("paths", "tfdem new --from a folder", "new", [os.path.join(root, "c_folder"), "--from", folder], root,
          [folder, "cannot read"], absent=[os.path.join(root, "c_folder")])
    check("paths", "tfdem new without --from", "new", [os.path.join(root, "c_none")], root, ["--from"],
          absent=[os.path.join(root, "c_none")])


def check_failing_disk_on_new(root):
    """A full disk, a read-only file system, a refused folder and Ctrl-C part way through
    tfdem new leave nothing (or the replaced case as it was), and a re-run works."""
    folder = os.path.join(root, "disk")
    source = write(os.path.join(folder, "inputs", "bed.yaml"), BED)
    dest = os.path.join(folder, "case")
    with failing(os, "fsync", full_disk(), after_calls=5):
        check("full disk", "tfdem new on a full disk (the 6th file) leaves nothing", "new", [dest, "--from", source],
              folder, [dest, "disk is full"], unchanged=[folder])
    check("full disk", "... and a re-run works", "new", [dest, "--from", source], folder, code=0)
    old = snapshot(dest)
    with failing(os, "fsync", full_disk(), after_calls=3):
        check("full disk", "tfdem new --force on a full disk leaves the old case as it was", "new",
              [dest, "--from", source, "--force"], folder, ["disk is full"], unchanged=[folder])
    record("full disk", "... byte for byte", snapshot(dest) == old)
    other = os.path.join(folder, "other")
    with failing(os, "rename", OSError(errno.EROFS, os.strerror(errno.EROFS))):
        check("read-only", "tfdem new on a read-only file system", "new", [other, "--from", source], folder,
              [other, "read-only"], unchanged=[folder])
    with failing(tempfile, "mkdtemp", PermissionError(errno.EACCES, os.strerror(errno.EACCES), folder),
                 when=lambda *a, **k: k.get("dir") == folder):
        check("read-only", "tfdem new in a folder it may not write", "new", [other, "--from", source], folder,
              ["making the case's folder in", folder, "permission denied"], unchanged=[folder])
    with failing(tfdem.newcase, "write_file_synced", KeyboardInterrupt(), after_calls=2):
        check("interrupted", "Ctrl-C during tfdem new leaves nothing", "new", [other, "--from", source], folder,
              code=130, unchanged=[folder])
    dead = subprocess.Popen(["true"])
    dead.wait()
    leftover = os.path.join(folder, f".other{tfdem.newcase.TEMPORARY}{dead.pid}-abc")
    write(os.path.join(leftover, "coupling.yaml"), "half\n")
    check("interrupted", "a killed tfdem new's folder is cleared by the next run", "new", [other, "--from", source],
          folder, code=0, absent=[leftover])


def make_case(root, name, text=BED):
    source = write(os.path.join(root, f"{name}.yaml"), text)
    path = os.path.join(root, name)
    outcome = invoke("new", [path, "--from", source], root)
    assert outcome.code == 0, outcome.err
    return path


def check_pack(root):
    """tfdem pack: packing.yaml checked; the data file put in place whole with its stamp last;
    --verify against the stamp; a full disk, a read-only rename or Ctrl-C leave the previous
    bed and stamp."""
    case = make_case(root, "pack_case")
    packing = os.path.join(case, "packing.yaml")
    good = open(packing).read()
    count = int(good.split("count:")[1].split()[0])
    bad = [
        ("malformed YAML", "an empty packing.yaml", "", ["packing.yaml", "empty"]),
        ("malformed YAML", "packing.yaml not YAML", "count: [800\n", ["packing.yaml:", "not valid YAML"]),
        ("malformed YAML", "packing.yaml a list", "- 800\n", ["packing.yaml", "expected a mapping"]),
        ("wrong type", "count in words", good.replace(f"count: {count}", "count: abc"), ["count", "abc"]),
        ("wrong type", "mass_fractions a number", good + "mass_fractions: 0.5\n", ["mass_fractions", "0.5"]),
        ("non-finite", "floor .nan", good.replace("floor: 0.004", "floor: .nan"), ["floor", ".nan"]),
        ("out of range", "count 0", good.replace(f"count: {count}", "count: 0"), ["count", "0"]),
        ("out of range", "seed 12", good + "seed: 12\n", ["seed", "12", "prime"]),
        ("out of range", "seed not a prime", good + "seed: 15485864\n", ["seed", "15485864", "prime"]),
        ("out of range", "mass_fraction_small 0", good + "mass_fraction_small: 0\n", ["mass_fraction_small", "0"]),
        ("out of range", "floor -0.01", good.replace("floor: 0.004", "floor: -0.01"), ["floor", "-0.01"]),
        ("fractional count", "count 800.7", good.replace(f"count: {count}", "count: 800.7"), ["count", "800.7"]),
        ("duplicate key", "count twice", good + "count: 900\n", ["count", str(count), "900", "given twice"]),
        ("unknown key", "cout", good.replace("count:", "cout:"), ["cout", "did you mean 'count'"]),
        ("number syntax", "count 0x10", good.replace(f"count: {count}", "count: 0x10"), ["count", "0x10"]),
    ]
    with stand_in_pour():
        for kind, name, text, names in bad:
            write(packing, text)
            check(kind, f"tfdem pack: {name}", "pack", [case], root, names, unchanged=[case])
        write(packing, good.replace(f"count: {count}", "count: 1e2"))
        check("number syntax", "tfdem pack: count 1e2 pours 100", "pack", [case], root, code=0,
              after=lambda o: None if "100 particles" in o.out else o.out)
        write(packing, good)
        check("stamp", "tfdem pack writes the bed and its stamp", "pack", [case], root, code=0,
              after=lambda o: None if os.path.isfile(os.path.join(case, "bed.data.tfdem-packed")) else "no stamp")
        data = os.path.join(case, "bed.data")
        text = open(data).read()
        record("stamp", "the packed bed is at rest, of its sizes' type, on the mid-plane",
               " 0.01 -0.02 " not in text and "\n1 1 0.001 " in text and "0 0.001 zlo zhi" in text)
        check("stamp", "tfdem pack --verify of a packed bed", "pack", ["--verify", case], root, code=0)
        for option, value in (("--ranks", "0"), ("--ranks", "-2"), ("--ranks", "1.5"), ("--ranks", "two")):
            check("option value", f"tfdem pack {option} {value}", "pack", [case, option, value], root,
                  [option, value], unchanged=[case])
        packed = snapshot(case)
        for fault, error, names in (("fsync", full_disk(), ["disk is full"]),
                                    ("replace", OSError(errno.EROFS, os.strerror(errno.EROFS)), ["read-only"])):
            with failing(os, fault, error):
                check("full disk" if fault == "fsync" else "read-only",
                      f"tfdem pack when os.{fault} fails keeps the previous bed and stamp", "pack", [case], root,
                      [case] + names, unchanged=[case])

        def interrupted(args, cwd, log_name, ranks=1, **_):
            fake_pour(args, cwd, log_name, ranks)
            raise KeyboardInterrupt

        with replaced(tfdem.run, "run", interrupted):
            check("interrupted", "Ctrl-C after LIGGGHTS wrote its raw file keeps the previous bed", "pack", [case],
                  root, code=130, unchanged=[case])
        record("full disk", "... the case is as it was, byte for byte, with no temporary file",
               snapshot(case) == packed)
        check("full disk", "... and a re-run works", "pack", [case], root, code=0)
    check_stamp(root, case, good)
    for name, argv, names in (("a case that does not exist", [os.path.join(root, "nowhere")], ["nowhere", "no such"]),
                              ("a folder that is not a case", [os.path.join(root, "inputs")], ["coupling.yaml"]),
                              ("--verify of a missing case", ["--verify", os.path.join(root, "nowhere")], ["nowhere"])):
        check("paths", f"tfdem pack: {name}", "pack", argv, root, names)


def check_stamp(root, case, packing_text):
    """--verify (and the generated Allrun) refuse a data file that is not tfdem pack's own."""
    data, stamp = os.path.join(case, "bed.data"), os.path.join(case, "bed.data.tfdem-packed")
    original = open(data).read()
    write(data, original + "# edited\n")
    check("stamp", "bed.data edited after packing", "pack", ["--verify", case], root,
          [data, "changed since tfdem pack", "run tfdem pack"])
    allrun = subprocess.run([os.path.join(case, "Allrun")], capture_output=True, text=True, timeout=60)
    record("stamp", "the generated Allrun refuses the edited bed before meshing", allrun.returncode == 2
           and "run tfdem pack" in allrun.stderr and not os.path.exists(os.path.join(case, "log.blockMesh")),
           allrun.stderr[-300:])
    write(data, original)
    write(os.path.join(case, "packing.yaml"), packing_text.replace("floor: 0.004", "floor: 0.005"))
    check("stamp", "packing.yaml changed after packing", "pack", ["--verify", case], root,
          ["packing.yaml", "0.005", "run tfdem pack"])
    write(os.path.join(case, "packing.yaml"), packing_text)
    kept = open(stamp).read()
    write(stamp, "{not json")
    check("stamp", "a stamp that is not JSON", "pack", ["--verify", case], root, [stamp, "run tfdem pack"])
    os.remove(stamp)
    check("stamp", "the stamp deleted", "pack", ["--verify", case], root, ["no stamp", "run tfdem pack"])
    write(stamp, kept)
    check("stamp", "stamp restored: verified", "pack", ["--verify", case], root, code=0)
    stats_root = os.path.join(root, "stats_of_edited_bed")
    write(data, original + "# edited\n")
    check("stamp", "tfdem stats refuses a template whose bed differs from its stamp", "stats",
          [case, "--end-time", "0.1", "--root", stats_root], root, ["changed since tfdem pack"], absent=[stats_root])
    levels = write(os.path.join(root, "stamp_levels.yaml"), LEVELS)
    check("stamp", "the fluidization driver refuses a bed that differs from its stamp", "fluidization",
          [levels, "--case", case], root, ["changed since tfdem pack"],
          absent=[os.path.join(case, "log.blockMesh")])
    write(data, original)
    os.remove(data)
    check("stamp", "the stamp without its bed", "pack", ["--verify", case], root, [data, "no packed bed"])
    write(data, original)


def check_stats(root):
    case = make_case(root, "stats_case")
    base = [case, "--end-time", "1"]
    options = [("--batch", "0"), ("--batch", "-1"), ("--batch", "nan"), ("--batch", "abc"), ("--band", "0"),
               ("--band", "inf"), ("--band", ".inf"), ("--end-time", "0"), ("--end-time", "nan"), ("--ranks", "0"),
               ("--ranks", "1.5"), ("--dp-height", "-0.1"), ("--dp-height", "0"), ("--gas", "halved")]
    for option, value in options:
        argv = base + [option, value] if option != "--end-time" else [case, option, value]
        check("option value", f"tfdem stats {option} {value}", "stats", argv, root, [option, value], unchanged=[case])
    for window, names in ((["1", "0.5"], ["--window", "1", "0.5"]), (["nan", "1"], ["--window", "nan"]),
                          (["0.2", "2"], ["--window", "2"])):
        check("option value", f"tfdem stats --window {' '.join(window)}", "stats", base + ["--window"] + window, root,
              names, unchanged=[case])
    check("option value", "tfdem stats --band longer than the window", "stats", base + ["--band", "0.9"], root,
          ["--band", "0.9", "window"], unchanged=[case])
    check("option value", "tfdem stats without --end-time", "stats", [case], root, ["--end-time"], unchanged=[case])
    check("paths", "tfdem stats of a case that does not exist", "stats",
          [os.path.join(root, "nowhere"), "--end-time", "1"], root, ["nowhere", "not a case"])
    a_file = write(os.path.join(root, "stats_root_file"), "mine\n")
    check("paths", "tfdem stats --root a file", "stats", base + ["--root", a_file], root, [a_file, "a file"],
          unchanged=[a_file])
    user = os.path.join(root, "stats_user_folder")
    write(os.path.join(user, "results.csv"), "t,x\n0,1\n")
    check("paths", "tfdem stats --root a folder of the user's (it would be replaced)", "stats",
          base + ["--root", user], root, [user, "not a run's"], unchanged=[user])
    check("paths", "tfdem stats of a case never packed", "stats", base + ["--root", os.path.join(root, "st")], root,
          ["tfdem pack"], absent=[os.path.join(root, "st")])


def check_pareto(root):
    folder = os.path.join(root, "pareto")
    make_case(folder, "case")
    sweep = os.path.join(folder, "sweep.yaml")

    def edit(old, new):
        assert old in SWEEP, old
        return SWEEP.replace(old, new, 1)

    bad = [
        ("malformed YAML", "an empty sweep", "", ["sweep.yaml", "empty"]),
        ("malformed YAML", "a sweep that is a list", "- reference\n", ["sweep.yaml", "expected a mapping"]),
        ("malformed YAML", "a sweep not YAML", edit("window: [0.05, 0.2]", "window: [0.05, 0.2"),
         ["sweep.yaml:", "not valid YAML"]),
        ("wrong type", "points as a list", edit("points:\n  reference: {gas_time_step: 2.5e-4}\n  default: {}",
                                                "points: [reference, default]"), ["points", "expected a mapping"]),
        ("wrong type", "window a number", edit("window: [0.05, 0.2]", "window: 0.2"), ["window", "0.2"]),
        ("wrong type", "refine in words", edit("default: {}", "default: {refine: 2x2}"),
         ["points.default.refine", "2x2"]),
        ("wrong type", "a template that is a number", edit("template: ./case", "template: 5"), ["template", "5"]),
        ("wrong type", "a coupling change that is a list", edit("default: {}", "default: {coupling: [a, b]}"),
         ["points.default.coupling", "expected a mapping"]),
        ("non-finite", "end_time .inf", edit("end_time: 0.2", "end_time: .inf"), ["end_time", ".inf"]),
        ("non-finite", "a DEM step .nan", edit("default: {}", "default: {dem_time_step: .nan}"),
         ["points.default.dem_time_step", ".nan"]),
        ("out of range", "a window past the end", edit("window: [0.05, 0.2]", "window: [0.05, 0.3]"),
         ["window[1]", "0.3"]),
        ("out of range", "a band longer than the window", edit("band: 0.01", "band: 0.5"), ["band", "0.5"]),
        ("out of range", "ranks 0", edit("default: {}", "default: {ranks: 0}"), ["points.default.ranks", "0"]),
        ("out of range", "batch 0", edit("batch: 0.05", "batch: 0"), ["batch", "0"]),
        ("fractional count", "ranks 1.5", edit("default: {}", "default: {ranks: 1.5}"),
         ["points.default.ranks", "1.5"]),
        ("fractional count", "refine [2, 1.5]", edit("default: {}", "default: {refine: [2, 1.5]}"),
         ["points.default.refine[1]", "1.5"]),
        ("duplicate key", "a point given twice", SWEEP + "  default: {ranks: 2}\n", ["default", "given twice"]),
        ("unknown key", "end_tme", edit("end_time:", "end_tme:"), ["end_tme", "did you mean 'end_time'"]),
        ("unknown key", "a point's dem_timestep", edit("default: {}", "default: {dem_timestep: 1e-5}"),
         ["points.default.dem_timestep", "did you mean 'dem_time_step'"]),
        ("unknown key", "a reference that is no point", edit("reference: reference", "reference: refrence"),
         ["reference", "refrence", "did you mean 'reference'"]),
        ("unknown key", "a gas layout misspelt", edit("default: {}", "default: {gas: wole}"),
         ["points.default.gas", "wole", "did you mean 'whole'"]),
        ("empty name", "a point named ../x", edit("default: {}", "../x: {}"), ["points.../x", "plain folder name"]),
        ("empty name", "an empty template", edit("template: ./case", "template: ''"), ["template"]),
        ("paths", "a template that is not a case", edit("template: ./case", "template: ./nowhere"),
         ["template './nowhere'", "is not a case"]),
    ]
    for kind, name, text, names in bad:
        write(sweep, text)
        check(kind, f"pareto.py: {name}", "pareto", ["run", sweep], folder, names, unchanged=[folder])
    write(sweep, SWEEP)
    for option, value in (("--jobs", "0"), ("--jobs", "abc"), ("--end-time", "0"), ("--end-time", "-1"),
                          ("--cost", "money")):
        check("option value", f"pareto.py run {option} {value}", "pareto", ["run", sweep, option, value], folder,
              [option, value], unchanged=[folder])
    check("option value", "pareto.py --points of no such point", "pareto", ["run", sweep, "--points", "refrence"],
          folder, ["refrence", "did you mean 'reference'"], unchanged=[folder])
    check("paths", "pareto.py: a sweep file that does not exist", "pareto",
          ["run", os.path.join(folder, "nowhere.yaml")], folder, ["nowhere.yaml", "cannot read"], unchanged=[folder])
    check("paths", "pareto.py: a sweep that is a folder", "pareto", ["run", folder], folder, [folder, "cannot read"],
          unchanged=[folder])
    a_file = write(os.path.join(root, "pareto_root_file"), "x\n")
    check("paths", "pareto.py --root a file", "pareto", ["run", sweep, "--root", a_file], folder, [a_file],
          unchanged=[a_file, folder])
    check("paths", "pareto.py report before any run", "pareto", ["report", sweep], folder,
          ["reference", "has not finished"])


def check_fluidization(root):
    case = make_case(root, "curve_case")
    levels = os.path.join(root, "levels.yaml")
    bad = [
        ("malformed YAML", "empty levels", "", ["levels.yaml", "empty"]),
        ("malformed YAML", "levels not YAML", "levels: [[0.4, 0.2]\n", ["levels.yaml:", "not valid YAML"]),
        ("malformed YAML", "a list at the top", "- [0.4, 0.2]\n", ["levels.yaml", "expected a mapping"]),
        ("wrong type", "levels as a mapping", "levels: {a: 1}\nanalysis: {fluidized: 1.8}\n",
         ["levels", "expected a list"]),
        ("wrong type", "a level of one number", LEVELS.replace("[1.8, 0.5]", "[1.8]"), ["levels[1]", "expected"]),
        ("wrong type", "analysis as a list", LEVELS.replace("analysis: {fluidized: 1.8}", "analysis: [1.8]"),
         ["analysis", "expected a mapping"]),
        ("non-finite", "a velocity .nan", LEVELS.replace("[1.8, 0.5]", "[.nan, 0.5]"), ["levels[1]", ".nan"]),
        ("out of range", "a hold time of 0", LEVELS.replace("[1.8, 0.5]", "[1.8, 0]"), ["levels[1] hold time", "0"]),
        ("out of range", "fluidized above every level", LEVELS.replace("fluidized: 1.8", "fluidized: 3"),
         ["analysis.fluidized", "3"]),
        ("duplicate key", "analysis twice", LEVELS + "analysis: {fluidized: 0.4}\n", ["analysis", "given twice"]),
        ("unknown key", "fluidised", LEVELS.replace("fluidized:", "fluidised:"),
         ["analysis.fluidised", "did you mean 'fluidized'"]),
        ("unknown key", "level", LEVELS.replace("levels:", "level:"), ["level", "did you mean 'levels'"]),
    ]
    for kind, name, text, names in bad:
        write(levels, text)
        check(kind, f"fluidization.py: {name}", "fluidization", [levels, "--case", case], root, names,
              unchanged=[case])
    check("paths", "fluidization.py --case that does not exist", "fluidization",
          [levels, "--case", os.path.join(root, "nowhere")], root, ["nowhere", "not a case"])
    check("paths", "fluidization.py: levels that do not exist", "fluidization",
          [os.path.join(root, "no_levels.yaml"), "--case", case], root, ["no_levels.yaml", "cannot read"],
          unchanged=[case])


def check_run_module(root):
    case = make_case(root, "run_case")
    for name, argv, names in (("decompose 0 ranks", ["decompose", case, "0"], ["RANKS", "'0'"]),
                              ("decompose abc ranks", ["decompose", case, "abc"], ["RANKS", "'abc'"]),
                              ("no arguments", [], ["usage"]),
                              ("an unknown action", ["split", case], ["split", "usage"]),
                              ("a case that does not exist", ["decompose", os.path.join(root, "nowhere"), "2"],
                               ["nowhere", "not a case"])):
        check("option value" if "ranks" in name or "action" in name or "arguments" in name else "paths",
              f"python3 -m tfdem.run {name}", "run", argv, root, names, unchanged=[case])


def check_internal_errors(root):
    """An unexpected exception: one line naming the command, what it was doing and the file,
    exit 1; --debug and TFDEM_DEBUG=1 show the traceback."""
    source = write(os.path.join(root, "internal", "bed.yaml"), BED)
    dest = os.path.join(root, "internal", "case")

    def one_line(outcome):
        lines = outcome.err.strip().splitlines()
        wanted = ["tfdem new: internal error while deriving the case from", source, "ZeroDivisionError", "--debug"]
        return None if len(lines) == 1 and all(w in lines[0] for w in wanted) else "not the one line expected"

    def boom(*args, **kwargs):
        raise ZeroDivisionError("float division by zero")

    with replaced(tfdem.newcase, "derive", boom):
        check("internal error", "an unexpected exception in tfdem new", "new", [dest, "--from", source], root,
              code=1, absent=[dest], after=one_line)
        outcome = invoke("new", [dest, "--from", source, "--debug"], root)
        record("internal error", "--debug shows the traceback", isinstance(outcome.exception, ZeroDivisionError))
        os.environ[tfdem.frontdoor.DEBUG_ENV] = "1"
        try:
            outcome = invoke("new", [dest, "--from", source], root)
        finally:
            del os.environ[tfdem.frontdoor.DEBUG_ENV]
        record("internal error", "TFDEM_DEBUG=1 shows the traceback", isinstance(outcome.exception, ZeroDivisionError))
    with replaced(tfdem.bedstats, "run_batch", boom):
        case = make_case(root, "internal_stats")
        check("internal error", "an unexpected exception in tfdem stats", "stats", [case, "--end-time", "1"], root,
              ["tfdem stats: internal error", "ZeroDivisionError", "--debug"], code=1)


def check_atomic_writes(root):
    """write_text_atomic, save_figure_atomic and a batch's status file on a full disk: the
    previous file is kept, and no temporary file is left."""
    from tfdem.frontdoor import save_figure_atomic, write_text_atomic
    folder = os.path.join(root, "atomic")
    target = write(os.path.join(folder, "report.json"), '{"old": 1}\n')
    with failing(os, "fsync", full_disk()):
        try:
            write_text_atomic(target, '{"new": 2}\n')
            raised = False
        except OSError as e:
            raised = e.errno == errno.ENOSPC
    record("full disk", "write_text_atomic on a full disk keeps the previous file",
           raised and snapshot(folder) == {"report.json": b'{"old": 1}\n'}, str(snapshot(folder).keys()))
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    figure_path = write(os.path.join(folder, "plot.png"), b"old png", "wb")
    fig = plt.figure()
    with failing(os, "replace", OSError(errno.EROFS, os.strerror(errno.EROFS))):
        try:
            save_figure_atomic(fig, figure_path)
            raised = False
        except OSError as e:
            raised = e.errno == errno.EROFS
    plt.close(fig)
    record("read-only", "save_figure_atomic on a read-only disk keeps the previous figure",
           raised and open(figure_path, "rb").read() == b"old png" and sorted(os.listdir(folder)) ==
           ["plot.png", "report.json"], str(os.listdir(folder)))
    run = tfdem.batch.CaseRun("r", os.path.join(folder, "run"))
    os.makedirs(run.case.path)
    run.set_status(state="running", end_time=1.0)
    with failing(os, "fsync", full_disk()):
        try:
            run.set_status(state="done")
        except OSError:
            pass
    record("full disk", "a batch's status file on a full disk keeps the previous status",
           run.status() == {"state": "running", "end_time": 1.0} and os.listdir(run.case.path) ==
           [tfdem.batch.STATUS], str(os.listdir(run.case.path)))
    record("option value", "run_batch refuses 0 jobs instead of waiting for ever",
           _raises(lambda: tfdem.batch.run_batch([], 1.0, 0), tfdem.batch.BatchError))


def _raises(action, kind):
    try:
        action()
    except kind:
        return True
    return False


def main():
    with tempfile.TemporaryDirectory() as root:
        root = os.path.realpath(root)
        check_bed_refusals(root)
        check_number_syntax(root)
        check_names_and_folders(root)
        check_failing_disk_on_new(root)
        check_pack(root)
        check_stats(root)
        check_pareto(root)
        check_fluidization(root)
        check_run_module(root)
        check_internal_errors(root)
        check_atomic_writes(root)
    total = sum(len(v) for v in results.values())
    failed = [(k, n, d) for k, v in results.items() for n, ok, d in v if not ok]
    print(f"\n{total} cases, {len(failed)} failed; per class (passed/cases):")
    for kind, cases in sorted(results.items()):
        print(f"  {kind:<18} {sum(ok for _, ok, _ in cases)}/{len(cases)}")
    if failed:
        print("failed:\n" + "\n".join(f"  [{k}] {n}: {d}" for k, n, d in failed))
        sys.exit(1)


if __name__ == "__main__":
    main()
