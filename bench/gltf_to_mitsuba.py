"""A glTF 2.0 scene as a Mitsuba 3 scene dict, for bench/mitsuba_compare.py (issue 16).

Reads the JSON and the buffers with numpy (accessors, node hierarchy) and builds what TRay
renders from the same file: each triangle primitive placed by each node as an `mi.Mesh` in
world space (positions, normals, TEXCOORD_0); each glTF material as Mitsuba's `principled`
(base colour factor x texture, metallic and roughness from the factors x the packed texture's
B and G channels split into separate bitmaps, alpha = roughness^2 in both), under `normalmap`
when it has a normal texture, wrapped in `twosided` (TRay shades both faces of every surface);
full transmission as `dielectric` with the same ior; emission (factor x texture x
KHR_materials_emissive_strength) as an `area` emitter on the mesh; TRAY_environment's
background as a `constant` emitter; a KHR_lights_punctual directional light as `directional`;
the camera with the same pose and vertical field of view, box filter. Textures are decoded to linear float (sRGB decoding for base colour and emission
done here) and passed raw, bilinear, with the sampler's wrap mode.

Anything else raises ConversionError naming it, rather than rendering something else: the
converter carries what the bench scenes use, nothing more. What it cannot carry exactly (see
docs/bench/mitsuba.md): Mitsuba's principled diffuse is Disney's, TRay's a Lambertian under a
GGX coat; Mitsuba has no texture filtering over the pixel footprint (no mip-maps); `normalmap`
builds its frame from dp/du with bitangent = n x t always, TRay flips it on mirrored UVs;
occlusion textures are used by neither.
"""
import base64
import json
import os
import struct
import tempfile

import mitsuba as mi
import numpy as np


class ConversionError(Exception):
    pass


COMPONENTS = {"SCALAR": 1, "VEC2": 2, "VEC3": 3, "VEC4": 4, "MAT4": 16}
DTYPES = {5120: np.int8, 5121: np.uint8, 5122: np.int16, 5123: np.uint16, 5125: np.uint32,
          5126: np.float32}
WRAP = {33071: "clamp", 33648: "mirror", 10497: "repeat"}


class Gltf:
    """A glTF file's JSON and binary data, with numpy views of its accessors and images."""

    def __init__(self, path):
        self.path, self.folder = path, os.path.dirname(os.path.abspath(path))
        with open(path, "rb") as f:
            data = f.read()
        self.bin = None
        if data[:4] == b"glTF":
            n = struct.unpack("<I", data[12:16])[0]
            self.doc = json.loads(data[20:20 + n])
            self.bin = data[28 + n:]
        else:
            self.doc = json.loads(data)
        self._buffers, self._images = {}, {}

    def buffer(self, i):
        if i not in self._buffers:
            uri = self.doc["buffers"][i].get("uri")
            if uri is None:
                self._buffers[i] = self.bin
            elif uri.startswith("data:"):
                self._buffers[i] = base64.b64decode(uri.split(",", 1)[1])
            else:
                with open(os.path.join(self.folder, uri), "rb") as f:
                    self._buffers[i] = f.read()
        return self._buffers[i]

    def view_bytes(self, v):
        view = self.doc["bufferViews"][v]
        start = view.get("byteOffset", 0)
        return self.buffer(view["buffer"])[start:start + view["byteLength"]], view.get("byteStride")

    def accessor(self, i):
        """(count, components) float64 array, or (count,) for SCALAR."""
        a = self.doc["accessors"][i]
        if "sparse" in a or "bufferView" not in a:
            raise ConversionError(f"accessor {i}: sparse or view-less accessors not supported")
        dtype, comps = np.dtype(DTYPES[a["componentType"]]), COMPONENTS[a["type"]]
        data, stride = self.view_bytes(a["bufferView"])
        stride = stride or dtype.itemsize * comps
        start = a.get("byteOffset", 0)
        rows = np.ndarray((a["count"], comps), dtype, data, start, (stride, dtype.itemsize))
        out = rows.astype(np.float64)
        if a.get("normalized"):
            out /= np.iinfo(dtype).max
        return out[:, 0] if comps == 1 else out

    def image(self, i):
        """Float32 (H, W, C) array of an image's 8-bit values in [0, 1], decoded by Mitsuba."""
        if i not in self._images:
            img = self.doc["images"][i]
            if "uri" in img:
                path = os.path.join(self.folder, img["uri"])
                bmp = mi.Bitmap(path)
            else:
                data, _ = self.view_bytes(img["bufferView"])
                with tempfile.NamedTemporaryFile(suffix=".img") as f:
                    f.write(data)
                    f.flush()
                    bmp = mi.Bitmap(f.name)
            a = np.array(bmp)
            scale = 255.0 if a.dtype == np.uint8 else 65535.0 if a.dtype == np.uint16 else 1.0
            self._images[i] = a.astype(np.float32) / scale
        return self._images[i]


