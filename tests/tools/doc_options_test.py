#!/usr/bin/env python3
"""Fails when README.md or a page under docs/ names a command-line option that the tool's
--help lacks, naming the file and line.

    doc_options_test.py SOURCE_DIR BIN_DIR     (BIN_DIR holds tray-render, tray-merge, tray-farm)

What counts as naming an option of TRay's tools:
- a command line that runs tray-render, tray-merge or tray-farm, in a code block or in an
  inline code span: every --name after the tool's name, up to the end of that command (a pipe,
  ;, &&, || or a # comment), must be in that tool's --help (tray-farm passes what it does not
  know to tray-render, so tray-farm's command lines may also use tray-render's options);
- an inline code span that starts with --name (`--spp 64`) in prose: the option must be in the
  --help of one of the three tools, unless its paragraph (or list item) names another
  program (in inline code, a path such as `tools/compare-mitsuba.sh` or `build/path_bench` or a
  .sh/.py file; anywhere, an external command such as cmake, valgrind, callgrind, blender,
  mitsuba or sbatch): then it is taken as that program's option and not checked here.
Lines of code blocks that run other programs are not read, nor --name in plain prose.
"""
import glob
import os
import re
import subprocess
import sys

TOOLS = ("tray-render", "tray-merge", "tray-farm")
EXTERNAL = {"cmake", "ctest", "ninja", "valgrind", "callgrind", "cachegrind", "perf", "blender",
            "mitsuba", "git", "pip", "python", "python3", "sbatch", "srun", "squeue", "sacct",
            "oiiotool", "iinfo", "apt-get", "sudo"}
OPTION = re.compile(r"(?<![\w-])--([A-Za-z0-9][\w-]*)")
SPAN = re.compile(r"`([^`\n]+)`")


def declared_options(help_text):
    """Option names declared in a --help text (CLI11 or argparse): on each line that starts with
    a dash, the names before the description (which begins after two or more spaces)."""
    names = set()
    for line in help_text.splitlines():
        stripped = line.strip()
        if not stripped.startswith("-"):
            continue
        names.update(OPTION.findall(re.split(r"\s{2,}", stripped)[0]))
    return names


def run_help(command):
    result = subprocess.run(command + ["--help"], capture_output=True, text=True, check=True)
    return result.stdout


def tool_options(bin_dir):
    render = declared_options(run_help([os.path.join(bin_dir, "tray-render")]))
    merge = declared_options(run_help([os.path.join(bin_dir, "tray-merge")]))
    farm_cmd = [sys.executable, os.path.join(bin_dir, "tray-farm")]
    farm_help = run_help(farm_cmd)
    farm = declared_options(farm_help)
    subcommands = re.search(r"\{([\w,-]+)\}", farm_help)
    for sub in subcommands.group(1).split(",") if subcommands else []:
        farm |= declared_options(run_help(farm_cmd + [sub]))
    return {"tray-render": render, "tray-merge": merge, "tray-farm": farm | render}


def tool_of(word):
    word = word.strip("\"'()[]")
    base = word.rsplit("/", 1)[-1]
    return base if base in TOOLS else None


def command_options(text):
    """(tool, option) for each option on the tool's command lines in `text` (one logical
    line of shell)."""
    found = []
    text = re.sub(r"(^|\s)#.*", "", text)  # comments ('####' in a file name is not one)
    for command in re.split(r"\|\||&&|[|;]", text):
        words = command.split()
        for i, word in enumerate(words):
            tool = tool_of(word)
            if tool:
                found += [(tool, name) for w in words[i + 1:] for name in OPTION.findall(w)
                          if w.startswith("--")]
                break
    return found


def names_other_program(paragraph):
    if any(word.lower() in EXTERNAL for word in re.findall(r"[\w-]+", paragraph)):
        return True
    for span in SPAN.findall(paragraph):
        first = span.split()[0] if span.split() else ""
        if tool_of(first) or first.startswith("-"):
            continue
        if "/" in first or re.search(r"\.(sh|py)$", first):
            return True
    return False


def check_file(path, shown, options, union):
    errors = []
    lines = open(path, encoding="utf-8").read().split("\n")
    in_code, pending, start = False, "", 0
    paragraph_of = paragraphs(lines)
    for number, line in enumerate(lines, 1):
        if line.lstrip().startswith("```"):
            in_code, pending = not in_code, ""
            continue
        if in_code:
            if not pending:
                start = number
            pending += line
            if pending.endswith("\\"):
                pending = pending[:-1] + " "
                continue
            for tool, name in command_options(pending):
                if name not in options[tool]:
                    errors.append(f"{shown}:{start}: {tool} has no --{name} (not in its --help)")
            pending = ""
            continue
        other = None
        for span in SPAN.findall(line):
            if any(tool_of(w) for w in span.split()):
                for tool, name in command_options(span):
                    if name not in options[tool]:
                        errors.append(f"{shown}:{number}: {tool} has no --{name} "
                                      "(not in its --help)")
            elif OPTION.match(span):
                name = OPTION.match(span).group(1)
                if name in union:
                    continue
                if other is None:
                    other = names_other_program(paragraph_of[number - 1])
                if not other:
                    errors.append(f"{shown}:{number}: --{name} is an option of none of "
                                  f"{', '.join(TOOLS)} (not in their --help)")
    return errors


def paragraphs(lines):
    """For each line, the text of its paragraph: lines between blank lines and headings, each
    list item and table row on its own."""
    out, block = [], []

    def flush():
        out.extend(["\n".join(block)] * len(block))
        block.clear()

    for line in lines:
        if not line.strip() or line.startswith("#") or re.match(r"\s*([-*|]|\d+\.)\s", line):
            flush()
        block.append(line)
    flush()
    return out


def main():
    source, bin_dir = sys.argv[1], sys.argv[2]
    options = tool_options(bin_dir)
    union = set().union(*options.values())
    files = [os.path.join(source, "README.md")]
    files += sorted(glob.glob(os.path.join(source, "docs", "**", "*.md"), recursive=True))
    errors = []
    for path in files:
        errors += check_file(path, os.path.relpath(path, source), options, union)
    for error in errors:
        print(error)
    if errors:
        print(f"FAIL: {len(errors)} option(s) named in the docs are not in the tools' --help: "
              "fix the doc, or the option's declaration (then tools/gen-options-doc.sh)")
        return 1
    print(f"ok: {len(files)} files, options of {', '.join(TOOLS)} all in their --help")
    return 0


if __name__ == "__main__":
    sys.exit(main())
