"""A single bubble in a flat bed (seed 001 §5, Fig. 8-9; tutorials/single_bubble): the bubble
found in a gas-fraction map, its size, shape and position, and the mixing of a coloured layer.

The bubble is a 4-connected region of cells with gas fraction above a threshold (0.8, as the
issue defines it) that does not reach the top row (the freeboard) and is the largest such
region; while the jet blows it is the region standing on the jet. Its equivalent diameter is
that of the circle of its area, D = sqrt(4 A / pi); its aspect ratio is its height over its
width (cell extents); its position is its area centroid.
"""
import math
import os
from collections import deque

import numpy

from tfdem import outputs
from tfdem.frontdoor import write_text_atomic

BUBBLE_GAS_FRACTION = 0.8


def cell_rows_columns(case_path, grid, time_name="0"):
    """(row, column) of each cell of a case on its uniform grid, from the cell centres
    OpenFOAM's `postProcess -func writeCellCentres` wrote to <time>/C (blocks order cells
    block by block, so the field order is not the grid's)."""
    out = []
    for x, y, _ in outputs.field(case_path, time_name, "C"):
        out.append((int((y - grid.origin[1]) // grid.spacing[1]), int((x - grid.origin[0]) // grid.spacing[0])))
    return out


def to_map(values, rows_columns, shape):
    """A (rows, columns) array of a cell field given in the case's cell order."""
    grid_map = numpy.full(shape, numpy.nan)
    for value, (r, c) in zip(values, rows_columns):
        grid_map[r, c] = value
    return grid_map


def regions(mask):
    """Labels (1, 2, ...) of the 4-connected regions of a boolean (rows, columns) array; 0 outside."""
    labels = numpy.zeros(mask.shape, dtype=int)
    count = 0
    for start in zip(*numpy.nonzero(mask)):
        if labels[start]:
            continue
        count += 1
        labels[start] = count
        queue = deque([start])
        while queue:
            r, c = queue.popleft()
            for nr, nc in ((r + 1, c), (r - 1, c), (r, c + 1), (r, c - 1)):
                if 0 <= nr < mask.shape[0] and 0 <= nc < mask.shape[1] and mask[nr, nc] and not labels[nr, nc]:
                    labels[nr, nc] = count
                    queue.append((nr, nc))
    return labels


def find_bubble(gas_fraction, dx, dy, threshold=BUBBLE_GAS_FRACTION):
    """The bubble of a (rows, columns) gas-fraction map with cells dx x dy: dict area (m^2),
    diameter (equivalent, m), aspect (height / width), x, y (centroid, m, from the map's
    corner), or None when there is no region below the freeboard."""
    labels = regions(gas_fraction > threshold)
    freeboard = set(labels[-1][labels[-1] > 0])
    best = None
    for label in range(1, labels.max() + 1):
        if label in freeboard:
            continue
        rows, columns = numpy.nonzero(labels == label)
        if best is None or len(rows) > len(best[0]):
            best = (rows, columns)
    if best is None:
        return None
    rows, columns = best
    area = len(rows) * dx * dy
    return {"area": area, "diameter": math.sqrt(4 * area / math.pi),
            "aspect": (rows.max() - rows.min() + 1) * dy / ((columns.max() - columns.min() + 1) * dx),
            "x": (columns.mean() + 0.5) * dx, "y": (rows.mean() + 0.5) * dy}


def coloured_above(initial_height, ids, heights, interface, middle=None):
    """Fraction of the coloured particles (those that started below `interface`: dict id ->
    initial height) that are above `middle` now (default: the interface; ids and heights of
    the particles now)."""
    middle = interface if middle is None else middle
    coloured = [h for i, h in zip(ids, heights) if initial_height.get(i, math.inf) < interface]
    if not coloured:
        raise ValueError("no coloured particle (none started below the interface)")
    return sum(h > middle for h in coloured) / len(coloured)


def bubble_history(case_path, grid, gas_fraction_field):
    """[(t, bubble or None)] over a run's written times after 0 that hold `gas_fraction_field`
    (a DPM's voidFraction, a two-fluid model's alpha.air), on the run's uniform grid."""
    cells = cell_rows_columns(case_path, grid)
    shape = (grid.counts[1], grid.counts[0])
    out = []
    for name in outputs.times(case_path):
        if float(name) <= 0 or not os.path.exists(os.path.join(case_path, name, gas_fraction_field)):
            continue
        gas = to_map(outputs.field(case_path, name, gas_fraction_field), cells, shape)
        out.append((float(name), find_bubble(gas, grid.spacing[0], grid.spacing[1])))
    return out


def write_history(path, history, mixing):
    """A run's bubble (history: [(t, bubble or None)]) and the coloured share above the median
    height (mixing: {t: share}, where measured) at each written time, as CSV."""
    lines = ["t (s),bubble diameter (m),bubble aspect (height/width),bubble centroid height (m),"
             "coloured fraction above the median height"]
    for t, b in history:
        cells = f"{b['diameter']:.5g},{b['aspect']:.4g},{b['y']:.5g}" if b else ",,"
        near = [m for s, m in mixing.items() if abs(s - t) < 1e-6]
        lines.append(f"{t:g},{cells},{f'{near[0]:.5g}' if near else ''}")
    os.makedirs(os.path.dirname(path), exist_ok=True)
    write_text_atomic(path, "\n".join(lines) + "\n")
