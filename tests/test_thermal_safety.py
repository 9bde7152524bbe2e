"""Thermal runaway is reported, never passed off as a result: oil temperature limits (thermal.OIL_T_MAX),
the co-simulation step is discarded with the thermal_runaway flag, 'bearing thermal' exits 4."""
import math

import pytest

from bearing_core.session.cosim import CoSimParameters, CoSimSession, StepRejected
from bearing_core.lubrication.lubricants import OILS
from bearing_core.heat.thermal import OIL_T_MAX, ThermalRunaway, oil_temperature_limit


def test_every_oil_has_a_sourced_temperature_limit():
    for name in OILS:
        T, src = OIL_T_MAX.get(name, (None, ""))
        assert T is not None and 350.0 < T <= 473.15 and src, name
    assert oil_temperature_limit("iso-vg32-mineral") == pytest.approx(393.15)


def test_session_discards_a_runaway_step_and_raises_the_flag():
    """Thermal network on, thermal_time_scale 1e6 (1000 thermal seconds per 1 ms step), churning, oil
    fraction 0.05, no oil flow, 7218B at 10,000 rpm, Fx 1 kN, Fz 3 kN: the losses drive the network's ball
    node far past the oil's 120 degC limit (unbounded, the network is linear). The first step past the limit
    is rejected with a 'thermal runaway' message, the Integer output thermal_runaway is 1, and the
    temperatures stay those of the last accepted state (finite, below the limit)."""
    s = CoSimSession(CoSimParameters(thermal=True, thermal_time_scale=1e6, churning=True, oil_fraction=0.05))
    inp = {"shaft_speed": 10000 * math.pi / 30, "Fx": 1000.0, "Fz": 3000.0}
    s.initialize(0.0, inp)
    assert s.outputs["thermal_runaway"] == 0
    t = 0.0
    with pytest.raises(StepRejected, match="thermal runaway"):
        for _ in range(3):
            s.step(t, 1e-3, inp)
            t += 1e-3
    o = s.outputs
    assert o["thermal_runaway"] == 1
    for k in ("temperature_ball", "temperature_inner_ring", "temperature_outer_ring", "temperature_oil"):
        assert math.isfinite(o[k]) and o[k] <= 393.15


def test_thermal_runaway_message_names_node_limit_and_oil():
    e = ThermalRunaway({"ball": 1768.0, "oil": 400.0}, 393.15, "iso-vg32-mineral", "at 10000 rpm")
    msg = str(e)
    assert "thermal runaway at 10000 rpm" in msg and "ball" in msg and "1768 K" in msg and "393 K" in msg
    assert "iso-vg32-mineral" in msg


def test_bearing_thermal_reports_runaway_with_exit_status_4(capsys):
    """'bearing thermal --bearing 7218B --speed-rpm 10000 --fz 3000 --oil-fraction 0.05' (no oil flow): the
    steady state is past the oil's limit -- 'THERMAL RUNAWAY' on stderr and exit status 4, no temperatures
    reported as a result."""
    from bearing_core.cli import EXIT_THERMAL_RUNAWAY, main
    rc = main(["thermal", "--bearing", "7218B", "--speed-rpm", "10000", "--fz", "3000", "--oil-fraction", "0.05"])
    err = capsys.readouterr().err
    assert rc == EXIT_THERMAL_RUNAWAY == 4
    assert "THERMAL RUNAWAY" in err and "exceeds" in err
