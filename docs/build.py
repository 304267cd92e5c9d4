"""The docs site: docs/src/ (Markdown; the reference pages written by docs/reference.py) built by
MkDocs (Debian's mkdocs, installed by scripts/setup.sh) into build/docs/, in strict mode: a
broken link, a page missing from the navigation or a missing image stops it.

    python3 docs/build.py [--out DIR]      (./tfdem docs)

Prints the path of the built home page. Exit 1 when MkDocs refuses the site.
"""
import argparse
import os
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
DEFAULT_OUT = os.path.join(HERE, "..", "build", "docs")


def build(out):
    done = subprocess.run(["mkdocs", "build", "--strict", "--clean", "-f", os.path.join(HERE, "mkdocs.yml"),
                           "-d", os.path.abspath(out)], capture_output=True, text=True)
    return done.returncode, done.stdout + done.stderr


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--out", default=DEFAULT_OUT, help="the site's folder (default build/docs)")
    args = parser.parse_args(argv)
    code, output = build(args.out)
    if code != 0:
        print(output, file=sys.stderr)
        print("docs/build.py: MkDocs refused the site (above): fix the page or link it names", file=sys.stderr)
        return 1
    print(os.path.join(os.path.abspath(args.out), "index.html"))
    return 0


if __name__ == "__main__":
    sys.exit(main())