def node_matrix(node):
    if "matrix" in node:
        return np.array(node["matrix"], np.float64).reshape(4, 4).T  # column-major
    t = np.eye(4)
    t[:3, 3] = node.get("translation", [0, 0, 0])
    x, y, z, w = node.get("rotation", [0, 0, 0, 1])
    r = np.eye(4)
    r[:3, :3] = [[1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)],
                 [2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)],
                 [2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)]]
    s = np.diag(list(node.get("scale", [1, 1, 1])) + [1])
    return t @ r @ s


def placed_nodes(doc):
    """(node index, world matrix) of the default scene's nodes, parents first."""
    scene = doc["scenes"][doc.get("scene", 0)]
    stack = [(n, np.eye(4)) for n in scene["nodes"]]
    while stack:
        n, parent = stack.pop()
        world = parent @ node_matrix(doc["nodes"][n])
        yield n, world
        stack += [(c, world) for c in doc["nodes"][n].get("children", [])]


def srgb_to_linear(c):
    return np.where(c <= 0.04045, c / 12.92, ((c + 0.055) / 1.055) ** 2.4)


def bitmap(gltf, info, channels, srgb=False, scale=None, transform=None):
    """A raw bilinear `bitmap` texture dict of a textureInfo's image, channels picked, sRGB
    decoded if asked, times `scale` (per channel), then `transform` (a function of the array)."""
    if "extensions" in info or info.get("texCoord", 0) != 0:
        raise ConversionError(f"texture {info['index']}: texCoord 1 or texture extensions")
    tex = gltf.doc["textures"][info["index"]]
    img = gltf.image(tex["source"])
    if img.ndim == 2:
        img = img[:, :, None]
    a = img[:, :, [min(c, img.shape[2] - 1) for c in channels]]
    if srgb:
        a = srgb_to_linear(a)
    if scale is not None:
        a = a * np.asarray(scale, np.float32)
    if transform is not None:
        a = transform(a)
    sampler = gltf.doc.get("samplers", [{}])[tex["sampler"]] if "sampler" in tex else {}
    wrap = WRAP[sampler.get("wrapS", 10497)]
    if WRAP[sampler.get("wrapT", 10497)] != wrap:
        raise ConversionError(f"texture {info['index']}: different wrap modes in u and v")
    nearest = sampler.get("magFilter") == 9728
    return {"type": "bitmap", "bitmap": mi.Bitmap(np.ascontiguousarray(a, np.float32)),
            "raw": True, "filter_type": "nearest" if nearest else "bilinear", "wrap_mode": wrap}


