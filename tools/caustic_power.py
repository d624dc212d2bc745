#!/usr/bin/env python3
"""The caustic of scenes/transport/caustic-spot.gltf by ray-optics quadrature, and renders
checked against it (issue 38's closed form).

A spot light aimed at a smooth glass ball (IOR 1.5) above a diffuse floor, its cone inside the
ball's silhouette: all light on the floor came off the ball (Fresnel reflection at entry) or
through it (two refractions, with k internal reflections between). Each light ray's fate is
exact geometric optics on a sphere: the entry angle fixes the inner angle, which every internal
bounce keeps, so Fresnel's unpolarised reflectance F is the same at every interface and a ray
carries F (reflected), (1-F)^2 (straight through), (1-F)^2 F (one internal reflection), ... .
Integrating I falloff(alpha) dOmega over the cone (midpoint rule in cos(alpha) and azimuth)
gives the power landing in each pixel of the scene's orthographic view of the floor; a diffuse
floor of albedo rho then shows radiance rho E / pi there.

Paths with one diffuse vertex and at most one internal reflection are those of length <= 5
segments from the camera (camera-floor, floor-ball, ..., ball-light): render with
--max-depth 5 (MAX_DEPTH), which also leaves out floor -> ball -> floor interreflection. The
reference sums exactly those paths; it prints what k >= 2 would add.

  tools/caustic_power.py                  print the reference power
  tools/caustic_power.py RENDER.exr ...   and each render's measured power, its error, and the
                                          error of the 4 quadrants' powers (regional bias)
  --reference-exr OUT.exr                 also write the reference radiance image
"""
import argparse
import importlib.util
import math
import os
import sys

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
_spec = importlib.util.spec_from_file_location("scenes",
                                               os.path.join(HERE, "make-transport-scenes.py"))
S = importlib.util.module_from_spec(_spec)
_spec.loader.exec_module(S)


def fresnel(cos_i, eta):
    """Unpolarised Fresnel reflectance of a dielectric, light arriving from outside."""
    sin2_t = (1 - cos_i ** 2) / eta ** 2
    cos_t = np.sqrt(np.maximum(0.0, 1 - sin2_t))
    rs = (cos_i - eta * cos_t) / (cos_i + eta * cos_t)
    rp = (eta * cos_i - cos_t) / (eta * cos_i + cos_t)
    return 0.5 * (rs * rs + rp * rp), cos_t


def pixel_weights():
    """Which pixels are measured: inside the view, centre farther than EXCLUDED_RADIUS from the
    ball's footprint. Pixel (row, col): col along +x, row along +z (the camera's up is -Z, so
    row 0, the image's top, is the most negative z)."""
    n, h = S.IMAGE_SIZE, S.VIEW_HALF
    c = (np.arange(n) + 0.5) / n * 2 * h - h
    x = S.VIEW_CENTER[0] + c[None, :]
    z = S.VIEW_CENTER[1] + c[:, None]
    return (np.hypot(x - S.BALL_CENTER[0], z - S.BALL_CENTER[2]) > S.EXCLUDED_RADIUS)


def land(image, origin, direction, weight):
    """Adds the power `weight` of rays (origin, direction) to the pixel where they meet y = 0."""
    down = direction[:, 1] < 0
    o, d, w = origin[down], direction[down], weight[down]
    s = -o[:, 1] / d[:, 1]
    x = o[:, 0] + s * d[:, 0]
    z = o[:, 2] + s * d[:, 2]
    n, h = S.IMAGE_SIZE, S.VIEW_HALF
    col = np.floor((x - (S.VIEW_CENTER[0] - h)) / (2 * h) * n).astype(np.int64)
    row = np.floor((z - (S.VIEW_CENTER[1] - h)) / (2 * h) * n).astype(np.int64)
    inside = (col >= 0) & (col < n) & (row >= 0) & (row < n)
    np.add.at(image, (row[inside], col[inside]), w[inside])


