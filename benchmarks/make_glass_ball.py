#!/usr/bin/env python3
"""Writes the glass caustics benchmark's scene (issue 61 item 2): the grey floor of make_glass_panes.py (made
Lambertian: no specular layer), a
clear glass ball (radius 1, KHR_materials_volume, ior 1.5) 1.5 above it and a point light 3.5 above the ball's
centre, seen from above at an angle beside the ball. The ball focuses the light into a bright spot on the floor below
it: rcsplat's --light-through-glass caustics draws it from the glass caustic map, straight shadow rays (the default)
a tinted shadow, and Mitsuba's particle tracer (ptracer) the converged truth.

    python3 benchmarks/make_glass_ball.py OUT_DIR   # writes OUT_DIR/ball.gltf"""
import json
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from make_glass_interior import Mesh  # noqa: E402
from make_glass_panes import grey_floor, write  # noqa: E402

CENTRE, RADIUS, LIGHT_HEIGHT, INTENSITY = (0.0, 2.5, -0.5), 1.0, 6.0, 60.0


def main():
    out = sys.argv[1] if len(sys.argv) > 1 else "glass_ball"
    os.makedirs(out, exist_ok=True)
    floor, grey = grey_floor()
    # Lambertian (no specular layer), as Mitsuba's diffuse: the two floors then agree and the ratios are the glass's.
    grey["extensions"] = {"KHR_materials_specular": {"specularFactor": 0.0}}
    ball = Mesh()
    ball.sphere(CENTRE, RADIUS, rings=48, segments=96)
    glass = {"name": "glass ball", "pbrMetallicRoughness": {"baseColorFactor": [1, 1, 1, 1], "metallicFactor": 0,
                                                            "roughnessFactor": 0},
             "extensions": {"KHR_materials_transmission": {"transmissionFactor": 1.0},
                            "KHR_materials_ior": {"ior": 1.5}, "KHR_materials_volume": {"thicknessFactor": 1.0}}}
    write(out, "ball", [(floor, grey), (ball, glass)])
    path = os.path.join(out, "ball.gltf")
    with open(path) as f:
        doc = json.load(f)
    doc["extensionsUsed"] += ["KHR_lights_punctual", "KHR_materials_specular"]
    doc["extensions"] = {"KHR_lights_punctual": {"lights": [{"type": "point", "intensity": INTENSITY,
                                                              "color": [1, 1, 1]}]}}
    doc["nodes"].append({"translation": [CENTRE[0], LIGHT_HEIGHT, CENTRE[2]],
                         "extensions": {"KHR_lights_punctual": {"light": 0}}})
    doc["scenes"][0]["nodes"].append(len(doc["nodes"]) - 1)
    with open(path, "w") as f:
        json.dump(doc, f, indent=1)


if __name__ == "__main__":
    main()
