#!/usr/bin/env python3
"""Fails the build when a source file includes a header from a layer it may not use.

TRay's library folders are layers (docs/architecture.md): each may include only itself and the
layers listed for it below, so dependencies point one way and no cycle can form. The CMake
targets link the same way (tray_<layer> links only the layers below it); this check runs
before anything compiles and names the offending line, which a missing symbol at link time
would not.

Usage: check_layers.py SOURCE_DIR [STAMP_FILE]
"""
import pathlib
import re
import sys

# layer -> the layers it may include besides itself. Keep in step with the CMake targets and
# with the table in docs/architecture.md.
ALLOWED = {
    "core": set(),
    "textures": {"core"},
    "film": {"core"},
    "shapes": {"core"},
    "accel": {"core", "textures", "shapes"},  # shapes: Embree's own curves, subdivision
    "materials": {"core"},
    "lights": {"core"},
    "integrators": {"core", "textures", "film", "materials", "lights"},
    "io": {"core", "textures", "film"},
    "gltf": {"core", "textures", "film", "shapes", "accel", "materials", "lights", "io"},
    "render": {"core", "textures", "film", "shapes", "accel", "materials", "lights",
               "integrators", "io", "gltf"},
    "cli": {"core", "textures", "film", "shapes", "accel", "materials", "lights", "integrators",
            "io", "gltf", "render"},
    # The Python module: over the command line's option table and checks, as tray-render.
    "python": {"core", "textures", "film", "shapes", "accel", "materials", "lights",
               "integrators", "io", "gltf", "render", "cli"},
}
# Both spellings: "core/x.h" and <core/x.h> (a project header in angle brackets is still one).
INCLUDE = re.compile(r'^\s*#\s*include\s+["<]([a-z_]+)/[^">]+[">]', re.MULTILINE)


def violations(root: pathlib.Path):
    for layer, allowed in ALLOWED.items():
        for path in sorted((root / layer).rglob("*")):
            if path.suffix not in (".h", ".cpp"):
                continue
            text = path.read_text(encoding="utf-8", errors="replace")
            for m in INCLUDE.finditer(text):
                target = m.group(1)
                if target in ALLOWED and target != layer and target not in allowed:
                    line = text.count("\n", 0, m.start()) + 1
                    may = ", ".join(sorted(allowed)) or "nothing else"
                    yield (f"{path.relative_to(root)}:{line}: layer '{layer}' includes "
                           f"'{target}/' (it may use: {may}; see docs/architecture.md)")


def main() -> int:
    root = pathlib.Path(sys.argv[1])
    found = list(violations(root))
    for v in found:
        print(v, file=sys.stderr)
    if found:
        return 1
    if len(sys.argv) > 2:
        pathlib.Path(sys.argv[2]).write_text("ok\n")
    return 0


if __name__ == "__main__":
    sys.exit(main())
