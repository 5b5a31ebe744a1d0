"""Writes the malformed inputs of the regression corpus into a folder.

usage: make-inputs.py INPUTS OUT
INPUTS is test/Run/Inputs (the fall program and the tet mesh); OUT gets one
scene (with its meshes) or program per case, named after the case.
"""
import json
import os
import sys

inputs, out = sys.argv[1], sys.argv[2]
fall = os.path.abspath(os.path.join(inputs, "fall.mlir"))


def write(name, text):
    with open(os.path.join(out, name), "w") as f:
        f.write(text)


def scene(name, externs=None, fields=None, sets=None, mesh="chain.node",
          raw_externs=None):
    """A fall.mlir scene on `mesh`; raw_externs is JSON text spliced in."""
    points = {"mesh": "chain",
              "fields": {"x": {"coordinates": "mesh"}, "v": [1, 0, 0]}}
    points["fields"].update(fields or {})
    doc = {"program": fall, "meshes": {"chain": mesh},
           "sets": {"points": points, **(sets or {})},
           "externs": {"h": 0.5, "g": [0, -2, 0], **(externs or {})},
           "step": "step", "frames": 2,
           "outputs": [{"format": "csv", "path": name + ".csv",
                        "set": "points", "fields": ["x"]}]}
    text = json.dumps(doc, indent=1)
    if raw_externs:
        text = text.replace('"h": 0.5', raw_externs + ', "h": 0.5')
    write(name + ".json", text)


write("chain.node", "3 3 0 0\n0 0 0 0\n1 1 0 0\n2 3 0 0\n")

# Numbers: beyond doubles, beyond int32 (3e9 would wrap to -2^31).
scene("overflow", raw_externs='"big": 1e999')
scene("int32-wrap", raw_externs='"n": {"type": "int32", "value": 3e9}')
scene("deep-json", raw_externs='"deep": ' + "[" * 200000 + "1" +
      "]" * 200000)

# Scene expressions nested 200000 deep, or 200000 terms long.
n = 200000
for case, expr in [("expr-parens", "(" * n + "x" + ")" * n),
                   ("expr-minus", "-" * n + "x"),
                   ("expr-not", "not " * n + "x < 1"),
                   ("expr-sum", "x + " * n + "x")]:
    scene(case, sets={"extra": {"mesh": "chain", "fields": {
        "c": {"expr" if case != "expr-not" else "if": expr,
              **({"then": 1, "else": 0} if case == "expr-not" else {})}}}})

# Memory beyond the machine: a huge set, a huge field shape, a refinement.
scene("huge-set", sets={"extra": {"size": 2000000000,
                                   "fields": {"f": {"shape": [1000]}}}})
scene("huge-shape", sets={"extra": {"size": 10, "fields": {
    "f": {"shape": [100000, 100000]}}}})
write("one-tet.node", "4 3 0 0\n0 0 0 0\n1 1 0 0\n2 0 1 0\n3 0 0 1\n")
write("one-tet.ele", "1 4 0\n0 0 1 2 3\n")
scene("refine-10", mesh={"file": "one-tet.node", "refine": 10})
scene("refine-11", mesh={"file": "one-tet.node", "refine": 11})

# Mesh headers that promise more than the file holds.
write("count.node", "2000000000 3 0 0\n0 0 0 0\n")
scene("tetgen-count", mesh="count.node")
write("count.msh", "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n"
      "2000000000\n1 0 0 0\n")
scene("gmsh-count", mesh="count.msh")
write("count4.msh", "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n$Nodes\n"
      "1 2000000000 1 2000000000\n3 1 0 2000000000\n1\n")
scene("gmsh4-count", mesh="count4.msh")

# Coordinates that are not numbers a simulation can use.
write("nan.node", "3 3 0 0\n0 0 0 0\n1 nan 0 0\n2 3 0 0\n")
scene("nan-coordinate", mesh="nan.node")
write("inf.obj", "v 0 0 0\nv 1 inf 0\nv 0 1 0\nf 1 2 3\n")
scene("inf-coordinate", mesh="inf.obj")

# A 2-D .node file under tets; tets numbered unlike their points.
write("flat.node", "4 2 0 0\n0 0 0\n1 1 0\n2 0 1\n3 1 1\n")
write("flat.ele", "1 4 0\n0 0 1 2 3\n")
scene("flat-tets", mesh="flat.node")
write("shifted.node", "4 3 0 0\n1 0 0 0\n2 1 0 0\n3 0 1 0\n4 0 0 1\n")
write("shifted.ele", "1 4 0\n0 1 2 3 4\n")
scene("shifted-tets", mesh="shifted.node")

# Tets of zero volume or inverted among good ones: a warning, and the run
# goes on.
write("bad.node", "5 3 0 0\n0 0 0 0\n1 1 0 0\n2 0 1 0\n3 0 0 1\n4 1 1 2\n")
write("bad.ele", "4 4 0\n0 0 1 2 3\n1 1 2 3 4\n2 0 2 1 3\n3 0 1 1 3\n")
scene("bad-tets", mesh="bad.node")
scene("bad-tets-strict", mesh={"file": "bad.node", "strict": True})

# The same two tets numbered from 0 and from 1, under examples/fem: the
# 1-based mesh must give the same result.
with open(os.path.join(inputs, "fem-tet.json")) as f:
    fem = json.load(f)
fem["program"] = os.path.abspath(os.path.join(inputs, fem["program"]))
for base in (0, 1):
    name = "pyramid%d" % base
    write(name + ".node", "5 3 0 0\n" + "".join(
        "%d %s\n" % (i + base, p) for i, p in
        enumerate(["0 0 0", "1 0 0", "0 1 0", "0 0 1", "1 1 2"])))
    write(name + ".ele", "2 4 0\n" + "".join(
        "%d %s\n" % (i + base, " ".join(str(v + base) for v in tet))
        for i, tet in enumerate([[0, 1, 2, 3], [1, 2, 3, 4]])))
    fem["meshes"] = {"tet": name + ".node"}
    write(name + ".json", json.dumps(fem, indent=1))

# Two outputs writing one file.
scene("collision")
with open(os.path.join(out, "collision.json")) as f:
    doc = json.load(f)
doc["outputs"].append({"format": "csv", "path": "./sub/../collision.csv",
                       "set": "points", "fields": ["v"]})
write("collision.json", json.dumps(doc, indent=1))

# Simit programs whose trees are 100000 deep, and a tuple of 2^31 - 1.
write("sum.sim", "func f(a : float) -> (x : float)\n  x = a" +
      " + a" * 100000 + ";\nend\n")
write("transpose.sim", "func f(a : vector[3](float)) -> (x : "
      "vector[3](float))\n  x = a" + "'" * 100000 + ";\nend\n")
write("tuple.sim", "element Point\n  x : float;\nend\n"
      "func f(p : (Point*2147483647))\nend\n")
# The tallest sum allowed: 999 '+' (a tree 1000 deep) compiles and runs.
write("sum-999.sim", "export func f(a : float) -> (x : float)\n  x = a" +
      " + a" * 999 + ";\nend\n")
