#!/bin/sh
# Sets up Mitsuba 3 for bench/mitsuba_compare.py: libLLVM 19 (for the llvm_ad_rgb variant) and a
# venv at build/mitsuba-venv with mitsuba==3.9.1 from PyPI. Idempotent; run as root on Debian.
# OPTIONAL: only the Mitsuba comparison benchmark needs this. The renderer itself uses Debian
# packages only (tools/setup.sh) and never depends on pip or Mitsuba.
set -eu
cd "$(dirname "$0")/.."
VENV=build/mitsuba-venv
MITSUBA_VERSION=3.9.1

# libLLVM 15 crashes Dr.Jit ("Cannot select fminimum"); Debian's libllvm19 works.
if [ ! -e /usr/lib/x86_64-linux-gnu/libLLVM.so.19.1 ]; then
  apt-get update && apt-get install -y libllvm19
fi
if ! python3 -c 'import ensurepip, venv' 2>/dev/null; then
  apt-get update && apt-get install -y python3-venv
fi
if [ ! -x "$VENV/bin/python" ]; then
  mkdir -p build
  python3 -m venv "$VENV"
fi
# numpy: the comparison computes its RMSE on the images as arrays.
if ! "$VENV/bin/python" -c "import numpy, mitsuba, sys; sys.exit(mitsuba.__version__ != '$MITSUBA_VERSION')" \
  2>/dev/null; then
  "$VENV/bin/pip" install --quiet "mitsuba==$MITSUBA_VERSION" numpy
fi
echo "Mitsuba $MITSUBA_VERSION ready: $VENV/bin/python" \
  "(export DRJIT_LIBLLVM_PATH=/usr/lib/x86_64-linux-gnu/libLLVM.so.19.1)"
