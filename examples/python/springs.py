"""springs-bunny (bench/scenes.md) from Python: runs the scene frame by
frame, plots how far the bunny sags, and writes the plot to a PNG.

    python3 examples/python/springs.py [OUT_DIR]   # default: build/python-springs
"""

import pathlib
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import simit  # noqa: E402

root = pathlib.Path(__file__).resolve().parents[2]
out = pathlib.Path(sys.argv[1] if len(sys.argv) > 1 else root / "build" / "python-springs")
scene = simit.Scene(root / "examples" / "springs" / "springs-bunny.json", frames=100, time=True)
y = scene.sets["points"]["x"][:, 1]  # the points' heights, updated in place by every step
scene.init()
rest = y.copy()
sag = [0.0]
for frame in range(scene.frames):
    scene.step()
    sag.append((rest - y).max())
out.mkdir(parents=True, exist_ok=True)
plt.plot(sag)
plt.xlabel("frame")
plt.ylabel("largest drop of a point")
plt.title(f"springs-bunny, {scene.times['frame_ms']:.2f} ms per frame")
plt.savefig(out / "springs-bunny.png")
print(out / "springs-bunny.png")
