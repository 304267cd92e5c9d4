"""Time averages of chaotic signals with an honest error: batch means, spectra, and the checks
of that error: ensembles of independent realizations, blocking curves, integrated
autocorrelation times."""
import math
import statistics

import numpy


def window(t, y, start, end):
    """The samples of y with start <= t <= end."""
    return [v for ti, v in zip(t, y) if start - 1e-12 <= ti <= end + 1e-12]


def value_at(t, y, when):
    """The last sample of y at or before time `when` (the first sample when all are later)."""
    best = y[0]
    for ti, v in zip(t, y):
        if ti > when + 1e-12:
            break
        best = v
    return best


def mean(values):
    if not values:
        raise ValueError("mean of no samples")
    return sum(values) / len(values)


def std(values):
    """Standard deviation of the samples (population)."""
    m = mean(values)
    return math.sqrt(sum((v - m) ** 2 for v in values) / len(values))


def interval_mean(t, y, start, end):
    """Mean of the samples of y with start < t <= end (half-open: back-to-back intervals share
    no sample); ValueError when there is none."""
    values = [v for ti, v in zip(t, y) if start < ti <= end + 1e-9]
    if not values:
        raise ValueError(f"no samples between {start} and {end} s: did the run finish?")
    return sum(values) / len(values)


def mean_and_error(values):
    """Mean of independent samples (e.g. batch means) and its standard error, sqrt(s^2 / n)
    with the sample variance s^2 (n - 1 in the denominator)."""
    if len(values) < 2:
        raise ValueError(f"{len(values)} sample(s): a standard error needs two")
    m = sum(values) / len(values)
    variance = sum((v - m) ** 2 for v in values) / (len(values) - 1)
    return m, math.sqrt(variance / len(values))


def fit_linear_quadratic(x, y):
    """Least-squares (a, b) of y = a x + b x^2 (through the origin)."""
    s11 = sum(v ** 2 for v in x)
    s12 = sum(v ** 3 for v in x)
    s22 = sum(v ** 4 for v in x)
    y1 = sum(u * w for u, w in zip(x, y))
    y2 = sum(u ** 2 * w for u, w in zip(x, y))
    det = s11 * s22 - s12 * s12
    if det == 0:
        raise ValueError(f"{len(x)} point(s) cannot fix a x + b x^2: need two distinct x")
    return (y1 * s22 - y2 * s12) / det, (s11 * y2 - s12 * y1) / det


def batches(t, y, start, end, batch):
    """The samples of y in each of the round((end - start) / batch) consecutive batches of
    `batch` seconds from `start`, as lists (a batch may be empty)."""
    count = int(round((end - start) / batch))
    return [window(t, y, start + k * batch, start + (k + 1) * batch - 1e-9) for k in range(count)]


def mean_of_batches(values):
    """Mean of per-batch values and its standard error, the values' standard deviation over
    sqrt(n - 1) (nan with fewer than two)."""
    m = mean(values)
    if len(values) < 2:
        return m, float("nan")
    return m, std(values) / math.sqrt(len(values) - 1)


def batch_means(t, y, start, end, batch):
    """Mean of y over [start, end] with its standard error from batch means: the window is cut
    into batches of `batch` seconds (longer than the signal's correlation time), the error is
    the standard deviation of the batch means over sqrt(batches - 1). Returns (mean, standard
    error, number of batches); the error is nan with fewer than two batches."""
    means = [mean(values) for values in batches(t, y, start, end, batch) if values]
    if not means:
        raise ValueError(f"no samples in [{start}, {end}]")
    m, error = mean_of_batches(means)
    return m, error, len(means)


def dominant_frequency(t, y):
    """Frequency (Hz) of the largest peak of the signal's Fourier spectrum (mean removed;
    uniform sampling assumed)."""
    y = numpy.asarray(y, dtype=float)
    if y.size < 4:
        raise ValueError("too few samples for a spectrum")
    power = numpy.abs(numpy.fft.rfft(y - y.mean())) ** 2
    frequencies = numpy.fft.rfftfreq(y.size, (t[-1] - t[0]) / (y.size - 1))
    return float(frequencies[1 + int(numpy.argmax(power[1:]))])


def ensemble(values):
    """Mean over independent realizations (runs from independent initial states) with its
    standard error s / sqrt(n), s the sample standard deviation (ddof = 1): an error that needs
    no assumption on how long one run's signal stays correlated. Returns {"mean", "error",
    "spread" (s, the scatter of one realization), "n", "values"}; ValueError with fewer than
    two values."""
    values = [float(v) for v in values]
    m, error = mean_and_error(values)
    return {"mean": m, "error": error, "spread": error * math.sqrt(len(values)), "n": len(values), "values": values}


def difference(a, b):
    """a - b of two independent estimates {"mean", "error"}, the errors added in quadrature:
    sqrt(e_a^2 + e_b^2)."""
    return {"mean": a["mean"] - b["mean"], "error": math.hypot(a["error"], b["error"])}


def default_batch_sizes(n, fewest_batches=4):
    """Batch lengths 1, 2, 4, ... samples (Flyvbjerg-Petersen's halving) that leave at least
    `fewest_batches` batches in n samples."""
    sizes, k = [], 1
    while n // k >= fewest_batches:
        sizes.append(k)
        k *= 2
    return sizes


