# Paths for the Python tests: the source tree and the asperity binary of the same build
# (ctest sets ASPERITY and ASPERITY_SOURCE_DIR, and PYTHONPATH to build/python).
import os
import pathlib

import pytest

SOURCE = pathlib.Path(os.environ.get("ASPERITY_SOURCE_DIR", pathlib.Path(__file__).resolve().parents[2]))
BINARY = os.environ.get("ASPERITY", str(SOURCE / "build" / "asperity"))


@pytest.fixture
def source():
    return SOURCE


@pytest.fixture
def binary():
    return BINARY
