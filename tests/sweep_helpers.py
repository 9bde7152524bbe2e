"""Evaluators for tests/test_sweep.py, imported by name on the Dask workers ('sweep_helpers:...').

They wrap the real quasi-static and dynamic models; RaisingQuasiStatic raises at one chosen load so that a
failing point can be checked, SlowQuasiStatic takes a fixed extra time per point so that a worker can be killed
while the sweep runs, FailingDynamic fails at its start or inside the integration of a batch."""
import time

from bearing_core.maps.sweep import DynamicWindow, QuasiStaticEvaluator

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


FAIL_ADVANCE_FZ_N = 777.0


class FailingDynamic(DynamicWindow):
    """The dynamic window model, failing at its start for fz_N = FAIL_FZ_N and inside the integration (the
    model's second advance raises) for fz_N = FAIL_ADVANCE_FZ_N."""
    name = "failing-dynamic"

    def _start(self, point, options, models=None):
        if point["fz_N"] == FAIL_FZ_N:
            raise RuntimeError(f"deliberate failure at fz_N = {FAIL_FZ_N}")
        run = super()._start(point, options, models)
        if point["fz_N"] == FAIL_ADVANCE_FZ_N:
            m, advance = run.m, run.m.advance

            def failing(t_end, omega_end=None, record_dt=None):
                if m.t > 0.0:
                    raise FloatingPointError("deliberate failure in the integration")
                return advance(t_end, omega_end, record_dt)
            m.advance = failing
        return run