def blocking_curve(y, sizes=None):
    """Standard error of the mean of the series y as a function of the batch length k
    (samples): y cut into n_b = len(y) // k consecutive batches (the remainder left out), the
    error s_b / sqrt(n_b) of their means (s_b with ddof = 1), with that error's own relative
    uncertainty 1 / sqrt(2 (n_b - 1)) (Flyvbjerg & Petersen, J. Chem. Phys. 91, 461 (1989);
    s_b^2 / n_b is their c_0 / (n' - 1)). For correlated samples the error rises
    with k until the batches are longer than the correlation time, then stays on a plateau,
    the true error of the mean; batches shorter than that give too small an error. sizes:
    batch lengths in samples (default: default_batch_sizes). Returns a list of {"size",
    "batches", "error", "error_of_error"}."""
    y = numpy.asarray(y, dtype=float)
    curve = []
    for k in sizes or default_batch_sizes(y.size):
        count = y.size // k
        if count < 2:
            raise ValueError(f"batches of {k} samples: {y.size} samples make {count}, a standard error needs two")
        means = y[:count * k].reshape(count, k).mean(axis=1)
        error = float(means.std(ddof=1) / math.sqrt(count))
        curve.append({"size": k, "batches": count, "error": error,
                      "error_of_error": error / math.sqrt(2 * (count - 1))})
    return curve


def autocorrelation(y):
    """Normalized autocorrelation rho(t) = C(t) / C(0), t = 0 ... N - 1, with the biased
    estimator C(t) = 1/N sum_{i=0}^{N-1-t} (y_i - ybar)(y_{i+t} - ybar) (the usual one: its
    error stays bounded at large t); by FFT, zero-padded so that it is not circular."""
    y = numpy.asarray(y, dtype=float)
    n = y.size
    if n < 2:
        raise ValueError(f"{n} sample(s): an autocorrelation needs two")
    d = y - y.mean()
    spectrum = numpy.fft.rfft(d, 2 * n)
    c = numpy.fft.irfft(spectrum * numpy.conj(spectrum))[:n] / n
    if c[0] == 0:
        raise ValueError("a constant series has no autocorrelation")
    return c / c[0]


def integrated_autocorrelation_time(y, c=5.0):
    """Integrated autocorrelation time of the series y in samples, tau = 1 + 2 sum_{t=1}^{M}
    rho(t) (autocorrelation; sokal_window picks M), so that var(mean) = var(y) tau / N: N / tau
    samples are worth as many independent ones (white noise tau = 1; AR(1) with coefficient
    phi tau = (1 + phi) / (1 - phi)). Returns (tau, M)."""
    return sokal_window(autocorrelation(y), c)


def sokal_window(rho, c=5.0):
    """(tau(M), M) for the autocorrelation rho(0 ... N - 1): tau(M) = 1 + 2 sum_{t=1}^{M} rho(t)
    at Sokal's automatic window, the smallest M with M >= c tau(M), long enough to hold the
    correlated part, short enough to leave out the noise of rho's tail (Sokal, "Monte Carlo
    methods in statistical mechanics: foundations and new algorithms", 1997 lecture notes;
    c = 5 as in emcee's autocorr). M is sought below N / 2: further out rho is mostly its own
    noise, and the biased estimator's full sum is exactly -1/2 (tau(N - 1) = 0 always).
    ValueError when no such M exists: the series is too short for its correlation time."""
    rho = numpy.asarray(rho, dtype=float)
    windows = numpy.arange(1, (rho.size + 1) // 2)
    taus = 1.0 + 2.0 * numpy.cumsum(rho[1:1 + windows.size])
    ok = windows >= c * taus
    if not ok.any():
        raise ValueError(f"{rho.size} samples: no window M < {rho.size / 2:g} satisfies M >= {c:g} tau(M)"
                         + (f" (tau reaches {taus.max():.3g})" if taus.size else "")
                         + "; the series is too short for its correlation time")
    first = int(numpy.argmax(ok))
    return float(taus[first]), int(windows[first])


def chi_square_quantile(p, dof):
    """The p-quantile of the chi-square distribution with `dof` degrees of freedom, by the
    Wilson-Hilferty cube-root normal approximation, dof (1 - 2/(9 dof) + z sqrt(2/(9 dof)))^3
    with z the normal p-quantile (within 1 % of the tables for dof >= 6 at p = 0.05 and 0.95;
    7 % low at dof 3's 0.05)."""
    z = statistics.NormalDist().inv_cdf(p)
    a = 2.0 / (9.0 * dof)
    return dof * (1.0 - a + z * math.sqrt(a)) ** 3


def spread_ratio_range(dof, level=0.9):
    """The central `level` range of s / sigma for a sample standard deviation s with `dof`
    degrees of freedom of normal values with standard deviation sigma: sqrt(chi2_q / dof) at
    q = (1 -+ level) / 2, since dof s^2 / sigma^2 is chi-square. A measured s / sigma outside
    it says sigma was misjudged."""
    low, high = (1 - level) / 2, (1 + level) / 2
    return math.sqrt(chi_square_quantile(low, dof) / dof), math.sqrt(chi_square_quantile(high, dof) / dof)
