#!/usr/bin/env python3
"""Mitsuba 3 as a peer (issue 12): renders the glTF subset rcsplat simulates with Mitsuba's path tracer (llvm_ad_rgb)
from the view and bounce count of an rcsplat reference, and reports
  (a) agreement: Mitsuba's converged image against rcsplat's reference, mean ratio per channel (over pixels whose
      reference is not black) and relMSE of 8x8 block means: this validates rcsplat's ground truth. Pixel sampling
      differs a little (Mitsuba: a box filter over the pixel; rcsplat's reference: a 4x4 sub-pixel grid).
  (b) equal error: the seconds Mitsuba's path tracer needs to reach the error of an rcsplat cache render, each
      against its own converged image (rcsplat's cache against rcsplat's reference, Mitsuba against Mitsuba's
      converged render), per-pixel relMSE and block relMSE of the full image, interpolated in log-log between
      the sample counts that bracket it.

The glTF subset: triangle meshes (node transforms, POSITION, NORMAL, TEXCOORD_0, indices), base colour factor and
texture (sRGB), metallic and roughness factors (rcsplat's own BRDF as a Mitsuba plugin, benchmarks/
mitsuba_gltf_bsdf.py: Mitsuba has no glTF material, and its roughplastic and principled differ from it by 15-30% on a
rough Cornell box), emissive factor and strength (area lights), KHR_lights_punctual point, spot and directional lights (intensity as radiant intensity, as rcsplat reads
it), glass (KHR_materials_transmission with factor 1: thin-walled as Mitsuba's thindielectric, with a
KHR_materials_volume as its dielectric, ior from KHR_materials_ior, the base colour as the transmission's tint), and
a uniform sky (--sky) as a constant emitter. Not converted (named when met): textures other than base colour, vertex
colours, alpha, a transmission factor below 1, a volume's attenuation, environment maps, the range of punctual lights.
A scene without lights gets rcsplat's default light in rcsplat but none here: refused. The two thin-walled models
differ by design: glTF's (rcsplat's) is one interface, passing 1 - R; Mitsuba's thindielectric is a slab's two,
passing (1 - R) / (1 + R) with the light bouncing between them.

  bash benchmarks/setup_python.sh          # once
  benchmarks/.venv/bin/python benchmarks/mitsuba_peer.py SCENE.gltf --reference REF.exr [--cache CACHE.exr] \\
      [--converged-spp 1024] [--spp 4,16,64,256] [-o DIR] [--json OUT.json]
"""
import argparse
import base64
import glob
import json
import math
import os
import struct
import sys
import time

import numpy as np

from rcsplat_images import attributes, read_layer, write_exr

COMPONENT = {5120: np.int8, 5121: np.uint8, 5122: np.int16, 5123: np.uint16, 5125: np.uint32, 5126: np.float32}
DIFFUSE_ONLY = False  # --bsdf diffuse
PRINCIPLED = False  # --bsdf principled
COUNT = {"SCALAR": 1, "VEC2": 2, "VEC3": 3, "VEC4": 4, "MAT4": 16}


def find_llvm():
    if os.environ.get("DRJIT_LIBLLVM_PATH"):
        return
    for pattern in ["/usr/lib/x86_64-linux-gnu/libLLVM.so.19*", "/usr/lib/llvm-19/lib/libLLVM*.so*",
                    "/usr/lib/*/libLLVM-1[7-9]*.so*"]:
        found = sorted(glob.glob(pattern))
        if found:
            os.environ["DRJIT_LIBLLVM_PATH"] = found[0]
            return


