#!/usr/bin/env python3
"""Writes Dabrovic Sponza with things that move (issue 62), into OUT_DIR (the scene's files are copied there, since a
scene reads nothing outside its own folder):

  sponza_lift.gltf   animation 0 'Lift' raises node 3 ('object31', 480 of the scene's 66,000 triangles) by 1 m over
                     5 s, LINEAR, before the scene's own still camera: what a move costs on a real scene (item 1).
  sponza_carry.gltf  animation 0 'Carry' moves the camera along the repository's walk
                     (benchmarks/walkthrough/sponza_walk.txt, sampled at 24 frames/s with the walk's own curve:
                     Catmull-Rom over time for eye and target, up and field of view linear) and carries a point lamp
                     with it, 0.4 m above and 0.8 m ahead of the eye (item 4's third scene). The scene's own light
                     stays where it is.

    python3 benchmarks/moving/make_moving_sponza.py SPONZA_DIR OUT_DIR
SPONZA_DIR holds sponza.gltf, sponza.bin and textures/ (../shared/scenes/sponza_dabrovic)."""
import copy
import json
import math
import os
import shutil
import struct
import sys

FPS = 24.0
LAMP_INTENSITY = 12.0  # candela: a hand lamp beside the scene's 157 (its light at 17 m)


def read_walk(path):
    keys = []
    for line in open(path):
        line = line.split("#")[0].split()
        if line:
            v = [float(x) for x in line]
            keys.append({"t": v[0], "eye": v[1:4], "target": v[4:7], "up": v[7:10], "fov": v[10]})
    return keys


def walk_at(keys, t):
    """The walk's pose at t, as host/sequence/camera_path.cpp evaluates a keyframe file."""
    if t <= keys[0]["t"]:
        k = keys[0]
        return k["eye"], k["target"], k["up"], k["fov"]
    if t >= keys[-1]["t"]:
        k = keys[-1]
        return k["eye"], k["target"], k["up"], k["fov"]
    n, k = len(keys), 0
    while k + 2 < n and keys[k + 1]["t"] <= t:
        k += 1

    def tangent(i, name):
        a, b = max(i - 1, 0), min(i + 1, n - 1)
        return [(keys[b][name][c] - keys[a][name][c]) / (keys[b]["t"] - keys[a]["t"]) for c in range(3)]

    h = keys[k + 1]["t"] - keys[k]["t"]
    u = (t - keys[k]["t"]) / h
    u2, u3 = u * u, u * u * u

    def hermite(name):
        m0, m1 = tangent(k, name), tangent(k + 1, name)
        return [(2 * u3 - 3 * u2 + 1) * keys[k][name][c] + (u3 - 2 * u2 + u) * h * m0[c] +
                (-2 * u3 + 3 * u2) * keys[k + 1][name][c] + (u3 - u2) * h * m1[c] for c in range(3)]

    up = [keys[k]["up"][c] + u * (keys[k + 1]["up"][c] - keys[k]["up"][c]) for c in range(3)]
    return hermite("eye"), hermite("target"), up, keys[k]["fov"] + u * (keys[k + 1]["fov"] - keys[k]["fov"])


def normalize(v):
    n = math.sqrt(sum(x * x for x in v))
    return [x / n for x in v]


def cross(a, b):
    return [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]


def look_rotation(forward, up):
    """The unit quaternion (x, y, z, w) that turns a glTF camera (looking down -z, up +y) to look along forward."""
    z = normalize([-f for f in forward])
    x = normalize(cross(up, z))
    y = cross(z, x)
    m = [[x[0], y[0], z[0]], [x[1], y[1], z[1]], [x[2], y[2], z[2]]]  # columns x, y, z
    trace = m[0][0] + m[1][1] + m[2][2]
    if trace > 0:
        s = 2 * math.sqrt(trace + 1)
        return [(m[2][1] - m[1][2]) / s, (m[0][2] - m[2][0]) / s, (m[1][0] - m[0][1]) / s, s / 4]
    i = max(range(3), key=lambda a: m[a][a])
    j, k = (i + 1) % 3, (i + 2) % 3
    s = 2 * math.sqrt(1 + m[i][i] - m[j][j] - m[k][k])
    q = [0.0, 0.0, 0.0, 0.0]
    q[i] = s / 4
    q[j] = (m[j][i] + m[i][j]) / s
    q[k] = (m[k][i] + m[i][k]) / s
    q[3] = (m[k][j] - m[j][k]) / s
    return q


