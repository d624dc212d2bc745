#!/usr/bin/env python3
"""Writes the heavier bench scenes of bench/mitsuba_compare.py into scenes/bench/ (issue 16).

scenes/bench/heavy-helmets.gltf: DamagedHelmet and WaterBottle (textured) on a glossy metal floor, a
glass sphere (KHR_materials_transmission + ior), lit by a constant sky (TRAY_environment
background = Mitsuba `constant`) and one emissive quad (KHR_materials_emissive_strength = a
Mitsuba `area` emitter of that radiance). scenes/bench/heavy-spheres.gltf:
MetalRoughSpheresNoTextures (~1M triangles) as it is, under a white sky of radiance 1, with a
camera of its own.

The assets stay in ../shared: the scenes reference their buffers and images by relative URI
(a .glb as a buffer whose bufferViews start after its BIN chunk header), so tray-render needs
--allow-any-path for them; bench/mitsuba_compare.py copies them into a folder of their own.
Occlusion textures are left out (neither renderer uses them). Run from anywhere:
  python3 tools/make-heavy-scenes.py
"""
import base64
import json
import math
import os
import struct
from array import array

ROOT = os.path.normpath(os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
# A folder of their own: tests/accel/bvh_render_test.cpp loads every file directly in scenes/
# without --allow-any-path (and these repeat shared assets that test already covers).
SCENES = os.path.join(ROOT, "scenes", "bench")
SHARED = os.path.normpath(os.path.join(ROOT, "..", "shared"))


def read_asset(path):
    """(json, byte offset of the BIN chunk's data or None) of a .gltf or .glb."""
    with open(path, "rb") as f:
        data = f.read()
    if data[:4] != b"glTF":
        return json.loads(data), None
    json_len = struct.unpack("<I", data[12:16])[0]
    return json.loads(data[20:20 + json_len]), 20 + json_len + 8


def shift(items, key, by):
    for item in items:
        if key in item:
            item[key] += by


def merge(doc, asset_path):
    """Appends an asset's buffers ... nodes to `doc`; returns its scene's root nodes (new ids)."""
    src, bin_offset = read_asset(asset_path)
    rel = lambda uri: os.path.relpath(os.path.join(os.path.dirname(asset_path), uri), SCENES)
    base = {k: len(doc.setdefault(k, [])) for k in
            ("buffers", "bufferViews", "accessors", "images", "samplers", "textures", "materials",
             "meshes", "nodes")}
    for b in src.get("buffers", []):
        if "uri" in b:
            b["uri"] = rel(b["uri"])
        else:  # a .glb's BIN chunk: the whole file, viewed from its data's offset on
            b["uri"] = rel(os.path.basename(asset_path))
            b["byteLength"] = os.path.getsize(asset_path)
    views = src.get("bufferViews", [])
    shift(views, "buffer", base["buffers"])
    if bin_offset is not None:
        for v in views:
            v["byteOffset"] = v.get("byteOffset", 0) + bin_offset
    shift(src.get("accessors", []), "bufferView", base["bufferViews"])
    for img in src.get("images", []):
        if "uri" in img:
            img["uri"] = rel(img["uri"])
    shift(src.get("images", []), "bufferView", base["bufferViews"])
    shift(src.get("textures", []), "sampler", base["samplers"])
    shift(src.get("textures", []), "source", base["images"])
    for m in src.get("materials", []):
        m.pop("occlusionTexture", None)  # neither renderer uses it
        pbr = m.get("pbrMetallicRoughness", {})
        for info in (pbr.get("baseColorTexture"), pbr.get("metallicRoughnessTexture"),
                     m.get("normalTexture"), m.get("emissiveTexture")):
            if info:
                info["index"] += base["textures"]
    for mesh in src.get("meshes", []):
        for p in mesh["primitives"]:
            p["attributes"] = {k: v + base["accessors"] for k, v in p["attributes"].items()}
            if "indices" in p:
                p["indices"] += base["accessors"]
            if "material" in p:
                p["material"] += base["materials"]
    for n in src.get("nodes", []):
        if "mesh" in n:
            n["mesh"] += base["meshes"]
        if "children" in n:
            n["children"] = [c + base["nodes"] for c in n["children"]]
    for k in base:
        doc[k].extend(src.get(k, []))
    roots = src["scenes"][src.get("scene", 0)]["nodes"]
    return [r + base["nodes"] for r in roots]


def look_at(eye, target):
    """glTF node rotation (x, y, z, w) of a camera at `eye` looking at `target` (+Y up)."""
    unit = lambda v: [c / math.sqrt(sum(x * x for x in v)) for c in v]
    cross = lambda a, b: [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2],
                          a[0] * b[1] - a[1] * b[0]]
    f = unit([t - e for t, e in zip(target, eye)])
    right = unit(cross(f, [0, 1, 0]))
    up = cross(right, f)
    # Rotation matrix columns: right, up, -f (the camera looks down its -Z).
    m = [[right[i], up[i], -f[i]] for i in range(3)]
    w = math.sqrt(max(0.0, 1 + m[0][0] + m[1][1] + m[2][2])) / 2
    return [(m[2][1] - m[1][2]) / (4 * w), (m[0][2] - m[2][0]) / (4 * w),
            (m[1][0] - m[0][1]) / (4 * w), w]


