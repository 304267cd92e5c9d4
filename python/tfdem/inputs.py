"""Every input of the Python commands read and checked one way: YAML files with the solver's
rules (coupling/src/config.cpp, yaml-cpp) and command-line values, each refusal naming the
file, the key, the value and the fix.

YAML as the solver reads it:
  - numbers in decimal with an optional exponent: 1e-3 and 1.0e4 are numbers (YAML 1.1, which
    PyYAML follows, reads them as text); 0x10, 1_000 and 1:30 are text, which no number key
    takes; so is 017 (octal to YAML 1.1 and to the solver's whole numbers, seventeen to its
    decimals: refused rather than guessed);
  - .inf and .nan are read, and then refused by every number key (the solver refuses them too);
  - a key given twice in one mapping is refused (the solver's parser refuses it; PyYAML would
    keep the last silently).

Checked values (Source): number() finite and within a range, count() a whole number (800.7,
"abc" and true are refused, never truncated), mapping() the keys a section takes (an unknown
key with the nearest known name), sequence() a list of a length, choice() one of some names,
boolean() true or false.
"""
import argparse
import difflib
import math
import re

import yaml

from tfdem.errors import Reported


class InputError(Reported):
    """An input is wrong; the message is 'file: key: value: what is expected / the fix'."""


class CaseError(InputError):
    """A case file lacks what is asked of it; the message names the file and the entry."""


def read_text(path, error=CaseError):
    """A file's text; `error` naming the file and the reason when it cannot be read."""
    try:
        with open(path) as f:
            return f.read()
    except OSError as e:
        raise error(f"{path}: cannot read ({e.strerror})") from None


# Scalars the solver reads as numbers (yaml-cpp's as<double>: a decimal with an optional
# exponent; as<long>: decimal digits), without a leading zero (017: octal or decimal?)
INTEGER = re.compile(r"^[-+]?(?:0|[1-9][0-9]*)$")
FLOAT = re.compile(r"^[-+]?(?:(?:0|[1-9][0-9]*)(?:\.[0-9]*)?|\.[0-9]+)(?:[eE][-+]?[0-9]+)?$")
LEADING_ZERO = re.compile(r"^[-+]?0[0-9]")
NON_FINITE = re.compile(r"^(?:[-+]?\.(?:inf|Inf|INF)|\.(?:nan|NaN|NAN))$")
MERGE_TAG = "tag:yaml.org,2002:merge"


class SolverLoader(yaml.SafeLoader):
    """SafeLoader with the solver's numbers and no duplicate keys."""

    def construct_mapping(self, node, deep=False):
        if isinstance(node, yaml.MappingNode):
            self._refuse_duplicates(node)
        return super().construct_mapping(node, deep)

    def _refuse_duplicates(self, node):
        seen = {}
        for key_node, value_node in node.value:
            if key_node.tag == MERGE_TAG:
                continue
            key = self.construct_object(key_node, deep=True)
            try:
                hash(key)
            except TypeError:
                raise yaml.constructor.ConstructorError(
                    None, None, "a key that is a list or a mapping; keys are names", key_node.start_mark) from None
            if key in seen:
                first_line, first_value = seen[key]
                raise DuplicateKeyError(key, first_line, first_value, key_node.start_mark.line + 1,
                                        _node_text(value_node), key_node.start_mark)
            seen[key] = (key_node.start_mark.line + 1, _node_text(value_node))


class DuplicateKeyError(yaml.YAMLError):
    """A mapping gives one key twice."""

    def __init__(self, key, first_line, first_value, line, value, mark):
        super().__init__()
        self.key, self.first_line, self.first_value, self.line, self.value = key, first_line, first_value, line, value
        self.problem_mark = mark


def _node_text(node):
    return node.value if isinstance(node, yaml.ScalarNode) else ("a list" if isinstance(node, yaml.SequenceNode)
                                                                 else "a mapping")


def _construct_integer(loader, node):
    text = loader.construct_scalar(node)
    if not INTEGER.match(text):
        raise yaml.constructor.ConstructorError(None, None, f"'{text}' is not a whole number in decimal",
                                                node.start_mark)
    return int(text, 10)


def _construct_float(loader, node):
    text = loader.construct_scalar(node)
    if NON_FINITE.match(text):
        return float(text.lower().replace(".", ""))
    if not (FLOAT.match(text) or INTEGER.match(text)):
        raise yaml.constructor.ConstructorError(None, None, f"'{text}' is not a number", node.start_mark)
    return float(text)


