#!/usr/bin/env python3
"""Writes issue 62's held-out animated scenes, each a glTF whose first animation moves a mesh rigidly for 5 s
(120 frames at 24 frames/s) before a still camera:

  crossing.gltf  a box room open toward the camera (white floor, ceiling and back, red left wall, green right wall),
                 lit by a point light under the ceiling; an orange block slides across the floor from left to right:
                 its colour bleed and contact shadow go with it, and where it was must come back to the empty floor.
  door.gltf      a dark room with a doorway in its back wall onto a lit room behind; the door swings open about its
                 hinge over the 5 s, so light spills in through a widening gap.

    python3 benchmarks/make_moving_scenes.py OUT_DIR"""
import json
import math
import os
import struct
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from make_glass_interior import Mesh  # noqa: E402

SECONDS = 5.0


class Gltf:
    def __init__(self):
        self.blob = bytearray()
        self.doc = {"asset": {"version": "2.0", "generator": "rcsplat benchmarks/make_moving_scenes.py"},
                    "extensionsUsed": ["KHR_lights_punctual"], "scene": 0, "scenes": [{"nodes": []}], "nodes": [],
                    "meshes": [], "materials": [], "bufferViews": [], "accessors": [], "animations": []}

    def accessor(self, data, fmt, count, type_, component, minmax=None):
        while len(self.blob) % 4:
            self.blob.append(0)
        offset = len(self.blob)
        self.blob.extend(struct.pack("<" + fmt * len(data), *data))
        self.doc["bufferViews"].append({"buffer": 0, "byteOffset": offset, "byteLength": len(self.blob) - offset})
        acc = {"bufferView": len(self.doc["bufferViews"]) - 1, "componentType": component, "count": count,
               "type": type_}
        if minmax:
            acc["min"], acc["max"] = minmax
        self.doc["accessors"].append(acc)
        return len(self.doc["accessors"]) - 1

    def material(self, name, rgb):
        self.doc["materials"].append({"name": name, "doubleSided": True, "pbrMetallicRoughness": {
            "baseColorFactor": list(rgb) + [1.0], "metallicFactor": 0.0, "roughnessFactor": 1.0}})
        return len(self.doc["materials"]) - 1

    def node(self, node, root=True):
        self.doc["nodes"].append(node)
        index = len(self.doc["nodes"]) - 1
        if root:
            self.doc["scenes"][0]["nodes"].append(index)
        return index

    def mesh(self, parts, name, **node):
        """A node holding one mesh of (Mesh, material) primitives."""
        prims = []
        for mesh, material in parts:
            lo = [min(p[k] for p in mesh.p) for k in range(3)]
            hi = [max(p[k] for p in mesh.p) for k in range(3)]
            pos = self.accessor([c for p in mesh.p for c in p], "f", len(mesh.p), "VEC3", 5126, (lo, hi))
            nor = self.accessor([c for n in mesh.n for c in n], "f", len(mesh.n), "VEC3", 5126)
            idx = self.accessor(mesh.i, "I", len(mesh.i), "SCALAR", 5125)
            prims.append({"attributes": {"POSITION": pos, "NORMAL": nor}, "indices": idx, "material": material})
        self.doc["meshes"].append({"name": name, "primitives": prims})
        return self.node(dict(name=name, mesh=len(self.doc["meshes"]) - 1, **node))

    def animate(self, name, node, path, times, values):
        width = 4 if path == "rotation" else 3
        t = self.accessor(times, "f", len(times), "SCALAR", 5126, ([min(times)], [max(times)]))
        v = self.accessor([c for value in values for c in value], "f", len(values), "VEC%d" % width, 5126)
        self.doc["animations"].append({"name": name, "samplers": [{"input": t, "output": v}],
                                       "channels": [{"sampler": 0, "target": {"node": node, "path": path}}]})

    def camera(self, eye, pitch_degrees=0.0, yfov=0.9):
        self.doc["cameras"] = [{"type": "perspective", "perspective": {"yfov": yfov, "znear": 0.05,
                                                                        "aspectRatio": 4.0 / 3.0}}]
        a = math.radians(pitch_degrees) / 2.0
        self.node({"name": "Camera", "camera": 0, "translation": list(eye), "rotation": [math.sin(a), 0, 0, math.cos(a)]})

    def point_light(self, position, intensity):
        self.doc["extensions"] = {"KHR_lights_punctual": {"lights": [{"type": "point", "intensity": intensity,
                                                                      "color": [1, 1, 1]}]}}
        self.node({"name": "Light", "translation": list(position), "extensions": {"KHR_lights_punctual": {"light": 0}}})

    def write(self, out, name):
        with open(os.path.join(out, name + ".bin"), "wb") as f:
            f.write(self.blob)
        self.doc["buffers"] = [{"uri": name + ".bin", "byteLength": len(self.blob)}]
        with open(os.path.join(out, name + ".gltf"), "w") as f:
            json.dump(self.doc, f, indent=1)


