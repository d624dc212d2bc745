#!/usr/bin/env python3
"""Writes scenes/whitted.gltf: Whitted's classic scene (a mirror sphere and a glass sphere over
a red-and-yellow checkered floor). The checker is two triangle-mesh primitives, one per
material; the spheres are TRAY_shape analytic spheres. Usage: tools/make_whitted_scene.py OUT"""
import base64, json, struct, sys

N = 12  # tiles per side, each 1 unit
pos = {0: [], 1: []}
for i in range(N):
    for j in range(N):
        x0, z0 = i - N / 2, j - N / 2 - 3
        quad = [(x0, 0, z0), (x0, 0, z0 + 1), (x0 + 1, 0, z0 + 1), (x0 + 1, 0, z0)]
        tris = [quad[0], quad[1], quad[2], quad[0], quad[2], quad[3]]  # CCW seen from +Y
        pos[(i + j) % 2].extend(tris)

blob = b""
views, accessors, meshes = [], [], []
for k in (0, 1):
    data = b"".join(struct.pack("<3f", *p) for p in pos[k])
    views.append({"buffer": 0, "byteOffset": len(blob), "byteLength": len(data)})
    xs = [p[0] for p in pos[k]]; zs = [p[2] for p in pos[k]]
    accessors.append({"bufferView": k, "componentType": 5126, "count": len(pos[k]), "type": "VEC3",
                      "min": [min(xs), 0, min(zs)], "max": [max(xs), 0, max(zs)]})
    blob += data
meshes.append({"name": "checker floor", "primitives": [
    {"attributes": {"POSITION": 0}, "material": 0},
    {"attributes": {"POSITION": 1}, "material": 1}]})

def phong(diffuse, specular=(0, 0, 0), shininess=32, kr=0.0, kt=0.0, ambient=None):
    return {"TRAY_materials_phong": {"ambient": list(ambient or diffuse), "diffuse": list(diffuse),
            "specular": list(specular), "shininess": shininess, "reflectance": kr, "transmittance": kt}}

materials = [
    {"name": "checker yellow", "pbrMetallicRoughness": {"baseColorFactor": [0.9, 0.8, 0.2, 1],
     "metallicFactor": 0, "roughnessFactor": 0.8}, "extensions": phong((0.9, 0.8, 0.2))},
    {"name": "checker red", "pbrMetallicRoughness": {"baseColorFactor": [0.8, 0.1, 0.08, 1],
     "metallicFactor": 0, "roughnessFactor": 0.8}, "extensions": phong((0.8, 0.1, 0.08))},
    {"name": "mirror", "pbrMetallicRoughness": {"baseColorFactor": [0.95, 0.95, 0.95, 1],
     "metallicFactor": 1, "roughnessFactor": 0},
     "extensions": phong((0.05, 0.05, 0.05), (0.6, 0.6, 0.6), 300, kr=0.85)},
    {"name": "glass", "pbrMetallicRoughness": {"baseColorFactor": [1, 1, 1, 1], "metallicFactor": 0,
     "roughnessFactor": 0},
     "extensions": dict(phong((0, 0, 0), (0.6, 0.6, 0.6), 400, kr=0.08, kt=0.9),
                        KHR_materials_transmission={"transmissionFactor": 1},
                        KHR_materials_ior={"ior": 1.5})},
]

gltf = {
    "asset": {"version": "2.0", "generator": "TRay tools/make_whitted_scene.py"},
    "extensionsUsed": ["TRAY_shape", "TRAY_materials_phong", "TRAY_environment", "KHR_lights_punctual",
                       "KHR_materials_transmission", "KHR_materials_ior"],
    "extensions": {"KHR_lights_punctual": {"lights": [
        {"type": "point", "color": [1, 1, 1], "intensity": 60.0}]}},
    "scene": 0,
    "scenes": [{"nodes": [0, 1, 2, 3, 4], "extensions": {"TRAY_environment": {
        "ambient": [0.08, 0.08, 0.1], "background": [0.35, 0.55, 0.9]}}}],
    "nodes": [
        {"name": "floor", "mesh": 0},
        {"name": "mirror sphere", "translation": [-1.1, 1.0, -4.0],
         "extensions": {"TRAY_shape": {"type": "sphere", "radius": 1.0, "material": 2}}},
        {"name": "glass sphere", "translation": [0.9, 1.3, -2.3],
         "extensions": {"TRAY_shape": {"type": "sphere", "radius": 0.8, "material": 3}}},
        {"name": "light", "translation": [2.0, 6.0, 1.0], "extensions": {"KHR_lights_punctual": {"light": 0}}},
        {"name": "camera", "camera": 0, "translation": [0.0, 1.6, 2.2],
         "rotation": [-0.0998, 0.0, 0.0, 0.995]},
    ],
    "cameras": [{"type": "perspective", "perspective": {"yfov": 0.75, "aspectRatio": 1.3333, "znear": 0.05}}],
    "meshes": meshes,
    "materials": materials,
    "accessors": accessors,
    "bufferViews": views,
    "buffers": [{"byteLength": len(blob),
                 "uri": "data:application/octet-stream;base64," + base64.b64encode(blob).decode()}],
}
with open(sys.argv[1] if len(sys.argv) > 1 else "scenes/whitted.gltf", "w") as f:
    json.dump(gltf, f, indent=1)
