#!/usr/bin/env python3
"""Small exact statistics for the replication's reports, in the standard
library only (no SciPy on the machines the project targets):

  wilson(k, n)          95% Wilson score interval of a proportion k/n
  fisher_exact(table)   two-sided Fisher exact test of a 2x2 table
  kruskal_wallis(*xs)   Kruskal-Wallis H (ties corrected) and its p value
  holm(ps)              Holm's step-down adjustment of a family of p values
  chi2_sf(x, df)        the chi-square survival function

Each is checked against published values in tests/scripts/stats_test.py.
"""

import math


def wilson(k, n, z=1.959963984540054):
    """The Wilson score interval (lo, hi) of k successes in n trials; z is
    the normal quantile (default: 95%). (0, 1) for n = 0."""
    if n <= 0:
        return (0.0, 1.0)
    if not 0 <= k <= n:
        raise ValueError(f"{k} successes out of {n} trials")
    p = k / n
    z2 = z * z
    centre = (p + z2 / (2 * n)) / (1 + z2 / n)
    half = z * math.sqrt(p * (1 - p) / n + z2 / (4 * n * n)) / (1 + z2 / n)
    return (max(0.0, centre - half), min(1.0, centre + half))


def _log_choose(n, k):
    return math.lgamma(n + 1) - math.lgamma(k + 1) - math.lgamma(n - k + 1)


def fisher_exact(table):
    """Two-sided p value of Fisher's exact test of [[a, b], [c, d]]: the
    total probability, under fixed margins, of the tables no more likely
    than the observed one (with a relative tolerance of 1e-7, as R and
    SciPy)."""
    (a, b), (c, d) = table
    if min(a, b, c, d) < 0:
        raise ValueError("counts must be >= 0")
    row1, col1, n = a + b, a + c, a + b + c + d
    if n == 0:
        return 1.0
    low, high = max(0, col1 - (n - row1)), min(row1, col1)

    def log_p(x):
        return (_log_choose(col1, x) + _log_choose(n - col1, row1 - x) -
                _log_choose(n, row1))

    observed = log_p(a)
    total = 0.0
    for x in range(low, high + 1):
        lp = log_p(x)
        if lp <= observed + math.log1p(1e-7):
            total += math.exp(lp)
    return min(1.0, total)


def _gamma_q(s, x):
    """The regularised upper incomplete gamma function Q(s, x)."""
    if x <= 0:
        return 1.0
    if x < s + 1:  # The series for P, then Q = 1 - P.
        term = 1.0 / s
        total = term
        for k in range(1, 10000):
            term *= x / (s + k)
            total += term
            if abs(term) < abs(total) * 1e-16:
                break
        return max(0.0, 1.0 - total * math.exp(-x + s * math.log(x) -
                                               math.lgamma(s)))
    # Lentz's continued fraction for Q.
    tiny = 1e-300
    b = x + 1 - s
    c = 1 / tiny
    d = 1 / b
    h = d
    for i in range(1, 10000):
        an = -i * (i - s)
        b += 2
        d = an * d + b
        d = tiny if abs(d) < tiny else d
        c = b + an / c
        c = tiny if abs(c) < tiny else c
        d = 1 / d
        delta = d * c
        h *= delta
        if abs(delta - 1) < 1e-16:
            break
    return math.exp(-x + s * math.log(x) - math.lgamma(s)) * h


def chi2_sf(x, df):
    """P(X > x) for X chi-square with df degrees of freedom."""
    if df <= 0:
        raise ValueError("df must be > 0")
    return _gamma_q(df / 2, x / 2)


def kruskal_wallis(*groups):
    """(H, p) of the Kruskal-Wallis test of two or more samples: H with
    the correction for ties, p from the chi-square with k - 1 degrees of
    freedom. (0, 1) when every value is equal."""
    samples = [list(g) for g in groups]
    if len(samples) < 2 or any(len(g) == 0 for g in samples):
        raise ValueError("need two or more non-empty samples")
    pooled = sorted((v, i) for i, g in enumerate(samples) for v in g)
    n = len(pooled)
    rank_sums = [0.0] * len(samples)
    ties = 0.0
    start = 0
    while start < n:
        end = start
        while end + 1 < n and pooled[end + 1][0] == pooled[start][0]:
            end += 1
        rank = (start + end) / 2 + 1  # Mid-rank of the tied run.
        for j in range(start, end + 1):
            rank_sums[pooled[j][1]] += rank
        t = end - start + 1
        ties += t ** 3 - t
        start = end + 1
    correction = 1 - ties / (n ** 3 - n)
    if correction <= 0:
        return (0.0, 1.0)
    h = 12 / (n * (n + 1)) * sum(
        r * r / len(g) for r, g in zip(rank_sums, samples)) - 3 * (n + 1)
    h /= correction
    return (h, chi2_sf(h, len(samples) - 1))


def holm(p_values):
    """Holm's step-down adjustment of a family of p values (the same
    order back): each adjusted p is at least its raw p, never above 1,
    and never below the adjusted p of a smaller raw p."""
    order = sorted(range(len(p_values)), key=lambda i: p_values[i])
    m = len(p_values)
    adjusted = [0.0] * m
    running = 0.0
    for rank, i in enumerate(order):
        running = max(running, min(1.0, (m - rank) * p_values[i]))
        adjusted[i] = running
    return adjusted
