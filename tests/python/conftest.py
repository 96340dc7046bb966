"""Shared set-up of the Python front end's tests: the source tree, the CLI, a small Sod scene."""

import os
import pathlib

import pytest

SOURCE_DIR = pathlib.Path(os.environ.get("STAGGER_SOURCE_DIR", pathlib.Path(__file__).resolve().parents[2]))
SCENES = SOURCE_DIR / "apps" / "scenes"
# Sod, 100 x 5 zones to t = 0.05: a few hundred cycles, well under a second.
SMALL_SOD = {"time.end": 0.05, "output.dump_interval": 0.025}


@pytest.fixture
def cli():
    path = os.environ.get("STAGGER_CLI")
    if not path:
        pytest.skip("STAGGER_CLI (the stagger executable) is not set; ctest sets it")
    return path
