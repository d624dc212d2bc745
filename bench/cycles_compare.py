#!/usr/bin/env python3
"""TRay's path tracer against Blender's Cycles on shared glTF assets (issue 14, "Speed"), both
measured in this run on this machine, one thread each.

Scene per asset: the asset on a grey diffuse ground plane, a camera framing it, a glTF
directional light (KHR_lights_punctual, irradiance --sun) and an HDR environment map
(env_bench's sky, its sun disk clamped away by --sky-max, scaled by --env-intensity). Blender builds
the scene once (its glTF importer, then its exporter writes merged.glb) and both renderers read
that same file: TRay directly, Cycles through Blender's importer. Conventions (the lighting
issue's, which make the Cornell box match Mitsuba within 0.02%): importer and exporter lighting
mode COMPAT (a sun's strength in W/m² is the glTF intensity), sun angle 0 (a delta light, as
glTF's directional), Cycles max_bounces = TRay --max-depth − 2, box filter of width 1, no
adaptive sampling, no denoising, no glossy filter (Cycles' default "Filter Glossy"
1.0 blurs caustic paths: biased) and no light threshold, Standard view transform (EXR values
scene-linear). Indirect samples are clamped at --clamp-indirect (10) in both (TRay's
--clamp-indirect, Cycles' "Clamp Indirect"): unclamped, the sun's caustics off the helmet's
metal onto the ground keep even 2048-spp references noisy, and both renderers' RMSE stalls at
the reference's own noise (measured: 0.031 at 64 and at 256 spp), deciding nothing.

The environment map is lat-long in both, with TRay's orientation (u = 0.5 towards glTF +Z,
u = 0.25 towards +X) reproduced in Blender by a Mapping node turning the lookup by +90° about Z
(glTF +Z is Blender's -Y); --check-env renders the map alone in both and prints the mean
relative difference (the orientation is right when it is small).

Error: each renderer's RMSE against its OWN converged render (--ref-spp); their material models
differ slightly, so the images are compared by eye (side by side PNGs in --out), not pixel to
pixel. Time: wall time of each render minus that renderer's 1-spp render (scene load, BVH and
texture set-up excluded alike). Both estimators are unbiased, so MSE = c / spp and time =
t x spp: c and t are fitted over every spp count (each the mean of --seeds renders, so that one
firefly does not decide), and the figure is the time TRay needs to reach the MSE Cycles has at
--target-spp against Cycles' time for --target-spp: (c_Cycles t_Cycles) / (c_TRay t_TRay).

Usage (Debian's blender 3.4; tools/setup-blender.sh installs it):
  blender -b --factory-startup --python bench/cycles_compare.py -- [--build build] [--out DIR]
      [--size 160] [--ref-spp 1024] [--target-spp 64] [--assets DamagedHelmet,WaterBottle]
"""
import argparse
import math
import os
import subprocess
import sys
import time

import numpy as np

if not hasattr(np, "bool"):  # numpy 1.24 dropped np.bool (2.x has it again); Blender 3.4 uses it
    np.bool = bool
import bpy  # noqa: E402  (inside Blender only)

HERE = os.path.dirname(os.path.abspath(__file__))


def lighting(op):
    """The glTF operator's COMPAT lighting option under its name in this Blender (3.4:
    convert_lighting_mode; 3.6 and later, 5.2 included: export_import_convert_lighting_mode)."""
    names = op.get_rna_type().properties.keys()
    key = "convert_lighting_mode" if "convert_lighting_mode" in names else \
        "export_import_convert_lighting_mode"
    return {key: "COMPAT"}


# tray-render without $OCIO: `import bpy` points it at Blender's own config (OCIO 2.5 format),
# which Debian 12's OpenColorIO 2.1 aborts on (../shared/notes/cycles5.md).
TRAY_ENV = {k: v for k, v in os.environ.items() if k != "OCIO"}
SHARED = os.path.normpath(os.path.join(HERE, "..", "..", "shared"))
ASSETS = {
    "DamagedHelmet": os.path.join(SHARED, "gltf-samples", "DamagedHelmet.glb"),
    "WaterBottle": os.path.join(SHARED, "gltf-features", "WaterBottle", "WaterBottle.gltf"),
}
LINES = []


def say(text=""):
    print(text, flush=True)
    LINES.append(text)


