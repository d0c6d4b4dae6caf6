"""Shared by the benchmark scripts: rcsplat's EXR layers as numpy arrays (PyPI OpenEXR) and the tone mapping of its
PNGs (host/image/tone_map.h), so that Python tools judge what rcsplat's own `compare` judges."""
import numpy as np
import OpenEXR


def read_layer(path, layer=""):
    """An RGB layer ("" for the image itself, "indirect", "albedo", ...) as float32 H x W x 3; normal is X, Y, Z."""
    channels = OpenEXR.File(path).channels()
    name = layer or "RGB"
    if name in channels:
        return np.asarray(channels[name].pixels, dtype=np.float32)
    parts = [channels.get(f"{layer}.{c}") for c in "XYZ"]
    if all(p is not None for p in parts):
        return np.stack([np.asarray(p.pixels, dtype=np.float32) for p in parts], axis=-1)
    raise SystemExit(f"{path}: has no layer '{layer}' (has {', '.join(sorted(channels))})")


def attributes(path):
    return {k: v for k, v in OpenEXR.File(path).header().items() if str(k).startswith("rcsplat:")}


def write_exr(path, rgb, layers=None, header=None):
    """An RGB image plus optional named RGB layers."""
    channels = {"RGB": np.ascontiguousarray(rgb, dtype=np.float32)}
    for name, data in (layers or {}).items():
        channels[name] = np.ascontiguousarray(data, dtype=np.float32)
    h = {"compression": OpenEXR.ZIP_COMPRESSION, "type": OpenEXR.scanlineimage}
    h.update(header or {})
    with OpenEXR.File(h, channels) as f:
        f.write(path)


def display(linear, exposure_stops=0.0):
    """Linear radiance to sRGB-encoded display values in [0, 1], as rcsplat writes PNGs (before quantising)."""
    x = np.maximum(np.nan_to_num(linear, nan=0.0, posinf=0.0, neginf=0.0) * 2.0 ** exposure_stops, 0.0)
    x = np.clip(x * (2.51 * x + 0.03) / (x * (2.43 * x + 0.59) + 0.14), 0.0, 1.0)
    return np.where(x <= 0.0031308, 12.92 * x, 1.055 * np.power(x, 1.0 / 2.4) - 0.055).astype(np.float32)


def exposure_grid(rows, stops, path, dpi=100):
    """A figure of images (rows of (label, EXR path)) at several exposures (stops), tone-mapped as rcsplat's PNGs are,
    saved to path."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, axes = plt.subplots(len(rows), len(stops), figsize=(3.0 * len(stops), 2.6 * len(rows)), squeeze=False)
    for r, (name, image) in enumerate(rows):
        img = read_layer(image)
        for c, stop in enumerate(stops):
            ax = axes[r][c]
            ax.imshow(display(img, stop))
            ax.set_xticks([])
            ax.set_yticks([])
            if c == 0:
                ax.set_ylabel(name, fontsize=8)
            if r == 0:
                ax.set_title(f"{stop:+d} stops", fontsize=8)
    fig.tight_layout()
    fig.savefig(path, dpi=dpi)
