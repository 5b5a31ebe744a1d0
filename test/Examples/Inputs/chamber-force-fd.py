#!/usr/bin/python3
"""The chamber example's residual force against central differences of its
energy, computed here with NumPy from the mesh and the scene's parameters:
  E(x) = sum over tets of W psi(F) - nRT log V(x),  nRT = p0 V(X),
  psi = mu/2 (|F|^2 - 3) - mu log J + lambda/2 (log J)^2,
  V(x) = sum over cavity triangles of det[a b c] / 6.
The residual r = -dE/dx (on the free vertices) of the positions of frame 1
is the f that simit-run writes in frame 2 (chamber.csv, every frame).
Usage: chamber-force-fd.py DIR (with chamber.node/.ele/.face/.json and
out/chamber.csv)."""

import csv
import json
import os
import sys

import numpy as np

folder = sys.argv[1]


def table(ext):
    with open(os.path.join(folder, "chamber" + ext)) as f:
        rows = [line.split() for line in f][1:]
    return np.array([[float(v) for v in row[1:]] for row in rows if row])


X = table(".node")
tets = table(".ele").astype(int)
tris = table(".face").astype(int)
scene = json.load(open(os.path.join(folder, "chamber.json")))
E, nu, p0 = (scene["externs"][k] for k in ("youngs", "poisson", "p0"))
mu, lam = E / (2 * (1 + nu)), E * nu / ((1 + nu) * (1 - 2 * nu))
z = X[:, 2]
free = ~(z < z.min() + 1e-6 * (z.max() - z.min()))

frames = {}
with open(os.path.join(folder, "out", "chamber.csv")) as f:
    for row in csv.DictReader(f):
        frames.setdefault(int(row["frame"]), []).append(row)
x1 = np.array([[float(r[f"x_{i}"]) for i in range(3)] for r in frames[1]])
f2 = np.array([[float(r[f"f_{i}"]) for i in range(3)] for r in frames[2]])


def shapes(x):
    return np.stack([x[tets[:, i]] - x[tets[:, 3]] for i in range(3)], axis=2)


Bm = np.linalg.inv(shapes(X))
W = np.abs(np.linalg.det(shapes(X))) / 6


def volume(x):
    a, b, c = (x[tris[:, i]] for i in range(3))
    return np.einsum("ij,ij->", a, np.cross(b, c)) / 6


nRT = p0 * volume(X)


def energy(x):
    F = shapes(x) @ Bm
    logJ = np.log(np.linalg.det(F))
    psi = mu / 2 * (np.einsum("tij,tij->t", F, F) - 3) - mu * logJ \
        + lam / 2 * logJ ** 2
    return (W * psi).sum() - nRT * np.log(volume(x))


h = 1e-6 * (X.max() - X.min())
gradient = np.zeros_like(x1)
for v in np.flatnonzero(free):
    for i in range(3):
        xp, xm = x1.copy(), x1.copy()
        xp[v, i] += h
        xm[v, i] -= h
        gradient[v, i] = (energy(xp) - energy(xm)) / (2 * h)
error = np.linalg.norm(f2 + gradient) / np.linalg.norm(f2)
print(f"free vertices: {free.sum()}, |r| = {np.linalg.norm(f2):.6g}")
print(f"relative error of r against -dE/dx: {error:.3e}")
print("force is -dE/dx:", "yes" if error < 1e-6 else "no")