def parse_args():
    argv = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
    p = argparse.ArgumentParser(prog="cycles_compare.py")
    p.add_argument("--build", default=os.path.join(HERE, "..", "build"))
    p.add_argument("--out", default="/tmp/tray-cycles")
    p.add_argument("--size", type=int, default=160)
    p.add_argument("--ref-spp", type=int, default=1024)
    p.add_argument("--target-spp", type=int, default=64)
    p.add_argument("--spp", default="4,16,64,256")
    p.add_argument("--max-depth", type=int, default=8)
    p.add_argument("--seeds", type=int, default=2, help="renders per spp count, MSE averaged")
    p.add_argument("--clamp-indirect", type=float, default=10.0,
                   help="both renderers clamp indirect samples (0: off; see the docstring)")
    p.add_argument("--sun", type=float, default=3.0)
    p.add_argument("--env-intensity", type=float, default=1.0)
    p.add_argument("--sky-max", type=float, default=2.0, help="clamp of the sky map (its sun)")
    p.add_argument("--assets", default="DamagedHelmet,WaterBottle")
    p.add_argument("--tray-args", default="", help="extra tray-render options")
    p.add_argument("--check-env", action="store_true")
    return p.parse_args(argv)


def reset():
    bpy.ops.wm.read_factory_settings(use_empty=True)


def world_bounds():
    lo, hi = np.full(3, np.inf), np.full(3, -np.inf)
    for ob in bpy.context.scene.objects:
        if ob.type != "MESH":
            continue
        for corner in ob.bound_box:
            w = np.array(ob.matrix_world @ __import__("mathutils").Vector(corner))
            lo, hi = np.minimum(lo, w), np.maximum(hi, w)
    return lo, hi


def build_scene(asset, merged, sun):
    """Asset + ground + camera + sun, exported by Blender as one .glb that both renderers read."""
    import mathutils
    reset()
    bpy.ops.import_scene.gltf(filepath=asset, import_shading="NORMALS",
                              **lighting(bpy.ops.import_scene.gltf))
    lo, hi = world_bounds()
    centre, radius = (lo + hi) / 2, float(np.linalg.norm(hi - lo)) / 2
    bpy.ops.mesh.primitive_plane_add(size=radius * 12, location=(centre[0], centre[1], lo[2]))
    ground = bpy.context.object
    mat = bpy.data.materials.new("ground")
    mat.use_nodes = True
    bsdf = mat.node_tree.nodes["Principled BSDF"]
    bsdf.inputs["Base Color"].default_value = (0.5, 0.5, 0.5, 1)
    bsdf.inputs["Roughness"].default_value = 1.0
    bsdf.inputs["Metallic"].default_value = 0.0
    ground.data.materials.append(mat)
    # Camera in front (Blender -Y is glTF +Z, where assets face), a little to the right and up.
    eye = mathutils.Vector(centre) + radius * mathutils.Vector((1.0, -4.4, 1.2))
    cam_data = bpy.data.cameras.new("camera")
    cam_data.angle = math.radians(40)
    cam = bpy.data.objects.new("camera", cam_data)
    bpy.context.scene.collection.objects.link(cam)
    cam.location = eye
    cam.rotation_euler = (mathutils.Vector(centre) - eye).to_track_quat("-Z", "Y").to_euler()
    bpy.context.scene.camera = cam
    light = bpy.data.lights.new("sun", type="SUN")
    light.energy = sun
    light.angle = 0.0
    sun_ob = bpy.data.objects.new("sun", light)
    bpy.context.scene.collection.objects.link(sun_ob)
    sun_ob.rotation_euler = (math.radians(50), 0, math.radians(-140))
    bpy.context.scene.render.resolution_x = bpy.context.scene.render.resolution_y = 100
    bpy.ops.export_scene.gltf(filepath=merged, export_format="GLB", export_cameras=True,
                              export_lights=True, **lighting(bpy.ops.export_scene.gltf))


def feed(source, target, links):
    """Gives node input `target` what input `source` has: its link, or its constant."""
    if source.is_linked:
        links.new(source.links[0].from_socket, target)
    else:
        target.default_value = source.default_value


