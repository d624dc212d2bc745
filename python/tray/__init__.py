"""TRay from Python (docs/python.md).

    import tray
    image = tray.render("scene.gltf", integrator="path", spp=64, resolution=(320, 240), seed=0)
    image.beauty          # H x W x 4 float32 (scene-linear RGB, alpha)
    image.aovs["N"]       # an AOV asked for with aov="normal": H x W x 3, image.channels["N"]
    image.write("out.exr")

Every option of `tray-render --help` is a keyword, spelled with '_' for '-' (--max-depth:
max_depth=...), checked by the same code as the command line's, with the same messages:
a mistake raises tray.Error carrying the line tray-render prints after "tray-render: error: ".
"""
import os as _os

# The native module finds TRay's OCIO config through $OCIO: tray-render finds it beside its
# executable, but here the executable is the Python interpreter. A user's $OCIO is kept.
_CONFIG = _os.path.join(_os.path.dirname(__file__), "ocio", "config.ocio")
if not _os.environ.get("OCIO") and _os.path.isfile(_CONFIG):
    _os.environ["OCIO"] = _CONFIG

from ._tray import Error, Image, RenderStats, __version__  # noqa: E402
from . import _tray  # noqa: E402

__all__ = ["render", "Scene", "Error", "Image", "RenderStats", "option_names", "command_line"]

# tray-render's options that ask it to print, not to render.
_NOT_RENDER_OPTIONS = {"help", "version", "help_markdown"}


def option_names():
    """The keywords tray.render takes: tray-render's long options with '_' for '-'."""
    return [n for n in _tray.option_names() if n not in _NOT_RENDER_OPTIONS]


def _text(key, value):
    """A keyword's value as the command line spells it."""
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, (list, tuple)):
        # resolution=(W, H) is WxH; region=(x0, y0, x1, y1), sample_range=(a, b) and
        # aov=["depth", "normal"] are comma separated.
        return ("x" if key == "resolution" else ",").join(_text(key, v) for v in value)
    if isinstance(value, float):
        return repr(value)  # the shortest text that reads back as the same double
    if isinstance(value, _os.PathLike):
        return _os.fspath(value)
    return str(value)


def command_line(scene, **options):
    """The tray-render arguments (without the program name) that `options` stand for.

    Each keyword becomes --name=value ('_' for '-'); True/False for flags; None leaves the
    option out (its default); output may be a list (-o repeated)."""
    args = [_os.fspath(scene)]
    for key, value in options.items():
        if key in _NOT_RENDER_OPTIONS:
            raise Error(f"{key}: not an option of tray.render (it makes tray-render print)")
        if value is None:
            continue
        name = "--" + key.replace("_", "-")
        values = value if key == "output" and isinstance(value, (list, tuple)) else [value]
        args += [f"{name}={_text(key, v)}" for v in values]
    return args


def render(scene, *, progress=None, **options):
    """Renders `scene` (a .gltf/.glb path) with tray-render's options as keywords.

    Returns a tray.Image (a list of them, one per frame, with frames="A-B"). Files are written
    only when output= names them (tray-render's default out.exr is not). progress: a callable
    given the fraction of the image done (on this thread, at most every 50 ms, and the last
    fraction); a string is tray-render's --progress, checked and otherwise unused. Ctrl-C stops
    the render after the pixels under way (outputs asked for are written as tray-render writes
    an interrupted render) and raises KeyboardInterrupt; an exception from `progress` stops it
    the same way. Raises tray.Error for bad options or a scene that cannot be rendered."""
    if isinstance(progress, str):
        options["progress"] = progress
        progress = None
    elif progress is not None and not callable(progress):
        raise TypeError("progress: expected a callable taking the fraction done, or None")
    return _tray.render(command_line(scene, **options), progress)


