#!/usr/bin/python3
"""Reads the `newton K: |r| = R ...` lines of the chamber example and says
whether Newton's method converged quadratically: the order estimate
log(r[k+1] / r[k]) / log(r[k] / r[k-1]) of the last three residuals above
rounding (1e-12 |r_0|) must be at least 1.8 (linear convergence gives 1)."""

import math
import re
import sys

residuals = []
for line in open(sys.argv[1]):
    m = re.match(r"newton (\d+): \|r\| = (\S+)", line)
    if m:
        assert int(m.group(1)) == len(residuals), line
        residuals.append(float(m.group(2)))
if len(residuals) < 3:
    sys.exit(f"newton-order: {len(residuals)} residuals, need 3")
above = [r for r in residuals if r > 1e-12 * residuals[0]]
for k in range(1, len(residuals)):
    print(f"step {k}: |r| = {residuals[k]:.3e}, |r| / |r_prev|^2 = "
          f"{residuals[k] / residuals[k - 1] ** 2:.3e}")
if len(above) < 3:
    sys.exit("newton-order: fewer than 3 residuals above rounding")
a, b, c = above[-3:]
order = math.log(c / b) / math.log(b / a)
print(f"order: {order:.2f}")
print("quadratic:", "yes" if order >= 1.8 else "no")
