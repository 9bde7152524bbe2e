"""Fan/pump load (FMI 2.0 co-simulation slave, pythonfmu): torque = breakaway_torque + rated_torque (w / rated_speed)^2
against the rotation; work integrates torque x speed with the speed input held over the step."""
from pythonfmu import Fmi2Causality, Fmi2Slave, Fmi2Variability, Real
from pythonfmu.enums import Fmi2Initial

PARAMS = (("rated_torque", 40.0, "N.m"), ("rated_speed", 300.0, "rad/s"), ("breakaway_torque", 2.0, "N.m"))


class FanLoad(Fmi2Slave):
    author = "bearing-tribodynamics ssp_examples"
    description = "Quadratic (fan) load torque"

    def __init__(self, **kwargs):
        super().__init__(**kwargs)
        for name, start, unit in PARAMS:
            setattr(self, name, start)
            self.register_variable(Real(name, causality=Fmi2Causality.parameter, variability=Fmi2Variability.fixed,
                                        initial=Fmi2Initial.exact, description=f"[{unit}]"))
        self.shaft_speed = 0.0
        self.register_variable(Real("shaft_speed", causality=Fmi2Causality.input,
                                    variability=Fmi2Variability.continuous, description="[rad/s]"))
        for name, unit in (("torque", "N.m"), ("power", "W"), ("work", "J")):
            setattr(self, name, 0.0)
            self.register_variable(Real(name, causality=Fmi2Causality.output, variability=Fmi2Variability.continuous,
                                        initial=Fmi2Initial.calculated, description=f"[{unit}]"))

    def _publish(self):
        w = max(self.shaft_speed, 0.0)
        self.torque = float((self.breakaway_torque if w > 0.0 else 0.0) + self.rated_torque * (w / self.rated_speed) ** 2)
        self.power = float(self.torque * w)

    def enter_initialization_mode(self):
        self._publish()

    def exit_initialization_mode(self):
        self._publish()

    def do_step(self, current_time, step_size):
        self._publish()
        self.work += self.power * step_size
        return True
