#!/usr/bin/env python3
"""Writes the scenes of docs/materials-iridescence-dispersion.md: scenes/materials/
iridescence.gltf (thin films on spheres) and scenes/materials/dispersion.gltf (glass spheres,
with and without KHR_materials_dispersion, in front of white bars)."""
import json
import math
import os

HERE = os.path.dirname(os.path.abspath(__file__))
OUT = os.path.join(HERE, "..", "scenes", "materials")


def look_at(eye, target):
    """glTF node rotation (x, y, z, w) of a camera at eye looking at target (+Y up)."""
    f = [t - e for t, e in zip(target, eye)]
    n = math.sqrt(sum(c * c for c in f))
    f = [c / n for c in f]
    z = [-c for c in f]  # the camera looks down -Z
    up = [0.0, 1.0, 0.0]
    x = [up[1] * z[2] - up[2] * z[1], up[2] * z[0] - up[0] * z[2], up[0] * z[1] - up[1] * z[0]]
    n = math.sqrt(sum(c * c for c in x))
    x = [c / n for c in x]
    y = [z[1] * x[2] - z[2] * x[1], z[2] * x[0] - z[0] * x[2], z[0] * x[1] - z[1] * x[0]]
    m = [[x[0], y[0], z[0]], [x[1], y[1], z[1]], [x[2], y[2], z[2]]]
    tr = m[0][0] + m[1][1] + m[2][2]
    if tr > 0:
        s = math.sqrt(tr + 1.0) * 2
        return [(m[2][1] - m[1][2]) / s, (m[0][2] - m[2][0]) / s, (m[1][0] - m[0][1]) / s, 0.25 * s]
    raise ValueError("camera orientation not handled")


def shape(name, kind, material, translation=(0, 0, 0), **kw):
    ext = {"type": kind, "material": material}
    ext.update(kw)
    return {"name": name, "extensions": {"TRAY_shape": ext}, "translation": list(translation)}


def pbr(name, color, metallic, roughness, extensions=None, emissive=None):
    m = {"name": name, "pbrMetallicRoughness": {"baseColorFactor": list(color) + [1],
                                                 "metallicFactor": metallic,
                                                 "roughnessFactor": roughness}}
    if extensions:
        m["extensions"] = extensions
    if emissive:
        m["emissiveFactor"] = [1, 1, 1]
        m.setdefault("extensions", {})["KHR_materials_emissive_strength"] = {
            "emissiveStrength": emissive}
    return m


def document(nodes, materials, eye, target, background, yfov=0.5, aspect=2.0):
    nodes = nodes + [{"name": "camera", "camera": 0, "translation": list(eye),
                      "rotation": look_at(eye, target)}]
    used = sorted({k for m in materials for k in m.get("extensions", {})} | {"TRAY_shape"})
    return {
        "asset": {"version": "2.0", "generator": "tools/make-spectral-scenes.py"},
        "scene": 0,
        "scenes": [{"nodes": list(range(len(nodes))),
                    "extensions": {"TRAY_environment": {"background": background}}}],
        "nodes": nodes, "materials": materials,
        "cameras": [{"type": "perspective",
                     "perspective": {"yfov": yfov, "aspectRatio": aspect, "znear": 0.01}}],
        "extensionsUsed": used + ["TRAY_environment"],
    }


def iridescence():
    def film(nm, ior=1.33):
        return {"KHR_materials_iridescence": {"iridescenceFactor": 1.0, "iridescenceIor": ior,
                                              "iridescenceThicknessMaximum": nm}}
    materials = [pbr("floor", (0.4, 0.4, 0.4), 0.0, 1.0),
                 # The base without a film (reference): a dark, glossy dielectric.
                 pbr("plain black", (0.02, 0.02, 0.02), 0.0, 0.05)]
    # A soap bubble's look: the same base under water films of growing thickness.
    for nm in (250, 400, 550):
        materials.append(pbr(f"soap film {nm} nm", (0.02, 0.02, 0.02), 0.0, 0.05, film(nm)))
    # A metal (titanium-like grey) under an oxide film of IOR 1.8.
    materials.append(pbr("oxide film on metal", (0.6, 0.6, 0.62), 1.0, 0.15, film(250, 1.8)))
    materials.append(pbr("softbox", (0, 0, 0), 0.0, 1.0, emissive=8.0))
    nodes = [shape("floor", "plane", 0)]
    for i in range(5):
        nodes.append(shape(f"sphere{i}", "sphere", 1 + i, (-2.2 + 1.1 * i, 0.5, 0), radius=0.5))
    nodes.append(shape("softbox", "sphere", 6, (1.5, 4.0, 4.0), radius=1.2))
    return document(nodes, materials, (0, 1.6, 5.5), (0, 0.45, 0), [0.35, 0.4, 0.5],
                    aspect=2.5)


def dispersion():
    glass = {"KHR_materials_transmission": {"transmissionFactor": 1},
             "KHR_materials_ior": {"ior": 1.5}}
    dispersive = dict(glass)
    dispersive["KHR_materials_dispersion"] = {"dispersion": 1.0}  # Abbe number 20
    materials = [
        pbr("floor", (0.3, 0.3, 0.3), 0.0, 1.0),
        pbr("dispersive glass", (1, 1, 1), 0.0, 0.0, dispersive),
        pbr("plain glass", (1, 1, 1), 0.0, 0.0, glass),
        pbr("bar", (0, 0, 0), 0.0, 1.0, emissive=4.0),
    ]
    nodes = [shape("floor", "plane", 0),
             shape("dispersive", "sphere", 1, (-0.75, 0.7, 0), radius=0.6),
             shape("plain", "sphere", 2, (0.75, 0.7, 0), radius=0.6)]
    for i in range(7):  # white bars behind the spheres
        x = -2.4 + 0.8 * i
        nodes.append(shape(f"bar{i}", "box", 3, (x, 1.0, -2.0),
                           min=[-0.06, -1.0, -0.06], max=[0.06, 1.0, 0.06]))
    return document(nodes, materials, (0, 0.9, 4.0), (0, 0.75, 0), [0.02, 0.02, 0.025])


def main():
    os.makedirs(OUT, exist_ok=True)
    for name, doc in (("iridescence", iridescence()), ("dispersion", dispersion())):
        with open(os.path.join(OUT, name + ".gltf"), "w") as f:
            json.dump(doc, f, indent=1)
            f.write("\n")


if __name__ == "__main__":
    main()
