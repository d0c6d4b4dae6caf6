#!/usr/bin/env python3
"""Renders every glTF file under a directory with rcsplat and prints one table row per model: the features the file
uses, the exit code, seconds, warnings, what rcsplat says it does not simulate, and whether every pixel is finite.

Meant for the Khronos glTF-Sample-Models (embedded or binary variants, obtained separately; never committed without
their licences). Standard library only:

    benchmarks/gltf_survey.py DIR [--rcsplat build/rcsplat] [--width 256] [--gi splat] [--json survey.json]
"""
import argparse
import json
import os
import pathlib
import struct
import subprocess
import sys
import tempfile
import time


def gltf_document(path):
    """The glTF JSON of a .gltf or .glb file, or None when it cannot be read."""
    try:
        data = path.read_bytes()
        if path.suffix.lower() == ".glb":
            if len(data) < 20 or data[:4] != b"glTF":
                return None
            length, kind = struct.unpack_from("<II", data, 12)
            if kind != 0x4E4F534A:  # "JSON"
                return None
            return json.loads(data[20:20 + length])
        return json.loads(data)
    except (OSError, ValueError):
        return None


def features(doc):
    """Short names of what a file uses beyond plain triangles and factors."""
    if doc is None:
        return ["unreadable"]
    found = set(doc.get("extensionsUsed", []))
    meshes = doc.get("meshes", [])
    for mesh in meshes:
        for prim in mesh.get("primitives", []):
            attributes = prim.get("attributes", {})
            if "COLOR_0" in attributes:
                found.add("COLOR_0")
            if prim.get("targets"):
                found.add("morph")
            if prim.get("mode", 4) != 4:
                found.add("mode %d" % prim["mode"])
    if any("sparse" in a for a in doc.get("accessors", [])):
        found.add("sparse")
    if doc.get("skins"):
        found.add("skin")
    if doc.get("animations"):
        found.add("animation")
    for camera in doc.get("cameras", []):
        found.add(camera.get("type", "?") + " camera")
    for material in doc.get("materials", []):
        mode = material.get("alphaMode", "OPAQUE")
        if mode != "OPAQUE":
            found.add("alpha " + mode)
    if doc.get("textures"):
        found.add("textures")
    return sorted(found)


def survey(paths, rcsplat, width, gi, timeout):
    rows = []
    with tempfile.TemporaryDirectory() as scratch:
        for path in paths:
            out, summary = os.path.join(scratch, "out.exr"), os.path.join(scratch, "summary.json")
            for f in (out, summary):
                if os.path.exists(f):
                    os.remove(f)
            command = [rcsplat, "render", str(path), "-o", out, "--json", summary, "--width", str(width), "--gi", gi, "-q"]
            start = time.monotonic()
            try:
                run = subprocess.run(command, capture_output=True, text=True, timeout=timeout)
                code, stderr = run.returncode, run.stderr
            except subprocess.TimeoutExpired:
                code, stderr = "timeout", ""
            seconds = time.monotonic() - start
            warnings = [line for line in stderr.splitlines() if line.startswith("warning:")]
            errors = [line for line in stderr.splitlines() if line.startswith("error:")]
            info = {}
            if code == 0 and os.path.exists(summary):
                with open(summary) as f:
                    info = json.load(f)
            rows.append({
                "model": path.name,
                "features": features(gltf_document(path)),
                "exit": code,
                "seconds": round(seconds, 2),
                "warnings": len(warnings),
                "not_simulated": info.get("not_simulated", []),
                "finite": (info.get("nonfinite_values") == 0) if info else None,
                "error": errors[0][len("error: "):] if errors else "",
            })
            row = rows[-1]
            print("%-32s exit %-7s %6.2f s  %s" % (row["model"], row["exit"], row["seconds"],
                                                   row["error"] or ("finite" if row["finite"] else "NON-FINITE")),
                  file=sys.stderr)
    return rows


def markdown(rows):
    lines = ["| model | features | exit | s | warnings | not simulated (what rcsplat does instead) | finite |",
             "|---|---|---|---|---|---|---|"]
    for r in rows:
        note = "; ".join(r["not_simulated"]) or "-"
        if r["error"]:
            note = "error: " + r["error"]
        finite = "yes" if r["finite"] else ("-" if r["finite"] is None else "**no**")
        lines.append("| %s | %s | %s | %.2f | %d | %s | %s |" % (r["model"], ", ".join(r["features"]) or "-", r["exit"],
                                                                 r["seconds"], r["warnings"], note, finite))
    return "\n".join(lines)


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("directory", type=pathlib.Path)
    parser.add_argument("--rcsplat", default=str(pathlib.Path(__file__).resolve().parent.parent / "build" / "rcsplat"))
    parser.add_argument("--width", type=int, default=256)
    parser.add_argument("--gi", default="splat")
    parser.add_argument("--timeout", type=float, default=600.0)
    parser.add_argument("--json", help="also write the rows as JSON")
    args = parser.parse_args()
    paths = sorted(p for p in args.directory.rglob("*") if p.suffix.lower() in (".gltf", ".glb"))
    if not paths:
        sys.exit("%s: no .gltf or .glb files" % args.directory)
    rows = survey(paths, args.rcsplat, args.width, args.gi, args.timeout)
    print(markdown(rows))
    if args.json:
        with open(args.json, "w") as f:
            json.dump(rows, f, indent=2)


if __name__ == "__main__":
    main()
