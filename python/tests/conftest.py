"""Shared fixtures: where the shipped scenes are (the source tree's, or an installed prefix's
share/dampbound/scenes, given by DAMPBOUND_SCENES_DIR)."""
import os
import pathlib

import pytest


@pytest.fixture
def scenes_dir():
    d = os.environ.get("DAMPBOUND_SCENES_DIR")
    if not d:
        d = str(pathlib.Path(__file__).resolve().parents[2] / "scenes")
    assert os.path.isdir(d), f"no scenes folder at {d} (set DAMPBOUND_SCENES_DIR)"
    return pathlib.Path(d)
