"""Compiled code runs without the GIL: a Python thread changes a field while
a compiled call waits for that change."""

import threading

import simit

# Marks that it runs, then waits (up to 60 s) until go becomes non-zero.
WAIT = """
element Flag
  started : float;
  go : float;
end
extern flags : set{Flag};

export func waitForGo() -> (seen : float)
  flags.started = flags.started + 1.0;
  t0 = clock();
  var g = dot(flags.go, flags.go);
  while (g == 0.0) and (clock() - t0 < 6.0e7)
    g = dot(flags.go, flags.go);
  end
  seen = g;
end
"""


def test_a_python_thread_runs_while_compiled_code_does():
    program = simit.compile(WAIT)
    flags = simit.Set("flags", size=1)
    started = flags.add_field("started")
    go = flags.add_field("go")
    program.waitForGo.bind(flags=flags)

    def release_the_call():
        # Runs Python (needs the GIL) only while the call is under way.
        while started[0] == 0.0:
            pass
        go[0] = 1.0

    helper = threading.Thread(target=release_the_call)
    helper.start()
    seen = program.waitForGo()
    helper.join()
    # With the GIL held, the helper could not have set go before the call
    # gave up, and it would return 0.
    assert seen == 1.0
