#!/usr/bin/env python3
"""Writes rcsplat's own glTF interior for issue 61: a 6 x 3 x 5 m room whose front wall has two glass windows
(thin-walled KHR_materials_transmission), brick walls with a normal map (tangents left to the loader), a table, a
glass vase with a volume (KHR_materials_volume, tinted), a clearcoated ball (KHR_materials_clearcoat) and a sheen
cushion (KHR_materials_sheen), and a camera inside looking at the windows. Light comes from outside: render it with
an environment map whose sun shines through the windows (benchmarks/make_sky.py; benchmarks/glass_interior.sh does
both).

    python3 benchmarks/make_glass_interior.py OUT_DIR

Writes OUT_DIR/glass_interior.gltf, .bin and bricks_normal.png. Pure Python (struct, zlib): no dependency."""
import json
import math
import os
import struct
import sys
import zlib


class Mesh:
    """Triangles of one material: positions, normals, uvs, indices."""

    def __init__(self):
        self.p, self.n, self.uv, self.i = [], [], [], []

    def quad(self, a, b, c, d, uv_scale=1.0):
        """A planar quad a b c d (counter-clockwise seen from the side it faces), uvs in metres times uv_scale."""
        e1 = [b[k] - a[k] for k in range(3)]
        e2 = [d[k] - a[k] for k in range(3)]
        n = [e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2], e1[0] * e2[1] - e1[1] * e2[0]]
        length = math.sqrt(sum(x * x for x in n))
        n = [x / length for x in n]
        w, h = math.sqrt(sum(x * x for x in e1)), math.sqrt(sum(x * x for x in e2))
        base = len(self.p)
        for q, (s, t) in zip((a, b, c, d), ((0, 0), (w, 0), (w, h), (0, h))):
            self.p.append(list(q))
            self.n.append(n)
            self.uv.append([s * uv_scale, -t * uv_scale])
        self.i += [base, base + 1, base + 2, base, base + 2, base + 3]

    def box(self, lo, hi):
        """An axis-aligned box, its faces wound outward."""
        x0, y0, z0 = lo
        x1, y1, z1 = hi
        self.quad((x0, y1, z1), (x1, y1, z1), (x1, y1, z0), (x0, y1, z0))  # top, +y
        self.quad((x0, y0, z0), (x1, y0, z0), (x1, y0, z1), (x0, y0, z1))  # bottom, -y
        self.quad((x0, y0, z1), (x1, y0, z1), (x1, y1, z1), (x0, y1, z1))  # +z
        self.quad((x1, y0, z0), (x0, y0, z0), (x0, y1, z0), (x1, y1, z0))  # -z
        self.quad((x1, y0, z1), (x1, y0, z0), (x1, y1, z0), (x1, y1, z1))  # +x
        self.quad((x0, y0, z0), (x0, y0, z1), (x0, y1, z1), (x0, y1, z0))  # -x

    def sphere(self, centre, radius, rings=24, segments=48):
        base = len(self.p)
        for r in range(rings + 1):
            theta = math.pi * r / rings
            for s in range(segments + 1):
                phi = 2.0 * math.pi * s / segments
                n = [math.sin(theta) * math.cos(phi), math.cos(theta), math.sin(theta) * math.sin(phi)]
                self.p.append([centre[k] + radius * n[k] for k in range(3)])
                self.n.append(n)
                self.uv.append([s / segments, r / rings])
        for r in range(rings):
            for s in range(segments):
                a = base + r * (segments + 1) + s
                b = a + segments + 1
                self.i += [a, a + 1, b, a + 1, b + 1, b]

    def cylinder(self, centre, radius, height, segments=48):
        """A closed cylinder standing on centre, wound outward (a volume)."""
        cx, cy, cz = centre
        for s in range(segments):
            a0, a1 = 2 * math.pi * s / segments, 2 * math.pi * (s + 1) / segments
            p0 = (cx + radius * math.cos(a0), cz + radius * math.sin(a0))
            p1 = (cx + radius * math.cos(a1), cz + radius * math.sin(a1))
            base = len(self.p)
            quad = [(p0[0], cy, p0[1]), (p0[0], cy + height, p0[1]), (p1[0], cy + height, p1[1]), (p1[0], cy, p1[1])]
            for q, a in zip(quad, (a0, a0, a1, a1)):
                self.p.append(list(q))
                self.n.append([math.cos(a), 0.0, math.sin(a)])
                self.uv.append([a / (2 * math.pi), q[1] - cy])
            self.i += [base, base + 1, base + 2, base, base + 2, base + 3]
            for y, up in ((cy + height, 1.0), (cy, -1.0)):  # caps
                base = len(self.p)
                for q in ((cx, y, cz), (p0[0], y, p0[1]), (p1[0], y, p1[1])):
                    self.p.append(list(q))
                    self.n.append([0.0, up, 0.0])
                    self.uv.append([0.0, 0.0])
                self.i += [base, base + 2, base + 1] if up > 0 else [base, base + 1, base + 2]


