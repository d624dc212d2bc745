#!/usr/bin/env python3
"""Renders every model of a Khronos glTF-Sample-Assets checkout beside its own screenshot
(issue 39): docs/gallery/khronos/README.md, one row per model with the repository's screenshot,
TRay's `path` render at its defaults and under an HDR map, the verdict a person gave on looking
at the three (docs/gallery/khronos/verdicts.tsv) and the counts.

  /usr/bin/python3 tools/khronos_gallery.py MODELS_DIR [--size 128] [--spp 16] [--build build]
      [--map courtyard.exr] [--only NAME ...] [--readme-only]

MODELS_DIR is the repository's Models/ folder (tools/fetch-khronos-samples.sh makes one). A model
is rendered from its first complete variant of glTF, glTF-Binary, glTF-Embedded (the core
formats; Draco, KTX2 and quantized variants are other encodings of the same asset). A variant is
incomplete when MODELS_DIR/../absent.txt lists one of its files (a snapshot that left its largest
files out): such a model is listed as "absent from the snapshot", not rendered and not counted
against TRay. Animated models are rendered at --time 1, as docs/gallery's shared set is.
"""
import argparse
import json
import os
import struct
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
OUT = ROOT / "docs" / "gallery" / "khronos"
VARIANTS = ("glTF", "glTF-Binary", "glTF-Embedded")
VERDICTS = ("as authored", "difference", "wrong")


def gltf_json(path: Path) -> dict:
    """The JSON of a .gltf, or of a .glb's first chunk (glTF 2.0 spec, section 4.4)."""
    data = path.read_bytes()
    if path.suffix.lower() == ".glb":
        length, kind = struct.unpack_from("<II", data, 12)
        if kind != 0x4E4F534A:  # "JSON"
            return {}
        data = data[20 : 20 + length]
    try:
        return json.loads(data.decode("utf-8"))
    except (UnicodeDecodeError, json.JSONDecodeError):
        return {}


def choose_file(model: Path, absent: set) -> tuple:
    """(file, variant) of the first complete core variant, else (None, what is absent)."""
    missing = []
    for variant in VARIANTS:
        folder = model / variant
        if not folder.is_dir():
            continue
        gone = sorted(p for p in absent if p.startswith(f"{model.name}/{variant}/"))
        if gone:
            missing += gone
            continue
        files = sorted(folder.glob("*.gltf")) + sorted(folder.glob("*.glb"))
        named = [f for f in files if f.stem == model.name]
        if named or files:
            return (named or files)[0], variant
    return None, ", ".join(Path(p).name for p in missing) or "no core variant"


def screenshot(model: Path, size: int) -> bool:
    """The repository's screenshot (metadata.json names it) fitted into SIZE² as a PNG."""
    meta = load_metadata(model)
    shot = model / meta.get("screenshot", "screenshot/screenshot.png")
    if not shot.is_file():
        candidates = sorted((model / "screenshot").glob("screenshot.*"))
        if not candidates:
            return False
        shot = candidates[0]
    target = OUT / f"{model.name}-screenshot.png"
    run = subprocess.run(["oiiotool", str(shot), "--ch", "R,G,B", "--fit:pad=1",
                          f"{size}x{size}", "-o", str(target)], capture_output=True, text=True)
    return run.returncode == 0


def load_metadata(model: Path) -> dict:
    try:
        return json.loads((model / "metadata.json").read_text())
    except (OSError, json.JSONDecodeError):
        return {}


def render(args, scene: Path, png: Path, extra: list) -> str:
    """Renders one image; returns the first error line, or "" on success."""
    cmd = [str(ROOT / args.build / "tray-render"), "-q", "--integrator", "path", "--spp",
           str(args.spp), "--resolution", f"{args.size}x{args.size}", "--allow-any-path",
           *extra, str(scene), "-o", str(png)]
    run = subprocess.run(cmd, capture_output=True, text=True)
    if run.returncode == 0:
        return ""
    lines = [l for l in run.stderr.splitlines() if "error" in l] or run.stderr.splitlines()
    line = (lines[0] if lines else f"exit {run.returncode}").strip()
    return line.replace(f"tray-render: error: {scene}: ", "")  # the row names the model


def read_verdicts() -> dict:
    verdicts = {}
    path = OUT / "verdicts.tsv"
    if path.is_file():
        for line in path.read_text().splitlines():
            if line.startswith("#") or not line.strip():
                continue
            cells = line.split("\t") + ["", ""]
            verdicts[cells[0]] = (cells[1], cells[2])
    return verdicts


def licence(model: Path) -> str:
    legal = load_metadata(model).get("legal", [])
    parts = [f"{l.get('artist', '?')}, {l.get('spdx') or l.get('license', '?')}" for l in legal]
    return "; ".join(dict.fromkeys(parts)) or "see the model's LICENSE.md"


