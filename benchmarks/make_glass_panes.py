#!/usr/bin/env python3
"""Writes the glass benchmark's small glTF scenes (issue 61 item 4): a grey Lambertian floor under a uniform sky, seen
from above at an angle, with one glass object between the sky and the floor and in the camera's view:
  none.gltf   the floor alone (the control: rcsplat and Mitsuba agree on the sky's light on it)
  thin.gltf   a tinted thin-walled pane (KHR_materials_transmission, ior 1.5)
  clear.gltf  the same pane untinted
  slab.gltf   a clear slab 0.3 thick (KHR_materials_volume, ior 1.5)

    python3 benchmarks/make_glass_panes.py OUT_DIR"""
import json
import os
import struct
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from make_glass_interior import Mesh  # noqa: E402


def write(out, name, meshes):
    blob = bytearray()
    views, accessors, gltf_meshes, nodes, materials = [], [], [], [], []

    def add(data, fmt, count, type_, component, minmax=None):
        while len(blob) % 4:
            blob.append(0)
        offset = len(blob)
        blob.extend(struct.pack("<" + fmt * len(data), *data))
        views.append({"buffer": 0, "byteOffset": offset, "byteLength": len(blob) - offset})
        acc = {"bufferView": len(views) - 1, "componentType": component, "count": count, "type": type_}
        if minmax:
            acc["min"], acc["max"] = minmax
        accessors.append(acc)
        return len(accessors) - 1

    for mesh, material in meshes:
        materials.append(material)
        lo = [min(p[k] for p in mesh.p) for k in range(3)]
        hi = [max(p[k] for p in mesh.p) for k in range(3)]
        pos = add([c for p in mesh.p for c in p], "f", len(mesh.p), "VEC3", 5126, (lo, hi))
        nor = add([c for n in mesh.n for c in n], "f", len(mesh.n), "VEC3", 5126)
        idx = add(mesh.i, "I", len(mesh.i), "SCALAR", 5125)
        gltf_meshes.append({"primitives": [{"attributes": {"POSITION": pos, "NORMAL": nor}, "indices": idx,
                                            "material": len(materials) - 1}]})
        nodes.append({"mesh": len(gltf_meshes) - 1})
    # Looking down at 35 degrees from the vertical, toward -z.
    nodes.append({"camera": 0, "translation": [0.0, 5.0, 3.5], "rotation": [-0.4617486, 0.0, 0.0, 0.8870108]})
    with open(os.path.join(out, name + ".bin"), "wb") as f:
        f.write(blob)
    doc = {"asset": {"version": "2.0", "generator": "rcsplat benchmarks/make_glass_panes.py"},
           "extensionsUsed": ["KHR_materials_transmission", "KHR_materials_ior", "KHR_materials_volume"],
           "scene": 0, "scenes": [{"nodes": list(range(len(nodes)))}], "nodes": nodes, "meshes": gltf_meshes,
           "materials": materials,
           "cameras": [{"type": "perspective", "perspective": {"yfov": 0.9, "znear": 0.05, "aspectRatio": 1.0}}],
           "buffers": [{"uri": name + ".bin", "byteLength": len(blob)}], "bufferViews": views, "accessors": accessors}
    with open(os.path.join(out, name + ".gltf"), "w") as f:
        json.dump(doc, f, indent=1)


def grey_floor():
    """The 12 x 12 grey (0.5) Lambertian floor at y = 0 and its material."""
    floor = Mesh()
    floor.quad((-6, 0, 6), (6, 0, 6), (6, 0, -6), (-6, 0, -6))
    grey = {"name": "floor", "pbrMetallicRoughness": {"baseColorFactor": [0.5, 0.5, 0.5, 1], "metallicFactor": 0,
                                                      "roughnessFactor": 1}}
    return floor, grey


def main():
    out = sys.argv[1] if len(sys.argv) > 1 else "glass_panes"
    os.makedirs(out, exist_ok=True)
    floor, grey = grey_floor()
    pane = Mesh()
    pane.quad((-1.5, 1.2, 1.0), (1.5, 1.2, 1.0), (1.5, 1.2, -2.0), (-1.5, 1.2, -2.0))
    thin = {"name": "thin pane", "doubleSided": True,
            "pbrMetallicRoughness": {"baseColorFactor": [0.9, 0.8, 0.6, 1], "metallicFactor": 0, "roughnessFactor": 0},
            "extensions": {"KHR_materials_transmission": {"transmissionFactor": 1.0}, "KHR_materials_ior": {"ior": 1.5}}}
    slab = Mesh()
    slab.box((-1.5, 0.9, -2.0), (1.5, 1.2, 1.0))
    clear = {"name": "slab", "pbrMetallicRoughness": {"baseColorFactor": [1, 1, 1, 1], "metallicFactor": 0,
                                                      "roughnessFactor": 0},
             "extensions": {"KHR_materials_transmission": {"transmissionFactor": 1.0},
                            "KHR_materials_ior": {"ior": 1.5}, "KHR_materials_volume": {"thicknessFactor": 0.3}}}
    write(out, "none", [(floor, grey)])
    write(out, "thin", [(floor, grey), (pane, thin)])
    untinted = json.loads(json.dumps(thin))
    untinted["pbrMetallicRoughness"]["baseColorFactor"] = [1, 1, 1, 1]
    write(out, "clear", [(floor, grey), (pane, untinted)])
    write(out, "slab", [(floor, grey), (slab, clear)])


if __name__ == "__main__":
    main()
