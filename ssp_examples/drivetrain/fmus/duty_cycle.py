"""Drive cycle (FMI 2.0 co-simulation slave, pythonfmu): the loads on the two bearings and the motor's supply
frequency as functions of time, as a table of up to MAX_PHASES phases. Phase 1 is the state at the start; phase k
(k = 2 .. phases) begins at phase{k}_time [s] and moves every output linearly from its value at that time to the
phase's values over phase{k}_ramp [s] (0: a step), then holds them. The phases' times must increase, and a ramp
must end before the next phase begins. Outputs the values at the end of each step: loads Fx_A, Fz_A, Fx_B, Fz_B
[N], the motor's frequency_ratio [1] (supply frequency / rated; 0: supply off) and the index of the current phase.
Default: one phase, the drivetrain's constant loads at the rated supply (make_ssp.py binds the cycles)."""
from pythonfmu import Fmi2Causality, Fmi2Slave, Fmi2Variability, Integer, Real
from pythonfmu.enums import Fmi2Initial

MAX_PHASES = 8
OUTPUTS = (("Fx_A", "N"), ("Fz_A", "N"), ("Fx_B", "N"), ("Fz_B", "N"), ("frequency_ratio", "1"))
DEFAULT = (0.0, 0.0, 1000.0, 3000.0, 500.0, 2000.0, 1.0)   # time, ramp [s], Fx_A, Fz_A, Fx_B, Fz_B [N], ratio
FIELDS = (("time", "s"), ("ramp", "s")) + OUTPUTS


class DutyCycle(Fmi2Slave):
    author = "bearing-tribodynamics ssp_examples"
    description = "Drive cycle: bearing loads and motor supply frequency over time (phase table)"

    def __init__(self, **kwargs):
        super().__init__(**kwargs)
        self.phases = 1
        self.register_variable(Integer("phases", causality=Fmi2Causality.parameter,
                                       variability=Fmi2Variability.fixed, initial=Fmi2Initial.exact,
                                       description=f"number of phases used (1 .. {MAX_PHASES})"))
        for k in range(1, MAX_PHASES + 1):
            for (f, unit), start in zip(FIELDS, DEFAULT):
                name = f"phase{k}_{f}"
                setattr(self, name, start)
                self.register_variable(Real(name, causality=Fmi2Causality.parameter,
                                            variability=Fmi2Variability.fixed, initial=Fmi2Initial.exact,
                                            description=f"[{unit}]"))
        for name, unit in OUTPUTS + (("phase", "1"),):
            setattr(self, name, 0.0)
            self.register_variable(Real(name, causality=Fmi2Causality.output, variability=Fmi2Variability.continuous,
                                        initial=Fmi2Initial.calculated, description=f"[{unit}]"))
        self._t0 = 0.0

    def setup_experiment(self, start_time, stop_time=None, tolerance=None):
        self._t0 = float(start_time)

    def _at(self, t):
        """Outputs at time t [s] and the index of the phase in force."""
        n = max(1, min(int(self.phases), MAX_PHASES))
        v = [getattr(self, f"phase1_{f}") for f, _ in OUTPUTS]
        phase = 1
        for k in range(2, n + 1):
            t_k, ramp = getattr(self, f"phase{k}_time"), getattr(self, f"phase{k}_ramp")
            if t < t_k:
                break
            frac = 1.0 if ramp <= 0.0 or t >= t_k + ramp else (t - t_k) / ramp
            v = [a + frac * (getattr(self, f"phase{k}_{f}") - a) for a, (f, _) in zip(v, OUTPUTS)]
            phase = k
        return v, phase

    def _publish(self, t):
        v, phase = self._at(t)
        for (name, _), x in zip(OUTPUTS, v):
            setattr(self, name, float(x))
        self.phase = float(phase)

    def enter_initialization_mode(self):
        self._publish(self._t0)

    def exit_initialization_mode(self):
        self._publish(self._t0)

    def do_step(self, current_time, step_size):
        self._publish(current_time + step_size)
        return True
