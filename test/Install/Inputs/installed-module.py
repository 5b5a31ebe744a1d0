"""Runs a scene with the simit package found on PYTHONPATH; prints where the
package and the project's libraries were loaded from, and the heights of the
points at the end."""

import sys

import simit

print("package:", simit.__file__)
scene = simit.Scene(sys.argv[1])
scene.run()
with open("/proc/self/maps") as maps:
    engine = {line.split()[-1] for line in maps if "libSimitEngine" in line}
print("engine:", *engine)
print("y = %.6f %.6f" % tuple(scene.sets["points"]["x"][:, 1]))
