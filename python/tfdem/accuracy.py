"""Errors of a run's bed metrics against a reference run, separated from statistical noise
(the speed-against-error sweeps, bench/pareto).

Each scalar metric is a time average over a window with its standard error from batch means;
a point's error is |value - reference| and it is within noise below twice the combined error
sqrt(e^2 + e_ref^2). The solids-fraction map's error is the L1 of the two time-averaged maps
on the coarser grid; its noise floor is the larger of the two runs' L1 between the halves of
the window.

The fluctuation of Delta p is split at the bed's time scale: `dp20_std` is the fluctuation of
Delta p averaged over `band` seconds (a sweep's setting; 0.05 s keeps bubbles, slugs and the
jet's pulsation, the paper's Fig. 3, below 20 Hz), `dp20_jitter` the rest. The jitter is numerical: with the centroid void fraction a particle
crossing a cell face changes two cells' eps by V_p / V_cell in one gas step, which the
pressure equation's d(eps)/dt source turns into a pressure kick of size 1 / gas step (its
amplitude grows as the gas step shrinks, bench/README.md).
"""
import math

import numpy

from tfdem.bed import l1_difference, to_grid
from tfdem.stats import batch_means, batches, dominant_frequency, mean_of_batches, std

METRICS = ("dp20_mean", "dp20_std", "dp20_jitter", "mean_height", "dp20_frequency", "solids_map")


def batch_stat(t, y, start, end, batch):
    """{'value', 'error'}: batch-means mean and standard error of y over [start, end]."""
    m, e, _ = batch_means(list(t), list(y), start, end, batch)
    return {"value": m, "error": e}


def batch_std(t, y, start, end, batch):
    """{'value', 'error'}: the mean over batches of y's standard deviation within each batch, and
    its standard error (the fluctuation amplitude, measured the same way at every point)."""
    stds = [std(values) for values in batches(list(t), list(y), start, end, batch) if len(values) > 1]
    if not stds:
        raise ValueError(f"no samples in [{start}, {end}]")
    m, e = mean_of_batches(stds)
    return {"value": m, "error": e}


def running_mean(t, y, span):
    """(t, y) of the mean of y over `span` seconds around each sample (uniformly sampled y; as
    many samples as fit in span, an odd number, at least one): the first and last half-span
    are dropped."""
    t, y = numpy.asarray(t), numpy.asarray(y)
    step = float(numpy.median(numpy.diff(t)))
    k = max(1, int(round(span / step)) // 2 * 2 + 1)
    if len(y) < k:
        raise ValueError(f"{len(y)} samples: a {span} s running mean needs {k}")
    return t[k // 2:len(t) - k // 2], numpy.convolve(y, numpy.ones(k) / k, mode="valid")


def scalar_metrics(dp_t, dp, height_t, height, start, end, batch, band):
    """The scalar metrics of one run over [start, end] (batches and band in seconds)."""
    dp_t, dp = numpy.asarray(dp_t), numpy.asarray(dp)
    pick = (dp_t >= start - 1e-9) & (dp_t <= end + 1e-9)
    upto = dp_t <= end + 1e-9  # no running mean reaches past the window: a run that ran on scores the same
    band_t, in_band = running_mean(dp_t[upto], dp[upto], band)
    half = (numpy.count_nonzero(upto) - len(in_band)) // 2
    jitter = dp[upto][half:half + len(in_band)] - in_band
    return {"dp20_mean": batch_stat(dp_t, dp, start, end, batch),
            "dp20_std": batch_std(band_t, in_band, start, end, batch),
            "dp20_jitter": batch_std(band_t, jitter, start, end, batch),
            "mean_height": batch_stat(height_t, height, start, end, batch),
            "dp20_frequency": {"value": dominant_frequency(dp_t[pick], dp[pick]), "error": 1.0 / (end - start)}}


def scalar_error(point, reference):
    """{'error', 'sigma', 'within_noise'} of a point's metric against the reference's."""
    error = abs(point["value"] - reference["value"])
    sigma = math.sqrt(point["error"] ** 2 + reference["error"] ** 2)
    return {"error": error, "sigma": sigma, "within_noise": bool(error < 2 * sigma)}


def map_error(point, reference, start, end):
    """L1 of the time-averaged solids-fraction maps (on the coarser grid) and its noise floor:
    the larger of the two runs' L1 between the first and second half of the window."""
    middle = 0.5 * (start + end)

    def average(d, a, b):
        return d.field_average(d.solids, a, b)

    coarse = reference if reference.solids.shape[1] <= point.solids.shape[1] else point
    shape = coarse.shape
    error = l1_difference(to_grid(average(point, start, end), shape), to_grid(average(reference, start, end), shape))
    noise = max(l1_difference(to_grid(average(d, start, middle), shape), to_grid(average(d, middle, end), shape))
                for d in (point, reference))
    return {"error": error, "sigma": noise / 2, "within_noise": bool(error < noise)}


def pareto_front(costs, errors):
    """Indices of the points no other point beats in both cost and error (ties kept)."""
    front = []
    for i, (c, e) in enumerate(zip(costs, errors)):
        if not any((c2 <= c and e2 <= e) and (c2 < c or e2 < e) for c2, e2 in zip(costs, errors)):
            front.append(i)
    return front
