"""What the report scripts share: a binomial proportion's interval.

Standard library only; imported by scripts/bench-report.py and scripts/free-space-room.py.
"""

import math

Z95 = 1.959963984540054  # the 97.5 % quantile of the standard normal


def wilson(k, n, z=Z95):
    """The Wilson score interval of a binomial proportion k/n: (low, high), or None for n = 0."""
    if n <= 0:
        return None
    p = k / n
    denom = 1 + z * z / n
    center = (p + z * z / (2 * n)) / denom
    half = z / denom * math.sqrt(p * (1 - p) / n + z * z / (4 * n * n))
    low = 0.0 if k <= 0 else max(0.0, center - half)
    high = 1.0 if k >= n else min(1.0, center + half)
    return low, high