def principled_emission(mat, p):
    """An Emission shader with Principled node p's emission colour and strength, or None when
    it does not emit. A single-sided glTF material emits from its front only, as in TRay
    (Cycles' emission is two-sided): its strength is scaled by 1 - backfacing."""
    strength = p.inputs["Emission Strength"]
    if not strength.is_linked and strength.default_value <= 0:
        return None
    nodes, links = mat.node_tree.nodes, mat.node_tree.links
    e = nodes.new("ShaderNodeEmission")
    feed(p.inputs["Emission Color"], e.inputs["Color"], links)
    if not mat.use_backface_culling:
        feed(strength, e.inputs["Strength"], links)
        return e.outputs["Emission"]
    front = nodes.new("ShaderNodeMath")
    front.operation = "SUBTRACT"
    front.inputs[0].default_value = 1.0
    links.new(nodes.new("ShaderNodeNewGeometry").outputs["Backfacing"], front.inputs[1])
    scaled = nodes.new("ShaderNodeMath")
    scaled.operation = "MULTIPLY"
    links.new(front.outputs["Value"], scaled.inputs[0])
    feed(strength, scaled.inputs[1], links)
    links.new(scaled.outputs["Value"], e.inputs["Strength"])
    return e.outputs["Emission"]


def diffuse_for_rough_dielectrics():
    """Materials with metallic 0 and roughness 1 and no texture on either become a Diffuse BSDF
    (the convention that makes Cycles' Cornell box match Mitsuba's), plus an Emission shader
    where they emit: TRay's glTF material at roughness 1 is Lambertian, Principled keeps a
    specular layer."""
    for mat in bpy.data.materials:
        if not mat.use_nodes:
            continue
        nodes, links = mat.node_tree.nodes, mat.node_tree.links
        for p in [n for n in nodes if n.type == "BSDF_PRINCIPLED"]:
            metal, rough = p.inputs["Metallic"], p.inputs["Roughness"]
            if metal.is_linked or rough.is_linked or metal.default_value != 0 or \
                    rough.default_value != 1:
                continue
            d = nodes.new("ShaderNodeBsdfDiffuse")
            feed(p.inputs["Base Color"], d.inputs["Color"], links)
            out = d.outputs["BSDF"]
            # Keep the Principled node's emission (the Cornell box's light is such a material).
            emission = principled_emission(mat, p)
            if emission is not None:
                add = nodes.new("ShaderNodeAddShader")
                links.new(out, add.inputs[0])
                links.new(emission, add.inputs[1])
                out = add.outputs["Shader"]
            for link in list(p.outputs["BSDF"].links):
                links.new(out, link.to_socket)


def import_merged(merged):
    """A fresh Blender scene holding the glTF file (the comparison's conventions: its first
    camera, suns of angle 0, Lambertian materials as Diffuse BSDFs)."""
    reset()
    if merged:
        bpy.ops.import_scene.gltf(filepath=merged, **lighting(bpy.ops.import_scene.gltf))
    scene = bpy.context.scene
    cams = [o for o in scene.objects if o.type == "CAMERA"]
    if cams:
        scene.camera = cams[0]
    for o in scene.objects:
        if o.type == "LIGHT" and o.data.type == "SUN":
            o.data.angle = 0.0
    diffuse_for_rough_dielectrics()
    return scene


def cycles_settings(scene, size, spp, depth, seed=0, clamp=0.0):
    """Cycles set as the comparison runs it: CPU, one thread, no adaptive sampling, no
    denoising, max_bounces = depth - 2, box filter of width 1, EXR out in scene-linear."""
    scene.render.engine = "CYCLES"
    c = scene.cycles
    c.device = "CPU"
    c.samples = spp
    c.use_adaptive_sampling = False
    c.use_denoising = False
    c.seed = seed
    c.max_bounces = max(0, depth - 2)
    c.diffuse_bounces = c.glossy_bounces = c.transmission_bounces = c.max_bounces
    c.transparent_max_bounces = c.max_bounces
    c.volume_bounces = 0
    c.caustics_reflective = c.caustics_refractive = True
    c.sample_clamp_direct = 0.0
    c.sample_clamp_indirect = clamp
    # Unbiased like TRay: no glossy blur after diffuse bounces (Cycles' default 1.0 removes
    # exactly the caustic fireflies the comparison is about), no light threshold.
    c.blur_glossy = 0.0
    c.light_sampling_threshold = 0.0
    c.pixel_filter_type = "BOX"
    c.filter_width = 1.0
    scene.render.threads_mode = "FIXED"
    scene.render.threads = 1
    scene.render.resolution_x = scene.render.resolution_y = size
    scene.render.resolution_percentage = 100
    scene.render.film_transparent = False
    scene.view_settings.view_transform = "Standard"
    scene.view_settings.look = "None"
    scene.render.image_settings.file_format = "OPEN_EXR"
    scene.render.image_settings.color_depth = "32"


