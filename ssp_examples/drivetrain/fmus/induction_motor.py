"""Induction motor torque curve (FMI 2.0 co-simulation slave, pythonfmu): Kloss' formula
T = 2 T_k / (s / s_k + s_k / s), slip s = (sync_speed - shaft_speed) / sync_speed, T_k the breakdown torque at slip
s_k. The torque follows the shaft speed input of the step; work integrates torque x speed with the input held
over the step (the power this motor delivers as the master sees it).

Inverter supply: the input frequency_ratio (supply frequency / rated, start 1: the rated supply) scales the
synchronous speed at constant V/f, so breakdown torque and breakdown slip speed s_k sync_speed stay (stator
resistance and electrical transients neglected); above synchronous speed the torque brakes (generator). A ratio
<= 0 switches the supply off (torque 0)."""
from pythonfmu import Fmi2Causality, Fmi2Slave, Fmi2Variability, Real
from pythonfmu.enums import Fmi2Initial

PARAMS = (("breakdown_torque", 120.0, "N.m"), ("breakdown_slip", 0.15, "1"), ("sync_speed", 314.159265, "rad/s"))


class InductionMotor(Fmi2Slave):
    author = "bearing-tribodynamics ssp_examples"
    description = "Induction motor torque-speed curve (Kloss)"

    def __init__(self, **kwargs):
        super().__init__(**kwargs)
        for name, start, unit in PARAMS:
            setattr(self, name, start)
            self.register_variable(Real(name, causality=Fmi2Causality.parameter, variability=Fmi2Variability.fixed,
                                        initial=Fmi2Initial.exact, description=f"[{unit}]"))
        self.shaft_speed = 0.0
        self.register_variable(Real("shaft_speed", causality=Fmi2Causality.input,
                                    variability=Fmi2Variability.continuous, description="[rad/s]"))
        self.frequency_ratio = 1.0
        self.register_variable(Real("frequency_ratio", causality=Fmi2Causality.input,
                                    variability=Fmi2Variability.continuous,
                                    description="[1] supply frequency / rated frequency; <= 0: supply off"))
        for name, unit in (("torque", "N.m"), ("power", "W"), ("work", "J")):
            setattr(self, name, 0.0)
            self.register_variable(Real(name, causality=Fmi2Causality.output, variability=Fmi2Variability.continuous,
                                        initial=Fmi2Initial.calculated, description=f"[{unit}]"))

    def _torque(self, w):
        r = self.frequency_ratio
        if r <= 0.0:
            return 0.0
        sync = self.sync_speed * r
        s = (sync - w) / sync
        if s == 0.0:
            return 0.0
        sk = self.breakdown_slip / r
        return 2.0 * self.breakdown_torque / (s / sk + sk / s)

    def _publish(self):
        self.torque = float(self._torque(self.shaft_speed))
        self.power = float(self.torque * self.shaft_speed)

    def enter_initialization_mode(self):
        self._publish()

    def exit_initialization_mode(self):
        self._publish()

    def do_step(self, current_time, step_size):
        self._publish()                       # torque for the input held over this step
        self.work += self.power * step_size
        return True
