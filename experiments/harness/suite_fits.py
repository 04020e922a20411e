"""Least-squares fits of a line plot's points (plot_suite.py's "fit": "power"), in the standard
library alone so that they are tested without matplotlib.

A power fit y = c x^k measures how a cost grows only when the cost has no fixed part: a time
of 86 ms + 61 ms per Mpx (the exact oracle's frame on knecht-fig56, H200) fits k = 0.45 over
0.15-8.6 Mpx although every added pixel costs the same.
So each power fit comes with the fixed-plus-marginal (affine) fit y = a + b x over the same
points, a the fixed cost and b the cost per unit of x, and with each model's relative residual,
the root mean square of (y - model) / y, which says which of the two describes the points."""
import math


def usable(points):
    """The (x, y) of the (x, y, ...) points with x > 0 and y > 0: those both fits use."""
    return [(p[0], p[1]) for p in points if p[0] > 0 and p[1] > 0]


def _least_squares(pairs):
    """(intercept, slope) of the least-squares line through the (u, v) pairs; None with fewer
    than three pairs or a single u."""
    if len(pairs) < 3:
        return None
    mu = sum(u for u, _ in pairs) / len(pairs)
    mv = sum(v for _, v in pairs) / len(pairs)
    suu = sum((u - mu) ** 2 for u, _ in pairs)
    if suu <= 0:
        return None
    slope = sum((u - mu) * (v - mv) for u, v in pairs) / suu
    return mv - slope * mu, slope


def power_fit(points):
    """(c, k) of y = c x^k fitted by least squares to log y against log x over the usable
    points (at least three), else None."""
    line = _least_squares([(math.log(x), math.log(y)) for x, y in usable(points)])
    return None if line is None else (math.exp(line[0]), line[1])


def affine_fit(points):
    """(a, b) of y = a + b x fitted by least squares to y against x over the usable points (at
    least three), else None: a is the fixed cost, b the marginal cost per unit of x."""
    return _least_squares(usable(points))


def relative_residual(points, model):
    """The root mean square of (y - model(x)) / y over the usable points."""
    pairs = usable(points)
    return math.sqrt(sum(((y - model(x)) / y) ** 2 for x, y in pairs) / len(pairs))


def fits(points):
    """Both fits of the points with their relative residuals, as plots.json records them:
    {"points", "power": {"c", "k", "residual"}, "affine": {"a", "b", "residual"}}, or None
    when there is no power fit."""
    power = power_fit(points)
    affine = affine_fit(points)
    if power is None or affine is None:
        return None
    c, k = power
    a, b = affine
    return {"points": len(usable(points)),
            "power": {"c": c, "k": k,
                      "residual": relative_residual(points, lambda x: c * x ** k)},
            "affine": {"a": a, "b": b,
                       "residual": relative_residual(points, lambda x: a + b * x)}}


def describe(fit):
    """'k = 0.66 (residual 12 %); a + b x: a = 86.1, b = 6.1e-05 (residual 0.4 %)'."""
    p, a = fit["power"], fit["affine"]
    return "k = %.2f (residual %.3g %%); a + b x: a = %.4g, b = %.4g (residual %.3g %%)" % (
        p["k"], 100 * p["residual"], a["a"], a["b"], 100 * a["residual"])
