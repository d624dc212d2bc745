#!/usr/bin/env python3
"""The hostile suite (issue 40): cases derived from tray-render's own option table and from every
number of a small glTF scene, each asserting TRay's promise for bad input:

  - it ends with exit 0 (the value is accepted and the image written) or 2 (refused);
    never a signal, an abort (134), a crash or exit 1;
  - a refusal is one line on stderr, "tray-render: error: ...";
  - a refused run leaves the output that was there untouched;
  - no run goes over the memory bound (peak resident memory of the child, getrusage).

Options come from `tray-render --help-markdown` (the table docs/options.md is made from): every
option that takes a value gets NaN, +-Inf, -0, 1e40, 2^32 + 64, -1, an empty value and a word.
Scene numbers: every number in scenes/whitted.gltf (transforms, material factors, camera and
light fields, TRAY_* extensions) gets NaN-like and extreme replacements in JSON (1e40, -1e40,
-1, 0, 4294967360, 1e-45). Prints the number of cases; exits 1 naming each case that broke the
promise.

Usage: hostile_test.py SOURCE_DIR BIN_DIR WORK_DIR [quick]  (quick: every seventh scene number)"""

import concurrent.futures
import json
import os
import re
import resource
import shutil
import subprocess
import sys

SOURCE, BIN, WORK = (os.path.abspath(a) for a in sys.argv[1:4])
QUICK = "quick" in sys.argv[4:]
RENDER = os.path.join(BIN, "tray-render")
SCENE = os.path.join(SOURCE, "scenes", "whitted.gltf")
MEMORY_BOUND_MB = 200  # issue 40: a rejected input stays under 200 MB (an 8x6 render: ~140 MB)
OPTION_VALUES = ["nan", "inf", "-inf", "-0", "1e40", "1e19", "4294967360", "-1", "", "abc"]
# Values no option may take: not finite, beyond float, or empty (one checked parse for all).
MUST_REFUSE = {"nan", "inf", "-inf", "1e40", ""}
SCENE_VALUES = ["1e40", "-1e40", "-1", "0", "4294967360", "1e-45"]
# Options that print and exit rather than render.
KEEP_OUT = {"--help-markdown", "--help", "-h", "--version"}


def option_cases():
    """(option, value, must it be refused) from the option table: a numeric option (its type
    FLOAT, INT, number or integer) refuses every value of MUST_REFUSE; any option an empty one
    (a word like "nan" may be a name: a camera, a colorspace only an EXR output reads)."""
    table = subprocess.run([RENDER, "--help-markdown"], capture_output=True, text=True).stdout
    cases = []
    for line in table.splitlines():
        m = re.match(r"\| `(--[a-z0-9-]+)`[^|]*\| ([^|]*)\|", line)
        if not m or m.group(1) in KEEP_OUT:
            continue
        kind = m.group(2).strip()
        if kind == "flag":
            cases.append((m.group(1), "=maybe", True))
            continue
        numeric = re.match(r"(FLOAT|INT|number|integer)", kind) is not None
        for v in OPTION_VALUES:
            cases.append((m.group(1), v, v == "" or (numeric and v in MUST_REFUSE)))
    return cases


def scene_cases():
    """(path, json text) pairs: whitted.gltf with one number replaced."""
    with open(SCENE) as f:
        doc = json.load(f)
    paths = []

    def walk(node, path):
        if isinstance(node, dict):
            for k, v in node.items():
                walk(v, path + [k])
        elif isinstance(node, list):
            for i, v in enumerate(node):
                walk(v, path + [i])
        elif isinstance(node, (int, float)) and not isinstance(node, bool):
            paths.append(path)

    walk(doc, [])
    cases = []
    for path in paths:
        if "buffers" in path and "byteLength" not in path:
            continue
        for v in SCENE_VALUES:
            copy = json.loads(json.dumps(doc))
            node = copy
            for k in path[:-1]:
                node = node[k]
            node[path[-1]] = "__HOSTILE__"
            text = json.dumps(copy).replace('"__HOSTILE__"', v)
            cases.append(("/".join(str(p) for p in path) + "=" + v, text))
    return cases


def run_case(name, args, folder, must_refuse):
    """Runs one case in its own folder with a good image in place; returns (a problem or None,
    the exit code)."""
    os.makedirs(folder, exist_ok=True)
    out = os.path.join(folder, "out.png")
    with open(out, "wb") as f:
        f.write(b"an earlier image")
    def bound():
        # A runaway stops here (address space, not resident memory: the libraries' and
        # threads' reservations are far larger than what is resident). The bound itself is
        # checked on the children's peak resident memory below.
        resource.setrlimit(resource.RLIMIT_AS, (8 << 30, 8 << 30))

    r = subprocess.run([RENDER] + args + ["--resolution", "8x6", "-q", "-o", out],
                       capture_output=True, text=True, preexec_fn=bound, timeout=120, cwd=folder)
    err = r.stderr
    errors = [l for l in err.splitlines() if not l.startswith("warning:")]
    if r.returncode not in (0, 2):
        return f"{name}: exit {r.returncode}: {err.strip()[:200]}", r.returncode
    if must_refuse and r.returncode != 2:
        return f"{name}: accepted (exit {r.returncode}): a value no option may take", 0
    if r.returncode == 2:
        if len(errors) != 1 or not errors[0].startswith("tray-render: error: "):
            return f"{name}: refusal is not one error line: {err.strip()[:300]}", 2
        with open(out, "rb") as f:
            if f.read() != b"an earlier image":
                return f"{name}: refused, but the output was changed", 2
    return None, r.returncode


def main():
    shutil.rmtree(WORK, ignore_errors=True)
    os.makedirs(WORK)
    jobs = []
    for option, value, refuse in option_cases():
        args = [SCENE, option + value] if value.startswith("=") else [SCENE, option, value]
        jobs.append((f"{option} {value!r}", args, refuse))
    scenes = scene_cases()
    if QUICK:
        scenes = scenes[::7]
    for i, (name, text) in enumerate(scenes):
        path = os.path.join(WORK, f"scene{i}.gltf")
        with open(path, "w") as f:
            f.write(text)
        jobs.append((f"whitted.gltf {name}", [path, "--allow-any-path"], False))
    problems, codes = [], {0: 0, 2: 0}
    with concurrent.futures.ThreadPoolExecutor(max_workers=os.cpu_count() or 2) as pool:
        futures = [pool.submit(run_case, name, args, os.path.join(WORK, f"case{i}"), refuse)
                   for i, (name, args, refuse) in enumerate(jobs)]
        for f in futures:
            p, code = f.result()
            if p:
                problems.append(p)
            elif code in codes:
                codes[code] += 1
    peak_mb = resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss / 1024
    print(f"hostile suite: {len(jobs)} cases ({len(jobs) - len(scenes)} option values, "
          f"{len(scenes)} scene numbers): {codes[2]} refused in one line, {codes[0]} accepted "
          f"and rendered, {len(problems)} broke the promise; largest child peak "
          f"{peak_mb:.0f} MB (bound {MEMORY_BOUND_MB} MB)")
    # Both kinds of answer were met: the cases reach the checks, not only the parser.
    if codes[2] < len(jobs) // 4 or codes[0] < len(jobs) // 10:
        problems.append("too few refusals or acceptances: the cases did not exercise TRay")
    for p in problems:
        print("  " + p)
    if peak_mb > MEMORY_BOUND_MB:
        problems.append("memory bound")
    if not problems:
        shutil.rmtree(WORK, ignore_errors=True)
    sys.exit(1 if problems else 0)


if __name__ == "__main__":
    main()