def add_mesh(doc, positions, normals, indices, material, name):
    """A mesh whose data is one data: URI buffer; returns the mesh index."""
    pos = array("f", [c for p in positions for c in p])
    nrm = array("f", [c for n in normals for c in n])
    idx = array("I", [i for t in indices for i in t])
    blob = pos.tobytes() + nrm.tobytes() + idx.tobytes()  # little-endian on x86 and ARM
    lo = [min(pos[k::3]) for k in range(3)]
    hi = [max(pos[k::3]) for k in range(3)]
    size = lambda a: len(a) * a.itemsize
    b = len(doc["buffers"])
    doc["buffers"].append({"byteLength": len(blob), "uri": "data:application/octet-stream;base64,"
                           + base64.b64encode(blob).decode()})
    v = len(doc["bufferViews"])
    doc["bufferViews"] += [
        {"buffer": b, "byteOffset": 0, "byteLength": size(pos)},
        {"buffer": b, "byteOffset": size(pos), "byteLength": size(nrm)},
        {"buffer": b, "byteOffset": size(pos) + size(nrm), "byteLength": size(idx)}]
    a = len(doc["accessors"])
    doc["accessors"] += [
        {"bufferView": v, "componentType": 5126, "count": len(positions), "type": "VEC3",
         "min": lo, "max": hi},
        {"bufferView": v + 1, "componentType": 5126, "count": len(normals), "type": "VEC3"},
        {"bufferView": v + 2, "componentType": 5125, "count": len(idx), "type": "SCALAR"}]
    doc["meshes"].append({"name": name, "primitives": [
        {"attributes": {"POSITION": a, "NORMAL": a + 1}, "indices": a + 2, "material": material}]})
    return len(doc["meshes"]) - 1


def uv_sphere(rings=16, segments=32):
    """Unit sphere, counter-clockwise seen from outside, smooth normals."""
    pts = []
    for i in range(rings + 1):
        th = math.pi * i / rings
        for j in range(segments + 1):
            ph = 2 * math.pi * j / segments
            pts.append([math.sin(th) * math.cos(ph), math.cos(th), -math.sin(th) * math.sin(ph)])
    tris = []
    for i in range(rings):
        for j in range(segments):
            a, b = i * (segments + 1) + j, (i + 1) * (segments + 1) + j
            if i > 0:
                tris.append([a, b, a + 1])
            if i < rings - 1:
                tris.append([a + 1, b, b + 1])
    return pts, pts, tris


def quad(half, y, down):
    """A square of side 2·half at height y facing +Y (or −Y when `down`)."""
    p = [[-half, y, -half], [-half, y, half], [half, y, half], [half, y, -half]]
    tris = [[0, 1, 2], [0, 2, 3]]
    if down:
        tris = [[0, 2, 1], [0, 3, 2]]
    n = [[0, -1 if down else 1, 0]] * 4
    return p, n, tris


