#!/usr/bin/env python3
"""Writes a procedural equirectangular sky with a sun as a Radiance .hdr file, for trying --environment without
downloading a map: a blue gradient above the horizon, a darker ground below and a sun disc.

    python3 benchmarks/make_sky.py OUT.hdr [--width 512] [--sun-elevation 40] [--sun-azimuth 30] [--sun 20000]

The layout is rcsplat's (and Mitsuba's): rows from +Y down, the centre column toward -Z, u = (1 + atan2(x, -z) / pi) / 2.
Pure Python (no numpy): flat RGBE scanlines, which every .hdr reader accepts."""
import argparse
import math


def rgbe(r, g, b):
    m = max(r, g, b)
    if m < 1e-32:
        return bytes((0, 0, 0, 0))
    mantissa, exponent = math.frexp(m)
    scale = mantissa * 256.0 / m
    return bytes((int(r * scale), int(g * scale), int(b * scale), exponent + 128))


def main():
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("out")
    p.add_argument("--width", type=int, default=512)
    p.add_argument("--sun-elevation", type=float, default=40.0, help="degrees above the horizon")
    p.add_argument("--sun-azimuth", type=float, default=30.0, help="degrees from -Z toward +X")
    p.add_argument("--sun", type=float, default=20000.0, help="the sun disc's radiance")
    p.add_argument("--sun-radius", type=float, default=1.5, help="the sun disc's angular radius in degrees")
    a = p.parse_args()
    w, h = a.width, a.width // 2
    el, az = math.radians(a.sun_elevation), math.radians(a.sun_azimuth)
    sun = (math.cos(el) * math.sin(az), math.sin(el), -math.cos(el) * math.cos(az))
    cos_sun = math.cos(math.radians(a.sun_radius))
    rows = []
    for j in range(h):
        theta = math.pi * (j + 0.5) / h
        row = bytearray()
        for i in range(w):
            phi = 2.0 * math.pi * (i + 0.5) / w - math.pi
            d = (math.sin(theta) * math.sin(phi), math.cos(theta), -math.sin(theta) * math.cos(phi))
            if d[1] > 0.0:
                t = d[1]
                c = (0.35 + 0.25 * t, 0.5 + 0.25 * t, 0.9 + 0.3 * t)
            else:
                c = (0.12, 0.1, 0.08)
            if d[0] * sun[0] + d[1] * sun[1] + d[2] * sun[2] > cos_sun:
                c = (a.sun, a.sun * 0.93, a.sun * 0.82)
            row += rgbe(*c)
        rows.append(bytes(row))
    with open(a.out, "wb") as f:
        f.write(b"#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n")
        f.write(("-Y %d +X %d\n" % (h, w)).encode())
        for row in rows:
            f.write(row)


if __name__ == "__main__":
    main()
