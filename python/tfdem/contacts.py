"""Particle contacts of one frame under the definitions seed 000 could have meant (stateless).

Seed 000 defines N_c as "the number of contacting neighbors of one particle" and the bulk
coordination number as "the average number of contacting neighbors of a particle" (Fig. 5);
"a particle is in a binary collision when Nc=1, or is in a multicontact when Nc>1". Fig. 11
plots "the ratio of particles in multicontacts to the total number of particles in contact",
the text describes the same figure as "the ratio of the number of multicontacts over the
total number of collisions". It does not say whether walls are neighbours, whether a
contact needs an overlap or only proximity, or whether the defluidized corners count: the
functions below take each of these as a parameter.

Gaps are fractions of the diameter: a pair a, b is in contact when its surface gap is below
gap * (r_a + r_b), i.e. its centre distance below (r_a + r_b)(1 + gap); a particle touches a
plane wall when its surface gap is below gap * d_i = 2 gap r_i, i.e. its centre lies within
r_i (1 + 2 gap) of the plane (the same gap in units of d as for two equal spheres). gap = 0
is the overlap (> 0) that the coupling fix's N_c uses (engines/liggghts/fix_tfdem_coupling.cpp,
count_touching_neighbours: pairs of the granular pair list only, no walls).

Arrays: positions (n, 3), radii (n,), velocities (n, 3), NumPy; masks are boolean (n,)."""
import re

import numpy

try:
    from scipy.spatial import cKDTree
except ImportError:  # numpy binning below
    cKDTree = None


def frame_arrays(frame):
    """(positions, radii, velocities) of a vtk_particles dict ('diameter' or 'radius')."""
    positions = numpy.asarray(frame["position"], dtype=float)
    if "radius" in frame:
        radii = numpy.asarray(frame["radius"], dtype=float)
    else:
        radii = 0.5 * numpy.asarray(frame["diameter"], dtype=float)
    velocities = numpy.asarray(frame["velocity"], dtype=float) if "velocity" in frame else None
    return positions, radii, velocities


def _candidate_pairs(positions, reach):
    """(m, 2) index pairs i < j with centre distance <= reach (a superset: binned or k-d tree)."""
    n = len(positions)
    if n < 2:
        return numpy.zeros((0, 2), dtype=int)
    if cKDTree is not None:
        return cKDTree(positions).query_pairs(reach, output_type="ndarray").reshape(-1, 2)
    # numpy binning: cells of side reach, each particle against its own and the 26 next cells
    keys = numpy.floor((positions - positions.min(axis=0)) / reach).astype(numpy.int64)
    span = keys.max(axis=0) + 3
    flat = lambda k: (k[:, 0] * span[1] + k[:, 1]) * span[2] + k[:, 2]
    order = numpy.argsort(flat(keys + 1), kind="stable")
    sorted_keys = flat(keys + 1)[order]
    found = []
    for shift in numpy.array(numpy.meshgrid([-1, 0, 1], [-1, 0, 1], [-1, 0, 1])).T.reshape(-1, 3):
        target = flat(keys + 1 + shift)
        lo = numpy.searchsorted(sorted_keys, target, "left")
        hi = numpy.searchsorted(sorted_keys, target, "right")
        for i in numpy.nonzero(hi > lo)[0]:
            js = order[lo[i]:hi[i]]
            js = js[js > i]
            found.append(numpy.column_stack([numpy.full(len(js), i), js]))
    return numpy.concatenate(found) if found else numpy.zeros((0, 2), dtype=int)


def contact_pairs(positions, radii, gap=0.0):
    """(m, 2) int array of pairs i < j in contact: centre distance < (r_i + r_j)(1 + gap).
    gap = 0: overlapping pairs (overlap > 0), the coupling fix's contact; gap = 0.005, 0.01:
    surface gaps below 0.5 % and 1 % of the (mean) diameter count as contacts."""
    positions = numpy.asarray(positions, dtype=float)
    radii = numpy.asarray(radii, dtype=float)
    if len(positions) < 2:
        return numpy.zeros((0, 2), dtype=int)
    pairs = _candidate_pairs(positions, 2.0 * radii.max() * (1.0 + gap))
    if len(pairs) == 0:
        return numpy.zeros((0, 2), dtype=int)
    d = positions[pairs[:, 0]] - positions[pairs[:, 1]]
    reach = (radii[pairs[:, 0]] + radii[pairs[:, 1]]) * (1.0 + gap)
    keep = numpy.einsum("ij,ij->i", d, d) < reach * reach
    pairs = numpy.sort(pairs[keep], axis=1)
    return pairs[numpy.lexsort((pairs[:, 1], pairs[:, 0]))]


def walls_of_script(path):
    """[(axis, coordinate)] of the plane walls of a LIGGGHTS input: every 'fix ... wall/gran
    ... primitive type T xplane|yplane|zplane C' line (axis 0, 1, 2). Faces of the box that no
    such fix names (an open top, the quasi-2-D bed's front and back) are not walls."""
    walls = []
    with open(path) as f:
        for line in f:
            words = line.split("#")[0].split()
            if len(words) > 3 and words[0] == "fix" and words[3] == "wall/gran" and "primitive" in words:
                for k, w in enumerate(words):
                    if w in ("xplane", "yplane", "zplane"):
                        walls.append(("xyz".index(w[0]), float(words[k + 1])))
    return walls


def data_file_of_script(path):
    """The file name of a LIGGGHTS input's read_data line (None without one)."""
    with open(path) as f:
        for line in f:
            found = re.match(r"\s*read_data\s+(\S+)", line)
            if found:
                return found.group(1)
    return None


