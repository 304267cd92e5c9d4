"""Time averages of chaotic signals with an honest error: batch means, spectra."""
import math


def window(t, y, start, end):
    """The samples of y with start <= t <= end."""
    return [v for ti, v in zip(t, y) if start - 1e-12 <= ti <= end + 1e-12]


def mean(values):
    if not values:
        raise ValueError("mean of no samples")
    return sum(values) / len(values)


def std(values):
    """Standard deviation of the samples (population)."""
    m = mean(values)
    return math.sqrt(sum((v - m) ** 2 for v in values) / len(values))


def batch_means(t, y, start, end, batch):
    """Mean of y over [start, end] with its standard error from batch means: the window is cut
    into batches of `batch` seconds (longer than the signal's correlation time), the error is
    the standard deviation of the batch means over sqrt(batches - 1). Returns (mean, standard
    error, number of batches); the error is nan with fewer than two batches."""
    count = int(round((end - start) / batch))
    means = []
    for k in range(count):
        values = window(t, y, start + k * batch, start + (k + 1) * batch - 1e-9)
        if values:
            means.append(mean(values))
    if not means:
        raise ValueError(f"no samples in [{start}, {end}]")
    m = mean(means)
    if len(means) < 2:
        return m, float("nan"), len(means)
    return m, std(means) / math.sqrt(len(means) - 1), len(means)


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
