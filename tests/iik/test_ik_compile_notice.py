"""iik.ik.compile_notice: said when the kernel compiles, never when it is loaded from the cache."""

import json
import os
import subprocess
import sys
import textwrap

from iik.ik import COMPILE_MESSAGE

_PROGRAM = textwrap.dedent("""
    import json, sys, time, numpy as np, iik
    from iik.ik import compile_notice
    said = []
    with compile_notice(emit=said.append):
        iik.fk(np.zeros((3, 6)), iik.THESIS_ARM)  # the kernel's fk_many: compiled, or loaded from the cache
        time.sleep(float(sys.argv[1]))  # as slow as a loaded machine: the block outlasts any timer
    print(json.dumps(said))
""")


def _said(cache, seconds: float) -> list[str]:
    env = {**os.environ, "NUMBA_CACHE_DIR": str(cache)}
    out = subprocess.run([sys.executable, "-c", _PROGRAM, str(seconds)], env=env, capture_output=True,
                         text=True, timeout=600)
    assert out.returncode == 0, out.stderr
    return json.loads(out.stdout)


def test_said_once_when_compiling_and_not_when_loading_however_slow(tmp_path):
    assert _said(tmp_path, 0.0) == [COMPILE_MESSAGE]  # an empty cache: Numba compiles, once
    assert _said(tmp_path, 1.5) == []  # the next process loads it: nothing to say, even after 1.5 s