def png(width, height, rgb_rows):
    raw = b"".join(b"\x00" + bytes(row) for row in rgb_rows)

    def chunk(kind, data):
        return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data) & 0xFFFFFFFF)

    return (b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", width, height, 8, 2, 0, 0, 0)) +
            chunk(b"IDAT", zlib.compress(raw, 9)) + chunk(b"IEND", b""))


def brick_normal_map(size=256):
    """Bricks 2 x 1 of a 4 x 8 grid with bevelled mortar joints: tangent-space normals, +z out of the wall."""
    rows = []
    bricks_x, bricks_y, bevel = 4, 8, 0.06
    for j in range(size):
        row = []
        v = (j + 0.5) / size * bricks_y
        course = int(v)
        fy = v - course
        for i in range(size):
            u = (i + 0.5) / size * bricks_x + (0.5 if course % 2 else 0.0)
            fx = u - math.floor(u)
            nx = ny = 0.0
            if fx < bevel:
                nx = -0.7
            elif fx > 1.0 - bevel:
                nx = 0.7
            if fy < bevel:
                ny = 0.7
            elif fy > 1.0 - bevel:
                ny = -0.7
            nz = math.sqrt(max(1.0 - nx * nx - ny * ny, 0.05))
            length = math.sqrt(nx * nx + ny * ny + nz * nz)
            row += [int(round((c / length * 0.5 + 0.5) * 255)) for c in (nx, ny, nz)]
        rows.append(row)
    return png(size, size, rows)


