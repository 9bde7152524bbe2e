"""The kernel and numerics tests once more under numba's portable x86-64 target (NUMBA_CPU_NAME=generic: no
FMA, no AVX), in a subprocess with its own kernel cache. That is the code a precompiled, portable kernel cache
runs, and assertions that hold only for the host CPU's instruction set (fused multiply-adds, vector widths)
fail here on any machine."""
from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parent.parent
# the numerics (polynomial elementary functions, inline arctangent and cube root), the per-contact kernels
# (Hertz geometry, dry and EHL traction over the ellipse, pocket contacts) and the Rosenbrock-W linear algebra;
# the strict-against-fast comparison of whole right-hand sides (test_jit_flags.py) stays on the host target,
# where it costs one compilation of the model instead of two more
KERNEL_TESTS = ("test_mathx.py", "test_contact_kernels.py", "test_ehl_traction.py", "test_rosw_linear_algebra.py")
# whole-model runs inside those files (a second compilation of the model for little kernel coverage)
WHOLE_MODEL = "not quasistatic_tribological_model"


@pytest.mark.skipif(os.environ.get("NUMBA_CPU_NAME", "") == "generic", reason="already on the portable target")
def test_kernel_and_numerics_tests_on_the_portable_target():
    base = os.environ.get("NUMBA_CACHE_DIR") or str(ROOT / ".numba_cache")
    env = dict(os.environ, NUMBA_CPU_NAME="generic", NUMBA_CACHE_DIR=os.path.join(base, "generic"))
    env.pop("NUMBA_CPU_FEATURES", None)
    files = [str(ROOT / "tests" / f) for f in KERNEL_TESTS]
    r = subprocess.run([sys.executable, "-m", "pytest", "-q", "-p", "no:cacheprovider", "-k", WHOLE_MODEL, *files],
                       cwd=ROOT, env=env,
                       capture_output=True, text=True, timeout=1800)
    tail = "\n".join(r.stdout.splitlines()[-40:])
    assert r.returncode == 0, f"under NUMBA_CPU_NAME=generic:\n{tail}\n{r.stderr[-2000:]}"
    assert " passed" in tail and "failed" not in tail
