#!/usr/bin/env python3
"""Writes the scenes of docs/curves-subdivision.md (run from the repo root):

scenes/curves/fur_patch.gltf   a patch of round B-spline fur (TRAY_shape "curves") with
                               TRAY_materials_hair, three melanin amounts side by side
scenes/curves/ribbons.gltf     the same strands as flat Bezier ribbons (profile "flat")
scenes/curves/subdiv_cube.gltf Catmull-Clark cubes (TRAY_shape "subdivision"): plain, with
                               creased edges, and a glTF triangle mesh as the cage ("mesh")

Buffers are embedded (data URIs); the random strands come from a fixed seed.
"""
import base64
import json
import math
import random
import struct


class Builder:
    def __init__(self):
        self.data = bytearray()
        self.views, self.accessors = [], []

    def accessor(self, values, kind, comp, count):
        while len(self.data) % 4:
            self.data.append(0)
        fmt = {"f": "<%df", "I": "<%dI"}[comp] % len(values)
        offset = len(self.data)
        self.data += struct.pack(fmt, *values)
        self.views.append({"buffer": 0, "byteOffset": offset, "byteLength": len(self.data) - offset})
        acc = {"bufferView": len(self.views) - 1, "componentType": 5126 if comp == "f" else 5125,
               "count": count, "type": kind}
        if kind == "VEC3" and comp == "f":  # glTF requires min/max on POSITION accessors
            acc["min"] = [min(values[i::3]) for i in range(3)]
            acc["max"] = [max(values[i::3]) for i in range(3)]
        self.accessors.append(acc)
        return len(self.accessors) - 1

    def gltf(self, generator, **parts):
        doc = {"asset": {"version": "2.0", "generator": "TRay tools/make_curves_scenes.py: " + generator}}
        doc.update(parts)
        doc["buffers"] = [{"byteLength": len(self.data), "uri": "data:application/octet-stream;base64,"
                           + base64.b64encode(bytes(self.data)).decode()}]
        doc["bufferViews"] = self.views
        doc["accessors"] = self.accessors
        return doc


def rot_x(deg):
    a = math.radians(deg) / 2
    return [math.sin(a), 0, 0, math.cos(a)]


def strands(rng, n, size, length, points_per_strand, bezier):
    """Fur: strands rooted on a size x size square, leaning and curling a little."""
    pts, counts = [], []
    for i in range(n):
        for j in range(n):
            x0 = (i + rng.random()) / n * size - size / 2
            z0 = (j + rng.random()) / n * size - size / 2
            lean = rng.uniform(0.2, 0.5)
            ang = rng.uniform(0, 2 * math.pi)
            curl = rng.uniform(0.01, 0.03)
            L = length * rng.uniform(0.8, 1.1)
            k = points_per_strand
            for s in range(k):
                t = s / (k - 1)
                x = x0 + lean * L * t * t * math.cos(ang) + curl * math.sin(9 * t + ang)
                z = z0 + lean * L * t * t * math.sin(ang) + curl * math.cos(9 * t + ang)
                y = L * t * (1 - 0.3 * lean * t)
                r = 0.004 * (1 - 0.8 * t) + 0.0006
                pts += [x, y, z, r]
            counts.append(k)
    return pts, counts


def lights():
    return {"KHR_lights_punctual": {"lights": [
        {"type": "point", "color": [1, 0.95, 0.9], "intensity": 30.0},
        {"type": "point", "color": [0.8, 0.85, 1.0], "intensity": 12.0}]}}


def light_nodes():
    return [{"name": "key", "translation": [1.5, 2.5, 2.0], "extensions": {"KHR_lights_punctual": {"light": 0}}},
            {"name": "rim", "translation": [-1.5, 1.5, -2.0], "extensions": {"KHR_lights_punctual": {"light": 1}}}]


def floor_material():
    return {"name": "floor", "pbrMetallicRoughness": {"baseColorFactor": [0.6, 0.6, 0.58, 1],
                                                      "metallicFactor": 0, "roughnessFactor": 1}}


