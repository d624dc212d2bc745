#!/usr/bin/python3
"""tools/tray-denoise against the Cornell box's converged reference (Mitsuba 3, 4096 spp).

    denoise_test.py TRAY_RENDER SOURCE_DIR SHARED_DIR WORK_DIR

Renders the box at 4 spp with the all-sample albedo and normal, denoises it, and requires the
denoised RMSE to be several times below the noisy one; then checks the one-line errors (exit 2)
for a render without the auxiliary layers and for a missing denoiser. Exits 77 (ctest: skipped)
with a message when pyoidn is not installed (tools/setup-denoise.sh). WORK_DIR is removed
unless the test fails.
"""
import os
import shutil
import subprocess
import sys

render_bin, source_dir, shared_dir, work = sys.argv[1:5]
denoise = os.path.join(source_dir, "tools", "tray-denoise")
scene = os.path.join(shared_dir, "reference", "cornell-box.gltf")
reference = os.path.join(shared_dir, "reference", "cornell-box.ref.exr")


def run(*args, env=None):
    return subprocess.run(list(args), capture_output=True, text=True, env=env)


probe = run("/usr/bin/python3", "-c", "import numpy, OpenImageIO")
if probe.returncode != 0 or not os.path.exists(reference):
    print("SKIP: no python3-numpy / python3-openimageio (tools/setup.sh installs them) or no "
          "reference image:", probe.stderr.strip().splitlines()[-1:] or reference)
    sys.exit(77)

import numpy as np  # noqa: E402  (after the skip: python3-numpy comes with the denoiser set-up)
import OpenImageIO as oiio  # noqa: E402

os.makedirs(work, exist_ok=True)


def read(path, names):
    buf = oiio.ImageBuf(path)
    spec = buf.spec()
    pixels = buf.get_pixels(oiio.FLOAT).reshape(spec.height, spec.width, spec.nchannels)
    return pixels[:, :, [spec.channelnames.index(n) for n in names]]


def rmse(image, ref):
    # In the display range [0, 1]: the visible emitter (18 here) would otherwise dominate, and
    # what a denoiser must fix is the noise a viewer sees.
    return float(np.sqrt(((np.clip(image, 0, 1) - np.clip(ref, 0, 1)) ** 2).mean()))


noisy_exr = os.path.join(work, "noisy.exr")
out_exr = os.path.join(work, "denoised.exr")
r = run(render_bin, "--integrator=path", "--spp", "4", scene, "--resolution", "256x256",
        "--aov", "albedo,normal", "--float", "-q", "-o", noisy_exr)
assert r.returncode == 0, r.stderr
r = run(denoise, noisy_exr, "-o", out_exr)
if r.returncode == 2 and "not installed" in r.stderr:
    print("SKIP:", r.stderr.strip())
    shutil.rmtree(work)
    sys.exit(77)
assert r.returncode == 0, r.stderr

ref = read(reference, ["R", "G", "B"])
noisy = read(out_exr, ["noisy.R", "noisy.G", "noisy.B"])
denoised = read(out_exr, ["R", "G", "B"])
assert np.array_equal(noisy, read(noisy_exr, ["R", "G", "B"])), "the noisy layer is the input"
e_noisy, e_denoised = rmse(noisy, ref), rmse(denoised, ref)
print(f"Cornell box 256x256, 4 spp: RMSE noisy {e_noisy:.5f}, denoised {e_denoised:.5f}, "
      f"ratio {e_noisy / e_denoised:.2f}")
assert e_denoised * 3 < e_noisy, "denoising should cut the error at least threefold"

# Bad input: no auxiliary layers -> one line naming the file, exit 2.
plain_exr = os.path.join(work, "plain.exr")
assert run(render_bin, "--integrator=path", "--spp", "1", scene, "--resolution", "32x32", "-q",
           "-o", plain_exr).returncode == 0
r = run(denoise, plain_exr, "-o", os.path.join(work, "x.exr"))
assert r.returncode == 2 and r.stderr.count("\n") == 1 and "--aov albedo,normal" in r.stderr, r
# Issue 40: the output over the input, and a write that fails (a read-only folder), are one
# line and exit 2, with the input untouched and no temporary file left behind.
before = open(noisy_exr, "rb").read()
r = run(denoise, noisy_exr, "-o", noisy_exr)
assert r.returncode == 2 and r.stderr.count("\n") == 1 and "is the input" in r.stderr, r
assert open(noisy_exr, "rb").read() == before
taken = os.path.join(work, "taken.exr")  # a folder of that name: the last rename fails
os.mkdir(taken)
r = run(denoise, noisy_exr, "-o", taken)
assert r.returncode == 2 and r.stderr.count("\n") == 1 and "cannot write" in r.stderr, r
assert os.path.isdir(taken)
assert not [f for f in os.listdir(work) if f.endswith(".tmp.exr")], os.listdir(work)
# No denoiser where it is looked for -> one line, exit 2 (when this python lacks pyoidn).
if run("/usr/bin/python3", "-c", "import pyoidn").returncode != 0:
    env = dict(os.environ, TRAY_OIDN_PYTHON="/nonexistent/python3", XDG_DATA_HOME="/nonexistent")
    r = run("/usr/bin/python3", denoise, noisy_exr, "-o", os.path.join(work, "x.exr"), env=env)
    assert r.returncode == 2 and "not installed" in r.stderr and r.stderr.count("\n") == 1, r
shutil.rmtree(work)
print("ok")
