"""Turntable: an asset rendered from a camera circling it, the frames written as a GIF.

    /usr/bin/python3 python/examples/turntable.py ../shared/gltf-samples/DamagedHelmet.glb \
        turntable.gif --frames 36 --size 256 --spp 32

The scene is read once (tray.Scene): each frame only moves the camera, so the accelerator
built by the load serves every frame. The frames are display-referred as TRay's PNG output
(Image.to_display) and written by OpenImageIO's GIF writer."""
import argparse
import math

import numpy as np
import OpenImageIO as oiio

import tray


def turntable(path, frames, size, spp):
    """The frames (H x W x 3 uint8) of a camera orbiting the world's Y axis."""
    scene = tray.Scene(path, allow_any_path=True)
    start = np.array(scene.camera_to_world)
    images = []
    for f in range(frames):
        a = 2 * math.pi * f / frames
        orbit = np.identity(4)  # a rotation about +Y through the origin
        orbit[0, 0], orbit[0, 2], orbit[2, 0], orbit[2, 2] = (math.cos(a), math.sin(a),
                                                             -math.sin(a), math.cos(a))
        scene.camera_to_world = orbit @ start
        image = scene.render(spp=spp, resolution=(size, size), seed=f)
        images.append(image.to_display())
    return images


def write_gif(path, frames, fps=12):
    spec = oiio.ImageSpec(frames[0].shape[1], frames[0].shape[0], 3, oiio.UINT8)
    spec.attribute("FramesPerSecond", oiio.TypeDesc("rational"), (fps, 1))
    out = oiio.ImageOutput.create(path)
    if not out or not out.open(path, [spec] * len(frames)):
        raise RuntimeError(f"{path}: {oiio.geterror()}")
    for i, frame in enumerate(frames):
        if i and not out.open(path, spec, "AppendSubimage"):
            raise RuntimeError(f"{path}: {out.geterror()}")
        out.write_image(frame)
    out.close()


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("scene")
    parser.add_argument("gif")
    parser.add_argument("--frames", type=int, default=36)
    parser.add_argument("--size", type=int, default=256)
    parser.add_argument("--spp", type=int, default=32)
    args = parser.parse_args()
    write_gif(args.gif, turntable(args.scene, args.frames, args.size, args.spp))


if __name__ == "__main__":
    main()
