"""Functions with parameters and results, called from Python."""

import numpy as np

import simit

PARAMETERS = """
export func scale(a : float, v : tensor[3](float)) -> (r : tensor[3](float))
  r = a * v;
end

export func both(n : int, v : tensor[2](float)) -> (twice : int, s : float)
  twice = 2 * n;
  s = v(0) + v(1);
end
"""


def test_parameters_in_and_results_out():
    program = simit.compile(PARAMETERS)
    v = np.array([1.0, -2.0, 0.5])
    np.testing.assert_array_equal(program.scale(3.0, v), 3.0 * v)
    assert program.scale.num_parameters == 2
    assert program.both(21, [0.25, 0.5]) == (42, 0.75)
