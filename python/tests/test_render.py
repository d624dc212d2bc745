"""tray.render against tray-render: the same pixels, the same refusals, arrays laid out as
documented (docs/python.md)."""
import os
import signal
import subprocess
import threading

import numpy as np
import OpenImageIO as oiio
import pytest

# Small and quick: every test renders in well under a second.
OPTIONS = dict(spp=4, resolution=(40, 30), seed=7)


def cli(tray_render, *args):
    return subprocess.run([tray_render, *map(str, args)], capture_output=True, text=True)


def read_exr(path):
    """The EXR's pixels (H x W x C float32) and its channel names."""
    inp = oiio.ImageInput.open(str(path))
    assert inp, oiio.geterror()
    spec = inp.spec()
    pixels = inp.read_image(format=oiio.FLOAT)
    inp.close()
    return pixels, list(spec.channelnames), spec


def test_beauty_and_aovs_bit_identical_to_cli(tray, tray_render, scenes, tmp_path):
    scene = scenes / "textured.gltf"
    out = tmp_path / "cli.exr"
    r = cli(tray_render, scene, "--spp", 4, "--resolution", "40x30", "--seed", 7, "--aov",
            "depth,normal,albedo", "--float", "-q", "-o", out)
    assert r.returncode == 0, r.stderr
    image = tray.render(scene, aov="depth,normal,albedo", **OPTIONS)
    pixels, names, _ = read_exr(out)
    for layer, exr_names in image.exr_channels.items():
        array = image.beauty if layer == "beauty" else image.aovs[layer]
        columns = [names.index(n) for n in exr_names]
        # Bit-identical: the same floats, not merely close ones.
        assert np.array_equal(array, pixels[:, :, columns]), layer
    assert np.any(image.beauty[:, :, :3] > 0)


def test_write_is_the_cli_output(tray, tray_render, scenes, tmp_path):
    scene = scenes / "whitted.gltf"
    out = tmp_path / "cli.exr"
    assert cli(tray_render, scene, "--spp", 4, "--resolution", "40x30", "--seed", 7,
               "--integrator", "whitted", "-q", "-o", out).returncode == 0
    image = tray.render(scene, integrator="whitted", **OPTIONS)
    image.write(tmp_path / "py.exr")
    a, names_a, spec_a = read_exr(out)
    b, names_b, spec_b = read_exr(tmp_path / "py.exr")
    assert names_a == names_b and np.array_equal(a, b)
    assert spec_a.format == spec_b.format == oiio.HALF  # half unless float=True, as the CLI
    for key in ("tray:job", "tray:integrator", "tray:status", "tray:samplesPerPixel"):
        assert spec_a.getattribute(key) == spec_b.getattribute(key) == image.metadata[key], key
    image.write(tmp_path / "py.png")  # display-referred, as -o x.png
    assert oiio.ImageInput.open(str(tmp_path / "py.png")).spec().nchannels >= 3


def test_arrays_shapes_and_channel_order(tray, scenes):
    image = tray.render(scenes / "textured.gltf", aov="depth,normal,albedo", **OPTIONS)
    assert image.beauty.shape == (30, 40, 4) and image.beauty.dtype == np.float32
    assert image.channels["beauty"] == ["R", "G", "B", "A"]
    assert set(image.aovs) == {"Z", "N", "albedo"}
    assert image.channels["N"] == ["X", "Y", "Z"] and image.aovs["N"].shape == (30, 40, 3)
    assert image.aovs["Z"].shape == (30, 40, 1)
    assert image.exr_channels["N"] == ["N.X", "N.Y", "N.Z"]
    # Rows top first: the array is the film as the EXR stores it (checked against the CLI above);
    # normals: unit length, or shorter where a pixel averages several.
    length = np.linalg.norm(image.aovs["N"][image.beauty[:, :, 3] > 0.999], axis=1)
    assert np.median(length) == pytest.approx(1, abs=1e-3) and length.max() < 1 + 1e-3
    assert image.metadata["tray:spp"] == 4 and image.metadata["worldToCamera"].shape == (4, 4)
    assert image.complete and image.stats.rays > 0