class Gltf:
    """Just enough glTF 2.0 to hand Mitsuba what rcsplat renders."""

    def __init__(self, path):
        self.path, self.dir = path, os.path.dirname(os.path.abspath(path))
        with open(path) as f:
            self.doc = json.load(f)
        self.buffers = [self._buffer(b) for b in self.doc.get("buffers", [])]
        self.skipped = set()

    def _buffer(self, b):
        uri = b["uri"]
        if uri.startswith("data:"):
            return base64.b64decode(uri.split(",", 1)[1])
        with open(os.path.join(self.dir, uri), "rb") as f:
            return f.read()

    def accessor(self, index):
        a = self.doc["accessors"][index]
        view = self.doc["bufferViews"][a["bufferView"]]
        dtype, n = np.dtype(COMPONENT[a["componentType"]]), COUNT[a["type"]]
        data = self.buffers[view["buffer"]]
        offset = view.get("byteOffset", 0) + a.get("byteOffset", 0)
        stride = view.get("byteStride", dtype.itemsize * n)
        rows = np.lib.stride_tricks.as_strided(np.frombuffer(data, dtype=np.uint8, offset=offset),
                                               shape=(a["count"], dtype.itemsize * n), strides=(stride, 1))
        out = np.frombuffer(rows.copy().tobytes(), dtype=dtype).reshape(a["count"], n).astype(np.float64)
        if a.get("normalized"):
            out /= float(np.iinfo(dtype).max)
        return out

    @staticmethod
    def local_matrix(node):
        if "matrix" in node:
            return np.array(node["matrix"], dtype=np.float64).reshape(4, 4).T
        t = np.array(node.get("translation", [0, 0, 0]), dtype=np.float64)
        x, y, z, w = node.get("rotation", [0, 0, 0, 1])
        r = np.array([[1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)],
                      [2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)],
                      [2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)]])
        s = np.array(node.get("scale", [1, 1, 1]), dtype=np.float64)
        m = np.eye(4)
        m[:3, :3] = r * s
        m[:3, 3] = t
        return m

    def _walk(self):
        """(node, world matrix) for every node of the default scene."""
        scene = self.doc["scenes"][self.doc.get("scene", 0)]
        stack = [(n, np.eye(4)) for n in scene["nodes"]]
        while stack:
            index, parent = stack.pop()
            node = self.doc["nodes"][index]
            world = parent @ self.local_matrix(node)
            yield node, world
            stack.extend((c, world) for c in node.get("children", []))

    def instances(self):
        """(mesh index, world matrix) for every node with a mesh."""
        return [(node["mesh"], world) for node, world in self._walk() if "mesh" in node]

    def first_camera(self):
        """(eye, target, up, vertical fov in degrees) of the first node carrying a perspective camera."""
        for node, world in self._walk():
            if "camera" in node:
                cam = self.doc["cameras"][node["camera"]]
                if cam.get("type") != "perspective":
                    break
                eye = world[:3, 3]
                forward = world[:3, :3] @ np.array([0.0, 0.0, -1.0])
                up = world[:3, :3] @ np.array([0.0, 1.0, 0.0])
                return eye.tolist(), (eye + forward).tolist(), up.tolist(), math.degrees(cam["perspective"]["yfov"])
        sys.exit("mitsuba_peer: the reference has no rcsplat:camera and the scene no perspective camera")

    def lights(self):
        """(KHR_lights_punctual light, world matrix) for every node that carries one."""
        defs = self.doc.get("extensions", {}).get("KHR_lights_punctual", {}).get("lights", [])
        for node, world in self._walk():
            light = node.get("extensions", {}).get("KHR_lights_punctual")
            if light is not None:
                yield defs[light["light"]], world


def write_ply(path, positions, normals, uvs, faces):
    """Binary little-endian PLY: float x y z [nx ny nz] [u v], faces as uchar-counted int lists."""
    with open(path, "wb") as f:
        header = ["ply", "format binary_little_endian 1.0", f"element vertex {len(positions)}",
                  "property float x", "property float y", "property float z"]
        cols = [positions]
        if normals is not None:
            header += ["property float nx", "property float ny", "property float nz"]
            cols.append(normals)
        if uvs is not None:
            header += ["property float u", "property float v"]
            cols.append(uvs)
        header += [f"element face {len(faces)}", "property list uchar int vertex_indices", "end_header"]
        f.write(("\n".join(header) + "\n").encode())
        f.write(np.hstack(cols).astype("<f4").tobytes())
        face_rows = np.zeros(len(faces), dtype=[("n", "u1"), ("i", "<i4", 3)])
        face_rows["n"], face_rows["i"] = 3, faces
        f.write(face_rows.tobytes())


