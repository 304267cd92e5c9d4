"""Time averages of chaotic signals with an honest error: batch means, spectra."""
import math


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
    import numpy

    y = numpy.asarray(y, dtype=float)
    if y.size < 4:
        raise ValueError("too few samples for a spectrum")
    power = numpy.abs(numpy.fft.rfft(y - y.mean())) ** 2
    frequencies = numpy.fft.rfftfreq(y.size, (t[-1] - t[0]) / (y.size - 1))
    return float(frequencies[1 + int(numpy.argmax(power[1:]))])
