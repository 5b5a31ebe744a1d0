"""simit.compile(..., target="gpu"): the choice reaches the engine, and
without a CUDA device the first compile says why in one line. The driver
library is replaced (SIMIT_CUDA_LIBRARY) in a child process, because the
process opens its device once."""

import os
import subprocess
import sys

import pytest

import simit

from conftest import SPRINGS_SIM

CHILD = """
import simit, sys
program = simit.compile(sys.argv[1], target="gpu")
try:
    program.step
except simit.Error as error:
    print(error.message)
"""


def test_an_unknown_target_is_a_value_error():
    with pytest.raises(ValueError, match="target must be 'cpu' or 'gpu'"):
        simit.compile(SPRINGS_SIM, target="tpu")


def test_the_gpu_target_without_a_driver_says_why():
    env = dict(os.environ, SIMIT_CUDA_LIBRARY="libm.so.6")
    child = subprocess.run([sys.executable, "-c", CHILD, str(SPRINGS_SIM)],
                           env=env, capture_output=True, text=True,
                           check=True)
    assert child.stdout.strip() == \
        "no CUDA device: libm.so.6 lacks the driver function cuInit"