def reference(n_alpha=3000, n_phi=2000, max_internal=1):
    """Power per pixel (W) landing on the floor, paths with <= max_internal internal
    reflections; and the power that paths with more would add (everywhere on the floor)."""
    n = S.IMAGE_SIZE
    image = np.zeros((n, n))
    P = np.array(S.light_position())
    C = np.array(S.BALL_CENTER)
    R, eta, I0 = S.BALL_RADIUS, S.BALL_IOR, S.LIGHT_INTENSITY
    a = (C - P) / np.linalg.norm(C - P)
    u = np.cross(a, [0.0, 0.0, 1.0]) if abs(a[2]) < 0.9 else np.cross(a, [1.0, 0.0, 0.0])
    u /= np.linalg.norm(u)
    v = np.cross(a, u)
    cos_o, cos_i_cone = math.cos(S.OUTER_CONE), math.cos(S.INNER_CONE)
    extra = 0.0
    # Midpoint rule in cos(alpha) (uniform solid angle) and azimuth, a slice of alpha at a time.
    dcos = (1 - cos_o) / n_alpha
    dphi = 2 * math.pi / n_phi
    phi = (np.arange(n_phi) + 0.5) * dphi
    for i in range(n_alpha):
        ca = 1 - (i + 0.5) * dcos
        sa = math.sqrt(1 - ca * ca)
        t = min(max((ca - cos_o) / (cos_i_cone - cos_o), 0.0), 1.0)
        power = I0 * t * t * dcos * dphi  # per ray
        d = ca * a[None, :] + sa * (np.cos(phi)[:, None] * u + np.sin(phi)[:, None] * v)
        # Entry: the ray from P meets the sphere (the cone is inside the silhouette).
        oc = P - C
        b = d @ oc
        disc = b * b - (oc @ oc - R * R)
        s1 = -b - np.sqrt(disc)
        x1 = P + s1[:, None] * d
        n1 = (x1 - C) / R
        cos_in = -np.sum(d * n1, axis=1)
        F, cos_t = fresnel(cos_in, eta)
        w = np.full(n_phi, power)
        land(image, x1, d + 2 * cos_in[:, None] * n1, w * F)  # reflected at entry
        # Refracted in; every chord then has length 2 R cos_t and meets the surface at cos_t.
        dt = d / eta + (cos_in / eta - cos_t)[:, None] * n1
        x, dirn, inner = x1, dt, w * (1 - F)
        for k in range(0, 12):  # F^12 < 1e-16: nothing left
            x_next = x + (2 * R * cos_t)[:, None] * dirn
            n2 = x_next - C
            n2 /= np.linalg.norm(n2, axis=1)[:, None]  # back onto the sphere: no drift
            x_next = C + R * n2
            cdn = np.sum(dirn * n2, axis=1)  # = cos_t
            # Out: refract with eta' = 1/eta; the outside angle is the entry angle.
            out = eta * dirn + (cos_in - eta * cdn)[:, None] * n2
            out /= np.linalg.norm(out, axis=1)[:, None]
            if k <= max_internal:
                land(image, x_next, out, inner * (1 - F))
            else:
                extra += float(np.sum(inner * (1 - F)))
            # Reflect inside and go on.
            dirn = dirn - 2 * cdn[:, None] * n2
            dirn /= np.linalg.norm(dirn, axis=1)[:, None]
            x, inner = x_next, inner * F
    return image, extra


def read_red(path):
    import OpenImageIO as oiio
    inp = oiio.ImageInput.open(path)
    if not inp:
        sys.exit(f"{path}: cannot open ({oiio.geterror()})")
    px = inp.read_image(0, 0, 0, 3, "float")
    inp.close()
    if px.shape[0] != S.IMAGE_SIZE or px.shape[1] != S.IMAGE_SIZE:
        sys.exit(f"{path}: {px.shape[1]}x{px.shape[0]}, expected "
                 f"{S.IMAGE_SIZE}x{S.IMAGE_SIZE} (render with --resolution {S.IMAGE_SIZE}x{S.IMAGE_SIZE})")
    return px[:, :, 0].astype(np.float64)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("renders", nargs="*")
    ap.add_argument("--reference-exr")
    ap.add_argument("--quality", type=int, default=1, help="quadrature refinement factor")
    args = ap.parse_args()
    image, extra = reference(3000 * args.quality, 2000 * args.quality)
    mask = pixel_weights()
    total = float(np.sum(image * mask))
    emitted = float(np.sum(image))
    print(f"reference: {total:.6f} W on the measured floor "
          f"({emitted:.6f} W on the view; k>=2 internal reflections would add "
          f"{extra:.2e} W anywhere)")
    pixel_area = (2 * S.VIEW_HALF / S.IMAGE_SIZE) ** 2
    half = S.IMAGE_SIZE // 2
    quads = [(slice(0, half), slice(0, half)), (slice(0, half), slice(half, None)),
             (slice(half, None), slice(0, half)), (slice(half, None), slice(half, None))]
    if args.reference_exr:
        import OpenImageIO as oiio
        L = S.FLOOR_ALBEDO * image / pixel_area / math.pi
        buf = oiio.ImageBuf(np.repeat(L[:, :, None], 3, axis=2).astype(np.float32))
        buf.write(args.reference_exr)
    worst = 0.0
    for path in args.renders:
        L = read_red(path)
        power = L * math.pi / S.FLOOR_ALBEDO * pixel_area
        measured = float(np.sum(power * mask))
        err = measured / total - 1
        qerr = [float(np.sum((power * mask)[q]) / max(np.sum((image * mask)[q]), 1e-30) - 1)
                for q in quads if np.sum((image * mask)[q]) > 0.05 * total]
        print(f"{path}: {measured:.6f} W, error {100 * err:+.2f}%, quadrants "
              + " ".join(f"{100 * e:+.1f}%" for e in qerr))
        worst = max(worst, abs(err))
    return 0


if __name__ == "__main__":
    sys.exit(main())