def _solver_resolvers():
    """SafeLoader's implicit resolvers without YAML 1.1's int and float, plus the solver's."""
    resolvers = {}
    for first, entries in yaml.SafeLoader.yaml_implicit_resolvers.items():
        kept = [(tag, pattern) for tag, pattern in entries
                if tag not in ("tag:yaml.org,2002:int", "tag:yaml.org,2002:float")]
        if kept:
            resolvers[first] = kept
    for first in "-+0123456789.":
        resolvers.setdefault(first, [])
        resolvers[first] = [("tag:yaml.org,2002:int", INTEGER), ("tag:yaml.org,2002:float", FLOAT),
                            ("tag:yaml.org,2002:float", NON_FINITE)] + resolvers[first]
    return resolvers


SolverLoader.yaml_implicit_resolvers = _solver_resolvers()
SolverLoader.add_constructor("tag:yaml.org,2002:int", _construct_integer)
SolverLoader.add_constructor("tag:yaml.org,2002:float", _construct_float)


def parse_yaml(text, path="<text>", error=InputError):
    """YAML text read as the solver reads it (module doc); `error` (an InputError class) when
    it is not valid YAML or gives a key twice."""
    try:
        return yaml.load(text, Loader=SolverLoader)
    except DuplicateKeyError as e:
        raise error(f"{path}:{e.line}: {e.key}: given twice ({e.first_value} on line {e.first_line}, {e.value} on "
                    f"line {e.line}): keep one (the solver refuses a key given twice)") from None
    except yaml.MarkedYAMLError as e:
        mark = e.problem_mark or e.context_mark
        where = f"{path}:{mark.line + 1}:{mark.column + 1}" if mark else path
        problem = " ".join(p for p in (e.context, e.problem) if p)
        raise error(f"{where}: not valid YAML ({problem}): fix the file there") from None
    except yaml.YAMLError as e:
        raise error(f"{path}: not valid YAML ({' '.join(str(e).split())}): fix the file") from None


def load_yaml(path, error=InputError):
    """A YAML file read as the solver reads it (None when it is empty); `error` when it cannot
    be read or is not valid YAML."""
    try:
        with open(path, "rb") as f:
            text = f.read()
    except OSError as e:
        raise error(f"{path}: cannot read it ({e.strerror}): give the path of a readable file") from None
    return parse_yaml(text, path, error)


def shown(value):
    """A value as a message names it: numbers as YAML writes them, text quoted."""
    if value is None:
        return "(empty)"
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, float):
        if math.isnan(value):
            return ".nan"
        if math.isinf(value):
            return ".inf" if value > 0 else "-.inf"
        return repr(value)
    if isinstance(value, int):
        return str(value)
    if isinstance(value, str):
        return repr(value)
    if isinstance(value, list):
        return "a list" if len(repr(value)) > 60 else repr(value)
    if isinstance(value, dict):
        return "a mapping" if len(repr(value)) > 60 else repr(value)
    return str(value)


def suggestion(name, valid):
    """' (did you mean 'x'?)' for the nearest of `valid`, else the list of them."""
    near = difflib.get_close_matches(str(name), [str(v) for v in valid], n=1)
    return f" (did you mean '{near[0]}'?)" if near else f"; valid: {', '.join(str(v) for v in valid)}"


def outside(low, high, low_open, high_open):
    """What a value outside [low, high] (or open at either end) is: 'outside (0, 1]',
    'not above 0', 'below 0', ..."""
    if math.isinf(high) and not math.isinf(low):
        return f"not above {low:g}" if low_open else f"below {low:g}"
    if math.isinf(low) and not math.isinf(high):
        return f"not below {high:g}" if high_open else f"above {high:g}"
    return f"outside {'(' if low_open else '['}{low:g}, {high:g}{')' if high_open else ']'}"


def is_number(value):
    return isinstance(value, (int, float)) and not isinstance(value, bool)