def helmets():
    doc = {"asset": {"version": "2.0", "generator": "tools/make-heavy-scenes.py"},
           "extensionsUsed": ["KHR_materials_transmission", "KHR_materials_ior",
                              "KHR_materials_emissive_strength", "TRAY_environment"]}
    helmet = merge(doc, os.path.join(SHARED, "gltf-samples", "DamagedHelmet.glb"))
    bottle = merge(doc, os.path.join(SHARED, "gltf-features", "WaterBottle", "WaterBottle.gltf"))
    # Bilinear lookups in the finest level, as Mitsuba's bitmap does (it has no MIP-maps): TRay's
    # trilinear filtering over the pixel footprint cannot be carried over, so it is left out of
    # both (issue 16). LINEAR for both filters (glTF 2.0 §5.26), the assets' wrap modes kept.
    for sampler in doc["samplers"]:
        sampler.update({"magFilter": 9729, "minFilter": 9729})
    for texture in doc["textures"]:
        if "sampler" not in texture:
            texture["sampler"] = len(doc["samplers"])
            doc["samplers"].append({"magFilter": 9729, "minFilter": 9729})
    m = len(doc["materials"])
    doc["materials"] += [
        {"name": "glossy metal floor", "pbrMetallicRoughness": {
            "baseColorFactor": [0.55, 0.55, 0.6, 1], "metallicFactor": 1, "roughnessFactor": 0.3}},
        {"name": "glass", "pbrMetallicRoughness": {"metallicFactor": 0, "roughnessFactor": 0},
         "extensions": {"KHR_materials_transmission": {"transmissionFactor": 1},
                        "KHR_materials_ior": {"ior": 1.5}}},
        {"name": "light", "pbrMetallicRoughness": {
            "baseColorFactor": [0, 0, 0, 1], "metallicFactor": 0, "roughnessFactor": 1},
         "emissiveFactor": [1, 0.95, 0.85],
         "extensions": {"KHR_materials_emissive_strength": {"emissiveStrength": 12}}}]
    floor = add_mesh(doc, *quad(8, 0, False), m, "floor")
    sphere = add_mesh(doc, *uv_sphere(), m + 1, "glass sphere")
    light = add_mesh(doc, *quad(0.75, 0, True), m + 2, "rect light")
    eye, target = [0.4, 2.4, 6.5], [0.1, 0.8, 0]
    doc["cameras"] = [{"type": "perspective", "perspective": {"yfov": 0.6, "znear": 0.05}}]
    n = len(doc["nodes"])
    doc["nodes"] += [
        {"name": "helmet", "translation": [-1.15, 0.901, -0.2], "children": helmet},
        {"name": "bottle", "translation": [1.3, 1.0418, -0.4], "scale": [8, 8, 8],
         "children": bottle},
        {"name": "floor", "mesh": floor},
        {"name": "glass sphere", "mesh": sphere, "translation": [0.15, 0.55, 1.3],
         "scale": [0.55, 0.55, 0.55]},
        {"name": "rect light", "mesh": light, "translation": [-1, 4.5, 2.5]},
        {"name": "camera", "camera": 0, "translation": eye, "rotation": look_at(eye, target)}]
    doc["scene"] = 0
    doc["scenes"] = [{"nodes": list(range(n, n + 6)), "extensions": {
        "TRAY_environment": {"background": [0.25, 0.3, 0.4]}}}]
    return doc


def sun_helmets():
    """The helmets under a sun (a KHR_lights_punctual directional light) and a constant sky in
    place of the rect light: the sun-and-sky scene of the sampling charts (issue 37)."""
    doc = helmets()
    doc["extensionsUsed"].append("KHR_lights_punctual")
    doc["extensions"] = {"KHR_lights_punctual": {"lights": [
        {"name": "sun", "type": "directional", "color": [1, 0.95, 0.88], "intensity": 3}]}}
    nodes = doc["scenes"][0]["nodes"]
    light = next(i for i in nodes if doc["nodes"][i]["name"] == "rect light")
    doc["nodes"][light] = {"name": "sun", "rotation": look_at([-3, 6, 4], [0, 0, 0]),
                           "extensions": {"KHR_lights_punctual": {"light": 0}}}
    doc["scenes"][0]["extensions"]["TRAY_environment"] = {"background": [0.35, 0.45, 0.65]}
    return doc


def spheres():
    doc = {"asset": {"version": "2.0", "generator": "tools/make-heavy-scenes.py"},
           "extensionsUsed": ["TRAY_environment"]}
    roots = merge(doc, os.path.join(SHARED, "gltf-samples", "MetalRoughSpheresNoTextures.glb"))
    # The asset lies in the XY plane (x, y in about [-0.001, 0.0075]), facing +Z.
    eye, target = [0.0033, 0.0033, 0.0125], [0.0033, 0.0033, 0]
    doc["cameras"] = [{"type": "perspective", "perspective": {"yfov": 0.6, "znear": 0.0001}}]
    n = len(doc["nodes"])
    doc["nodes"].append({"name": "camera", "camera": 0, "translation": eye,
                         "rotation": look_at(eye, target)})
    doc["scene"] = 0
    doc["scenes"] = [{"nodes": roots + [n], "extensions": {
        "TRAY_environment": {"background": [1, 1, 1]}}}]
    return doc


def main():
    os.makedirs(SCENES, exist_ok=True)
    for name, doc in (("heavy-helmets.gltf", helmets()), ("heavy-spheres.gltf", spheres()),
                      ("sun-helmets.gltf", sun_helmets())):
        with open(os.path.join(SCENES, name), "w") as f:
            json.dump(doc, f, separators=(",", ":"))
            f.write("\n")
        print(os.path.relpath(os.path.join(SCENES, name), ROOT))


if __name__ == "__main__":
    main()
