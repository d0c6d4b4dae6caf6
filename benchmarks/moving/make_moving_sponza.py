#!/usr/bin/env python3
"""Writes Sponza (Dabrovic) with one small part moving, to measure what a move costs on a real scene (issue 62
item 1: a frame with one moving object, outside the indirect light, within 1.2x of a frame where nothing moves).
Animation 0 'Lift' raises node 3 ('object31', 480 of the scene's 66,000 triangles) by 1 m over 5 s, LINEAR.

    python3 benchmarks/moving/make_moving_sponza.py SPONZA_DIR OUT_DIR
SPONZA_DIR holds sponza.gltf, sponza.bin and textures/ (../shared/scenes/sponza_dabrovic); they are copied to OUT_DIR,
since a scene reads nothing outside its own folder."""
import json
import os
import shutil
import struct
import sys

src, out = sys.argv[1], sys.argv[2]
os.makedirs(out, exist_ok=True)
shutil.copy(os.path.join(src, "sponza.bin"), out)
if os.path.isdir(os.path.join(out, "textures")):
    shutil.rmtree(os.path.join(out, "textures"))
shutil.copytree(os.path.join(src, "textures"), os.path.join(out, "textures"))
doc = json.load(open(os.path.join(src, "sponza.gltf")))

seconds, node = 5.0, 3
times = [0.0, seconds]
lift = [0.0, 0.0, 0.0, 0.0, 1.0, 0.0]
blob = struct.pack("<2f", *times) + struct.pack("<6f", *lift)
with open(os.path.join(out, "lift.bin"), "wb") as f:
    f.write(blob)
doc["buffers"].append({"uri": "lift.bin", "byteLength": len(blob)})
b = len(doc["buffers"]) - 1
doc["bufferViews"] += [{"buffer": b, "byteOffset": 0, "byteLength": 8}, {"buffer": b, "byteOffset": 8, "byteLength": 24}]
v = len(doc["bufferViews"])
doc["accessors"] += [
    {"bufferView": v - 2, "componentType": 5126, "count": 2, "type": "SCALAR", "min": [0.0], "max": [seconds]},
    {"bufferView": v - 1, "componentType": 5126, "count": 2, "type": "VEC3"},
]
a = len(doc["accessors"])
doc["animations"] = [{"name": "Lift", "samplers": [{"input": a - 2, "output": a - 1, "interpolation": "LINEAR"}],
                      "channels": [{"sampler": 0, "target": {"node": node, "path": "translation"}}]}]
json.dump(doc, open(os.path.join(out, "sponza_lift.gltf"), "w"), indent=1)
print(os.path.join(out, "sponza_lift.gltf"))