def test_keywords_are_every_cli_option(tray, tray_render):
    help_text = cli(tray_render, "--help").stdout
    import re
    cli_names = {m.replace("-", "_") for m in re.findall(r"--([a-z][a-z0-9-]+)", help_text)}
    cli_names -= {"help", "version", "help_markdown"}
    assert cli_names <= set(tray.option_names())
    assert tray.command_line("s.gltf", resolution=(4, 3), aov=["depth", "normal"],
                             allow_any_path=True, max_depth=3, output=["a.exr", "b.png"]) == [
        "s.gltf", "--resolution=4x3", "--aov=depth,normal", "--allow-any-path=true",
        "--max-depth=3", "--output=a.exr", "--output=b.png"]


@pytest.mark.parametrize("keywords, args", [
    (dict(spp=0), ["--spp", "0"]),
    (dict(spp=-3), ["--spp=-3"]),
    (dict(integrator="nope"), ["--integrator", "nope"]),
    (dict(resolution="12"), ["--resolution", "12"]),
    (dict(seed=-1), ["--seed=-1"]),
    (dict(max_depth=1.5), ["--max-depth", "1.5"]),
    (dict(time_limit=float("nan")), ["--time-limit", "nan"]),
    (dict(camera=""), ["--camera="]),
    (dict(aov="bogus"), ["--aov", "bogus"]),
    (dict(output="x.tiff"), ["-o", "x.tiff"]),
    (dict(no_such_option=1), ["--no-such-option=1"]),
])
def test_bad_input_raises_the_cli_message(tray, tray_render, scenes, tmp_path, keywords, args):
    scene = scenes / "whitted.gltf"
    r = cli(tray_render, scene, "-q", *args)
    assert r.returncode == 2, r.stderr
    line = r.stderr.strip().splitlines()[-1]
    with pytest.raises(tray.Error) as e:
        tray.render(scene, **keywords)
    # tray-render prints the same message after its prefix (and a pointer to --help).
    assert line in (f"tray-render: error: {e.value}", f"tray-render: error: {e.value} (see --help)")


def test_missing_scene_raises_the_cli_message(tray, tray_render, tmp_path):
    missing = tmp_path / "missing.gltf"
    r = cli(tray_render, missing, "-q", "-o", tmp_path / "x.exr")
    with pytest.raises(tray.Error) as e:
        tray.render(missing)
    assert r.stderr.strip() == f"tray-render: error: {e.value}"
    assert not (tmp_path / "x.exr").exists()


def test_progress_callback(tray, scenes):
    fractions = []
    tray.render(scenes / "textured.gltf", progress=fractions.append, spp=2, resolution=(64, 48))
    assert fractions and fractions[-1] == 1.0
    assert fractions == sorted(fractions) and all(0 < f <= 1 for f in fractions)
    with pytest.raises(TypeError):
        tray.render(scenes / "textured.gltf", progress=3)


def test_exception_in_progress_stops_the_render(tray, scenes, tmp_path):
    def stop(fraction):
        raise RuntimeError("enough")
    out = tmp_path / "stopped.exr"
    with pytest.raises(RuntimeError, match="enough"):
        tray.render(scenes / "textured.gltf", progress=stop, spp=64, resolution=(160, 120),
                    output=out)
    # Stopped as tray-render stops on a signal: the pixels done, marked partial (resumable).
    spec = oiio.ImageInput.open(str(out)).spec()
    assert spec.getattribute("tray:status") == "partial"


def test_ctrl_c_stops_the_render(tray, scenes, tmp_path):
    out = tmp_path / "interrupted.exr"
    started = threading.Event()
    timer = threading.Timer(0, lambda: (started.wait(10), os.kill(os.getpid(), signal.SIGINT)))
    timer.start()
    with pytest.raises(KeyboardInterrupt):
        tray.render(scenes / "textured.gltf", progress=lambda f: started.set(), spp=4096,
                    resolution=(160, 120), output=out)
    timer.join()
    spec = oiio.ImageInput.open(str(out)).spec()
    assert spec.getattribute("tray:status") == "partial"
    assert spec.getattribute("tray:pixelsDone") < spec.getattribute("tray:pixelsTotal")


def test_frames_give_one_image_each(tray, scenes):
    images = tray.render(scenes / "textured.gltf", frames="0-1", spp=1, resolution=(8, 6))
    assert [i.beauty.shape for i in images] == [(6, 8, 4)] * 2
