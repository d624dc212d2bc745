#!/usr/bin/env python3
"""Writes scenes/torus.gltf: the analytic torus and quadrics of TRAY_shape (docs/shapes.md).

A torus, a torus minus a box (CSG), a capped cylinder, an open cone and a paraboloid bowl on a
floor, an emissive thin torus as an area light, under a point light. Run from the repo root.
"""
import json
import math


def phong(name, rgb, spec=0.3, shin=60, emissive=None):
    m = {"name": name,
         "pbrMetallicRoughness": {"baseColorFactor": rgb + [1], "metallicFactor": 0,
                                  "roughnessFactor": 0.5},
         "extensions": {"TRAY_materials_phong": {"ambient": rgb, "diffuse": rgb,
                                                 "specular": [spec] * 3, "shininess": shin,
                                                 "reflectance": 0.0, "transmittance": 0.0}}}
    if emissive:
        m["emissiveFactor"] = [1, 0.9, 0.75]
        m["extensions"]["KHR_materials_emissive_strength"] = {"emissiveStrength": emissive}
    return m


def shape(name, ext, t=None, r=None, s=None):
    n = {"name": name, "extensions": {"TRAY_shape": ext}}
    if t:
        n["translation"] = t
    if r:
        n["rotation"] = r
    if s:
        n["scale"] = s
    return n


def rot_x(deg):
    a = math.radians(deg) / 2
    return [math.sin(a), 0, 0, math.cos(a)]


materials = [phong("floor", [0.7, 0.7, 0.65], spec=0), phong("gold", [0.85, 0.6, 0.2], 0.6, 80),
             phong("teal", [0.2, 0.6, 0.6]), phong("red", [0.8, 0.2, 0.15]),
             phong("ivory", [0.9, 0.88, 0.8]), phong("lamp", [1, 1, 1], 0, 1, 12.0)]
nodes = [
    shape("floor", {"type": "plane", "material": 0}),
    shape("torus", {"type": "torus", "majorRadius": 0.8, "minorRadius": 0.25, "material": 1},
          t=[-1.8, 0.25, 0]),
    shape("cut torus", {"type": "csg", "op": "difference", "children": [3, 4], "material": 2},
          t=[0.3, 0.9, -0.3], r=rot_x(70)),
    shape("ring", {"type": "torus", "majorRadius": 0.7, "minorRadius": 0.3}),
    shape("bite", {"type": "box", "min": [0, 0, -2], "max": [2, 1, 2], "material": 3}),
    shape("cylinder", {"type": "cylinder", "radius": 0.45, "height": 1.2, "capped": True,
                       "material": 4}, t=[2.1, 0, 0.2]),
    shape("cone", {"type": "cone", "radius": 0.4, "height": 0.9, "material": 3}, t=[1.4, 0, 1.3]),
    shape("bowl", {"type": "paraboloid", "radius": 0.45, "height": 0.5, "capped": True,
                   "material": 2}, t=[-0.6, 0, 1.4]),
    shape("lamp ring", {"type": "torus", "majorRadius": 1.0, "minorRadius": 0.04, "material": 5},
          t=[0, 1.75, -1.7], r=rot_x(60)),
    {"name": "light", "translation": [2.5, 6.0, 3.0], "extensions": {"KHR_lights_punctual": {"light": 0}}},
    {"name": "camera", "camera": 0, "translation": [0.0, 3.0, 6.5],
     "rotation": [-0.2164396, 0, 0, 0.976296]},
]
gltf = {
    "asset": {"version": "2.0", "generator": "TRay tools/make_torus_scene.py"},
    "extensionsUsed": ["TRAY_shape", "TRAY_materials_phong", "KHR_lights_punctual",
                       "KHR_materials_emissive_strength"],
    "extensions": {"KHR_lights_punctual": {"lights": [{"type": "point", "color": [1, 1, 1],
                                                       "intensity": 60.0}]}},
    "scene": 0,
    "scenes": [{"nodes": [0, 1, 2, 5, 6, 7, 8, 9, 10]}],
    "nodes": nodes,
    "materials": materials,
    "cameras": [{"type": "perspective", "perspective": {"yfov": 0.7, "aspectRatio": 1.5,
                                                        "znear": 0.05}}],
}
with open("scenes/torus.gltf", "w") as f:
    json.dump(gltf, f, indent=1)
    f.write("\n")