def material_bsdf(gltf, m):
    pbr = m.get("pbrMetallicRoughness", {})
    ext = m.get("extensions", {})
    unknown = set(ext) - {"KHR_materials_transmission", "KHR_materials_ior",
                          "KHR_materials_emissive_strength"}
    if unknown or m.get("alphaMode", "OPAQUE") != "OPAQUE":
        raise ConversionError(f"material '{m.get('name')}': {sorted(unknown) or m['alphaMode']}")
    base = pbr.get("baseColorFactor", [1, 1, 1, 1])[:3]
    metallic, rough = pbr.get("metallicFactor", 1.0), pbr.get("roughnessFactor", 1.0)
    ior = ext.get("KHR_materials_ior", {}).get("ior", 1.5)
    transmission = ext.get("KHR_materials_transmission", {}).get("transmissionFactor", 0.0)
    if transmission > 0:
        if transmission != 1 or metallic != 0 or rough != 0 or "baseColorTexture" in pbr:
            raise ConversionError(f"material '{m.get('name')}': only smooth full transmission")
        # TRay: a smooth dielectric with exact Fresnel, transmission tinted by the base colour.
        return {"type": "dielectric", "int_ior": ior, "ext_ior": 1.0,
                "specular_transmittance": {"type": "rgb", "value": base}}
    bsdf = {"type": "principled", "eta": ior, "base_color": {"type": "rgb", "value": base},
            "metallic": metallic, "roughness": rough}
    if "baseColorTexture" in pbr:
        bsdf["base_color"] = bitmap(gltf, pbr["baseColorTexture"], [0, 1, 2], True, base)
    if "metallicRoughnessTexture" in pbr:  # glTF packs roughness in G, metalness in B
        info = pbr["metallicRoughnessTexture"]
        bsdf["roughness"] = bitmap(gltf, info, [1], scale=[rough])
        bsdf["metallic"] = bitmap(gltf, info, [2], scale=[metallic])
    if "normalTexture" in m:
        s = m["normalTexture"].get("scale", 1.0)
        # glTF scales the tangent-space x and y by `scale` before normalising; Mitsuba
        # normalises (2 rgb - 1), so scale them in the texture itself.
        rescale = lambda a: np.concatenate([((2 * a[:, :, :2] - 1) * s + 1) / 2, a[:, :, 2:]], 2)
        bsdf = {"type": "normalmap", "bsdf": bsdf,
                "normalmap": bitmap(gltf, m["normalTexture"], [0, 1, 2], transform=rescale)}
    return {"type": "twosided", "bsdf": bsdf}


def material_emitter(gltf, m):
    factor = np.array(m.get("emissiveFactor", [0, 0, 0]), np.float64)
    factor *= m.get("extensions", {}).get("KHR_materials_emissive_strength", {}).get(
        "emissiveStrength", 1.0)
    if not factor.any():
        return None
    if m.get("doubleSided"):
        raise ConversionError(f"material '{m.get('name')}': Mitsuba's area lights are one-sided")
    if "emissiveTexture" in m:
        return {"type": "area", "radiance": bitmap(gltf, m["emissiveTexture"], [0, 1, 2], True,
                                                   factor)}
    return {"type": "area", "radiance": {"type": "rgb", "value": factor.tolist()}}


def mesh(gltf, name, prim, world, bsdf, emitter):
    if prim.get("mode", 4) != 4:
        raise ConversionError(f"{name}: only TRIANGLES primitives")
    attr = prim["attributes"]
    if set(attr) - {"POSITION", "NORMAL", "TEXCOORD_0", "TANGENT"}:
        raise ConversionError(f"{name}: attributes {sorted(attr)}")
    pos = gltf.accessor(attr["POSITION"])
    idx = (gltf.accessor(prim["indices"]) if "indices" in prim
           else np.arange(len(pos))).astype(np.uint32).reshape(-1, 3)
    p = pos @ world[:3, :3].T + world[:3, 3]
    if np.linalg.det(world[:3, :3]) < 0:
        idx = idx[:, [0, 2, 1]]
    # Zero-area triangles: TRay drops them on load (they cannot be hit, but would count as
    # emitter area in Mitsuba).
    edges = np.cross(p[idx[:, 1]] - p[idx[:, 0]], p[idx[:, 2]] - p[idx[:, 0]])
    idx = idx[np.linalg.norm(edges, axis=1) > 0]
    props = mi.Properties()
    props["bsdf"] = mi.load_dict(bsdf)
    if emitter:
        props["emitter"] = mi.load_dict(emitter)
    out = mi.Mesh(name, len(p), len(idx), has_vertex_normals="NORMAL" in attr,
                  has_vertex_texcoords="TEXCOORD_0" in attr, props=props)
    params = mi.traverse(out)
    arrays = {"vertex_positions": p, "faces": idx}
    if "NORMAL" in attr:
        n = gltf.accessor(attr["NORMAL"]) @ np.linalg.inv(world[:3, :3])  # inverse transpose
        arrays["vertex_normals"] = n / np.maximum(np.linalg.norm(n, axis=1, keepdims=True), 1e-30)
    if "TEXCOORD_0" in attr:
        arrays["vertex_texcoords"] = gltf.accessor(attr["TEXCOORD_0"])  # both: v = 0 at the top
    for key, a in arrays.items():
        params[key] = type(params[key])(np.ascontiguousarray(a.ravel(), dtype=(
            np.uint32 if key == "faces" else np.float32)))
    params.update()
    return out


