"""Rigid shaft (FMI 2.0 co-simulation slave, pythonfmu): J dw/dt = motor_torque - load_torque - friction_torque_A
- friction_torque_B, the torques held over the step (so the speed is linear in time within a step and integrated
exactly). Besides speed and acceleration it reports its kinetic energy and, for the energy balance, the work of
each torque on the shaft integrated exactly over the step (shaft side)."""
from pythonfmu import Fmi2Causality, Fmi2Slave, Fmi2Variability, Real
from pythonfmu.enums import Fmi2Initial

IN = ("motor_torque", "load_torque", "friction_torque_A", "friction_torque_B")
OUT = (("shaft_speed", "rad/s"), ("shaft_accel", "rad/s2"), ("kinetic_energy", "J"), ("work_motor", "J"),
       ("work_load", "J"), ("work_friction", "J"))


class ShaftInertia(Fmi2Slave):
    author = "bearing-tribodynamics ssp_examples"
    description = "Rigid shaft inertia driven by motor, load and bearing friction torques"

    def __init__(self, **kwargs):
        super().__init__(**kwargs)
        for name, start, unit in (("inertia", 0.5, "kg.m2"), ("speed0", 0.0, "rad/s")):
            setattr(self, name, start)
            self.register_variable(Real(name, causality=Fmi2Causality.parameter, variability=Fmi2Variability.fixed,
                                        initial=Fmi2Initial.exact, description=f"[{unit}]"))
        for name in IN:
            setattr(self, name, 0.0)
            self.register_variable(Real(name, causality=Fmi2Causality.input, variability=Fmi2Variability.continuous,
                                        description="[N.m]"))
        for name, unit in OUT:
            setattr(self, name, 0.0)
            self.register_variable(Real(name, causality=Fmi2Causality.output, variability=Fmi2Variability.continuous,
                                        initial=Fmi2Initial.calculated, description=f"[{unit}]"))

    def _init(self):
        self.shaft_speed = float(self.speed0)
        self.kinetic_energy = 0.5 * self.inertia * self.shaft_speed ** 2

    def enter_initialization_mode(self):
        self._init()

    def exit_initialization_mode(self):
        self._init()

    def do_step(self, current_time, step_size):
        tf = self.friction_torque_A + self.friction_torque_B
        a = (self.motor_torque - self.load_torque - tf) / self.inertia
        w0 = self.shaft_speed
        w1 = w0 + a * step_size
        if w1 < 0.0 and w0 >= 0.0 and self.motor_torque <= self.load_torque + tf:
            w1 = 0.0                  # no reversal: friction holds a shaft at rest (not reached in the examples)
        wm = 0.5 * (w0 + w1)          # exact mean speed of the linear ramp over the step
        self.work_motor += self.motor_torque * wm * step_size
        self.work_load += self.load_torque * wm * step_size
        self.work_friction += tf * wm * step_size
        self.shaft_speed = w1
        self.shaft_accel = (w1 - w0) / step_size
        self.kinetic_energy = 0.5 * self.inertia * w1 * w1
        return True
