#!/usr/bin/env python3
"""Writes the textured glTF assets of content/levels/textured_street.json and the stall-sign
texture of content/levels/night_market_signs.json into content/assets/textured/.

Every texture is procedural (neon lettering, bricks with a height-derived normal map, a lattice
cutout, floor tiles), encoded here as PNG with the standard library only (zlib), and embedded in
its .gltf as a data URI, so the repository holds a few small text files and this script instead
of binary art. Deterministic: running it again reproduces the files byte for byte
(tests/textures/texture_cpu_test.cpp checks the committed files against a fresh run).

Usage: scripts/make_textured_assets.py [OUT_DIR]   (default: content/assets/textured)
"""
import base64
import json
import math
import os
import struct
import sys
import zlib


def png(width, height, pixel):
    """RGBA8 PNG bytes; pixel(x, y) -> (r, g, b, a) floats in [0, 1] (encoded values)."""
    rows = bytearray()
    for y in range(height):
        rows.append(0)  # filter: none
        for x in range(width):
            for c in pixel(x, y):
                rows.append(max(0, min(255, int(round(c * 255.0)))))

    def chunk(kind, data):
        body = kind + data
        return struct.pack(">I", len(data)) + body + struct.pack(">I", zlib.crc32(body) & 0xFFFFFFFF)

    header = struct.pack(">IIBBBBB", width, height, 8, 6, 0, 0, 0)  # 8-bit RGBA
    return (b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", header) +
            chunk(b"IDAT", zlib.compress(bytes(rows), 9)) + chunk(b"IEND", b""))


def smoothstep(a, b, x):
    t = max(0.0, min(1.0, (x - a) / (b - a)))
    return t * t * (3 - 2 * t)


# --- textures ---------------------------------------------------------------------------------

# A 5x7 bitmap font for the few letters the signs spell.
FONT = {
    "N": ["10001", "11001", "10101", "10011", "10001", "10001", "10001"],
    "O": ["01110", "10001", "10001", "10001", "10001", "10001", "01110"],
    "D": ["11110", "10001", "10001", "10001", "10001", "10001", "11110"],
    "L": ["10000", "10000", "10000", "10000", "10000", "10000", "11111"],
    "E": ["11111", "10000", "10000", "11110", "10000", "10000", "11111"],
    "S": ["01111", "10000", "10000", "01110", "00001", "00001", "11110"],
    "B": ["11110", "10001", "10001", "11110", "10001", "10001", "11110"],
    "A": ["01110", "10001", "10001", "11111", "10001", "10001", "10001"],
    "R": ["11110", "10001", "10001", "11110", "10100", "10010", "10001"],
    "T": ["11111", "00100", "00100", "00100", "00100", "00100", "00100"],
    "I": ["01110", "00100", "00100", "00100", "00100", "00100", "01110"],
    "M": ["10001", "11011", "10101", "10101", "10001", "10001", "10001"],
}


def neon_sign(text, colour, width=128, height=32):
    """Glowing lettering on black: lit strokes + a soft halo, a thin frame."""
    cell_w = width // (len(text) + 1)
    x0 = (width - cell_w * len(text)) // 2
    strokes = set()
    for i, ch in enumerate(text):
        glyph = FONT[ch]
        for gy, row in enumerate(glyph):
            for gx, bit in enumerate(row):
                if bit == "1":
                    strokes.add((i, gx, gy))

    def lit(x, y):
        # Distance (in glyph cells) to the nearest stroke cell of the letter under x.
        i = (x - x0) // cell_w
        if i < 0 or i >= len(text):
            return 99.0
        lx = ((x - x0) % cell_w) / cell_w * 6.0 - 0.5  # 5 columns + spacing
        ly = (y - height * 0.2) / (height * 0.6) * 7.0 - 0.5
        best = 99.0
        for gx in range(5):
            for gy in range(7):
                if (i, gx, gy) in strokes:
                    best = min(best, math.hypot(lx - gx, ly - gy))
        return best

    def pixel(x, y):
        d = lit(x, y)
        core = 1.0 - smoothstep(0.35, 0.6, d)
        halo = 0.25 * math.exp(-d * 1.5)
        frame = 1.0 if (x in (1, width - 2) or y in (1, height - 2)) else 0.0
        v = max(core, halo, 0.6 * frame)
        return (colour[0] * v, colour[1] * v, colour[2] * v, 1.0)

    return png(width, height, pixel)


