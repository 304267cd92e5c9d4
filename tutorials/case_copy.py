"""Copying a tutorial case to another directory, as the tutorials' run helpers and the tests
that reuse them do."""
import os
import shutil


def copy_case(source, dest, names):
    """Fresh dest with source's 0/, constant/ and system/ (without a mesh) and the named files."""
    shutil.rmtree(dest, ignore_errors=True)
    os.makedirs(dest)
    for sub in ("0", "constant", "system"):
        shutil.copytree(os.path.join(source, sub), os.path.join(dest, sub),
                        ignore=shutil.ignore_patterns("polyMesh"))
    for name in names:
        shutil.copy(os.path.join(source, name), dest)