def setup_cycles(merged, env, env_intensity, size, spp, depth, seed=0, clamp=0.0):
    scene = import_merged(merged)
    world = bpy.data.worlds.new("world")
    scene.world = world
    world.use_nodes = True
    nt = world.node_tree
    tex = nt.nodes.new("ShaderNodeTexEnvironment")
    tex.image = bpy.data.images.load(env)
    tex.interpolation = "Linear"
    coord = nt.nodes.new("ShaderNodeTexCoord")
    mapping = nt.nodes.new("ShaderNodeMapping")
    mapping.inputs["Rotation"].default_value = (0, 0, math.radians(90))
    nt.links.new(coord.outputs["Generated"], mapping.inputs["Vector"])
    nt.links.new(mapping.outputs["Vector"], tex.inputs["Vector"])
    bg = nt.nodes["Background"]
    bg.inputs["Strength"].default_value = env_intensity
    nt.links.new(tex.outputs["Color"], bg.inputs["Color"])
    world.cycles.sampling_method = "AUTOMATIC"
    cycles_settings(scene, size, spp, depth, seed, clamp)


def render_cycles(path):
    bpy.context.scene.render.filepath = path
    start = time.perf_counter()
    bpy.ops.render.render(write_still=True)
    return time.perf_counter() - start


def render_tray(args, merged, env, spp, path, threads=1, seed=0, extra=()):
    """One tray-render run (args.tray_args and `extra` appended); its wall seconds."""
    cmd = [os.path.join(args.build, "tray-render"), merged, "-q", "--integrator", "path",
           "--spp", str(spp), "--seed", str(seed), "--clamp-indirect", str(args.clamp_indirect),
           "--max-depth", str(args.max_depth), "--threads", str(threads),
           "--env", env, "--env-intensity", str(args.env_intensity), "--resolution",
           f"{args.size}x{args.size}", "--float", "-o", path] + args.tray_args.split() + list(extra)
    start = time.perf_counter()
    subprocess.run(cmd, check=True, env=TRAY_ENV)
    return time.perf_counter() - start


def read_rgb(path):
    img = bpy.data.images.load(path)
    w, h = img.size
    px = np.array(img.pixels[:], dtype=np.float64).reshape(h, w, 4)[::-1, :, :3]
    bpy.data.images.remove(img)
    return px


def rmse(a, b):
    return float(np.sqrt(np.mean((a - b) ** 2)))


def efficiency(points):
    """(MSE x spp, seconds per spp) fitted over (spp, seconds, mse) points: MSE = c / spp for an
    unbiased estimator, time = t x spp once set-up is subtracted. Fitting all spp counts (each
    averaged over seeds) keeps a single firefly from deciding the figure."""
    c = sum(mse * spp for spp, _, mse in points) / len(points)
    t = sum(seconds for _, seconds, _ in points) / sum(spp for spp, _, _ in points)
    return c, t


def compare(args, name, env):
    out = os.path.join(args.out, name)
    os.makedirs(out, exist_ok=True)
    merged = os.path.join(out, "merged.glb")
    build_scene(ASSETS[name], merged, args.sun)
    spps = [int(s) for s in args.spp.split(",")]
    fits = {}
    for renderer in ("tray", "cycles"):
        def render(spp, path, threads=1, seed=0):
            if renderer == "tray":
                return render_tray(args, merged, env, spp, path, threads, seed)
            setup_cycles(merged, env, args.env_intensity, args.size, spp, args.max_depth, seed,
                         args.clamp_indirect)
            bpy.context.scene.render.threads = threads
            return render_cycles(path)
        ref_path = os.path.join(out, f"{renderer}-ref.exr")
        render(args.ref_spp, ref_path, threads=os.cpu_count(), seed=1000)
        ref = read_rgb(ref_path)
        setup = render(1, os.path.join(out, f"{renderer}-1.exr"))
        points = []
        for spp in spps:
            seconds, mse = 0.0, 0.0
            for seed in range(args.seeds):
                path = os.path.join(out, f"{renderer}-{spp}-{seed}.exr")
                seconds += max(render(spp, path, seed=seed) - setup, 1e-6) / args.seeds
                mse += float(np.mean((read_rgb(path) - ref) ** 2)) / args.seeds
            points.append((spp, seconds, mse))
            say(f"  {name:14s} {renderer:6s} {spp:5d} spp  {seconds:8.3f} s  RMSE "
                f"{math.sqrt(mse):.5f}  (image mean {float(ref.mean()):.4f})")
        fits[renderer] = efficiency(points)
        subprocess.run(["oiiotool", ref_path, "--ch", "R,G,B", "--colorconvert", "linear", "sRGB",
                        "-o", os.path.join(out, f"{renderer}-ref.png")], check=False, env=TRAY_ENV)
    (c_cyc, t_cyc), (c_tray, t_tray) = fits["cycles"], fits["tray"]
    target = c_cyc / args.target_spp  # Cycles' MSE at --target-spp (fitted)
    cycles_time = t_cyc * args.target_spp
    tray_time = t_tray * c_tray / target
    say(f"  {name}: Cycles {args.target_spp} spp: RMSE {math.sqrt(target):.5f} in "
        f"{cycles_time:.3f} s; TRay reaches it in {tray_time:.3f} s "
        f"({c_tray / target:.0f} spp): TRay {cycles_time / tray_time:.2f}x faster")
    return cycles_time / tray_time