def texture_path(g, info):
    tex = g.doc["textures"][info["index"]]
    image = g.doc["images"][tex["source"]]
    if "uri" not in image or image["uri"].startswith("data:"):
        g.skipped.add("embedded texture images")
        return None
    return os.path.join(g.dir, image["uri"])


def bsdf_and_emitter(g, material_index):
    m = g.doc["materials"][material_index] if material_index is not None else {}
    pbr = m.get("pbrMetallicRoughness", {})
    factor = pbr.get("baseColorFactor", [1, 1, 1, 1])[:3]
    base = {"type": "rgb", "value": factor}
    if "baseColorTexture" in pbr:
        path = texture_path(g, pbr["baseColorTexture"])
        if path:
            base = {"type": "bitmap", "filename": path, "raw": False, "filter_type": "bilinear"}
            if any(abs(c - 1.0) > 1e-6 for c in factor):
                g.skipped.add("base colour factor times texture (the texture alone is used)")
    for key in ("normalTexture", "occlusionTexture", "emissiveTexture"):
        if key in m:
            g.skipped.add(key)
    if "metallicRoughnessTexture" in pbr:
        g.skipped.add("metallicRoughnessTexture")
    if m.get("alphaMode", "OPAQUE") != "OPAQUE":
        g.skipped.add("alpha")
    metallic, roughness = pbr.get("metallicFactor", 1.0), pbr.get("roughnessFactor", 1.0)
    extensions = m.get("extensions", {})
    transmission = extensions.get("KHR_materials_transmission", {}).get("transmissionFactor", 0.0)
    if transmission > 0.0:
        if transmission < 1.0 or metallic > 0.0 or roughness > 0.0:
            g.skipped.add("glass that is partly opaque, metallic or rough (converted as smooth glass all over)")
        ior = extensions.get("KHR_materials_ior", {}).get("ior", 1.5)
        volume = extensions.get("KHR_materials_volume", {})
        if "attenuationDistance" in volume:
            g.skipped.add("a volume's attenuation (clear here)")
        thick = volume.get("thicknessFactor", 0.0) > 0.0
        glass = {"type": "dielectric" if thick else "thindielectric", "int_ior": ior, "ext_ior": 1.0,
                 "specular_transmittance": base,
                 "specular_reflectance": extensions.get("KHR_materials_specular", {}).get("specularFactor", 1.0)}
        return glass, None
    if DIFFUSE_ONLY:
        bsdf = {"type": "diffuse", "reflectance": base}
    elif PRINCIPLED:
        # Mitsuba's principled BSDF (Disney's), with glTF's clearcoat and sheen mapped onto its own: a clearcoat of
        # alpha lerp(0.1, 0.001, gloss) (GTR1) for glTF's GGX alpha = roughness^2, and a sheen of its colour's
        # strongest channel (untinted). specular 0.5 is F0 0.04. The models differ (benchmarks/layers_mitsuba.sh).
        coat = extensions.get("KHR_materials_clearcoat", {})
        sheen = extensions.get("KHR_materials_sheen", {})
        coat_alpha = coat.get("clearcoatRoughnessFactor", 0.0) ** 2
        bsdf = {"type": "principled", "base_color": base, "metallic": metallic, "roughness": roughness,
                "specular": 0.5, "clearcoat": coat.get("clearcoatFactor", 0.0),
                "clearcoat_gloss": min(max((0.1 - coat_alpha) / 0.099, 0.0), 1.0),
                "sheen": max(sheen.get("sheenColorFactor", [0.0, 0.0, 0.0])), "sheen_tint": 0.0}
        for key in ("clearcoatTexture", "clearcoatRoughnessTexture", "clearcoatNormalTexture", "sheenColorTexture",
                    "sheenRoughnessTexture"):
            if key in coat or key in sheen:
                g.skipped.add("layer textures")
    else:
        bsdf = {"type": "rcsplat_gltf", "base_color": base, "metallic": metallic, "roughness": roughness}
    bsdf = {"type": "twosided", "bsdf": bsdf}
    strength = m.get("extensions", {}).get("KHR_materials_emissive_strength", {}).get("emissiveStrength", 1.0)
    emissive = [c * strength for c in m.get("emissiveFactor", [0, 0, 0])]
    emitter = {"type": "area", "radiance": {"type": "rgb", "value": emissive}} if max(emissive) > 0 else None
    return bsdf, emitter


