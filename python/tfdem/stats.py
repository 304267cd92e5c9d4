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


def _incomplete_beta(x, a, b):
    """The regularized incomplete beta function I_x(a, b), 0 <= x <= 1, by its continued
    fraction (modified Lentz; Press et al., Numerical Recipes, 3rd ed., sec. 6.4), on the side
    of x where it converges fast."""
    if x <= 0.0 or x >= 1.0:
        return 0.0 if x <= 0.0 else 1.0
    if x > (a + 1.0) / (a + b + 2.0):
        return 1.0 - _incomplete_beta(1.0 - x, b, a)
    front = math.exp(math.lgamma(a + b) - math.lgamma(a) - math.lgamma(b) + a * math.log(x) + b * math.log1p(-x)) / a
    tiny = 1e-300
    c, d = 1.0, 1.0 - (a + b) * x / (a + 1.0)
    d = 1.0 / (d if abs(d) > tiny else tiny)
    f = d
    for m in range(1, 500):
        for numerator in (m * (b - m) * x / ((a + 2 * m - 1) * (a + 2 * m)),
                          -(a + m) * (a + b + m) * x / ((a + 2 * m) * (a + 2 * m + 1))):
            d = 1.0 + numerator * d
            d = 1.0 / (d if abs(d) > tiny else tiny)
            c = 1.0 + numerator / c
            c = c if abs(c) > tiny else tiny
            f *= c * d
        if abs(c * d - 1.0) < 1e-15:
            break
    return front * f


def student_t_cdf(t, dof):
    """P(T <= t) for Student's t with `dof` (> 0, not necessarily whole) degrees of freedom:
    1 - I_{dof / (dof + t^2)}(dof / 2, 1 / 2) / 2 for t >= 0, symmetric about 0."""
    tail = 0.5 * _incomplete_beta(dof / (dof + t * t), 0.5 * dof, 0.5)
    return 1.0 - tail if t >= 0 else tail


def student_t_quantile(p, dof):
    """The p-quantile of Student's t with `dof` degrees of freedom (bisection of
    student_t_cdf to 1e-12)."""
    if not 0.0 < p < 1.0:
        raise ValueError(f"a quantile needs 0 < p < 1, not {p}")
    low, high = -1.0, 1.0
    while student_t_cdf(low, dof) > p:
        low *= 2.0
    while student_t_cdf(high, dof) < p:
        high *= 2.0
    while high - low > 1e-12 * max(1.0, abs(high)):
        middle = 0.5 * (low + high)
        if student_t_cdf(middle, dof) < p:
            low = middle
        else:
            high = middle
    return 0.5 * (low + high)


def welch_difference(a, b):
    """mean(a) - mean(b) of two sets of independent realizations, its standard error
    sqrt(s_a^2 / n_a + s_b^2 / n_b) and the Welch-Satterthwaite degrees of freedom (Welch,
    Biometrika 34 (1947) 28-35): {"mean", "error", "dof"}. ValueError with fewer than two
    values in a set, or when neither set varies."""
    a, b = [float(v) for v in a], [float(v) for v in b]
    if len(a) < 2 or len(b) < 2:
        raise ValueError(f"{len(a)} and {len(b)} realizations: a difference with its error needs two of each")
    va, vb = numpy.var(a, ddof=1) / len(a), numpy.var(b, ddof=1) / len(b)
    if va + vb == 0:
        raise ValueError("neither set of realizations varies: no error to test against")
    dof = (va + vb) ** 2 / (va ** 2 / (len(a) - 1) + vb ** 2 / (len(b) - 1))
    return {"mean": float(numpy.mean(a) - numpy.mean(b)), "error": float(math.sqrt(va + vb)), "dof": float(dof)}


