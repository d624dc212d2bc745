#!/usr/bin/env python3
"""Writes scenes/textured.gltf and its textures: a checker-textured plane (an external PNG,
tiled by KHR_texture_transform), a sphere and a box wearing an orientation grid (an embedded
data: URI PNG: colour ramps and a letter F that shows mirroring), the box also a generated
normal map of round bumps. All three are TRAY_shape analytic shapes using glTF materials.
Usage: tools/make_textured_scene.py [OUT.gltf]   (textures go to OUT's folder/textures/)"""
import base64, json, math, os, struct, sys, zlib


def png(width, height, pixel):
    """8-bit RGB PNG of pixel(x, y) -> (r, g, b), row 0 at the top."""
    raw = b"".join(b"\0" + bytes(c for x in range(width) for c in pixel(x, y)) for y in range(height))
    def chunk(kind, data):
        return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data))
    ihdr = struct.pack(">IIBBBBB", width, height, 8, 2, 0, 0, 0)
    return b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", ihdr) + chunk(b"IDAT", zlib.compress(raw, 9)) + chunk(b"IEND", b"")


def checker(x, y):
    return (235, 225, 200) if (x // 16 + y // 16) % 2 == 0 else (40, 60, 110)


F_STROKES = [(0.30, 0.20, 0.40, 0.80), (0.40, 0.20, 0.72, 0.30), (0.40, 0.45, 0.62, 0.55)]  # x0 y0 x1 y1


def grid(x, y, w=256, h=128):
    """u ramps red, v ramps green; white lines every 1/8; a dark F upright in each cell row."""
    u, v = (x + 0.5) / w, (y + 0.5) / h
    if x % (w // 8) == 0 or y % (h // 4) == 0:
        return (255, 255, 255)
    cu, cv = (u * 8) % 1, (v * 4) % 1  # position inside an 8 x 4 cell
    if any(x0 <= cu <= x1 and y0 <= cv <= y1 for x0, y0, x1, y1 in F_STROKES):
        return (20, 20, 20)
    return (int(60 + 190 * u), int(60 + 190 * v), 90)


def bumps(x, y, n=64, cells=4):
    """Tangent-space normals of a height field of round bumps (glTF: +X right, +Y up)."""
    period = n / cells
    cx, cy = (x % period) / period - 0.5, (y % period) / period - 0.5
    r2 = cx * cx + cy * cy
    if r2 >= 0.16:
        return (128, 128, 255)
    # h = sqrt(0.16 - r2): dh/dx = -cx / h; image y runs down, so up is -cy.
    hgt = math.sqrt(0.16 - r2)
    nx, ny, nz = cx / hgt, -cy / hgt, 1.0
    ln = math.sqrt(nx * nx + ny * ny + nz * nz)
    return tuple(int(round((c / ln * 0.5 + 0.5) * 255)) for c in (nx, ny, nz))


out = sys.argv[1] if len(sys.argv) > 1 else "scenes/textured.gltf"
folder = os.path.join(os.path.dirname(out) or ".", "textures")
os.makedirs(folder, exist_ok=True)
with open(os.path.join(folder, "checker.png"), "wb") as f:
    f.write(png(128, 128, checker))
grid_uri = "data:image/png;base64," + base64.b64encode(png(256, 128, grid)).decode()
bumps_uri = "data:image/png;base64," + base64.b64encode(png(64, 64, bumps)).decode()

gltf = {
    "asset": {"version": "2.0", "generator": "TRay tools/make_textured_scene.py"},
    "extensionsUsed": ["TRAY_shape", "TRAY_environment", "KHR_lights_punctual", "KHR_texture_transform"],
    "extensions": {"KHR_lights_punctual": {"lights": [
        {"type": "point", "color": [1, 0.97, 0.9], "intensity": 70.0},
        {"type": "directional", "color": [0.6, 0.7, 1.0], "intensity": 0.6}]}},
    "scene": 0,
    "scenes": [{"nodes": [0, 1, 2, 3, 4, 5], "extensions": {"TRAY_environment": {
        "ambient": [0.12, 0.12, 0.14], "background": [0.55, 0.65, 0.8]}}}],
    "nodes": [
        {"name": "checker plane", "extensions": {"TRAY_shape": {"type": "plane", "material": 0}}},
        {"name": "grid sphere", "translation": [-1.3, 1.0, -3.5], "rotation": [0, 0.2588, 0, 0.9659],
         "extensions": {"TRAY_shape": {"type": "sphere", "radius": 1.0, "material": 1}}},
        {"name": "bumpy box", "translation": [1.4, 0.8, -3.0], "rotation": [0, -0.3827, 0, 0.9239],
         "extensions": {"TRAY_shape": {"type": "box", "min": [-0.8, -0.8, -0.8], "max": [0.8, 0.8, 0.8],
                                       "material": 2}}},
        {"name": "lamp", "translation": [2.5, 5.0, 1.0], "extensions": {"KHR_lights_punctual": {"light": 0}}},
        {"name": "sky", "rotation": [-0.5, 0.3, 0.1, 0.8], "extensions": {"KHR_lights_punctual": {"light": 1}}},
        {"name": "camera", "camera": 0, "translation": [0.0, 2.0, 2.5], "rotation": [-0.17, 0.0, 0.0, 0.985]},
    ],
    "cameras": [{"type": "perspective", "perspective": {"yfov": 0.8, "aspectRatio": 1.3333, "znear": 0.05}}],
    "materials": [
        {"name": "checker", "pbrMetallicRoughness": {
            "baseColorTexture": {"index": 0, "extensions": {"KHR_texture_transform": {"scale": [0.25, 0.25]}}},
            "metallicFactor": 0, "roughnessFactor": 0.9}},
        {"name": "grid", "pbrMetallicRoughness": {"baseColorTexture": {"index": 1},
                                                  "metallicFactor": 0, "roughnessFactor": 0.6}},
        {"name": "bumpy grid", "pbrMetallicRoughness": {"baseColorTexture": {"index": 1},
                                                        "metallicFactor": 0, "roughnessFactor": 0.6},
         "normalTexture": {"index": 2, "scale": 1.0}},
    ],
    "samplers": [{"wrapS": 10497, "wrapT": 10497, "magFilter": 9729, "minFilter": 9987},
                 {"wrapS": 10497, "wrapT": 33071, "magFilter": 9729, "minFilter": 9987}],
    "textures": [{"source": 0, "sampler": 0}, {"source": 1, "sampler": 1}, {"source": 2, "sampler": 0}],
    "images": [{"uri": "textures/checker.png"}, {"uri": grid_uri}, {"uri": bumps_uri}],
}
with open(out, "w") as f:
    json.dump(gltf, f, indent=1)