class Source:
    """The values of one input (a file, or the command line): each check returns the value or
    raises `error` naming the source, the key, the value and the fix."""

    def __init__(self, path, error=InputError):
        self.path, self.error = path, error

    def fail(self, key, message):
        raise self.error(f"{self.path}: {key}: {message}" if key else f"{self.path}: {message}")

    def not_a_number(self, key, value, what):
        zero = " (a leading zero: octal or decimal? write it without the zero)"
        hint = zero if isinstance(value, str) and LEADING_ZERO.match(value) else ""
        self.fail(key, f"{shown(value)} is not a number{hint}: give {what}")

    def number(self, key, value, low=-math.inf, high=math.inf, low_open=False, high_open=False, what="a number"):
        """A finite number within [low, high] (or open at either end), as a float."""
        if not is_number(value):
            self.not_a_number(key, value, what)
        if not math.isfinite(value):
            self.fail(key, f"{shown(value)} is not a finite number: give {what}")
        inside = (value > low if low_open else value >= low) and (value < high if high_open else value <= high)
        if not inside:
            self.fail(key, f"{shown(value)} is {outside(low, high, low_open, high_open)}: give {what}")
        return float(value)

    def count(self, key, value, low=1, high=math.inf, what="a whole number"):
        """A whole number within [low, high], as an int (1e3 is 1000; 800.7 is refused)."""
        if not is_number(value):
            self.not_a_number(key, value, what)
        if not math.isfinite(value):
            self.fail(key, f"{shown(value)} is not a finite number: give {what}")
        if value != math.floor(value):
            self.fail(key, f"{shown(value)} is not a whole number: give {what}, e.g. {math.floor(value)} or "
                      f"{math.ceil(value)}")
        if not low <= value <= high:
            self.fail(key, f"{shown(value)} is {outside(low, high, False, False)}: give {what}")
        return int(value)

    def mapping(self, key, value, keys=None, what=None):
        """A mapping whose keys are all among `keys` (when given); an unknown key is named with
        the nearest known one."""
        if not isinstance(value, dict):
            expected = what or ("a mapping of " + ", ".join(keys) if keys else "a mapping of keys to values")
            if value is None and not key:
                self.fail("", f"the file is empty: expected {expected}")
            self.fail(key or "the file", f"expected {expected}, got {shown(value)}")
        for name in value:
            if not isinstance(name, str):
                valid = f"; valid keys: {', '.join(keys)}" if keys else ""
                self.fail(key or "the file", f"{shown(name)}: a key that is not a name{valid}")
            if keys is not None and name not in keys:
                self.fail(f"{key}.{name}" if key else name, f"unknown key{suggestion(name, list(keys))}")
        return value

    def sequence(self, key, value, shortest=0, longest=math.inf, what="a list"):
        """A list of shortest to longest items."""
        if not isinstance(value, list):
            self.fail(key, f"expected {what}, got {shown(value)}")
        if not shortest <= len(value) <= longest:
            self.fail(key, f"expected {what}, got {len(value)} item(s)")
        return value

    def boolean(self, key, value, what="true or false"):
        """true or false (YAML's booleans; 1, 0, 'yes' as text and the like are refused)."""
        if not isinstance(value, bool):
            self.fail(key, f"{shown(value)} is not true or false: give {what}")
        return value

    def choice(self, key, value, choices):
        """One of `choices` (names); another is named with the nearest of them."""
        if not isinstance(value, str) or value not in choices:
            self.fail(key, f"unknown value {shown(value)}{suggestion(value, list(choices))}")
        return value

    def text(self, key, value, what="a name"):
        """A non-empty name (text)."""
        if not isinstance(value, str) or not value.strip():
            self.fail(key, f"expected {what}, got {shown(value)}")
        return value

    def required(self, key, mapping, name, what):
        """mapping[name], which must be there."""
        if name not in mapping:
            self.fail(f"{key}.{name}" if key else name, f"missing: give {what}")
        return mapping[name]


# Command-line values: argparse types whose refusals name the value and the fix ------------------
NON_FINITE_WORDS = ("inf", "infinity", "nan", ".inf", ".nan")


def _parse_number(text, what):
    """A command-line number in the solver's syntax; refused when not finite."""
    word = text.strip().lower().lstrip("+-")
    if word in NON_FINITE_WORDS:
        raise argparse.ArgumentTypeError(f"{text!r} is not a finite number: give {what}")
    if not FLOAT.match(text.strip()):
        raise argparse.ArgumentTypeError(f"{text!r} is not a number: give {what}")
    return float(text)


def positive_number(what):
    """argparse type: a finite number above 0 (`what` says what it is, with its unit)."""
    def parse(text):
        value = _parse_number(text, what)
        if not value > 0:
            raise argparse.ArgumentTypeError(f"{text!r} is not above 0: give {what}")
        return value
    return parse


def non_negative_number(what):
    """argparse type: a finite number of 0 or more."""
    def parse(text):
        value = _parse_number(text, what)
        if value < 0:
            raise argparse.ArgumentTypeError(f"{text!r} is below 0: give {what}")
        return value
    return parse


def positive_count(what):
    """argparse type: a whole number of 1 or more."""
    def parse(text):
        if not INTEGER.match(text.strip()) or int(text) < 1:
            raise argparse.ArgumentTypeError(f"{text!r} is not a whole number of 1 or more: give {what}")
        return int(text)
    return parse
