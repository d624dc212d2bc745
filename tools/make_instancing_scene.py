#!/usr/bin/env python3
"""Writes a glTF scene of EXT_mesh_gpu_instancing (docs/instancing.md).

Default: scenes/instancing.gltf, the small test scene (5 x 5 x 5 = 125 rotated and scaled
spheres whose ROTATION is stored as normalized shorts, four emissive spheres placed by
TRANSLATION alone, a floor and a point light). With --count N (the benchmark,
bench/instancing_bench.py): N spheres on a square grid of fixed size (smaller as N grows, so
the image covers the same area), buffers in a .bin beside the .gltf. Run from the repo root.
"""
import argparse
import base64
import json
import math
import os
import struct


def uv_sphere(segments):
    """Unit UV sphere: positions, normals (same), uint32 indices."""
    rings = max(segments // 2, 2)
    pos, idx = [], []
    for r in range(rings + 1):
        theta = math.pi * r / rings
        for s in range(segments + 1):
            phi = 2 * math.pi * s / segments
            pos.append((math.sin(theta) * math.cos(phi), math.cos(theta),
                        math.sin(theta) * math.sin(phi)))
    for r in range(rings):
        for s in range(segments):
            a, b = r * (segments + 1) + s, (r + 1) * (segments + 1) + s
            if r > 0:
                idx += [a, a + 1, b]
            if r < rings - 1:
                idx += [a + 1, b + 1, b]
    return pos, idx


def quat(axis, deg):
    n = math.sqrt(sum(c * c for c in axis))
    a = math.radians(deg) / 2
    return [axis[0] / n * math.sin(a), axis[1] / n * math.sin(a), axis[2] / n * math.sin(a),
            math.cos(a)]


class Writer:
    """Collects binary data into one buffer and writes accessors over it."""

    def __init__(self):
        self.data = bytearray()
        self.views, self.accessors = [], []

    def add(self, fmt, rows, ctype, atype, normalized=False, target=None, minmax=False):
        while len(self.data) % 4:
            self.data.append(0)
        start = len(self.data)
        per = len(rows[0]) if isinstance(rows[0], (list, tuple)) else 1
        flat = [v for r in rows for v in (r if per > 1 else [r])]
        self.data += struct.pack("<%d%s" % (len(flat), fmt), *flat)
        view = {"buffer": 0, "byteOffset": start, "byteLength": len(self.data) - start}
        if target:
            view["target"] = target
        self.views.append(view)
        acc = {"bufferView": len(self.views) - 1, "componentType": ctype, "count": len(rows),
               "type": atype}
        if normalized:
            acc["normalized"] = True
        if minmax:
            acc["min"] = [min(r[i] for r in rows) for i in range(per)]
            acc["max"] = [max(r[i] for r in rows) for i in range(per)]
        self.accessors.append(acc)
        return len(self.accessors) - 1


def sphere_mesh(w, segments, material):
    pos, idx = uv_sphere(segments)
    p = w.add("f", pos, 5126, "VEC3", target=34962, minmax=True)
    n = w.add("f", pos, 5126, "VEC3", target=34962)
    i = w.add("I", idx, 5125, "SCALAR", target=34963)
    return {"primitives": [{"attributes": {"POSITION": p, "NORMAL": n}, "indices": i,
                            "material": material}]}


def material(name, rgb, emissive=None):
    m = {"name": name, "pbrMetallicRoughness": {"baseColorFactor": rgb + [1],
                                                "metallicFactor": 0, "roughnessFactor": 0.6}}
    if emissive:
        m["emissiveFactor"] = [1, 0.85, 0.6]
        m["extensions"] = {"KHR_materials_emissive_strength": {"emissiveStrength": emissive}}
    return m


def small_scene(w):
    """The test scene: 125 instances (normalized short rotations), 4 emissive instances."""
    t, r, s = [], [], []
    for k in range(125):
        x, y, z = k % 5, (k // 5) % 5, k // 25
        t.append((x * 0.5 - 1, y * 0.5 + 0.3, z * 0.5 - 1))
        q = quat((1, 1 + x, 0.5 + z), 20 * x + 15 * y + 10 * z)
        r.append(tuple(int(round(c * 32767)) for c in q))
        s.append((0.12 + 0.02 * x, 0.18 - 0.02 * y, 0.12 + 0.01 * z))
    inst = {"TRANSLATION": w.add("f", t, 5126, "VEC3"),
            "ROTATION": w.add("h", r, 5122, "VEC4", normalized=True),
            "SCALE": w.add("f", s, 5126, "VEC3")}
    # Node scale 0.1 after the instances (world = node * instance): lamps at (+-1.4, 2.2, +-1.4).
    lamps = {"TRANSLATION": w.add("f", [(-14, 22, -14), (14, 22, -14), (-14, 22, 14),
                                        (14, 22, 14)], 5126, "VEC3")}
    floor = w.add("f", [(-4, 0, -4), (4, 0, -4), (4, 0, 4), (-4, 0, 4)], 5126, "VEC3",
                  target=34962, minmax=True)
    fidx = w.add("H", [0, 2, 1, 0, 3, 2], 5123, "SCALAR", target=34963)
    meshes = [sphere_mesh(w, 12, 0), sphere_mesh(w, 8, 1),
              {"primitives": [{"attributes": {"POSITION": floor}, "indices": fidx,
                               "material": 2}]}]
    materials = [material("clay", [0.8, 0.45, 0.3]), material("lamp", [1, 1, 1], 40),
                 material("floor", [0.6, 0.6, 0.6])]
    nodes = [{"name": "Balls", "mesh": 0, "extensions": {"EXT_mesh_gpu_instancing":
                                                         {"attributes": inst}}},
             {"name": "Lamps", "mesh": 1, "scale": [0.1, 0.1, 0.1],
              "extensions": {"EXT_mesh_gpu_instancing": {"attributes": lamps}}},
             {"name": "Floor", "mesh": 2},
             {"name": "Camera", "camera": 0, "translation": [3.2, 3.0, 4.2],
              "rotation": quat_look(), },
             {"name": "Key", "translation": [2, 5, 3],
              "extensions": {"KHR_lights_punctual": {"light": 0}}}]
    lights = [{"type": "point", "color": [1, 1, 1], "intensity": 60}]
    return nodes, meshes, materials, lights


def quat_look():
    """Camera at (3.2, 3, 4.2) looking at (0, 0.9, 0): yaw about y, then pitch about x."""
    d = (-3.2, -2.1, -4.2)
    yaw = math.atan2(-d[0], -d[2])
    pitch = math.atan2(d[1], math.hypot(d[0], d[2]))
    qy = [0, math.sin(yaw / 2), 0, math.cos(yaw / 2)]
    qx = [math.sin(pitch / 2), 0, 0, math.cos(pitch / 2)]
    # q = qy * qx
    x1, y1, z1, w1 = qy
    x2, y2, z2, w2 = qx
    return [w1 * x2 + x1 * w2 + y1 * z2 - z1 * y2, w1 * y2 - x1 * z2 + y1 * w2 + z1 * x2,
            w1 * z2 + x1 * y2 - y1 * x2 + z1 * w2, w1 * w2 - x1 * x2 - y1 * y2 - z1 * z2]


def grid_scene(w, count, segments):
    """count spheres on a 100 x 100 grid, each with its own rotation and scale."""
    side = math.ceil(math.sqrt(count))
    step = 100.0 / side
    t, r, s = [], [], []
    for k in range(count):
        i, j = k % side, k // side
        t.append(((i + 0.5) * step - 50, 0.4 * step, (j + 0.5) * step - 50))
        r.append(tuple(quat((1, (k % 7) + 1, 0.5), (k * 37) % 360)))
        u = 0.3 + 0.1 * ((k * 13) % 5) / 4
        s.append((u * step, 0.4 * step, u * step))
    inst = {"TRANSLATION": w.add("f", t, 5126, "VEC3"), "ROTATION": w.add("f", r, 5126, "VEC4"),
            "SCALE": w.add("f", s, 5126, "VEC3")}
    meshes = [sphere_mesh(w, segments, 0)]
    materials = [material("clay", [0.8, 0.45, 0.3])]
    pitch = -math.radians(90)
    nodes = [{"name": "Grid", "mesh": 0, "extensions": {"EXT_mesh_gpu_instancing":
                                                        {"attributes": inst}}},
             {"name": "Camera", "camera": 0, "translation": [0, 90, 0],
              "rotation": [math.sin(pitch / 2), 0, 0, math.cos(pitch / 2)]},
             {"name": "Sun", "rotation": [math.sin(pitch / 2), 0, 0, math.cos(pitch / 2)],
              "extensions": {"KHR_lights_punctual": {"light": 0}}}]
    lights = [{"type": "directional", "color": [1, 1, 1], "intensity": 3}]
    return nodes, meshes, materials, lights


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--count", type=int, help="benchmark grid of COUNT instances")
    ap.add_argument("--segments", type=int, default=32, help="sphere segments (benchmark)")
    ap.add_argument("--out", default="scenes/instancing.gltf")
    a = ap.parse_args()
    w = Writer()
    if a.count:
        nodes, meshes, materials, lights = grid_scene(w, a.count, a.segments)
    else:
        nodes, meshes, materials, lights = small_scene(w)
    cam = {"type": "perspective", "perspective": {"yfov": 0.8, "znear": 0.05,
                                                  "aspectRatio": 1.5 if not a.count else 1.0}}
    buffer = {"byteLength": len(w.data)}
    if a.count:  # a .bin beside the .gltf: a data URI of 40 MB would be slow to parse
        bin_path = os.path.splitext(a.out)[0] + ".bin"
        with open(bin_path, "wb") as f:
            f.write(w.data)
        buffer["uri"] = os.path.basename(bin_path)
    else:
        buffer["uri"] = "data:application/octet-stream;base64," + base64.b64encode(
            bytes(w.data)).decode()
    doc = {"asset": {"version": "2.0", "generator": "tools/make_instancing_scene.py"},
           "extensionsUsed": ["EXT_mesh_gpu_instancing", "KHR_lights_punctual",
                              "KHR_materials_emissive_strength"],
           "scene": 0, "scenes": [{"nodes": list(range(len(nodes)))}], "nodes": nodes,
           "meshes": meshes, "materials": materials, "cameras": [cam],
           "extensions": {"KHR_lights_punctual": {"lights": lights}},
           "buffers": [buffer], "bufferViews": w.views, "accessors": w.accessors}
    if a.count:
        doc["extensionsUsed"].remove("KHR_materials_emissive_strength")
    with open(a.out, "w") as f:
        json.dump(doc, f, indent=None if a.count else 1, separators=(",", ":") if a.count else None)
        f.write("\n")


if __name__ == "__main__":
    main()
