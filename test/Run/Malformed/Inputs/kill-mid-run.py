"""Kills simit-run in the middle of a run and checks its outputs.

usage: kill-mid-run.py SIMIT_RUN PROGRAM MESH OUT

Runs fall.mlir on MESH once to the end (3 frames), then again for 100000
frames writing a .vtu file every frame, killed with SIGKILL once 20 files
are there. Every file under a final name must be complete: each .vtu ends
with </VTKFile>, and the CSV files (one gathering every frame, one written
at the last frame) are still those of the first run. Temporary files
(*.tmp-*) may be left behind. The moment of the kill decides only which
file was being written, not the outcome.
"""
import json
import os
import signal
import subprocess
import sys
import time

simit_run, program, mesh, out = sys.argv[1:]
os.makedirs(out, exist_ok=True)
scene = {
    "program": program,
    "meshes": {"m": mesh},
    "sets": {"points": {"mesh": "m", "fields": {
        "x": {"coordinates": "mesh"}, "v": [1, 0, 0]}}},
    "externs": {"h": 1e-3, "g": [0, -2, 0]},
    "step": "step",
    "frames": 3,
    "outputs": [
        {"format": "vtk", "path": "f_{frame}.vtu", "set": "points",
         "fields": ["v"]},
        {"format": "csv", "path": "all.csv", "set": "points",
         "fields": ["x"]},
        {"format": "csv", "path": "last.csv", "set": "points",
         "fields": ["v"], "last": True},
    ],
}
scene_path = os.path.join(out, "scene.json")
with open(scene_path, "w") as f:
    json.dump(scene, f)
outputs = os.path.join(out, "outputs")
command = [simit_run, "--scene", scene_path, "--output-dir", outputs,
           "--no-progress"]
subprocess.run(command, check=True)
earlier = {}
for name in ("all.csv", "last.csv"):
    with open(os.path.join(outputs, name)) as f:
        earlier[name] = f.read()

run = subprocess.Popen(command + ["--frames", "100000"])


def vtu_files():
    return [n for n in os.listdir(outputs)
            if n.endswith(".vtu") and ".tmp-" not in n]


deadline = time.time() + 120
while len(vtu_files()) < 20 and run.poll() is None and time.time() < deadline:
    time.sleep(0.005)
if run.poll() is not None:
    sys.exit("simit-run ended before it could be killed")
run.send_signal(signal.SIGKILL)
run.wait()

complete = 0
for name in sorted(os.listdir(outputs)):
    if ".tmp-" in name:
        continue
    with open(os.path.join(outputs, name)) as f:
        text = f.read()
    if name.endswith(".vtu"):
        if not text.endswith("</VTKFile>\n"):
            sys.exit("truncated: " + name)
    elif text != earlier.get(name):
        sys.exit("changed by the killed run: " + name)
    complete += 1
print("killed after at least 20 frames; %s files under final names, "
      "all complete" % ("20 or more" if complete >= 22 else str(complete)))
