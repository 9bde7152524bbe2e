"""Run-up speed profile (FMI 2.0 co-simulation slave, pythonfmu): speed_start until ramp_start, a linear ramp to
speed_end at ramp_end, then held. Outputs the speed and its derivative at the end of each step."""
from pythonfmu import Fmi2Causality, Fmi2Slave, Fmi2Variability, Real
from pythonfmu.enums import Fmi2Initial

PARAMS = (("speed_start", 50.0, "rad/s"), ("speed_end", 400.0, "rad/s"), ("ramp_start", 0.0, "s"),
          ("ramp_end", 1.0, "s"))


class SpeedRamp(Fmi2Slave):
    author = "bearing-tribodynamics ssp_examples"
    description = "Piecewise-linear run-up speed profile"

    def __init__(self, **kwargs):
        super().__init__(**kwargs)
        for name, start, unit in PARAMS:
            setattr(self, name, start)
            self.register_variable(Real(name, causality=Fmi2Causality.parameter, variability=Fmi2Variability.fixed,
                                        initial=Fmi2Initial.exact, description=f"[{unit}]"))
        for name, unit in (("shaft_speed", "rad/s"), ("shaft_accel", "rad/s2")):
            setattr(self, name, 0.0)
            self.register_variable(Real(name, causality=Fmi2Causality.output, variability=Fmi2Variability.continuous,
                                        initial=Fmi2Initial.calculated, description=f"[{unit}]"))
        self._t0 = 0.0

    def setup_experiment(self, start_time, stop_time=None, tolerance=None):
        self._t0 = float(start_time)

    def _at(self, t):
        """Speed at t and the slope that holds from t on (the rotor integrates its angle with it)."""
        if t < self.ramp_start or self.ramp_end <= self.ramp_start:
            return float(self.speed_start), 0.0
        if t >= self.ramp_end:
            return float(self.speed_end), 0.0
        r = (self.speed_end - self.speed_start) / (self.ramp_end - self.ramp_start)
        return float(self.speed_start + r * (t - self.ramp_start)), float(r)

    def enter_initialization_mode(self):
        self.shaft_speed, self.shaft_accel = self._at(self._t0)

    def exit_initialization_mode(self):
        self.shaft_speed, self.shaft_accel = self._at(self._t0)

    def do_step(self, current_time, step_size):
        self.shaft_speed, self.shaft_accel = self._at(current_time + step_size)
        return True