def equivalence_test(a, b, tolerance, alpha=0.05):
    """Two one-sided tests (Schuirmann, J. Pharmacokinet. Biopharm. 15 (1987) 657-680) that the
    means of two sets of realizations a and b differ by less than `tolerance` (> 0, in their
    unit): H0 |mu_a - mu_b| >= tolerance is rejected at level alpha when both t = (d +
    tolerance) / e and (tolerance - d) / e exceed Student's 1 - alpha quantile (Welch's d, e and
    dof: welch_difference), that is when the 1 - 2 alpha interval d -+ t e lies inside
    (-tolerance, tolerance). Returns {"mean", "error", "dof", "tolerance", "p" (the larger
    one-sided p), "interval" (the 1 - 2 alpha one), "equivalent"}. Failing to find a
    difference is not equivalence; this test is the one that can show it."""
    if not tolerance > 0:
        raise ValueError(f"an equivalence tolerance must be above 0, not {tolerance}")
    d = welch_difference(a, b)
    lower = 1.0 - student_t_cdf((d["mean"] + tolerance) / d["error"], d["dof"])
    upper = student_t_cdf((d["mean"] - tolerance) / d["error"], d["dof"])
    half = student_t_quantile(1.0 - alpha, d["dof"]) * d["error"]
    p = max(lower, upper)
    return dict(d, tolerance=float(tolerance), p=float(p), interval=[d["mean"] - half, d["mean"] + half],
                equivalent=bool(p < alpha))


def grid_convergence(h, phi, safety=1.25):
    """Richardson extrapolation and the grid convergence index of three grids (Celik, Ghia,
    Roache, Freitas, Coleman and Raad, J. Fluids Eng. 130 (2008) 078001, eq. 1-10), h the
    representative cell sizes and phi the values, finest first (h_1 < h_2 < h_3; the ratios
    r_21 = h_2 / h_1 and r_32 = h_3 / h_2 may differ). The apparent order p solves
    p = |ln|e_32 / e_21| + ln((r_21^p - s) / (r_32^p - s))| / ln r_21, s = sign(e_32 / e_21),
    e_21 = phi_2 - phi_1 (fixed-point iteration); phi_ext = (r_21^p phi_1 - phi_2) / (r_21^p -
    1); GCI_fine = safety |e_21 / phi_1| / (r_21^p - 1). s < 0 is oscillatory convergence
    (Celik's note: the GCI then says less). Returns {"order", "extrapolated", "relative_error",
    "extrapolated_error", "gci_fine", "oscillatory"}; ValueError when two grids give the same
    value (no order) or the iteration does not settle."""
    (h1, h2, h3), (f1, f2, f3) = [float(v) for v in h], [float(v) for v in phi]
    if not 0 < h1 < h2 < h3:
        raise ValueError(f"cell sizes {h}: give three, finest first, each coarser than the last")
    r21, r32 = h2 / h1, h3 / h2
    e21, e32 = f2 - f1, f3 - f2
    if e21 == 0 or e32 == 0:
        raise ValueError(f"values {phi}: two grids agree exactly, no order of convergence")
    s = math.copysign(1.0, e32 / e21)
    order = abs(math.log(abs(e32 / e21))) / math.log(r21)
    for _ in range(1000):
        ratio = (r21 ** order - s) / (r32 ** order - s)
        if ratio <= 0:
            raise ValueError(f"values {phi} on cells {h}: the apparent order has no solution")
        new = abs(math.log(abs(e32 / e21)) + math.log(ratio)) / math.log(r21)
        if abs(new - order) < 1e-12:
            order = new
            break
        order = new
    else:
        raise ValueError(f"values {phi} on cells {h}: the apparent order did not settle")
    factor = r21 ** order - 1.0
    extrapolated = (r21 ** order * f1 - f2) / factor
    return {"order": order, "extrapolated": extrapolated, "relative_error": abs(e21 / f1),
            "extrapolated_error": abs((extrapolated - f1) / extrapolated),
            "gci_fine": safety * abs(e21 / f1) / factor, "oscillatory": s < 0}
