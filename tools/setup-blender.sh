#!/usr/bin/env bash
# Installs Debian's Blender (3.4, for Cycles) when missing: the second peer renderer of
# bench/cycles_compare.py (docs/bench/cycles.md). Neither the build nor the tests need it.
#   tools/setup-blender.sh && blender -b --factory-startup --python bench/cycles_compare.py -- --help
set -euo pipefail
if ! command -v blender >/dev/null; then
  SUDO=""; [ "$(id -u)" -eq 0 ] || SUDO="sudo"
  $SUDO apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq --no-install-recommends blender >/dev/null
fi
blender --version | head -1
