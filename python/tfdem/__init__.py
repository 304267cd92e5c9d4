"""TFDEM's Python case package: what tutorials, tests, studies and benchmarks share.

- ``tfdem.case``: a case read from its own files (coupling.yaml, controlDict and its function
  objects, transportProperties, g, blockMeshDict, fvOptions, field patch values, the DEM
  script and its data file), copied and edited;
- ``tfdem.outputs``: its outputs (probes, particle statistics, fix-print files, dumps,
  particle VTK files, fields, solver logs), joined over restarts;
- ``tfdem.run``: running the programs (environment, MPI, decomposition, progress);
- ``tfdem.stats``: time averages with batch-means errors, spectra, fits;
- ``tfdem.physics``: reference physics with its seed equations (drag law, Ergun, U_mf, the
  settling sphere's ODE);
- ``tfdem.summary``: a run's own outputs as summary.csv and summary.png (``tfdem summary``);
- ``tfdem.fixed_bed``, ``tfdem.fluidization``: the fixed-bed (Ergun) and fluidization-curve
  set-ups of the tutorials, for any case built like them (a fluidization curve from a YAML
  file of levels).

Put ``<repository>/python`` on PYTHONPATH (``scripts/tfdem-env.sh`` and ctest do).
"""
import os

SOURCE_DIR = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))
TUTORIALS = os.path.join(SOURCE_DIR, "tutorials")  # cases a user copies
STUDIES = os.path.join(SOURCE_DIR, "studies")  # reproductions, each with its runner, report and results
BUILD_DIR = os.environ.get("TFDEM_BUILD", os.path.join(SOURCE_DIR, "build"))
