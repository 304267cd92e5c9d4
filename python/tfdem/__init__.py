"""TFDEM's Python case package: what tutorials, tests, studies and benchmarks share.

- ``tfdem.case``: a case read from its own files (coupling.yaml, controlDict,
  transportProperties, blockMeshDict, the DEM script and its data file), copied and edited;
- ``tfdem.outputs``: its outputs (probes, particle statistics, fix-print files, dumps,
  particle VTK files, fields, solver logs), joined over restarts;
- ``tfdem.run``: running the programs (environment, MPI, decomposition, progress);
- ``tfdem.stats``: time averages with batch-means errors, spectra.

Put ``<repository>/python`` on PYTHONPATH (``scripts/tfdem-env.sh`` and ctest do).
"""
import os

SOURCE_DIR = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))
TUTORIALS = os.path.join(SOURCE_DIR, "tutorials")
BUILD_DIR = os.environ.get("TFDEM_BUILD", os.path.join(SOURCE_DIR, "build"))