def write_readme(args, rows: list) -> None:
    verdicts = read_verdicts()
    counts = {v: 0 for v in VERDICTS}
    rendered = [r for r in rows if r["status"] == "rendered"]
    for r in rendered:
        v = verdicts.get(r["name"], ("not judged", ""))[0]
        counts[v] = counts.get(v, 0) + 1
    refused = [r for r in rows if r["status"] == "refused"]
    absent = [r for r in rows if r["status"] == "absent"]
    judged = sum(counts[v] for v in VERDICTS)
    share = 100.0 * counts["as authored"] / judged if judged else 0.0
    lines = [
        "# Gallery: the Khronos glTF sample models",
        "",
        f"`/usr/bin/python3 tools/khronos_gallery.py MODELS_DIR --size {args.size} --spp {args.spp}`"
        " over the `Models/` folder of a glTF-Sample-Assets snapshot"
        " (`tools/fetch-khronos-samples.sh` makes it). Each row: the repository's own screenshot,"
        f" TRay's `path` at {args.spp} spp and {args.size}×{args.size} with its defaults (the file's"
        " camera and lights, else TRay's automatic camera and default light; animated models at"
        f" `--time 1`), then under an HDR map (`--env {Path(args.map).name if args.map else 'none'}`)."
        " The verdicts are a person's, from looking at the three side by side"
        " (`verdicts.tsv`; the script only counts them). Screenshots are the viewers' renders"
        " under their own lights and cameras: framing and lighting differ by design; a verdict"
        " judges materials, geometry, textures and what the asset shows.",
        "",
        f"**{len(rows)} models: {len(rendered)} rendered — {counts['as authored']} as authored,"
        f" {counts['difference']} with a named difference, {counts['wrong']} wrong,"
        f" {counts.get('not judged', 0)} not judged ({share:.0f}% of those judged as authored);"
        f" {len(refused)} refused by TRay; {len(absent)} absent from the snapshot (files it left"
        " out, listed; not rendered).**",
        "",
        "| # | model | screenshot | defaults | under the map | verdict | difference | variant |",
        "|---|---|---|---|---|---|---|---|",
    ]
    for i, r in enumerate(rows, 1):
        n = r["name"]
        if r["status"] == "rendered":
            v, note = verdicts.get(n, ("not judged", ""))
            env = f"![]({n}-env.png)" if args.map else "—"
            shot = f"![]({n}-screenshot.png)" if r["shot"] else "—"
            lines.append(f"| {i} | {n} | {shot} | ![]({n}.png) | {env} | {v} | {note} | {r['variant']} |")
        elif r["status"] == "refused":
            lines.append(f"| {i} | {n} | — | — | — | refused | {r['why']} | {r['variant']} |")
        else:
            lines.append(f"| {i} | {n} | — | — | — | absent from the snapshot | {r['why']} | — |")
    lines += ["", "## Licences", "",
              "Screenshots are the models' own, shown small beside the renders; each model's"
              " licence (its metadata.json: artist, SPDX identifier) is:", ""]
    lines += [f"- {r['name']}: {r['licence']}" for r in rows]
    (OUT / "README.md").write_text("\n".join(lines) + "\n")
    print(f"khronos_gallery: {len(rows)} models, {len(rendered)} rendered: "
          f"{counts['as authored']} as authored, {counts['difference']} named differences, "
          f"{counts['wrong']} wrong, {counts.get('not judged', 0)} not judged; "
          f"{len(refused)} refused; {len(absent)} absent from the snapshot")


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("models", type=Path)
    parser.add_argument("--size", type=int, default=128)
    parser.add_argument("--spp", type=int, default=16)
    parser.add_argument("--build", default="build")
    parser.add_argument("--map", default=os.environ.get("TRAY_GALLERY_ENV", ""))
    parser.add_argument("--only", nargs="*", default=[])
    parser.add_argument("--readme-only", action="store_true")
    args = parser.parse_args()
    if not args.map:
        maps = sorted(ROOT.glob("build/cycles5-venv/lib/python3*/site-packages/bpy/*/datafiles/"
                                "studiolights/world/courtyard.exr"))
        args.map = str(maps[0]) if maps else ""
    if not args.models.is_dir():
        print(f"khronos_gallery: error: {args.models}: not a folder", file=sys.stderr)
        return 2
    absent_list = args.models.parent / "absent.txt"
    absent = set(absent_list.read_text().split("\n")) if absent_list.is_file() else set()
    absent = {p.removeprefix("Models/") for p in absent if p}
    OUT.mkdir(parents=True, exist_ok=True)
    # What each model's last render gave, kept so that --only and --readme-only rewrite the page
    # without rendering the rest again.
    kept_path = OUT / "status.json"
    kept = json.loads(kept_path.read_text()) if kept_path.is_file() else {}
    rows = []
    for model in sorted(p for p in args.models.iterdir() if p.is_dir()):
        name = model.name
        scene, variant = choose_file(model, absent)
        row = {"name": name, "variant": variant, "licence": licence(model), "shot": False}
        if scene is None:
            rows.append({**row, "status": "absent", "why": variant})
            continue
        if args.readme_only or (args.only and name not in args.only):
            if name in kept:
                rows.append(kept[name])
            continue
        row["shot"] = screenshot(model, args.size)
        extra = ["--time", "1"] if gltf_json(scene).get("animations") else []
        why = render(args, scene, OUT / f"{name}.png", extra)
        if not why and args.map:
            why = render(args, scene, OUT / f"{name}-env.png", extra + ["--env", args.map])
        rows.append({**row, "status": "refused" if why else "rendered", "why": why})
        print(f"{name}: {why or 'ok'}", flush=True)
    kept_path.write_text(json.dumps({r["name"]: r for r in rows}, indent=1) + "\n")
    write_readme(args, rows)
    return 0


if __name__ == "__main__":
    sys.exit(main())
