"""Time series the bed tutorials' plot scripts share: OpenFOAM probes and the mean particle
height that the DEM scripts write (run from a case directory)."""
import glob
import os


def pressure_probes(name="pressure"):
    """(t, [p at each probe]) rows of postProcessing/<name>/*/p, restarts joined in time order."""
    rows = []
    paths = glob.glob(os.path.join("postProcessing", name, "*", "p"))
    for path in sorted(paths, key=lambda f: float(f.split(os.sep)[-2])):
        for line in open(path):
            if line.startswith("#") or not line.strip():
                continue
            values = [float(v) for v in line.split()]
            if rows and values[0] <= rows[-1][0]:
                continue
            rows.append((values[0], values[1:]))
    return rows


def mean_height(path="mean_height.txt"):
    """(t, mean particle height) rows of the DEM script's `fix print` file."""
    return [tuple(map(float, line.split())) for line in open(path) if not line.startswith("#")]


def value_at(series, t):
    """Last sample of `series` at or before t."""
    best = series[0][1]
    for ts, v in series:
        if ts > t + 1e-12:
            break
        best = v
    return best
