#!/usr/bin/env python3
"""Writes scenes/transport/: the scenes that separate light-transport methods (issue 38).

  caustic-spot.gltf   a spot light aimed at a smooth glass ball above a diffuse floor, its cone
                      inside the ball's silhouette: every bit of light on the floor came through
                      (or off) the ball, a caustic path tracing cannot find (L S S D E). An
                      orthographic camera looks straight down; tools/caustic_power.py gives the
                      caustic's power on the visible floor by ray-optics quadrature.
  caustic-glass.gltf  the same caustic seen through a glass slab (L S S D S S E): neither
                      path tracing nor light tracing can connect it; photon mapping can.
  small-opening.gltf  a closed room lit only through a small opening by a bright ball outside.
  glossy-pair.gltf    two rough metal walls facing each other, a small bright ball between:
                      glossy interreflection (L G G D E and L G G E).

All are TRAY_shape boxes, spheres and planes (no buffers). The geometry constants live here;
caustic_power.py imports them. Usage: tools/make-transport-scenes.py [OUT_DIR]
"""
import json
import math
import os
import sys

ROOT = os.path.normpath(os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))

# --- caustic-spot: the closed-form scene ---------------------------------------------------
BALL_CENTER = (0.0, 1.0, 0.0)
BALL_RADIUS = 0.5
BALL_IOR = 1.5
LIGHT_DISTANCE = 3.0            # from the ball's centre
LIGHT_FROM_VERTICAL_DEG = 60.0
LIGHT_INTENSITY = 10.0          # radiant intensity on the axis (W/sr), radiometric units
FLOOR_ALBEDO = 0.5
# The cone stays inside the ball's silhouette (angular radius asin(R / D)): no light reaches
# the floor directly.
SILHOUETTE = math.asin(BALL_RADIUS / LIGHT_DISTANCE)
OUTER_CONE = 0.95 * SILHOUETTE
INNER_CONE = 0.85 * SILHOUETTE
# Orthographic camera looking down at the floor (half extents), its centre, the image size.
VIEW_CENTER = (2.0, 0.0)        # (x, z) on the floor
VIEW_HALF = 2.5
IMAGE_SIZE = 200
# Pixels whose centre lies within this distance of the ball's footprint centre are left out of
# the measurement: they see the ball (radius 0.5 from above), or its edge.
EXCLUDED_RADIUS = 0.6
MAX_DEPTH = 5  # segments: keeps every one-diffuse path with <= 1 internal reflection, drops
               # floor -> ball -> floor interreflection (documented in docs/light-transport.md)


def light_position():
    a = math.radians(LIGHT_FROM_VERTICAL_DEG)
    return (BALL_CENTER[0] - LIGHT_DISTANCE * math.sin(a),
            BALL_CENTER[1] + LIGHT_DISTANCE * math.cos(a), BALL_CENTER[2])


def normalize(v):
    n = math.sqrt(sum(c * c for c in v))
    return tuple(c / n for c in v)


def aim(direction):
    """Quaternion (x, y, z, w) turning the node's -Z onto `direction`."""
    a, b = (0.0, 0.0, -1.0), normalize(direction)
    d = sum(x * y for x, y in zip(a, b))
    if d < -0.999999:
        return [0.0, 1.0, 0.0, 0.0]
    axis = (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])
    q = [axis[0], axis[1], axis[2], 1.0 + d]
    n = math.sqrt(sum(c * c for c in q))
    return [c / n for c in q]


def look_at(eye, target):
    return {"translation": list(eye),
            "rotation": aim(tuple(t - e for t, e in zip(target, eye)))}


def pbr(name, color, metallic=0.0, roughness=1.0, **ext):
    m = {"name": name, "pbrMetallicRoughness": {"baseColorFactor": list(color) + [1],
         "metallicFactor": metallic, "roughnessFactor": roughness}}
    if ext:
        m["extensions"] = ext
    return m


def glass(name="glass"):
    return pbr(name, (1, 1, 1), 0.0, 0.0, KHR_materials_transmission={"transmissionFactor": 1},
               KHR_materials_ior={"ior": BALL_IOR})


def emitter(name, radiance):
    peak = max(radiance)
    m = pbr(name, (0, 0, 0))
    m["emissiveFactor"] = [c / peak for c in radiance]
    m["extensions"] = {"KHR_materials_emissive_strength": {"emissiveStrength": peak}}
    return m


class Doc:
    def __init__(self):
        self.nodes, self.materials, self.lights, self.cameras = [], [], [], []

    def material(self, m):
        self.materials.append(m)
        return len(self.materials) - 1

    def shape(self, name, shape, **trs):
        self.nodes.append(dict(name=name, extensions={"TRAY_shape": shape}, **trs))

    def write(self, path, extensions_used):
        doc = {"asset": {"version": "2.0", "generator": "tools/make-transport-scenes.py"},
               "scene": 0, "scenes": [{"nodes": list(range(len(self.nodes)))}],
               "nodes": self.nodes, "materials": self.materials, "cameras": self.cameras,
               "extensionsUsed": sorted(extensions_used)}
        if self.lights:
            doc["extensions"] = {"KHR_lights_punctual": {"lights": self.lights}}
        with open(path, "w") as f:
            json.dump(doc, f, indent=1)
            f.write("\n")