def bricks(width=128, height=64):
    """Base colour, roughness-metallic and a normal map from one brick height field."""
    rows, cols = 4, 4

    def height_at(x, y):
        by = y * rows / height
        row = int(by)
        bx = x * cols / width + (0.5 if row % 2 else 0.0)
        fx, fy = bx - math.floor(bx), by - row
        edge = min(fx, 1 - fx, fy, 1 - fy)
        return smoothstep(0.02, 0.08, edge)  # 0 in the mortar, 1 on the brick face

    def colour(x, y):
        by = y * rows / height
        row = int(by)
        col = int(x * cols / width + (0.5 if row % 2 else 0.0))
        tint = 0.85 + 0.15 * math.sin(row * 7.1 + col * 3.3)
        h = height_at(x, y)
        brick = (0.62 * tint, 0.27 * tint, 0.18 * tint)
        mortar = (0.55, 0.53, 0.5)
        return tuple(m + (b - m) * h for b, m in zip(brick, mortar)) + (1.0,)

    def rough_metal(x, y):
        h = height_at(x, y)
        return (0.0, 0.95 - 0.25 * h, 0.0, 1.0)  # G roughness, B metallic (none)

    def normal(x, y):
        dx = height_at((x + 1) % width, y) - height_at((x - 1) % width, y)
        dy = height_at(x, (y + 1) % height) - height_at(x, (y - 1) % height)
        # +Y is up in the image (glTF): the height rising downwards tilts the normal up.
        n = (-dx * 1.5, dy * 1.5, 1.0)
        inv = 1.0 / math.sqrt(sum(c * c for c in n))
        return tuple(0.5 + 0.5 * c * inv for c in n) + (1.0,)

    return png(width, height, colour), png(width, height, rough_metal), png(width, height, normal)


def lattice(width=64, height=32):
    """A diagonal fence lattice: opaque slats, cut-out holes (alpha 0)."""
    def pixel(x, y):
        a = (x + y) % 16 < 3 or (x - y) % 16 < 3 or y < 2 or y >= height - 2
        return (0.42, 0.3, 0.18, 1.0 if a else 0.0)
    return png(width, height, pixel)


def tiles(width=64, height=64):
    def pixel(x, y):
        tx, ty = x // 16, y // 16
        grout = x % 16 == 0 or y % 16 == 0
        base = 0.32 if (tx + ty) % 2 else 0.22
        v = 0.12 if grout else base
        return (v, v * 0.95, v * 0.9, 1.0)
    return png(width, height, pixel)


def stall_sign(width=64, height=32):
    """The night market's stall sign: bright lettering on a dark panel with a warm border."""
    return neon_sign("OM", (1.0, 0.85, 0.55), width, height)


# --- glTF -------------------------------------------------------------------------------------

def data_uri(data, mime="image/png"):
    return "data:%s;base64,%s" % (mime, base64.b64encode(data).decode("ascii"))


def quad_gltf(name, size, material, images, samplers=None, double_sided=False, facing="z"):
    """One quad of size (w, h) centred at the origin facing +Z (facing="z") or +Y ("y"), uv 0..1
    across it (v down the image, as glTF), with the given material and images."""
    w, h = size
    if facing == "z":
        pos = [-w / 2, -h / 2, 0, w / 2, -h / 2, 0, w / 2, h / 2, 0, -w / 2, h / 2, 0]
        nrm = [0, 0, 1] * 4
    else:
        pos = [-w / 2, 0, h / 2, w / 2, 0, h / 2, w / 2, 0, -h / 2, -w / 2, 0, -h / 2]
        nrm = [0, 1, 0] * 4
    uv = [0, 1, 1, 1, 1, 0, 0, 0]
    idx = [0, 1, 2, 0, 2, 3]
    blob = struct.pack("<12f", *pos) + struct.pack("<12f", *nrm) + struct.pack("<8f", *uv) + \
        struct.pack("<6I", *idx)
    material = dict(material, name=name)
    if double_sided:
        material["doubleSided"] = True
    doc = {
        "asset": {"version": "2.0", "generator": "lantern scripts/make_textured_assets.py"},
        "buffers": [{"byteLength": len(blob), "uri": data_uri(blob, "application/octet-stream")}],
        "bufferViews": [
            {"buffer": 0, "byteOffset": 0, "byteLength": 48},
            {"buffer": 0, "byteOffset": 48, "byteLength": 48},
            {"buffer": 0, "byteOffset": 96, "byteLength": 32},
            {"buffer": 0, "byteOffset": 128, "byteLength": 24},
        ],
        "accessors": [
            {"bufferView": 0, "componentType": 5126, "count": 4, "type": "VEC3",
             "min": [min(pos[0::3]), min(pos[1::3]), min(pos[2::3])],
             "max": [max(pos[0::3]), max(pos[1::3]), max(pos[2::3])]},
            {"bufferView": 1, "componentType": 5126, "count": 4, "type": "VEC3"},
            {"bufferView": 2, "componentType": 5126, "count": 4, "type": "VEC2"},
            {"bufferView": 3, "componentType": 5125, "count": 6, "type": "SCALAR"},
        ],
        "images": [{"name": n, "uri": data_uri(d)} for n, d in images],
        "textures": [{"source": i, "sampler": 0} for i in range(len(images))],
        "samplers": samplers or [{"magFilter": 9729, "minFilter": 9987, "wrapS": 10497, "wrapT": 10497}],
        "materials": [material],
        "meshes": [{"name": name, "primitives": [
            {"attributes": {"POSITION": 0, "NORMAL": 1, "TEXCOORD_0": 2}, "indices": 3, "material": 0}]}],
        "nodes": [{"name": name, "mesh": 0}],
        "scenes": [{"nodes": [0]}],
        "scene": 0,
    }
    text = json.dumps(material)
    used = {e for e in ("KHR_materials_emissive_strength", "KHR_texture_transform") if e in text}
    if used:
        doc["extensionsUsed"] = sorted(used)
    return doc


