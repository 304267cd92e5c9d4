"""What every Python command of the front door shares: how it ends, and how it writes.

run_command(): a known refusal prints `tfdem <cmd>: <message>` and exits 2; Ctrl-C exits 130;
a file-system failure (a full disk, a read-only or forbidden folder) names the path and the
fix and exits 2; anything else prints one line naming what the command was doing and on which
file, and exits 1. `--debug` (or TFDEM_DEBUG=1) shows the traceback instead.

write_text_atomic() and friends: a file is written whole or not at all (a temporary file in the
same folder, fsync, rename), so a full disk or a kill leaves the previous file.
"""
import contextlib
import errno
import os
import sys
import tempfile
import traceback

from tfdem.errors import Reported

DEBUG_ENV = "TFDEM_DEBUG"

FIXES = {
    errno.ENOSPC: "the disk is full: free space on it (or use a folder on another disk) and run again",
    errno.EDQUOT: "the disk quota is used up: free space (or use a folder on another disk) and run again",
    errno.EROFS: "the file system is read-only: use a folder on a writable disk",
    errno.EACCES: "permission denied: use a folder you may write to, or change its permissions",
    errno.EPERM: "not permitted: use a folder you may write to, or change its permissions",
    errno.ENOENT: "no such file or folder: check the path",
    errno.ENOTDIR: "a part of the path is a file, not a folder: check the path",
    errno.EISDIR: "it is a folder where a file is expected: check the path",
    errno.EEXIST: "it exists already: give another name, or remove it first",
    errno.ENOTEMPTY: "the folder is not empty: give another name, or remove it first",
}


@contextlib.contextmanager
def doing(action, path=""):
    """Name what the command is doing, and on which file, for a failure inside the block (the
    innermost block names it)."""
    try:
        yield
    except BaseException as e:
        if not hasattr(e, "tfdem_doing"):
            try:
                e.tfdem_doing = (action, str(path))
            except AttributeError:
                pass
        raise


def debugging(argv):
    return "--debug" in argv or os.environ.get(DEBUG_ENV, "") not in ("", "0")


def add_debug_option(parser):
    parser.add_argument("--debug", action="store_true",
                        help=f"show the traceback of an unexpected failure (also {DEBUG_ENV}=1)")


def file_system_message(e):
    """An OSError as 'what it was doing, on which file: the file the system names: what
    happened and the fix'."""
    action, path = getattr(e, "tfdem_doing", ("", ""))
    named = [p for p in (path, e.filename) if p]
    where = ": ".join(dict.fromkeys(str(p) for p in named)) or "(unnamed file)"
    fix = FIXES.get(e.errno, e.strerror or str(e))
    code = errno.errorcode.get(e.errno, e.errno)
    return f"{action + ' ' if action else ''}{where}: {fix} [{code}]"


def run_command(name, body, argv=None, known=()):
    """body(argv) as the command `name` (e.g. 'tfdem new'); returns its exit code. `known`:
    more exception classes to report by their message alone (exit 2)."""
    argv = sys.argv[1:] if argv is None else list(argv)
    debug = debugging(argv)
    try:
        return body(argv) or 0
    except SystemExit as e:  # argparse's refusal (it printed it) or --help
        return e.code if isinstance(e.code, int) else (0 if e.code is None else _print(name, e.code, 2))
    except KeyboardInterrupt:
        if debug:
            raise
        print(f"{name}: stopped", file=sys.stderr)
        return 130
    except (Reported,) + tuple(known) as e:
        if debug:
            traceback.print_exc()
        return _print(name, str(e), 2)
    except OSError as e:
        if debug:
            raise
        return _print(name, file_system_message(e), 2)
    except Exception as e:
        if debug:
            raise
        action, path = getattr(e, "tfdem_doing", (f"running {name}", " ".join(argv)))
        text = " ".join(str(e).split())
        return _print(name, f"internal error while {action} {path}: {type(e).__name__}: {text} "
                            "(run with --debug for the traceback)", 1)


def _print(name, message, code):
    print(f"{name}: {message}", file=sys.stderr)
    return code


# Writing whole files ----------------------------------------------------------------------------
def default_mode(executable=False):
    """The permissions open() would give a new file (0o666, or 0o777, less the umask)."""
    mask = os.umask(0o022)
    os.umask(mask)
    return (0o777 if executable else 0o666) & ~mask


def _sync_folder(folder):
    try:
        fd = os.open(folder or ".", os.O_RDONLY)
    except OSError:
        return
    try:
        os.fsync(fd)
    except OSError:
        pass
    finally:
        os.close(fd)


def write_bytes_atomic(path, data, mode=None):
    """Write `data` to `path` whole or not at all: a temporary file beside it, flushed and
    synced, then renamed over it; the temporary file is removed on any failure. A symbolic link
    is written through (its target replaced, as open() would). `mode`: the file's permissions
    (default: the previous file's, else what open() would give)."""
    path = os.path.realpath(path)
    folder = os.path.dirname(path)
    if mode is None:
        try:
            mode = os.stat(path).st_mode & 0o7777
        except OSError:
            mode = default_mode()
    try:
        fd, temp = tempfile.mkstemp(dir=folder, prefix=f".{os.path.basename(path)}.", suffix=".tfdem-tmp")
    except OSError as e:  # name the file meant, not the temporary one
        raise OSError(e.errno, e.strerror, path) from None
    try:
        with os.fdopen(fd, "wb") as f:
            f.write(data)
            f.flush()
            os.fsync(f.fileno())
        os.chmod(temp, mode)
        os.replace(temp, path)
    except BaseException:
        with contextlib.suppress(OSError):
            os.remove(temp)
        raise
    _sync_folder(folder)


def write_text_atomic(path, text, mode=None):
    """write_bytes_atomic() of text in UTF-8."""
    write_bytes_atomic(path, text.encode("utf-8"), mode)


def write_file_synced(path, data, mode=None):
    """Write a new file and sync it (a file inside a folder that is itself put in place by a
    rename, tfdem new's case: the rename is what makes it whole)."""
    with open(path, "wb") as f:
        f.write(data.encode("utf-8") if isinstance(data, str) else data)
        f.flush()
        os.fsync(f.fileno())
    os.chmod(path, default_mode() if mode is None else mode)


def replace_atomic(temp, path):
    """Rename a finished temporary file over `path` (synced first)."""
    with open(temp, "rb+") as f:
        os.fsync(f.fileno())
    os.replace(temp, path)
    _sync_folder(os.path.dirname(os.path.abspath(path)))


def save_figure_atomic(figure, path, **options):
    """matplotlib's savefig to a temporary file beside `path`, then renamed over it."""
    folder = os.path.dirname(os.path.abspath(path))
    base, extension = os.path.splitext(os.path.basename(path))
    fd, temp = tempfile.mkstemp(dir=folder, prefix=f".{base}.", suffix=f".tfdem-tmp{extension}")
    os.close(fd)
    try:
        figure.savefig(temp, format=extension.lstrip(".") or None, **options)
        os.chmod(temp, default_mode())
        replace_atomic(temp, path)
    except BaseException:
        with contextlib.suppress(OSError):
            os.remove(temp)
        raise
