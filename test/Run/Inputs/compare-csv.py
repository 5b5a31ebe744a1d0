"""compare-csv.py A.csv B.csv TOL: the numeric columns of two CSV files of
one shape agree to TOL relative to the largest magnitude of A."""
import csv
import sys

def read(path):
    with open(path) as f:
        rows = list(csv.reader(f))
    return rows[0], [[float(v) for v in row] for row in rows[1:]]

head_a, a = read(sys.argv[1])
head_b, b = read(sys.argv[2])
tol = float(sys.argv[3])
assert head_a == head_b and len(a) == len(b), "different shapes"
scale = max(abs(v) for row in a for v in row)
worst = max(abs(x - y) for ra, rb in zip(a, b) for x, y in zip(ra, rb))
if worst > tol * scale:
    sys.exit(f"largest difference {worst:g} > {tol:g} * {scale:g}")