def sign_asset(name, text, colour, strength):
    return quad_gltf(name, (2.0, 0.5), {
        "pbrMetallicRoughness": {"baseColorFactor": [0.02, 0.02, 0.02, 1], "metallicFactor": 0,
                                 "roughnessFactor": 0.6},
        "emissiveFactor": [1, 1, 1],
        "emissiveTexture": {"index": 0},
        "extensions": {"KHR_materials_emissive_strength": {"emissiveStrength": strength}},
    }, [(name, neon_sign(text, colour))])


def main():
    out = sys.argv[1] if len(sys.argv) > 1 else os.path.join(
        os.path.dirname(os.path.abspath(__file__)), "..", "content", "assets", "textured")
    os.makedirs(out, exist_ok=True)
    colour, rough, normal = bricks()
    transform = {"KHR_texture_transform": {"scale": [6.0, 3.0]}}
    assets = {
        "sign_noodles.gltf": sign_asset("sign_noodles", "NOODLES", (0.2, 0.95, 1.0), 60.0),
        "sign_bar.gltf": sign_asset("sign_bar", "BAR", (1.0, 0.25, 0.6), 80.0),
        "sign_tea.gltf": sign_asset("sign_tea", "TEA", (1.0, 0.8, 0.3), 50.0),
        "brick_wall.gltf": quad_gltf("brick_wall", (12.0, 4.0), {
            "pbrMetallicRoughness": {
                "baseColorTexture": {"index": 0, "extensions": transform},
                "metallicRoughnessTexture": {"index": 1, "extensions": transform},
                "metallicFactor": 1.0, "roughnessFactor": 1.0},
            "normalTexture": {"index": 2, "scale": 1.0, "extensions": transform},
        }, [("bricks", colour), ("bricks_rm", rough), ("bricks_n", normal)]),
        "fence.gltf": quad_gltf("fence", (3.0, 1.5), {
            "pbrMetallicRoughness": {"baseColorTexture": {"index": 0}, "metallicFactor": 0,
                                     "roughnessFactor": 0.8},
            "alphaMode": "MASK", "alphaCutoff": 0.5,
        }, [("lattice", lattice())], double_sided=True,
            samplers=[{"magFilter": 9728, "minFilter": 9984, "wrapS": 33071, "wrapT": 33071}]),
        "floor_tiles.gltf": quad_gltf("floor_tiles", (12.0, 12.0), {
            "pbrMetallicRoughness": {
                "baseColorTexture": {"index": 0, "extensions": {"KHR_texture_transform": {"scale": [6.0, 6.0]}}},
                "metallicFactor": 0, "roughnessFactor": 0.7},
        }, [("tiles", tiles())], facing="y"),
    }
    for name, doc in assets.items():
        with open(os.path.join(out, name), "w") as f:
            json.dump(doc, f, indent=1, sort_keys=True)
            f.write("\n")
    with open(os.path.join(out, "stall_sign.png"), "wb") as f:
        f.write(stall_sign())


if __name__ == "__main__":
    main()
