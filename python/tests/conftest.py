"""Fixtures of the tray module's tests: the module (skipped when it was not built), the
tray-render it is compared with, and the repository's scenes. ctest sets TRAY_PYTHON_DIR (the
build's python/ folder), TRAY_RENDER and TRAY_SOURCE_DIR (tests/CMakeLists.txt)."""
import os
import pathlib
import sys

import pytest

SOURCE = pathlib.Path(os.environ.get("TRAY_SOURCE_DIR", pathlib.Path(__file__).parents[2]))
if "TRAY_PYTHON_DIR" in os.environ:
    sys.path.insert(0, os.environ["TRAY_PYTHON_DIR"])


@pytest.fixture(scope="session")
def tray():
    return pytest.importorskip("tray", reason="the tray module was not built (no pybind11)")


@pytest.fixture(scope="session")
def tray_render():
    path = os.environ.get("TRAY_RENDER", str(SOURCE / "build" / "tray-render"))
    if not os.access(path, os.X_OK):
        pytest.skip(f"{path}: no tray-render to compare with")
    return path


@pytest.fixture(scope="session")
def scenes():
    return SOURCE / "scenes"


@pytest.fixture(scope="session")
def shared():
    return SOURCE.parent / "shared"