def parse_camera(text):
    parts = text.split()
    values = {parts[i]: parts[i + 1] for i in range(1, len(parts) - 1, 2)}
    vec = lambda k: [float(v) for v in values[k].split(",")]  # noqa: E731
    if parts[0] != "perspective":
        sys.exit("mitsuba_peer: only perspective cameras are converted")
    return vec("eye"), vec("target"), vec("up"), float(values["yfov_degrees"])


def scene_dict(g, mi, camera, width, height, bounces, work, sky=None, glass_depth=0, integrator="path"):
    eye, target, up, yfov = camera
    # Mitsuba counts a glass crossing as a bounce, rcsplat does not: glass_depth more for the crossings a path makes.
    # ptracer (light tracing) finds what a path tracer cannot: a point light focused by glass onto a diffuse floor.
    d = {"type": "scene",
         "integrator": {"type": integrator, "max_depth": bounces + 2 + glass_depth, "rr_depth": 1000,
                        "hide_emitters": False},
         "sensor": {"type": "perspective", "fov_axis": "y", "fov": yfov,
                    "to_world": mi.ScalarTransform4f().look_at(origin=eye, target=target, up=up),
                    "film": {"type": "hdrfilm", "width": width, "height": height, "rfilter": {"type": "box"},
                             "pixel_format": "rgb"},
                    "sampler": {"type": "independent", "sample_count": 1}}}
    count = 0
    for mesh_index, world in g.instances():
        normal_matrix = np.linalg.inv(world[:3, :3]).T
        for p_index, prim in enumerate(g.doc["meshes"][mesh_index]["primitives"]):
            if prim.get("mode", 4) != 4:
                g.skipped.add("non-triangle primitives")
                continue
            attrs = prim["attributes"]
            pos = g.accessor(attrs["POSITION"])
            pos = (np.hstack([pos, np.ones((len(pos), 1))]) @ world.T)[:, :3]
            normals = None
            if "NORMAL" in attrs:
                normals = g.accessor(attrs["NORMAL"]) @ normal_matrix.T
                normals /= np.maximum(np.linalg.norm(normals, axis=1, keepdims=True), 1e-20)
            uvs = g.accessor(attrs["TEXCOORD_0"]) if "TEXCOORD_0" in attrs else None
            if "COLOR_0" in attrs:
                g.skipped.add("vertex colours")
            faces = (g.accessor(prim["indices"]).astype(np.int64).reshape(-1, 3) if "indices" in prim
                     else np.arange(len(pos)).reshape(-1, 3))
            if np.linalg.det(world[:3, :3]) < 0:
                faces = faces[:, ::-1]
            ply = os.path.join(work, f"mesh_{count}.ply")
            write_ply(ply, pos, normals, uvs, faces)
            bsdf, emitter = bsdf_and_emitter(g, prim.get("material"))
            shape = {"type": "ply", "filename": ply, "bsdf": bsdf, "face_normals": normals is None}
            if emitter:
                shape["emitter"] = emitter
            d[f"shape_{count}"] = shape
            count += 1
    lights = 0
    if sky is not None:
        d["sky"] = {"type": "constant", "radiance": {"type": "rgb", "value": sky}}
        lights += 1
    for light, world in g.lights():
        colour = np.array(light.get("color", [1, 1, 1])) * light.get("intensity", 1.0)
        position = world[:3, 3].tolist()
        direction = (world[:3, :3] @ np.array([0.0, 0.0, -1.0])).tolist()
        if light.get("range"):
            g.skipped.add("punctual light range")
        if light["type"] == "point":
            d[f"light_{lights}"] = {"type": "point", "position": position,
                                    "intensity": {"type": "rgb", "value": colour.tolist()}}
        elif light["type"] == "spot":
            spot = light.get("spot", {})
            d[f"light_{lights}"] = {
                "type": "spot", "intensity": {"type": "rgb", "value": colour.tolist()},
                "cutoff_angle": math.degrees(spot.get("outerConeAngle", math.pi / 4)),
                "beam_width": math.degrees(spot.get("innerConeAngle", 0.0)),
                "to_world": mi.ScalarTransform4f().look_at(origin=position,
                                                           target=(np.array(position) + direction).tolist(),
                                                           up=[0, 1, 0] if abs(direction[1]) < 0.99 else [1, 0, 0])}
        elif light["type"] == "directional":
            d[f"light_{lights}"] = {"type": "directional", "direction": direction,
                                    "irradiance": {"type": "rgb", "value": colour.tolist()}}
        lights += 1
    emissive = any("emitter" in v for k, v in d.items() if k.startswith("shape_"))
    if not lights and not emissive:
        sys.exit("mitsuba_peer: the scene has no light of its own (rcsplat would add a default one); not converted")
    return d