def check_env(args, env):
    """The map alone, seen by a camera looking along glTF +Z, -Z and +X: both renderers."""
    out = os.path.join(args.out, "env-check")
    os.makedirs(out, exist_ok=True)
    diffs = []
    views = (("+Z", (0, 1, 0), 180), ("-Z", (0, 1, 0), 0), ("+X", (0, 1, 0), -90),
             ("+Y", (1, 0, 0), 90), ("-Y", (1, 0, 0), -90))
    for label, axis, rot in views:
        gltf = os.path.join(out, f"cam{label}.gltf")
        half = math.radians(rot) / 2
        q = tuple(a * math.sin(half) for a in axis) + (math.cos(half),)
        with open(gltf, "w") as f:
            f.write('{"asset":{"version":"2.0"},"scene":0,"scenes":[{"nodes":[0]}],'
                    f'"nodes":[{{"camera":0,"rotation":[{q[0]},{q[1]},{q[2]},{q[3]}]}}],'
                    '"cameras":[{"type":"perspective","perspective":'
                    '{"yfov":1.0,"aspectRatio":1.0,"znear":0.01}}]}')
        tray = os.path.join(out, f"tray{label}.exr")
        render_tray(args, gltf, env, 16, tray)
        setup_cycles(gltf, env, args.env_intensity, args.size, 16, args.max_depth)
        cyc = os.path.join(out, f"cycles{label}.exr")
        render_cycles(cyc)
        a, b = read_rgb(tray), read_rgb(cyc)
        diffs.append(float(np.mean(np.abs(a - b)) / max(np.mean(b), 1e-9)))
        say(f"  env check, camera towards {label}: TRay mean {a.mean():.4f}, "
            f"Cycles mean {b.mean():.4f}, mean |difference| / mean {diffs[-1]:.4f}")
    return max(diffs)


def main():
    args = parse_args()
    os.makedirs(args.out, exist_ok=True)
    maps = os.path.join(args.out, "maps")
    subprocess.run([os.path.join(args.build, "env_bench"), "--write-maps", maps], check=True,
                   stdout=subprocess.DEVNULL, env=TRAY_ENV)
    # The sky without its sun disk (clamped to the sky's own brightness): the sun is the glTF
    # directional light, as in the truck scene of the lighting issue (sun + background).
    env = os.path.join(maps, "sky-soft.exr")
    subprocess.run(["oiiotool", os.path.join(maps, "sky.exr"), "--clamp:max=" + str(args.sky_max),
                    "-o", env], check=True, env=TRAY_ENV)
    say(f"TRay vs Cycles ({bpy.app.version_string}), {args.size}x{args.size}, one thread each, "
        f"max depth {args.max_depth}, references {args.ref_spp} spp, sun {args.sun} + sky x "
        f"{args.env_intensity}")
    if args.check_env:  # both maps: the windows' differ by azimuth, the sky's by elevation
        check_env(args, os.path.join(maps, "windows.exr"))
        check_env(args, env)
        return
    ratios = [compare(args, name, env) for name in args.assets.split(",")]
    say(f"TRay's speed-up to Cycles' {args.target_spp}-spp noise: "
        + ", ".join(f"{r:.2f}x" for r in ratios))
    with open(os.path.join(args.out, "report.txt"), "w") as f:
        f.write("\n".join(LINES) + "\n")


if __name__ == "__main__":
    try:
        main()
    except Exception as e:  # Blender would otherwise keep running after a Python error
        print(f"cycles_compare: {e}", file=sys.stderr)
        sys.exit(1)
    sys.exit(0)