def caustic_doc(through_glass):
    d = Doc()
    floor = d.material(pbr("floor", (FLOOR_ALBEDO,) * 3))
    ball = d.material(glass())
    d.shape("floor", {"type": "plane", "material": floor})
    d.shape("ball", {"type": "sphere", "radius": BALL_RADIUS, "material": ball},
            translation=list(BALL_CENTER))
    p = light_position()
    d.lights.append({"type": "spot", "color": [1, 1, 1], "intensity": LIGHT_INTENSITY,
                     "spot": {"innerConeAngle": INNER_CONE, "outerConeAngle": OUTER_CONE}})
    d.nodes.append({"name": "spot", "extensions": {"KHR_lights_punctual": {"light": 0}},
                    **look_at(p, BALL_CENTER)})
    if not through_glass:
        d.cameras.append({"type": "orthographic", "orthographic": {
            "xmag": VIEW_HALF, "ymag": VIEW_HALF, "znear": 0.01, "zfar": 100}})
        # Looking down -Y, image up = -Z (x to the right).
        d.nodes.append({"name": "camera", "camera": 0,
                        "translation": [VIEW_CENTER[0], 6.0, VIEW_CENTER[1]],
                        "rotation": [-math.sqrt(0.5), 0, 0, math.sqrt(0.5)]})
    else:
        # A thick glass slab between a perspective camera and the caustic: the caustic is seen
        # only through two more specular refractions (L S S D S S E).
        slab = d.material(glass("slab"))
        d.shape("slab", {"type": "box", "min": [-0.1, -0.6, -1.2], "max": [0.1, 0.6, 1.2],
                         "material": slab}, translation=[3.3, 0.8, 0.0])
        d.cameras.append({"type": "perspective", "perspective": {
            "yfov": 0.7, "aspectRatio": 1.5, "znear": 0.01}})
        d.nodes.append({"name": "camera", "camera": 0, **look_at((5.5, 1.6, 0.0), (1.6, 0.0, 0.0))})
    return d


def small_opening_doc():
    d = Doc()
    wall = d.material(pbr("wall", (0.7, 0.7, 0.7)))
    floor = d.material(pbr("floor", (0.6, 0.5, 0.4)))
    lamp = d.material(emitter("lamp", (400.0, 380.0, 340.0)))
    t = 0.1  # wall thickness; the room is [-2, 2] x [0, 2.5] x [-2, 2] inside
    box = lambda name, lo, hi, m: d.shape(name, {"type": "box", "min": lo, "max": hi,
                                                 "material": m})
    box("floor", [-2 - t, -t, -2 - t], [2 + t, 0, 2 + t], floor)
    box("ceiling", [-2 - t, 2.5, -2 - t], [2 + t, 2.5 + t, 2 + t], wall)
    box("back", [-2 - t, 0, -2 - t], [2 + t, 2.5, -2], wall)
    box("front", [-2 - t, 0, 2], [2 + t, 2.5, 2 + t], wall)
    box("left", [-2 - t, 0, -2], [-2, 2.5, 2], wall)
    # The right wall (x = 2) with a 0.3 x 0.3 opening at height 1.6.
    box("right-low", [2, 0, -2], [2 + t, 1.45, 2], wall)
    box("right-high", [2, 1.75, -2], [2 + t, 2.5, 2], wall)
    box("right-near", [2, 1.45, -2], [2 + t, 1.75, -0.15], wall)
    box("right-far", [2, 1.45, 0.15], [2 + t, 1.75, 2], wall)
    d.shape("lamp", {"type": "sphere", "radius": 0.25, "material": lamp},
            translation=[3.2, 2.3, 0.0])
    d.cameras.append({"type": "perspective", "perspective": {
        "yfov": 1.1, "aspectRatio": 1.5, "znear": 0.01}})
    d.nodes.append({"name": "camera", "camera": 0, **look_at((-1.8, 1.4, 1.8), (0.8, 0.7, -0.6))})
    return d


def glossy_pair_doc():
    d = Doc()
    floor = d.material(pbr("floor", (0.6, 0.6, 0.6)))
    metal = d.material(pbr("metal", (0.95, 0.9, 0.8), metallic=1.0, roughness=0.15))
    lamp = d.material(emitter("lamp", (60.0, 60.0, 60.0)))
    d.shape("floor", {"type": "plane", "material": floor})
    d.shape("wall-left", {"type": "box", "min": [-1.6, 0, -1.5], "max": [-1.5, 2, 1.5],
                          "material": metal})
    d.shape("wall-right", {"type": "box", "min": [1.5, 0, -1.5], "max": [1.6, 2, 1.5],
                           "material": metal})
    d.shape("lamp", {"type": "sphere", "radius": 0.08, "material": lamp},
            translation=[-1.1, 1.5, 0.2])
    d.cameras.append({"type": "perspective", "perspective": {
        "yfov": 0.9, "aspectRatio": 1.5, "znear": 0.01}})
    d.nodes.append({"name": "camera", "camera": 0, **look_at((0.4, 1.2, 4.5), (0.0, 0.8, 0.0))})
    return d


def main():
    out = sys.argv[1] if len(sys.argv) > 1 else os.path.join(ROOT, "scenes", "transport")
    os.makedirs(out, exist_ok=True)
    base = {"TRAY_shape", "KHR_materials_transmission", "KHR_materials_ior"}
    caustic_doc(False).write(os.path.join(out, "caustic-spot.gltf"),
                             base | {"KHR_lights_punctual"})
    caustic_doc(True).write(os.path.join(out, "caustic-glass.gltf"),
                            base | {"KHR_lights_punctual"})
    small_opening_doc().write(os.path.join(out, "small-opening.gltf"),
                              {"TRAY_shape", "KHR_materials_emissive_strength"})
    glossy_pair_doc().write(os.path.join(out, "glossy-pair.gltf"),
                            {"TRAY_shape", "KHR_materials_emissive_strength"})


if __name__ == "__main__":
    main()