def wall_contacts(positions, radii, walls, gap=0.0):
    """(k, 2) int array of (particle index, wall index) contacts with plane walls
    [(axis, coordinate)]: centre within r_i (1 + 2 gap) of the plane, i.e. a surface gap below
    gap * d_i (gap = 0: overlapping the wall)."""
    positions = numpy.asarray(positions, dtype=float)
    radii = numpy.asarray(radii, dtype=float)
    rows = []
    for w, (axis, coordinate) in enumerate(walls):
        hit = numpy.nonzero(numpy.abs(positions[:, axis] - coordinate) < radii * (1.0 + 2.0 * gap))[0]
        rows.append(numpy.column_stack([hit, numpy.full(len(hit), w)]))
    return numpy.concatenate(rows).astype(int) if rows else numpy.zeros((0, 2), dtype=int)


def coordination(n, pairs, walls=None):
    """Per-particle N_c (n,) int: the number of contacting neighbours, each pair counted for
    both particles; with walls (a wall_contacts array) each touched wall adds one neighbour,
    without (None) walls are not neighbours (the coupling fix's N_c)."""
    pairs = numpy.asarray(pairs, dtype=int).reshape(-1, 2)
    nc = numpy.bincount(pairs.ravel(), minlength=n)
    if walls is not None and len(walls):
        nc = nc + numpy.bincount(numpy.asarray(walls, dtype=int)[:, 0], minlength=n)
    return nc


def _select(nc, mask):
    nc = numpy.asarray(nc)
    return nc if mask is None else nc[numpy.asarray(mask, dtype=bool)]


def bulk_coordination(nc, mask=None):
    """Bulk coordination number (Fig. 5): the mean N_c over all particles (or over those of
    mask, e.g. the particles outside static cells). NaN for no particle."""
    chosen = _select(nc, mask)
    return float(chosen.mean()) if len(chosen) else float("nan")


def multicontact_ratio(nc, mask=None):
    """Multicontact ratio of the Fig. 11 caption, "the ratio of particles in multicontacts to
    the total number of particles in contact": particles with N_c > 1 over particles with
    N_c >= 1 (the study's definition). NaN when no particle is in contact."""
    chosen = _select(nc, mask)
    touching = numpy.count_nonzero(chosen >= 1)
    return numpy.count_nonzero(chosen > 1) / touching if touching else float("nan")


def multicontact_fraction(nc, mask=None):
    """A looser reading, "the ratio of particles in multicontacts to the total number of
    particles": particles with N_c >= 2 over all particles (of mask)."""
    chosen = _select(nc, mask)
    return numpy.count_nonzero(chosen >= 2) / len(chosen) if len(chosen) else float("nan")


def multicontact_collision_ratio(nc, pairs, walls=None, mask=None):
    """The text's reading of Fig. 11, "the ratio of the number of multicontacts over the
    total number of collisions": contacts (pairs, and wall contacts when walls are given) of
    which some particle has N_c > 1 (the contact is part of a multicontact) over all contacts;
    a contact whose particles all have N_c = 1 is a binary collision. With mask, the contacts
    with at least one particle in mask. NaN without contacts."""
    nc = numpy.asarray(nc)
    pairs = numpy.asarray(pairs, dtype=int).reshape(-1, 2)
    multi = (nc[pairs[:, 0]] > 1) | (nc[pairs[:, 1]] > 1)
    inside = numpy.ones(len(pairs), dtype=bool) if mask is None else \
        (numpy.asarray(mask, dtype=bool)[pairs[:, 0]] | numpy.asarray(mask, dtype=bool)[pairs[:, 1]])
    count, total = numpy.count_nonzero(multi & inside), numpy.count_nonzero(inside)
    if walls is not None and len(walls):
        p = numpy.asarray(walls, dtype=int)[:, 0]
        wall_inside = numpy.ones(len(p), dtype=bool) if mask is None else numpy.asarray(mask, dtype=bool)[p]
        count += numpy.count_nonzero((nc[p] > 1) & wall_inside)
        total += numpy.count_nonzero(wall_inside)
    return count / total if total else float("nan")


def cell_indices(positions, origin, spacing, counts):
    """Flat index (x fastest, then y, z: blockMesh order) of the cell holding each centre on
    a uniform grid; centres outside are clipped to the nearest cell."""
    positions = numpy.asarray(positions, dtype=float)
    ijk = numpy.floor((positions - numpy.asarray(origin)) / numpy.asarray(spacing)).astype(int)
    ijk = numpy.clip(ijk, 0, numpy.asarray(counts) - 1)
    return (ijk[:, 2] * counts[1] + ijk[:, 1]) * counts[0] + ijk[:, 0]


def static_mask(positions, velocities, origin, spacing, counts, threshold):
    """Particles in 'static' cells: cells of a uniform grid (the gas cells, or cubes of a few
    diameters) whose particles' mean speed |v| is below threshold (m/s). True = static, to be
    left out (pass ~mask to the ratios). A defluidized corner's particles creep at 1e-5 to
    1e-3 m/s; a fluidized cell's mean speed is several cm/s."""
    speeds = numpy.linalg.norm(numpy.asarray(velocities, dtype=float), axis=1)
    cells = cell_indices(positions, origin, spacing, counts)
    total = int(numpy.prod(counts))
    number = numpy.bincount(cells, minlength=total)
    mean = numpy.bincount(cells, weights=speeds, minlength=total) / numpy.maximum(number, 1)
    return mean[cells] < threshold
