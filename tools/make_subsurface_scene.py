#!/usr/bin/env python3
"""Writes scenes/subsurface.gltf: translucent solids for TRay's random-walk subsurface
scattering (TRAY_materials_scattering, docs/subsurface.md).

A skin-like sphere, a marble-like torus and a jade-like capped cylinder on a grey floor, lit by
an emissive disk above and behind them (so light shows through the thin parts) and a sky; rough boundaries (light sampling at
the walk's exits through the microfacet transmission).
Coefficients are Jensen et al. 2001's measured skin and marble (sigma_s', sigma_a per mm) with
one scene unit = 10 mm. Run from the repo root.
"""
import json
import math


def medium(name, sigma_s, sigma_a, g, ior=1.4, roughness=0.0):
    return {"name": name,
            "pbrMetallicRoughness": {"baseColorFactor": [1, 1, 1, 1], "metallicFactor": 0,
                                     "roughnessFactor": roughness},
            "extensions": {
                "KHR_materials_transmission": {"transmissionFactor": 1},
                "KHR_materials_ior": {"ior": ior},
                # sigma_a = -ln(attenuationColor) / attenuationDistance (distance 1).
                "KHR_materials_volume": {"attenuationColor": [math.exp(-a) for a in sigma_a],
                                         "attenuationDistance": 1},
                "TRAY_materials_scattering": {"scatteringCoefficient": sigma_s,
                                              "anisotropy": g}}}


def shape(name, ext, t=None, r=None):
    n = {"name": name, "extensions": {"TRAY_shape": ext}}
    if t:
        n["translation"] = t
    if r:
        n["rotation"] = r
    return n


def main():
    mm = 10.0  # mm per scene unit
    materials = [
        {"name": "floor", "pbrMetallicRoughness": {"baseColorFactor": [0.5, 0.5, 0.5, 1],
                                                   "metallicFactor": 0, "roughnessFactor": 1}},
        # Jensen et al. 2001, skin1: sigma_s' = (0.74, 0.88, 1.01), sigma_a = (0.032, 0.17, 0.48)
        medium("skin", [0.74 * mm, 0.88 * mm, 1.01 * mm], [0.032 * mm, 0.17 * mm, 0.48 * mm],
               0.0, ior=1.4, roughness=0.35),
        # marble: sigma_s' = (2.19, 2.62, 3.00), sigma_a = (0.0021, 0.0041, 0.0071)
        medium("marble", [2.19 * mm, 2.62 * mm, 3.00 * mm],
               [0.0021 * mm, 0.0041 * mm, 0.0071 * mm], 0.0, ior=1.5, roughness=0.25),
        medium("jade", [6.0, 9.0, 7.0], [2.0, 0.25, 0.9], 0.3, ior=1.6, roughness=0.2),
        {"name": "lamp", "pbrMetallicRoughness": {"baseColorFactor": [0, 0, 0, 1],
                                                  "metallicFactor": 0},
         "emissiveFactor": [1, 0.92, 0.8],
         "extensions": {"KHR_materials_emissive_strength": {"emissiveStrength": 6}}},
    ]
    nodes = [
        shape("floor", {"type": "plane", "material": 0}),
        shape("skin sphere", {"type": "sphere", "radius": 0.5, "material": 1}, t=[-1.2, 0.5, 0]),
        shape("marble torus", {"type": "torus", "majorRadius": 0.55, "minorRadius": 0.22,
                               "material": 2}, t=[0.05, 0.77, -0.2],
              r=[math.sin(math.radians(70) / 2), 0, 0, math.cos(math.radians(70) / 2)]),
        shape("jade cylinder", {"type": "cylinder", "radius": 0.3, "height": 0.9,
                                "capped": True, "material": 3}, t=[1.2, 0, 0.1]),
        # The lamp faces down-forward: a disk tilted toward the objects from behind.
        shape("lamp", {"type": "disk", "radius": 1.5, "material": 4}, t=[0, 2.6, -2.2],
              r=[math.sin(math.radians(150) / 2), 0, 0, math.cos(math.radians(150) / 2)]),
        {"name": "camera", "camera": 0, "translation": [0, 1.5, 4.2],
         "rotation": [math.sin(math.radians(-14) / 2), 0, 0, math.cos(math.radians(-14) / 2)]},
    ]
    doc = {
        "asset": {"version": "2.0", "generator": "TRay tools/make_subsurface_scene.py"},
        "extensionsUsed": ["TRAY_shape", "TRAY_environment", "TRAY_materials_scattering",
                           "KHR_materials_transmission", "KHR_materials_ior",
                           "KHR_materials_volume", "KHR_materials_emissive_strength"],
        "scene": 0,
        "scenes": [{"nodes": list(range(len(nodes))),
                    "extensions": {"TRAY_environment": {"background": [0.2, 0.23, 0.3]}}}],
        "nodes": nodes,
        "cameras": [{"type": "perspective",
                     "perspective": {"yfov": 0.6, "aspectRatio": 1.5, "znear": 0.01}}],
        "materials": materials,
    }
    with open("scenes/subsurface.gltf", "w") as f:
        json.dump(doc, f, indent=1)
        f.write("\n")


if __name__ == "__main__":
    main()