def crossing(out):
    g = Gltf()
    white, red, green = g.material("white", (0.75, 0.75, 0.75)), g.material("red", (0.7, 0.1, 0.08)), \
        g.material("green", (0.12, 0.6, 0.1))
    orange = g.material("orange", (0.9, 0.45, 0.08))
    walls, left, right = Mesh(), Mesh(), Mesh()
    walls.quad((-2, 0, 2), (2, 0, 2), (2, 0, -2), (-2, 0, -2))   # floor, +y
    walls.quad((-2, 3, -2), (2, 3, -2), (2, 3, 2), (-2, 3, 2))   # ceiling, -y
    walls.quad((-2, 0, -2), (2, 0, -2), (2, 3, -2), (-2, 3, -2))  # back, +z
    left.quad((-2, 0, 2), (-2, 0, -2), (-2, 3, -2), (-2, 3, 2))   # left, +x
    right.quad((2, 0, -2), (2, 0, 2), (2, 3, 2), (2, 3, -2))      # right, -x
    g.mesh([(walls, white), (left, red), (right, green)], "Room")
    block = Mesh()
    block.box((-0.4, 0.0, -0.4), (0.4, 0.8, 0.4))
    node = g.mesh([(block, orange)], "Block", translation=[-1.4, 0.0, -0.3])
    g.animate("Cross", node, "translation", [0.0, SECONDS], [(-1.4, 0.0, -0.3), (1.4, 0.0, -0.3)])
    g.point_light((0.0, 2.7, 0.3), 25.0)
    g.camera((0.0, 1.5, 5.2), -5.0)
    g.write(out, "crossing")


def door(out):
    g = Gltf()
    white, blue = g.material("white", (0.75, 0.75, 0.75)), g.material("blue", (0.15, 0.25, 0.7))
    wood = g.material("door", (0.55, 0.35, 0.2))
    front, back = Mesh(), Mesh()
    # The dark room, z in [-2, 2], open toward the camera; its back wall at z = -2 has a doorway x in [-0.5, 0.5],
    # y in [0, 2].
    front.quad((-2, 0, 2), (2, 0, 2), (2, 0, -2), (-2, 0, -2))
    front.quad((-2, 3, -2), (2, 3, -2), (2, 3, 2), (-2, 3, 2))
    front.quad((-2, 0, 2), (-2, 0, -2), (-2, 3, -2), (-2, 3, 2))
    front.quad((2, 0, -2), (2, 0, 2), (2, 3, 2), (2, 3, -2))
    front.quad((-2, 0, -2), (-0.5, 0, -2), (-0.5, 3, -2), (-2, 3, -2))
    front.quad((0.5, 0, -2), (2, 0, -2), (2, 3, -2), (0.5, 3, -2))
    front.quad((-0.5, 2, -2), (0.5, 2, -2), (0.5, 3, -2), (-0.5, 3, -2))
    # The lit room behind, z in [-6, -2].
    back.quad((-2, 0, -2), (2, 0, -2), (2, 0, -6), (-2, 0, -6))
    back.quad((-2, 3, -6), (2, 3, -6), (2, 3, -2), (-2, 3, -2))
    back.quad((-2, 0, -6), (2, 0, -6), (2, 3, -6), (-2, 3, -6))
    back.quad((-2, 0, -2), (-2, 0, -6), (-2, 3, -6), (-2, 3, -2))
    back.quad((2, 0, -6), (2, 0, -2), (2, 3, -2), (2, 3, -6))
    g.mesh([(front, white), (back, blue)], "Rooms")
    slab = Mesh()
    slab.box((0.0, 0.0, -0.03), (1.0, 2.0, 0.03))
    hinge = g.mesh([(slab, wood)], "Door", translation=[-0.5, 0.0, -2.0])
    # Closed at 0 s; swung 100 degrees into the dark room by 5 s (about +y at the hinge, x = -0.5).
    keys = [0.0, 1.0, 2.0, 3.0, 4.0, SECONDS]
    g.animate("Open", hinge, "rotation", keys,
              [(0.0, math.sin(math.radians(-50.0 * k / SECONDS) * 1.0), 0.0, math.cos(math.radians(-50.0 * k / SECONDS)))
               for k in keys])
    g.point_light((0.0, 2.6, -4.5), 30.0)
    g.camera((0.6, 1.5, 1.9), -3.0)
    g.write(out, "door")


def main():
    out = sys.argv[1] if len(sys.argv) > 1 else "moving_scenes"
    os.makedirs(out, exist_ok=True)
    crossing(out)
    door(out)


if __name__ == "__main__":
    main()
