#!/usr/bin/env bash
# Installs Intel Open Image Denoise for tools/tray-denoise: the PyPI wheel pyoidn (it bundles the
# library; Debian has no OIDN package) in a virtual environment of Debian's python3, which also
# sees Debian's python3-openimageio and python3-numpy (tools/setup.sh installs those). The
# renderer needs none of it. Location: ${XDG_DATA_HOME:-~/.local/share}/tray/oidn-venv, where
# tray-denoise looks (or set TRAY_OIDN_PYTHON). Safe to run again.
set -euo pipefail
venv="${XDG_DATA_HOME:-$HOME/.local/share}/tray/oidn-venv"
if [ -x "$venv/bin/python3" ] && "$venv/bin/python3" -c "import pyoidn" 2>/dev/null; then
  exit 0
fi
/usr/bin/python3 -m venv --system-site-packages "$venv"
"$venv/bin/python3" -m pip install --quiet --disable-pip-version-check --retries 1 --timeout 30 pyoidn
"$venv/bin/python3" -c "import pyoidn, OpenImageIO, numpy"
echo "setup-denoise: pyoidn installed in $venv"