class Scene:
    """A scene read once and rendered many times, edited in between.

        scene = tray.Scene("helmets.gltf", allow_any_path=True)   # read, lit, accelerator built
        scene.look_at(eye=(0, 1, 4), target=(0, 0, 0), fov=40)
        scene.set_material(0, base_color=(0.8, 0.1, 0.1), roughness=0.3)
        image = scene.render(spp=16, resolution=(320, 240))       # reuses the accelerator

    The keywords given here are tray-render's, as tray.render takes them: those about the scene
    (scene, camera, env, env_rotate, env_intensity, accel, time, allow_any_path, memory limits)
    hold for every render; render(**options) adds or overrides the others (spp, integrator,
    resolution, aov, lens options, output, ...). Edits: the camera (camera_to_world, look_at,
    fov), light intensities, the environment's rotation, intensity and background, material
    factors. None changes geometry, so the accelerator built by the load serves every render."""

    def __init__(self, path, **options):
        self._path = path
        self._options = options
        self._native = _tray.Scene(command_line(path, **options))

    def render(self, *, progress=None, **options):
        """Renders the scene as it is now; keywords as tray.render's. Returns a tray.Image."""
        if isinstance(progress, str):
            options["progress"] = progress
            progress = None
        args = command_line(self._path, **{**self._options, **options})
        return self._native.render(args, progress)

    @property
    def load_seconds(self):
        """Seconds the load took: reading, lighting, building the accelerator."""
        return self._native.load_seconds

    @property
    def camera_to_world(self):
        """The camera's 4 x 4 camera-to-world matrix (glTF's camera: looking down -Z, +Y up)."""
        return self._native.camera_to_world

    @camera_to_world.setter
    def camera_to_world(self, matrix):
        self._native.camera_to_world = matrix

    @property
    def fov(self):
        """The vertical field of view in degrees."""
        import math
        return math.degrees(self._native.yfov)

    @fov.setter
    def fov(self, degrees):
        import math
        self._native.yfov = math.radians(degrees)

    def look_at(self, eye, target, up=(0.0, 1.0, 0.0), fov=None):
        """Places the camera at `eye` looking at `target`, `up` upwards (and sets fov)."""
        import numpy as np
        eye, target, up = (np.asarray(v, dtype=np.float64) for v in (eye, target, up))
        back = eye - target
        back /= np.linalg.norm(back)
        right = np.cross(up, back)
        right /= np.linalg.norm(right)
        m = np.identity(4)
        m[:3, 0], m[:3, 1], m[:3, 2], m[:3, 3] = right, np.cross(back, right), back, eye
        self.camera_to_world = m
        if fov is not None:
            self.fov = fov

    @property
    def lights(self):
        """The punctual lights: dicts of type, intensity (RGB: colour x intensity), position,
        direction."""
        return self._native.lights

    def set_light_intensity(self, index, rgb):
        """Sets light `index`'s intensity (RGB, colour x intensity; a number: grey)."""
        if isinstance(rgb, (int, float)):
            rgb = (rgb, rgb, rgb)
        self._native.set_light_intensity(index, list(rgb))

    @property
    def materials(self):
        """The materials' factors: dicts of name, base_color, metallic, roughness, emissive,
        transmission, ior."""
        return self._native.materials

    def material_index(self, name):
        for i, m in enumerate(self.materials):
            if m["name"] == name:
                return i
        raise Error(f"{name}: no material of that name")

    def set_material(self, material, **factors):
        """Sets factors of `material` (an index or a name): base_color, metallic, roughness,
        emissive, transmission, ior. Textures multiply them, as in glTF."""
        index = self.material_index(material) if isinstance(material, str) else material
        for key in ("base_color", "emissive"):
            if key in factors and factors[key] is not None:
                factors[key] = list(factors[key])[:3]
        self._native.set_material(index, **factors)

    environment_rotation = property(
        lambda self: self._native.environment_rotation,
        lambda self, v: setattr(self._native, "environment_rotation", v),
        doc="The environment map's rotation about +Y in degrees (as --env-rotate).")
    environment_intensity = property(
        lambda self: self._native.environment_intensity,
        lambda self, v: setattr(self._native, "environment_intensity", v),
        doc="The environment map's radiance scale (as --env-intensity).")
    background = property(
        lambda self: self._native.background,
        lambda self, v: setattr(self._native, "background", list(v)),
        doc="The constant background radiance (RGB) when there is no environment map.")
