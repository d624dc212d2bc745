#!/usr/bin/env python3
"""Writes scenes/anisotropy.gltf and scenes/diffuse-transmission.gltf, the sample scenes of
KHR_materials_anisotropy and KHR_materials_diffuse_transmission (docs/materials-extensions.md).
Analytic TRAY_shape spheres and disks carry their own tangent (dp/du, the azimuthal direction),
so the anisotropy direction follows circles of latitude (spheres) or circles about the centre
(the disk: a brushed record). Render them with `--integrator path` (the default, whitted, does
not read these extensions)."""
import json
import math
import os

ROOT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..")


def metal(name, rough, color, strength=None, rotation=0.0):
    m = {"name": name, "pbrMetallicRoughness": {"baseColorFactor": color + [1],
                                                 "metallicFactor": 1, "roughnessFactor": rough}}
    if strength is not None:
        m["extensions"] = {"KHR_materials_anisotropy": {"anisotropyStrength": strength,
                                                        "anisotropyRotation": rotation}}
    return m


def diffuse(name, color, dt=None, dt_color=None, double_sided=False):
    m = {"name": name, "doubleSided": double_sided,
         "pbrMetallicRoughness": {"baseColorFactor": color + [1], "metallicFactor": 0,
                                  "roughnessFactor": 1}}
    if dt is not None:
        m["extensions"] = {"KHR_materials_diffuse_transmission": {
            "diffuseTransmissionFactor": dt, "diffuseTransmissionColorFactor": dt_color}}
    return m


def light(name, t, index):
    return {"name": name, "translation": t, "extensions": {"KHR_lights_punctual": {"light": index}}}


def shape(name, t, spec, rotation=None):
    n = {"name": name, "translation": t, "extensions": {"TRAY_shape": spec}}
    if rotation:
        n["rotation"] = rotation
    return n


def camera_node(t, pitch):
    return {"name": "camera", "camera": 0, "translation": t,
            "rotation": [math.sin(pitch / 2), 0, 0, math.cos(pitch / 2)]}


def document(nodes, materials, lights, extensions_used, required):
    return {"asset": {"version": "2.0", "generator": "TRay tools/make_extension_scenes.py"},
            "extensionsUsed": sorted(set(extensions_used + ["TRAY_shape", "TRAY_environment",
                                                            "KHR_lights_punctual"])),
            "extensions": {"KHR_lights_punctual": {"lights": [
                {"type": "point", "color": [1, 1, 1], "intensity": i} for i in lights]}},
            "extensionsRequired": required,
            "scene": 0,
            "scenes": [{"nodes": list(range(len(nodes))),
                        "extensions": {"TRAY_environment": {"background": [0.02, 0.02, 0.025]}}}],
            "nodes": nodes,
            "cameras": [{"type": "perspective",
                         "perspective": {"yfov": 0.6, "aspectRatio": 1.5, "znear": 0.05}}],
            "materials": materials}


def anisotropy():
    materials = [
        diffuse("floor", [0.18, 0.18, 0.2]),
        metal("isotropic", 0.3, [0.95, 0.85, 0.6]),
        metal("anisotropic along the tangent", 0.3, [0.95, 0.85, 0.6], 0.9),
        metal("anisotropic, rotated 90 degrees", 0.3, [0.95, 0.85, 0.6], 0.9, math.pi / 2),
        metal("brushed disk", 0.25, [0.9, 0.9, 0.92], 0.95),
    ]
    nodes = [
        shape("floor", [0, 0, 0], {"type": "box", "min": [-30, -1, -30], "max": [30, 0, 30],
                                   "material": 0}),
        shape("isotropic", [-1.25, 0.55, 0], {"type": "sphere", "radius": 0.5, "material": 1}),
        shape("anisotropic", [0, 0.55, 0], {"type": "sphere", "radius": 0.5, "material": 2}),
        shape("rotated", [1.25, 0.55, 0], {"type": "sphere", "radius": 0.5, "material": 3}),
        shape("brushed disk", [0, 0.01, 1.3], {"type": "disk", "radius": 0.8, "material": 4}),
        light("lamp", [0.4, 3.0, 2.2], 0),
        camera_node([0, 2.3, 4.6], -0.42),
    ]
    return document(nodes, materials, [60.0], ["KHR_materials_anisotropy"],
                    ["KHR_materials_anisotropy"])


def diffuse_transmission():
    materials = [
        diffuse("floor", [0.3, 0.3, 0.3]),
        diffuse("leaf", [0.15, 0.35, 0.05], 0.6, [0.5, 0.9, 0.2], True),
        diffuse("opaque card", [0.15, 0.35, 0.05], None, None, True),
    ]
    # Two upright cards (disks facing the camera) with a small lamp behind each.
    upright = [math.sin(math.pi / 4), 0, 0, math.cos(math.pi / 4)]  # disk normal +y -> +z
    nodes = [
        shape("floor", [0, 0, 0], {"type": "box", "min": [-30, -1, -30], "max": [30, 0, 30],
                                   "material": 0}),
        shape("leaf", [-0.7, 0.8, 0], {"type": "disk", "radius": 0.6, "material": 1}, upright),
        shape("opaque", [0.7, 0.8, 0], {"type": "disk", "radius": 0.6, "material": 2}, upright),
        light("lamp behind leaf", [-0.7, 0.8, -0.5], 0),
        light("lamp behind card", [0.7, 0.8, -0.5], 0),
        light("fill", [0, 4, 4], 1),
        camera_node([0, 1.0, 3.2], -0.06),
    ]
    return document(nodes, materials, [1.5, 8.0], ["KHR_materials_diffuse_transmission"],
                    ["KHR_materials_diffuse_transmission"])


for name, doc in (("anisotropy.gltf", anisotropy()),
                  ("diffuse-transmission.gltf", diffuse_transmission())):
    with open(os.path.join(ROOT, "scenes", name), "w") as f:
        json.dump(doc, f, indent=1)
        f.write("\n")