def main():
    out = sys.argv[1] if len(sys.argv) > 1 else "glass_interior"
    os.makedirs(out, exist_ok=True)
    W, H, D = 6.0, 3.0, 5.0  # x, y, z; the window wall is z = 0, the camera looks toward -z
    meshes = {name: Mesh() for name in ("walls", "floor", "ceiling", "glass", "table", "vase", "ball", "cushion")}
    walls = meshes["walls"]
    # Window wall (z = 0, facing +z) around two openings.
    sill, lintel = 0.9, 2.4
    openings = [(1.0, 2.5), (3.5, 5.0)]
    xs = [0.0] + [x for o in openings for x in o] + [W]
    walls.quad((0, 0, 0), (W, 0, 0), (W, sill, 0), (0, sill, 0))
    walls.quad((0, lintel, 0), (W, lintel, 0), (W, H, 0), (0, H, 0))
    for k in range(0, len(xs), 2):  # the piers beside and between the openings
        walls.quad((xs[k], sill, 0), (xs[k + 1], sill, 0), (xs[k + 1], lintel, 0), (xs[k], lintel, 0))
    walls.quad((W, 0, D), (0, 0, D), (0, H, D), (W, H, D))  # back wall, facing -z
    walls.quad((0, 0, D), (0, 0, 0), (0, H, 0), (0, H, D))  # left, facing +x
    walls.quad((W, 0, 0), (W, 0, D), (W, H, D), (W, H, 0))  # right, facing -x
    meshes["floor"].quad((0, 0, D), (W, 0, D), (W, 0, 0), (0, 0, 0))
    meshes["ceiling"].quad((0, H, 0), (W, H, 0), (W, H, D), (0, H, D))
    for x0, x1 in openings:  # thin-walled panes, set a little into the openings
        meshes["glass"].quad((x0, sill, 0.05), (x1, sill, 0.05), (x1, lintel, 0.05), (x0, lintel, 0.05))
    meshes["table"].box((2.2, 0.70, 1.6), (3.8, 0.76, 2.6))
    for x, z in ((2.3, 1.7), (3.7, 1.7), (2.3, 2.5), (3.7, 2.5)):
        meshes["table"].box((x - 0.04, 0.0, z - 0.04), (x + 0.04, 0.70, z + 0.04))
    meshes["vase"].cylinder((3.3, 0.76, 2.1), 0.12, 0.35)
    meshes["ball"].sphere((2.7, 0.96, 2.1), 0.2)
    meshes["cushion"].box((0.4, 0.0, 3.2), (1.4, 0.25, 4.2))

    materials = [
        {"name": "brick", "pbrMetallicRoughness": {"baseColorFactor": [0.62, 0.36, 0.28, 1], "metallicFactor": 0,
                                                    "roughnessFactor": 0.9},
         "normalTexture": {"index": 0, "scale": 1.0}},
        {"name": "oak floor", "pbrMetallicRoughness": {"baseColorFactor": [0.45, 0.32, 0.2, 1], "metallicFactor": 0,
                                                        "roughnessFactor": 0.55}},
        {"name": "ceiling", "pbrMetallicRoughness": {"baseColorFactor": [0.85, 0.85, 0.82, 1], "metallicFactor": 0,
                                                      "roughnessFactor": 1}},
        {"name": "window glass", "doubleSided": True,
         "pbrMetallicRoughness": {"baseColorFactor": [0.92, 0.96, 0.95, 1], "metallicFactor": 0, "roughnessFactor": 0},
         "extensions": {"KHR_materials_transmission": {"transmissionFactor": 1.0},
                        "KHR_materials_ior": {"ior": 1.52}}},
        {"name": "table", "pbrMetallicRoughness": {"baseColorFactor": [0.3, 0.18, 0.1, 1], "metallicFactor": 0,
                                                    "roughnessFactor": 0.7}},
        {"name": "vase glass",
         "pbrMetallicRoughness": {"baseColorFactor": [1, 1, 1, 1], "metallicFactor": 0, "roughnessFactor": 0},
         "extensions": {"KHR_materials_transmission": {"transmissionFactor": 1.0},
                        "KHR_materials_ior": {"ior": 1.5},
                        "KHR_materials_volume": {"thicknessFactor": 0.24, "attenuationDistance": 0.3,
                                                 "attenuationColor": [0.4, 0.75, 0.55]}}},
        {"name": "clearcoat ball",
         "pbrMetallicRoughness": {"baseColorFactor": [0.6, 0.05, 0.04, 1], "metallicFactor": 0,
                                  "roughnessFactor": 0.5},
         "extensions": {"KHR_materials_clearcoat": {"clearcoatFactor": 1.0, "clearcoatRoughnessFactor": 0.05}}},
        {"name": "sheen cushion",
         "pbrMetallicRoughness": {"baseColorFactor": [0.12, 0.14, 0.35, 1], "metallicFactor": 0,
                                  "roughnessFactor": 1},
         "extensions": {"KHR_materials_sheen": {"sheenColorFactor": [0.8, 0.8, 1.0], "sheenRoughnessFactor": 0.4}}},
    ]
    material_of = {"walls": 0, "floor": 1, "ceiling": 2, "glass": 3, "table": 4, "vase": 5, "ball": 6, "cushion": 7}

    blob = bytearray()
    views, accessors, gltf_meshes, nodes = [], [], [], []

    def add(data, fmt, count, type_, component, target, minmax=None):
        while len(blob) % 4:
            blob.append(0)
        offset = len(blob)
        blob.extend(struct.pack("<" + fmt * (len(data)), *data))
        views.append({"buffer": 0, "byteOffset": offset, "byteLength": len(blob) - offset, "target": target})
        acc = {"bufferView": len(views) - 1, "componentType": component, "count": count, "type": type_}
        if minmax:
            acc["min"], acc["max"] = minmax
        accessors.append(acc)
        return len(accessors) - 1

    for name, m in meshes.items():
        flat = [c for p in m.p for c in p]
        lo = [min(p[k] for p in m.p) for k in range(3)]
        hi = [max(p[k] for p in m.p) for k in range(3)]
        pos = add(flat, "f", len(m.p), "VEC3", 5126, 34962, (lo, hi))
        nor = add([c for n in m.n for c in n], "f", len(m.n), "VEC3", 5126, 34962)
        uv = add([c for t in m.uv for c in t], "f", len(m.uv), "VEC2", 5126, 34962)
        idx = add(m.i, "I", len(m.i), "SCALAR", 5125, 34963)
        gltf_meshes.append({"name": name, "primitives": [{"attributes": {"POSITION": pos, "NORMAL": nor,
                                                                           "TEXCOORD_0": uv},
                                                            "indices": idx, "material": material_of[name]}]})
        nodes.append({"name": name, "mesh": len(gltf_meshes) - 1})
    # The camera inside by the back wall, looking at the windows and a little down.
    eye, target = (3.0, 1.55, 4.6), (3.0, 1.05, 0.0)
    f = [target[k] - eye[k] for k in range(3)]
    length = math.sqrt(sum(x * x for x in f))
    f = [x / length for x in f]
    pitch = math.asin(f[1])  # rotation about +x turning -z toward f (here f has no x)
    q = [math.sin(pitch / 2), 0.0, 0.0, math.cos(pitch / 2)]
    nodes.append({"name": "camera", "camera": 0, "translation": list(eye), "rotation": q})

    with open(os.path.join(out, "glass_interior.bin"), "wb") as fh:
        fh.write(blob)
    with open(os.path.join(out, "bricks_normal.png"), "wb") as fh:
        fh.write(brick_normal_map())
    doc = {
        "asset": {"version": "2.0", "generator": "rcsplat benchmarks/make_glass_interior.py"},
        "extensionsUsed": ["KHR_materials_transmission", "KHR_materials_ior", "KHR_materials_volume",
                           "KHR_materials_clearcoat", "KHR_materials_sheen"],
        "scene": 0,
        "scenes": [{"nodes": list(range(len(nodes)))}],
        "nodes": nodes,
        "meshes": gltf_meshes,
        "materials": materials,
        "cameras": [{"type": "perspective", "perspective": {"yfov": 1.05, "znear": 0.05, "aspectRatio": 4 / 3}}],
        "images": [{"uri": "bricks_normal.png"}],
        "samplers": [{"wrapS": 10497, "wrapT": 10497}],
        "textures": [{"source": 0, "sampler": 0}],
        "buffers": [{"uri": "glass_interior.bin", "byteLength": len(blob)}],
        "bufferViews": views,
        "accessors": accessors,
    }
    with open(os.path.join(out, "glass_interior.gltf"), "w") as fh:
        json.dump(doc, fh, indent=1)
    print(os.path.join(out, "glass_interior.gltf"))


if __name__ == "__main__":
    main()