class Buffer:
    """A .bin of float accessors appended to a glTF document."""

    def __init__(self, doc, uri):
        self.doc, self.uri, self.blob = doc, uri, bytearray()
        doc["buffers"].append({"uri": uri, "byteLength": 0})
        self.index = len(doc["buffers"]) - 1

    def floats(self, values, type_, count, minmax=None):
        offset = len(self.blob)
        self.blob += struct.pack("<%df" % len(values), *values)
        self.doc["bufferViews"].append({"buffer": self.index, "byteOffset": offset, "byteLength": len(values) * 4})
        acc = {"bufferView": len(self.doc["bufferViews"]) - 1, "componentType": 5126, "count": count, "type": type_}
        if minmax:
            acc["min"], acc["max"] = minmax
        self.doc["accessors"].append(acc)
        return len(self.doc["accessors"]) - 1

    def write(self, out):
        self.doc["buffers"][self.index]["byteLength"] = len(self.blob)
        with open(os.path.join(out, self.uri), "wb") as f:
            f.write(self.blob)


def lift(doc, out):
    doc = copy.deepcopy(doc)
    buf = Buffer(doc, "lift.bin")
    times = buf.floats([0.0, 5.0], "SCALAR", 2, ([0.0], [5.0]))
    moves = buf.floats([0, 0, 0, 0, 1, 0], "VEC3", 2)
    doc["animations"] = [{"name": "Lift", "samplers": [{"input": times, "output": moves, "interpolation": "LINEAR"}],
                          "channels": [{"sampler": 0, "target": {"node": 3, "path": "translation"}}]}]
    buf.write(out)
    return doc


def carry(doc, out, walk):
    doc = copy.deepcopy(doc)
    keys = read_walk(walk)
    frames = int(round(keys[-1]["t"] * FPS)) + 1
    times, eyes, turns, lamps = [], [], [], []
    for f in range(frames):
        t = f / FPS
        eye, target, up, _ = walk_at(keys, t)
        forward = normalize([target[c] - eye[c] for c in range(3)])
        times.append(t)
        eyes += eye
        turns += look_rotation(forward, up)
        lamps += [eye[c] + 0.4 * normalize(up)[c] + 0.8 * forward[c] for c in range(3)]
    camera_node = next(i for i, n in enumerate(doc["nodes"]) if "camera" in n)
    cam = doc["cameras"][doc["nodes"][camera_node]["camera"]]
    cam["perspective"]["yfov"] = math.radians(keys[0]["fov"])
    for k in ("matrix", "scale"):
        doc["nodes"][camera_node].pop(k, None)
    lights = doc["extensions"]["KHR_lights_punctual"]["lights"]
    lights.append({"type": "point", "name": "carried_lamp", "color": [1.0, 0.85, 0.6], "intensity": LAMP_INTENSITY})
    doc["nodes"].append({"name": "carried_lamp", "translation": lamps[:3],
                         "extensions": {"KHR_lights_punctual": {"light": len(lights) - 1}}})
    lamp_node = len(doc["nodes"]) - 1
    doc["scenes"][doc.get("scene", 0)]["nodes"].append(lamp_node)
    buf = Buffer(doc, "carry.bin")
    t = buf.floats(times, "SCALAR", frames, ([0.0], [times[-1]]))
    e = buf.floats(eyes, "VEC3", frames)
    r = buf.floats(turns, "VEC4", frames)
    l = buf.floats(lamps, "VEC3", frames)
    doc["animations"] = [{"name": "Carry",
                          "samplers": [{"input": t, "output": e}, {"input": t, "output": r}, {"input": t, "output": l}],
                          "channels": [{"sampler": 0, "target": {"node": camera_node, "path": "translation"}},
                                       {"sampler": 1, "target": {"node": camera_node, "path": "rotation"}},
                                       {"sampler": 2, "target": {"node": lamp_node, "path": "translation"}}]}]
    buf.write(out)
    return doc


def main():
    src, out = sys.argv[1], sys.argv[2]
    here = os.path.dirname(os.path.abspath(__file__))
    os.makedirs(out, exist_ok=True)
    shutil.copy(os.path.join(src, "sponza.bin"), out)
    if os.path.isdir(os.path.join(out, "textures")):
        shutil.rmtree(os.path.join(out, "textures"))
    shutil.copytree(os.path.join(src, "textures"), os.path.join(out, "textures"))
    doc = json.load(open(os.path.join(src, "sponza.gltf")))
    for name, scene in (("sponza_lift.gltf", lift(doc, out)),
                        ("sponza_carry.gltf", carry(doc, out, os.path.join(here, "..", "walkthrough", "sponza_walk.txt")))):
        json.dump(scene, open(os.path.join(out, name), "w"), indent=1)
        print(os.path.join(out, name))


if __name__ == "__main__":
    main()
