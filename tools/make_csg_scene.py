#!/usr/bin/env python3
"""Writes scenes/csg.gltf: a sampler of TRAY_shape CSG (docs/csg.md) on a floor. A glass lens
(intersection of two spheres), a die (box intersected with a sphere, minus six pips), a bowl
(sphere minus a box, then minus a smaller sphere), a block with a torus-shaped groove (box
minus a closed triangle-mesh torus), and a ball cut by a tilted half-space. CSG operands are
nodes referenced only from a TRAY_shape "children" list, each with its own transform and
material. Usage: tools/make_csg_scene.py [OUT]"""
import base64, json, math, struct, sys

# --- A closed torus mesh (ring radius 1, tube 0.3, around +Y), shared vertices -------------
NU, NV, R, r = 48, 24, 1.0, 0.3
positions, indices = [], []
for i in range(NU):
    for j in range(NV):
        u, v = 2 * math.pi * i / NU, 2 * math.pi * j / NV
        w = R + r * math.cos(v)
        positions.append((w * math.cos(u), r * math.sin(v), w * math.sin(u)))
vid = lambda i, j: (i % NU) * NV + (j % NV)
for i in range(NU):
    for j in range(NV):
        a, b, c, d = vid(i, j), vid(i + 1, j), vid(i + 1, j + 1), vid(i, j + 1)
        indices += [a, c, b, a, d, c]
pos_bytes = b"".join(struct.pack("<3f", *p) for p in positions)
idx_bytes = b"".join(struct.pack("<I", k) for k in indices)
blob = pos_bytes + idx_bytes
xs, ys, zs = zip(*positions)

def phong(diffuse, specular=(0, 0, 0), shininess=32, kr=0.0, kt=0.0):
    return {"TRAY_materials_phong": {"ambient": list(diffuse), "diffuse": list(diffuse),
            "specular": list(specular), "shininess": shininess, "reflectance": kr,
            "transmittance": kt}}

def material(name, color, **phong_args):
    return {"name": name, "pbrMetallicRoughness": {"baseColorFactor": list(color) + [1],
            "metallicFactor": 0, "roughnessFactor": 0.6}, "extensions": phong(color, **phong_args)}

materials = [
    material("floor", (0.7, 0.7, 0.65)),                                          # 0
    dict(material("glass", (0, 0, 0), specular=(0.6, 0.6, 0.6), shininess=400, kr=0.05, kt=0.92),
         extensions=dict(phong((0, 0, 0), (0.6, 0.6, 0.6), 400, 0.05, 0.92),
                         KHR_materials_transmission={"transmissionFactor": 1},
                         KHR_materials_ior={"ior": 1.5})),                         # 1
    material("ivory", (0.9, 0.88, 0.8), specular=(0.3, 0.3, 0.3), shininess=60),  # 2
    material("pip black", (0.05, 0.05, 0.05)),                                    # 3
    material("terracotta", (0.75, 0.35, 0.2)),                                    # 4
    material("glaze blue", (0.15, 0.3, 0.8), specular=(0.5, 0.5, 0.5), shininess=120),  # 5
    material("steel", (0.5, 0.52, 0.55), specular=(0.4, 0.4, 0.4), shininess=80),       # 6
    material("groove gold", (0.85, 0.65, 0.2)),                                   # 7
    material("cut green", (0.2, 0.7, 0.3)),                                       # 8
]

nodes = []
def node(name, shape=None, **trs):
    n = {"name": name}
    n.update(trs)
    if shape is not None:
        n["extensions"] = {"TRAY_shape": shape}
    nodes.append(n)
    return len(nodes) - 1

def csg(op, children, material=None):
    s = {"type": "csg", "op": op, "children": children}
    if material is not None:
        s["material"] = material
    return s

def sphere(radius, material=None):
    s = {"type": "sphere", "radius": radius}
    if material is not None:
        s["material"] = material
    return s

def box(lo, hi, material=None):
    s = {"type": "box", "min": lo, "max": hi}
    if material is not None:
        s["material"] = material
    return s

roots = [node("floor", {"type": "plane", "material": 0})]

# Lens: two unit spheres 1.2 apart; their intersection is a biconvex lens 0.8 thick.
lens_a = node("lens front", sphere(1.0), translation=[0, 0, -0.6])
lens_b = node("lens back", sphere(1.0), translation=[0, 0, 0.6])
roots.append(node("lens", csg("intersection", [lens_a, lens_b], 1), translation=[-0.4, 1.0, 1.5]))

