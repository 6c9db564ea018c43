"""The interval of a mean over specimens, one rule for every script that
checks a document's table against its CSVs (tests/layout/check_*.py) or
writes one (assets/scenes/triaxial_cells/tables.py).

It is the rule the C++ reports use (app/experiment/shear_box/study_stats.h):
the mean of n values and Student's 95 % half-width
t(0.975, n - 1) s / sqrt(n), with s the sample standard deviation; one value
has no interval (NaN). The quantile is SciPy's.
"""
import math

from scipy.stats import t as _student_t


def t975(dof):
    """Student's t quantile at 0.975 for dof degrees of freedom."""
    return float(_student_t.ppf(0.975, dof))


def mean_ci(values):
    """(mean, 95 % half-width) of values; the half-width is NaN for one value."""
    v = [float(x) for x in values]
    n = len(v)
    if n == 0:
        raise ValueError("mean_ci of no values")
    m = sum(v) / n
    if n < 2:
        return m, float("nan")
    sd = math.sqrt(sum((x - m) ** 2 for x in v) / (n - 1))
    return m, t975(n - 1) * sd / math.sqrt(n)
