"""How the render tables write a ratio over scene seeds (seed_table.py,
error_split.py, prepass_sweep.py): the geometric mean over the seeds, with
the range beside it."""
import math


def gmean(xs):
    """The geometric mean of the positive, finite values; NaN if none."""
    xs = [x for x in xs if x > 0 and math.isfinite(x)]
    return math.exp(sum(math.log(x) for x in xs) / len(xs)) if xs else float("nan")


def fmt(x):
    if not math.isfinite(x):
        return "—"
    return "%.2f" % x if x >= 0.1 else "%.2g" % x


def ratio_text(xs):
    """'g (min–max)' over the seeds; the value alone for one seed, '—' for none."""
    if not xs:
        return "—"
    if len(xs) == 1:
        return fmt(xs[0])
    return "%s (%s–%s)" % (fmt(gmean(xs)), fmt(min(xs)), fmt(max(xs)))
