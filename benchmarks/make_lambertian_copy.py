#!/usr/bin/env python3
"""A copy of a glTF scene whose every material is Lambertian (KHR_materials_specular with specularFactor 0: no
specular lobe), its buffers and images read from the original's folder through relative URIs. Separates a photon
map's density-estimation bias from its reflection model (benchmarks/RESULTS.md, issue 13 seventh step: Sponza).

    benchmarks/make_lambertian_copy.py ../shared/scenes/sponza_dabrovic/sponza.gltf OUT_DIR"""
import json
import os
import sys

src, out = sys.argv[1], sys.argv[2]
os.makedirs(out, exist_ok=True)
with open(src) as f:
    g = json.load(f)
for m in g.get("materials", []):
    m.setdefault("extensions", {})["KHR_materials_specular"] = {"specularFactor": 0.0}
if "KHR_materials_specular" not in g.get("extensionsUsed", []):
    g["extensionsUsed"] = g.get("extensionsUsed", []) + ["KHR_materials_specular"]
back = os.path.relpath(os.path.dirname(os.path.abspath(src)), os.path.abspath(out))
for item in g.get("buffers", []) + g.get("images", []):
    if "uri" in item and not item["uri"].startswith("data:"):
        item["uri"] = os.path.join(back, item["uri"]).replace(os.sep, "/")
name = os.path.splitext(os.path.basename(src))[0] + "_lambertian.gltf"
with open(os.path.join(out, name), "w") as f:
    json.dump(g, f)
print(os.path.join(out, name))