def fur_scene(profile, bezier, name):
    rng = random.Random(41)
    b = Builder()
    melanins = [(0.15, 0.4), (0.5, 0.8), (0.9, 0.3)]  # blond, auburn, dark
    materials = [floor_material()]
    nodes, roots = [], []
    for k, (mel, red) in enumerate(melanins):
        pts, counts = strands(rng, 16, 0.5, 0.45, 4 if bezier else 6, bezier)
        acc = b.accessor(pts, "VEC4", "f", len(pts) // 4)
        strand_acc = b.accessor(counts, "SCALAR", "I", len(counts))
        materials.append({"name": "hair %d" % k, "extensions": {"TRAY_materials_hair": {
            "melanin": mel, "melaninRedness": red, "roughness": 0.3, "azimuthalRoughness": 0.3,
            "ior": 1.55, "cuticleAngle": 2.0}}})
        nodes.append({"name": "fur %d" % k, "translation": [(k - 1) * 0.6, 0, 0],
                      "extensions": {"TRAY_shape": {"type": "curves", "basis": "bezier" if bezier else "bspline",
                                                    "profile": profile, "points": acc,
                                                    "strands": strand_acc, "material": k + 1}}})
    nodes.append({"name": "floor", "extensions": {"TRAY_shape": {"type": "plane", "material": 0}}})
    nodes += light_nodes()
    nodes.append({"name": "camera", "camera": 0, "translation": [0, 0.75, 1.9], "rotation": rot_x(-17)})
    return b.gltf(name, extensionsUsed=["TRAY_shape", "TRAY_materials_hair", "KHR_lights_punctual"],
                  extensions=lights(), scene=0, scenes=[{"nodes": list(range(len(nodes)))}],
                  nodes=nodes, materials=materials,
                  cameras=[{"type": "perspective", "perspective": {"yfov": 0.55, "aspectRatio": 1.5,
                                                                   "znear": 0.01}}])


CUBE_P = [-1, -1, -1, 1, -1, -1, 1, 1, -1, -1, 1, -1, -1, -1, 1, 1, -1, 1, 1, 1, 1, -1, 1, 1]
# Outward-wound quads (counter-clockwise seen from outside).
CUBE_Q = [0, 3, 2, 1, 4, 5, 6, 7, 0, 1, 5, 4, 2, 3, 7, 6, 1, 2, 6, 5, 0, 4, 7, 3]


def cube_triangles():
    tri = []
    for f in range(6):
        a, b_, c, d = CUBE_Q[4 * f:4 * f + 4]
        tri += [a, b_, c, a, c, d]
    return tri


def subdiv_scene():
    b = Builder()
    pos = b.accessor([0.4 * v for v in CUBE_P], "VEC3", "f", 8)
    counts = b.accessor([4] * 6, "SCALAR", "I", 6)
    idx = b.accessor(CUBE_Q, "SCALAR", "I", 24)
    # The top face's four edges creased (sharp), as a box with a soft bottom.
    creases = b.accessor([2, 3, 3, 7, 7, 6, 6, 2], "SCALAR", "I", 8)
    weights = b.accessor([10.0] * 4, "SCALAR", "f", 4)
    # A glTF triangle mesh (the cube, triangulated) as a cage.
    mesh_pos = b.accessor([0.4 * v for v in CUBE_P], "VEC3", "f", 8)
    mesh_idx = b.accessor(cube_triangles(), "SCALAR", "I", 36)
    materials = [floor_material(),
                 {"name": "clay", "pbrMetallicRoughness": {"baseColorFactor": [0.8, 0.35, 0.2, 1],
                                                           "metallicFactor": 0, "roughnessFactor": 0.5}},
                 {"name": "jade", "pbrMetallicRoughness": {"baseColorFactor": [0.25, 0.6, 0.4, 1],
                                                           "metallicFactor": 0, "roughnessFactor": 0.3}},
                 {"name": "steel", "pbrMetallicRoughness": {"baseColorFactor": [0.8, 0.8, 0.85, 1],
                                                            "metallicFactor": 1, "roughnessFactor": 0.25}}]
    cage = {"positions": pos, "faceVertexCounts": counts, "indices": idx}
    nodes = [
        {"name": "smooth cube", "translation": [-1.0, 0.4, 0],
         "extensions": {"TRAY_shape": dict(type="subdivision", material=1, tessellationRate=16, **cage)}},
        {"name": "creased cube", "translation": [0.0, 0.4, 0],
         "extensions": {"TRAY_shape": dict(type="subdivision", material=2, tessellationRate=16,
                                           creases=creases, creaseWeights=weights, **cage)}},
        {"name": "triangle cage", "translation": [1.0, 0.4, 0],
         "extensions": {"TRAY_shape": {"type": "subdivision", "mesh": 0, "material": 3}}},
        {"name": "floor", "extensions": {"TRAY_shape": {"type": "plane", "material": 0}}},
    ]
    nodes += light_nodes()
    nodes.append({"name": "camera", "camera": 0, "translation": [0, 1.3, 3.2], "rotation": rot_x(-18)})
    # The triangle mesh is only a cage: no node shows it (it is referenced by "mesh").
    meshes = [{"name": "cube cage", "primitives": [{"attributes": {"POSITION": mesh_pos},
                                                    "indices": mesh_idx, "material": 3}]}]
    return b.gltf("subdivision", extensionsUsed=["TRAY_shape", "KHR_lights_punctual"],
                  extensions=lights(), scene=0, scenes=[{"nodes": list(range(len(nodes)))}],
                  nodes=nodes, materials=materials, meshes=meshes,
                  cameras=[{"type": "perspective", "perspective": {"yfov": 0.6, "aspectRatio": 1.5,
                                                                   "znear": 0.01}}])


def write(path, doc):
    with open(path, "w") as f:
        json.dump(doc, f, indent=1)
        f.write("\n")


write("scenes/curves/fur_patch.gltf", fur_scene("round", False, "fur patch"))
write("scenes/curves/ribbons.gltf", fur_scene("flat", True, "ribbons"))
write("scenes/curves/subdiv_cube.gltf", subdiv_scene())