def sensor(doc, world, cam, size, spp, sampler):
    if cam["type"] != "perspective":
        raise ConversionError("only perspective cameras")
    # glTF cameras look down -Z with +X right; Mitsuba's down +Z with +X left: turn by pi
    # about Y.
    to_world = world @ np.diag([-1.0, 1.0, -1.0, 1.0])
    p = cam["perspective"]
    return {"type": "perspective", "fov_axis": "y", "fov": float(np.degrees(p["yfov"])),
            "near_clip": p.get("znear", 0.01), "far_clip": p.get("zfar", 1e7),
            "to_world": mi.ScalarTransform4f(to_world.tolist()),
            "film": {"type": "hdrfilm", "width": size[0], "height": size[1],
                     "rfilter": {"type": "box"}, "pixel_format": "rgb"},
            "sampler": {"type": sampler, "sample_count": spp}}


def punctual_light(doc, node, world):
    """A KHR_lights_punctual light as a Mitsuba emitter: directional only (what the bench
    scenes use), irradiance colour x intensity (TRay's convention, no photometric units),
    shining along the node's -Z."""
    lights = doc.get("extensions", {}).get("KHR_lights_punctual", {}).get("lights", [])
    light = lights[node["extensions"]["KHR_lights_punctual"]["light"]]
    if light.get("type") != "directional":
        raise ConversionError(f"light '{light.get('name')}': only directional lights")
    d = world[:3, :3] @ np.array([0.0, 0.0, -1.0])
    value = np.array(light.get("color", [1, 1, 1]), np.float64) * light.get("intensity", 1.0)
    return {"type": "directional", "direction": (d / np.linalg.norm(d)).tolist(),
            "irradiance": {"type": "rgb", "value": value.tolist()}}


def scene_dict(gltf, size, spp, max_depth, sampler="independent"):
    """The Mitsuba scene dict of a Gltf (load it with mi.load_dict under the chosen variant)."""
    doc = gltf.doc
    unknown = set(doc.get("extensionsUsed", [])) - {
        "KHR_materials_transmission", "KHR_materials_ior", "KHR_materials_emissive_strength",
        "TRAY_environment", "KHR_lights_punctual"}
    if unknown:
        raise ConversionError(f"extensions {sorted(unknown)}")
    out = {"type": "scene", "integrator": {"type": "path", "max_depth": max_depth}}
    camera = None
    for n, world in placed_nodes(doc):
        node = doc["nodes"][n]
        if "KHR_lights_punctual" in node.get("extensions", {}):
            out[f"light{n}"] = punctual_light(doc, node, world)
        if "camera" in node and camera is None:
            camera = sensor(doc, world, doc["cameras"][node["camera"]], size, spp, sampler)
        for k, prim in enumerate(doc["meshes"][node["mesh"]]["primitives"] if "mesh" in node
                                 else []):
            m = doc["materials"][prim["material"]] if "material" in prim else {}
            name = f"node{n}_{k}"
            out[name] = mesh(gltf, name, prim, world, material_bsdf(gltf, m),
                             material_emitter(gltf, m))
    if camera is None:
        raise ConversionError("the scene places no camera")
    out["sensor"] = camera
    env = doc["scenes"][doc.get("scene", 0)].get("extensions", {}).get("TRAY_environment", {})
    if set(env) - {"background"}:
        raise ConversionError(f"TRAY_environment fields {sorted(set(env) - {'background'})}")
    if any(env.get("background", [0, 0, 0])):
        out["sky"] = {"type": "constant",
                      "radiance": {"type": "rgb", "value": env["background"]}}
    return out
