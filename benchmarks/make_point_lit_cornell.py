#!/usr/bin/env python3
"""The Cornell box of ../shared/scenes (CornellBox-Original) lit by a point light instead of its ceiling emitter: the
light quad's node removed and a KHR_lights_punctual point light (intensity 3, warm white) put under the quad's
centre at y = 1.6. It shows the photon map's bias under a point light (benchmarks/RESULTS.md, issue 13 sixth step).

    benchmarks/make_point_lit_cornell.py ../shared/scenes/cornell_box_mcguire OUT_DIR"""
import json
import os
import shutil
import sys

src, out = sys.argv[1], sys.argv[2]
os.makedirs(out, exist_ok=True)
with open(os.path.join(src, "CornellBox-Original.gltf")) as f:
    g = json.load(f)
light = next(i for i, n in enumerate(g["nodes"]) if n["name"] == "light")
positions = g["accessors"][g["meshes"][g["nodes"][light]["mesh"]]["primitives"][0]["attributes"]["POSITION"]]
centre = [(lo + hi) / 2 for lo, hi in zip(positions["min"], positions["max"])]
del g["nodes"][light]
for scene in g["scenes"]:
    scene["nodes"] = [n if n < light else n - 1 for n in scene["nodes"] if n != light]
g["extensionsUsed"] = g.get("extensionsUsed", []) + ["KHR_lights_punctual"]
g.setdefault("extensions", {})["KHR_lights_punctual"] = {
    "lights": [{"type": "point", "color": [1, 0.85, 0.6], "intensity": 3.0}]}
g["nodes"].append({"name": "point_light", "translation": [centre[0], 1.6, centre[2]],
                   "extensions": {"KHR_lights_punctual": {"light": 0}}})
g["scenes"][g.get("scene", 0)]["nodes"].append(len(g["nodes"]) - 1)
with open(os.path.join(out, "cornell_point_light.gltf"), "w") as f:
    json.dump(g, f)
shutil.copy(os.path.join(src, "CornellBox-Original.bin"), out)
