#!/usr/bin/env python3
"""Writes the layers' Mitsuba benchmark scenes (issue 61 item 4): a grey Lambertian floor under a uniform sky, seen
from above at an angle, and one sphere on it of a rough dielectric (base colour (0.5, 0.3, 0.2), roughness 0.5):
  base.gltf   the sphere as it is (the control)
  coat.gltf   under a clearcoat (KHR_materials_clearcoat, factor 1, roughness 0.1)
  sheen.gltf  under a white sheen (KHR_materials_sheen, roughness 0.5)

    python3 benchmarks/make_layer_spheres.py OUT_DIR"""
import json
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from make_glass_interior import Mesh  # noqa: E402
from make_glass_panes import grey_floor, write  # noqa: E402

CENTRE, RADIUS = (0.0, 1.0, -0.5), 1.0


def main():
    out = sys.argv[1] if len(sys.argv) > 1 else "layer_spheres"
    os.makedirs(out, exist_ok=True)
    floor, grey = grey_floor()
    sphere = Mesh()
    sphere.sphere(CENTRE, RADIUS, rings=48, segments=96)
    base = {"name": "sphere", "pbrMetallicRoughness": {"baseColorFactor": [0.5, 0.3, 0.2, 1], "metallicFactor": 0,
                                                       "roughnessFactor": 0.5}}
    layers = {"base": {},
              "coat": {"KHR_materials_clearcoat": {"clearcoatFactor": 1.0, "clearcoatRoughnessFactor": 0.1}},
              "sheen": {"KHR_materials_sheen": {"sheenColorFactor": [1.0, 1.0, 1.0], "sheenRoughnessFactor": 0.5}}}
    for name, extensions in layers.items():
        material = json.loads(json.dumps(base))
        if extensions:
            material["extensions"] = extensions
        write(out, name, [(floor, grey), (sphere, material)])


if __name__ == "__main__":
    main()