# Die: rounded cube (box n sphere) minus six pip spheres on the faces.
rounded = node("die body", csg("intersection", [node("die cube", box([-0.5] * 3, [0.5] * 3)),
                                                 node("die ball", sphere(0.68))]))
pips = [node("pip %d" % k, sphere(0.12, 3), translation=t) for k, t in enumerate(
    [[0, 0.55, 0], [0, -0.55, 0], [0.55, 0, 0], [-0.55, 0, 0], [0, 0, 0.55], [0, 0, -0.55]])]
roots.append(node("die", csg("difference", [rounded] + pips, 2), translation=[-2.2, 0.5, 0.2],
                  rotation=[0, 0.3826834, 0, 0.9238795]))

# Bowl: sphere minus the box above its equator, minus a smaller sphere (the hollow).
bowl_outer = node("bowl outer", sphere(0.9, 5))
bowl_top = node("bowl top cut", box([-1, 0, -1], [1, 1, 1], 4))
bowl_hollow = node("bowl hollow", sphere(0.75, 4))
roots.append(node("bowl", csg("difference", [bowl_outer, bowl_top, bowl_hollow]),
                  translation=[2.2, 0.9, 0.0]))

# Block with a groove: a box minus a torus mesh (closed triangle mesh as a CSG child).
groove = node("groove torus", mesh=0, translation=[0, 0.5, 0], scale=[0.8, 0.8, 0.8])
block = node("block", box([-1.1, 0, -1.1], [1.1, 0.5, 1.1]))
roots.append(node("grooved block", csg("difference", [block, groove], 6), translation=[1.0, 0, -3.0]))

# Ball cut by a tilted half-space (a plane inside CSG is the solid y <= 0 of its node).
cut_plane = node("cut", {"type": "plane", "material": 8}, rotation=[0, 0, 0.258819, 0.9659258])
roots.append(node("cut ball", csg("intersection", [node("ball", sphere(0.7, 4)), cut_plane]),
                  translation=[-1.6, 0.7, -1.9]))

roots.append(node("light", translation=[2.5, 6.0, 3.0], extensions={"KHR_lights_punctual": {"light": 0}}))
roots.append(node("camera", camera=0, translation=[0.0, 3.2, 6.5], rotation=[-0.2164396, 0, 0, 0.976296]))

gltf = {
    "asset": {"version": "2.0", "generator": "TRay tools/make_csg_scene.py"},
    "extensionsUsed": ["TRAY_shape", "TRAY_materials_phong", "TRAY_environment", "KHR_lights_punctual",
                       "KHR_materials_transmission", "KHR_materials_ior"],
    "extensions": {"KHR_lights_punctual": {"lights": [{"type": "point", "color": [1, 1, 1], "intensity": 120.0}]}},
    "scene": 0,
    "scenes": [{"nodes": roots, "extensions": {"TRAY_environment": {
        "ambient": [0.06, 0.06, 0.08], "background": [0.3, 0.45, 0.7]}}}],
    "nodes": nodes,
    "cameras": [{"type": "perspective", "perspective": {"yfov": 0.7, "aspectRatio": 1.5, "znear": 0.05}}],
    "meshes": [{"name": "torus", "primitives": [{"attributes": {"POSITION": 0}, "indices": 1, "material": 7}]}],
    "materials": materials,
    "accessors": [
        {"bufferView": 0, "componentType": 5126, "count": len(positions), "type": "VEC3",
         "min": [min(xs), min(ys), min(zs)], "max": [max(xs), max(ys), max(zs)]},
        {"bufferView": 1, "componentType": 5125, "count": len(indices), "type": "SCALAR"}],
    "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": len(pos_bytes), "target": 34962},
                    {"buffer": 0, "byteOffset": len(pos_bytes), "byteLength": len(idx_bytes), "target": 34963}],
    "buffers": [{"byteLength": len(blob),
                 "uri": "data:application/octet-stream;base64," + base64.b64encode(blob).decode()}],
}
with open(sys.argv[1] if len(sys.argv) > 1 else "scenes/csg.gltf", "w") as f:
    json.dump(gltf, f, indent=1)