def rel_mse(image, ref):
    return float(np.mean((image - ref) ** 2 / (ref ** 2 + 0.01)))


def block_means(img, block=8):
    h, w = (img.shape[0] // block) * block, (img.shape[1] // block) * block
    return img[:h, :w].reshape(h // block, block, w // block, block, 3).mean(axis=(1, 3))


def block_rel_mse(image, ref, block=8):
    return rel_mse(block_means(image, block), block_means(ref, block))


def render(mi, scene, spp, seed):
    start = time.perf_counter()
    image = np.array(mi.render(scene, spp=spp, seed=seed), dtype=np.float32)[:, :, :3]
    return image, time.perf_counter() - start


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("scene")
    ap.add_argument("--reference", required=True, help="rcsplat reference .exr (its view and bounces are used)")
    ap.add_argument("--cache", help="an rcsplat cache render of the same view, for the equal-error time")
    ap.add_argument("--cache-seconds", type=float, help="its frame time (default: not reported)")
    ap.add_argument("--converged-spp", type=int, default=1024)
    ap.add_argument("--spp", default="4,16,64,256")
    ap.add_argument("-o", "--output", default="mitsuba_peer")
    ap.add_argument("--json")
    ap.add_argument("--glass-depth", type=int, default=0,
                    help="path depth added for glass crossings, which Mitsuba counts as bounces and rcsplat does not")
    ap.add_argument("--integrator", default="path", choices=["path", "ptracer"],
                    help="Mitsuba's path tracer (default) or its particle tracer, for caustics of point lights")
    ap.add_argument("--bsdf", default="gltf", choices=["gltf", "diffuse", "principled"],
                    help="gltf: rcsplat's BRDF as a Mitsuba plugin (default); diffuse: Mitsuba's Lambertian; "
                         "principled: Mitsuba's principled BSDF, glTF's clearcoat and sheen mapped onto it")
    a = ap.parse_args()
    global DIFFUSE_ONLY, PRINCIPLED
    DIFFUSE_ONLY = a.bsdf == "diffuse"
    PRINCIPLED = a.bsdf == "principled"
    find_llvm()
    import mitsuba as mi
    mi.set_variant("llvm_ad_rgb")
    import mitsuba_gltf_bsdf
    from sweep_equal_error import seconds_at_error
    mitsuba_gltf_bsdf.register(mi)

    attrs = attributes(a.reference)
    reference = read_layer(a.reference)
    height, width = reference.shape[:2]
    bounces = int(attrs.get("rcsplat:bounces", "1"))
    environment = attrs.get("rcsplat:environment", "none")
    sky = None
    if environment.startswith("uniform sky ("):
        sky = [float(v) for v in environment[len("uniform sky ("):].rstrip(")").split(",")]
    elif environment != "none":
        sys.exit("mitsuba_peer: environment maps are not converted (a uniform sky is)")
    os.makedirs(a.output, exist_ok=True)
    g = Gltf(a.scene)
    if "rcsplat:camera" in attrs:
        camera = parse_camera(attrs["rcsplat:camera"])
    else:  # a reference from before rcsplat wrote its view: the scene's first camera, as rcsplat's default
        camera = g.first_camera()
        print(f"{a.reference}: no rcsplat:camera attribute; using the scene's first camera")
    scene = mi.load_dict(scene_dict(g, mi, camera, width, height, bounces, a.output, sky, a.glass_depth,
                                    a.integrator))
    if g.skipped:
        print("not converted:", "; ".join(sorted(g.skipped)))

    render(mi, scene, 1, 7)  # compiles the kernels once
    converged, converged_s = render(mi, scene, a.converged_spp, 1)
    write_exr(os.path.join(a.output, f"mitsuba_{a.converged_spp}spp.exr"), converged)
    # Pixels that see an emitter, and their neighbours, are left out: a pixel split by an emitter's edge is all
    # pixel filter, and an emitter's radiance is an input, not a result.
    valid = reference.sum(axis=2) > 1e-4
    try:
        emitting = read_layer(a.reference, "emission").sum(axis=2) > 0
        near = emitting.copy()
        for dy in (-1, 0, 1):
            for dx in (-1, 0, 1):
                near |= np.roll(np.roll(emitting, dy, axis=0), dx, axis=1)
        valid &= ~near
    except SystemExit:
        pass
    ratio = [float(converged[..., c][valid].mean() / reference[..., c][valid].mean()) for c in range(3)]
    report = {"scene": a.scene, "reference": a.reference, "width": width, "height": height, "bounces": bounces,
              "mitsuba": mi.__version__, "variant": "llvm_ad_rgb", "not_converted": sorted(g.skipped),
              "converged_spp": a.converged_spp, "converged_seconds": converged_s,
              "agreement": {"mean_ratio_rgb": ratio, "block_rel_mse": block_rel_mse(converged, reference),
                            "rel_mse": rel_mse(converged, reference)}}
    print(f"agreement: Mitsuba {a.converged_spp} spp / rcsplat reference, mean ratio R {ratio[0]:.4f} G {ratio[1]:.4f} "
          f"B {ratio[2]:.4f}; 8x8 block relMSE {report['agreement']['block_rel_mse']:.3e} ({converged_s:.1f} s)")

    rows = []
    for spp in [int(s) for s in a.spp.split(",") if s]:
        render(mi, scene, spp, 11)  # warm-up: the kernel for this sample count
        image, seconds = render(mi, scene, spp, 2 + spp)
        rows.append({"spp": spp, "seconds": seconds, "rel_mse": rel_mse(image, converged),
                     "block_rel_mse": block_rel_mse(image, converged)})
        print(f"mitsuba {spp:5d} spp {seconds:8.3f} s  relMSE {rows[-1]['rel_mse']:.3e}  "
              f"block relMSE {rows[-1]['block_rel_mse']:.3e}")
    report["mitsuba_runs"] = rows
    if a.cache:
        cache = read_layer(a.cache)
        target = {"rel_mse": rel_mse(cache, reference), "block_rel_mse": block_rel_mse(cache, reference)}
        report["cache"] = {"image": a.cache, "seconds": a.cache_seconds, **target}
        for key in ("rel_mse", "block_rel_mse"):
            seconds, flag = seconds_at_error([(r["seconds"], r[key]) for r in rows], target[key])
            report["cache"][f"mitsuba_seconds_at_equal_{key}"] = seconds
            report["cache"][f"mitsuba_{key}_bound"] = flag  # ">": extrapolated, "<": the fewest samples reach it
            needs = "is not reached" if seconds is None else f"needs {flag}{seconds:.3f} s"
            print(f"equal {key}: cache {target[key]:.3e}"
                  + (f" in {a.cache_seconds:.3f} s" if a.cache_seconds else "") + f"; Mitsuba {needs}")
    if a.json:
        with open(a.json, "w") as f:
            json.dump(report, f, indent=2)


if __name__ == "__main__":
    main()
