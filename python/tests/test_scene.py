"""tray.Scene: read once, edited, rendered again; and the docs' examples (docs/python.md)."""
import pathlib
import subprocess
import sys

import numpy as np
import OpenImageIO as oiio
import pytest

OPTIONS = dict(spp=4, resolution=(40, 30), seed=3)


def test_scene_renders_what_render_renders(tray, scenes):
    path = scenes / "textured.gltf"
    scene = tray.Scene(path)
    a = scene.render(**OPTIONS)
    b = scene.render(**OPTIONS)  # again: the kept scene, the kept accelerator
    c = tray.render(path, **OPTIONS)
    assert np.array_equal(a.beauty, c.beauty) and np.array_equal(b.beauty, c.beauty)
    assert a.metadata["tray:job"] == c.metadata["tray:job"]


def test_material_edit_changes_only_while_it_holds(tray, scenes):
    scene = tray.Scene(scenes / "textured.gltf")
    before = scene.render(**OPTIONS).beauty.copy()
    original = scene.materials[0]
    scene.set_material(0, base_color=(1, 0, 0), roughness=0.2)
    assert scene.materials[0]["base_color"] == [1, 0, 0]
    edited = scene.render(**OPTIONS).beauty
    assert not np.array_equal(before, edited)
    scene.set_material(original["name"] or 0, base_color=original["base_color"],
                       roughness=original["roughness"])
    assert np.array_equal(before, scene.render(**OPTIONS).beauty)
    with pytest.raises(tray.Error, match="roughness"):
        scene.set_material(0, roughness=2)
    with pytest.raises(IndexError):
        scene.set_material(len(scene.materials), roughness=0.5)


def test_light_intensity_and_camera_edits(tray, scenes):
    scene = tray.Scene(scenes / "whitted.gltf")
    assert scene.lights and scene.lights[0]["type"] == "point"
    base = scene.render(integrator="whitted", **OPTIONS).beauty
    scene.set_light_intensity(0, 0)
    dark = scene.render(integrator="whitted", **OPTIONS).beauty
    assert dark[:, :, :3].sum() < base[:, :, :3].sum()
    start = np.array(scene.camera_to_world)
    scene.look_at(eye=start[:3, 3] * 1.5, target=(0, 0, 0), fov=30)
    assert scene.fov == pytest.approx(30)
    moved = scene.render(integrator="whitted", **OPTIONS).beauty
    assert not np.array_equal(moved, dark)
    with pytest.raises(tray.Error):
        scene.camera_to_world = np.zeros((4, 4))


def test_environment_rotation(tray, scenes, shared):
    env = shared / "reference" / "cornell-box.ref.exr"  # any EXR is a latitude-longitude map
    if not env.exists():
        pytest.skip(f"{env}: not here")
    scene = tray.Scene(scenes / "textured.gltf", env=env)
    a = scene.render(**OPTIONS).beauty.copy()
    scene.environment_rotation = 90
    assert scene.environment_rotation == 90
    assert not np.array_equal(a, scene.render(**OPTIONS).beauty)


EXAMPLES = pathlib.Path(__file__).parents[1] / "examples"


def test_docs_show_the_examples_run_here(tray):
    docs = (pathlib.Path(__file__).parents[2] / "docs" / "python.md").read_text()
    for name in ("turntable.py", "material_sweep.py"):
        assert (EXAMPLES / name).read_text().strip() in docs, name


def run_example(name, *args):
    import os
    env = dict(os.environ)
    env["PYTHONPATH"] = os.pathsep.join(p for p in sys.path if p)
    r = subprocess.run([sys.executable, str(EXAMPLES / name), *map(str, args)],
                       capture_output=True, text=True, env=env)
    assert r.returncode == 0, r.stderr


def test_turntable_example(tray, shared, tmp_path):
    helmet = shared / "gltf-samples" / "DamagedHelmet.glb"
    if not helmet.exists():
        pytest.skip(f"{helmet}: not here")
    gif = tmp_path / "turntable.gif"
    run_example("turntable.py", helmet, gif, "--frames", 3, "--size", 16, "--spp", 1)
    inp = oiio.ImageInput.open(str(gif))
    frames = [inp.read_image(oiio.UINT8)]
    while inp.seek_subimage(len(frames), 0):
        frames.append(inp.read_image(oiio.UINT8))
    assert len(frames) == 3 and frames[0].shape[:2] == (16, 16)
    assert not np.array_equal(frames[0], frames[1])  # the camera moved


def test_material_sweep_example(tray, scenes, tmp_path):
    png = tmp_path / "sweep.png"
    run_example("material_sweep.py", scenes / "textured.gltf", png, "--steps", 3, "--size", 16, "--spp", 4)
    row = oiio.ImageInput.open(str(png)).read_image(oiio.UINT8)
    assert row.shape == (16, 48, 3)
    assert not np.array_equal(row[:, :16], row[:, 32:])  # roughness 0 and 1 differ


def test_cmake_install_puts_it_where_python_finds_it(tray, tmp_path):
    """cmake --install --component python into a prefix: the package imports from there (from
    another folder, without $OCIO: it finds its own OCIO config) and renders."""
    import os
    import shutil
    build = pathlib.Path(tray.__file__).parents[2]
    if not (build / "CMakeCache.txt").exists() or not shutil.which("cmake"):
        pytest.skip("not a CMake build tree")
    r = subprocess.run(["cmake", "--install", str(build), "--prefix", str(tmp_path),
                        "--component", "python"], capture_output=True, text=True)
    assert r.returncode == 0, r.stderr
    site = tmp_path / "lib" / f"python{sys.version_info[0]}.{sys.version_info[1]}" / "dist-packages"
    env = {k: v for k, v in os.environ.items() if k not in ("OCIO", "PYTHONPATH")}
    env["PYTHONPATH"] = str(site)
    scene = pathlib.Path(__file__).parents[2] / "scenes" / "whitted.gltf"
    code = ("import tray; i = tray.render(%r, spp=1, resolution=(8, 6), allow_any_path=True);"
            "i.write('x.png'); print(tray.__file__)" % str(scene))
    r = subprocess.run([sys.executable, "-W", "ignore", "-c", code], capture_output=True,
                       text=True, env=env, cwd=tmp_path)
    assert r.returncode == 0, r.stderr
    assert r.stdout.strip().startswith(str(site)) and (tmp_path / "x.png").exists()
