"""Paths for the simit package's tests. Run them with the built package on
PYTHONPATH (scripts/test does):

    PYTHONPATH=build/python /usr/bin/python3 -m pytest python/test
"""

import os
import pathlib

import pytest

ROOT = pathlib.Path(__file__).resolve().parents[2]
SHARED = pathlib.Path(os.environ.get("SIMIT_SHARED_DIR", ROOT.parent / "shared"))
RUN_INPUTS = ROOT / "test" / "Run" / "Inputs"
SPRINGS_SIM = ROOT / "examples" / "springs" / "springs.sim"


@pytest.fixture
def springs_program():
    import simit
    return simit.compile(SPRINGS_SIM)
