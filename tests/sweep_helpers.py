"""Evaluators for tests/test_sweep.py, imported by name on the Dask workers ('sweep_helpers:...').

They wrap the real quasi-static model; RaisingQuasiStatic raises at one chosen load so that a failing point
can be checked, SlowQuasiStatic takes a fixed extra time per point so that a worker can be killed while the
sweep runs."""
import time

from bearing_core.sweep import QuasiStaticEvaluator

FAIL_FZ_N = 666.0


class RaisingQuasiStatic(QuasiStaticEvaluator):
    name = "raising-quasistatic"

    def __call__(self, point, options):
        if point["fz_N"] == FAIL_FZ_N:
            raise RuntimeError(f"deliberate failure at fz_N = {FAIL_FZ_N}")
        return super().__call__(point, options)


class SlowQuasiStatic(QuasiStaticEvaluator):
    name = "slow-quasistatic"

    def __call__(self, point, options):
        time.sleep(float(options.get("sleep_s", 0.4)))
        return super().__call__(point, options)
