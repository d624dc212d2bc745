"""Material sweep: roughness from 0 to 1, the renders side by side in a PNG.

    /usr/bin/python3 python/examples/material_sweep.py scenes/textured.gltf sweep.png --steps 5

Each step edits the material's factor and renders again: the scene is read and its
accelerator built once (tray.Scene)."""
import argparse

import numpy as np
import OpenImageIO as oiio

import tray


def sweep(path, material, steps, size, spp):
    """The renders (H x W x 3 uint8) at roughness 0 .. 1 of `material` (an index or a name;
    None: every material)."""
    scene = tray.Scene(path, allow_any_path=True)
    materials = range(len(scene.materials)) if material is None else [material]
    strip = []
    for i in range(steps):
        for m in materials:
            scene.set_material(m, roughness=i / max(steps - 1, 1))
        strip.append(scene.render(spp=spp, resolution=(size, size), seed=0).to_display())
    return strip


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("scene")
    parser.add_argument("png")
    parser.add_argument("--material", help="an index or a material's name (default: all)")
    parser.add_argument("--steps", type=int, default=5)
    parser.add_argument("--size", type=int, default=160)
    parser.add_argument("--spp", type=int, default=32)
    args = parser.parse_args()
    material = args.material
    if material is not None and material.isdigit():
        material = int(material)
    row = np.concatenate(sweep(args.scene, material, args.steps, args.size, args.spp), axis=1)
    out = oiio.ImageOutput.create(args.png)
    out.open(args.png, oiio.ImageSpec(row.shape[1], row.shape[0], 3, oiio.UINT8))
    out.write_image(row)
    out.close()


if __name__ == "__main__":
    main()
