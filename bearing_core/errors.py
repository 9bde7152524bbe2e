"""Error types of bearing_core.

Every validation error names the parameter, the offending value and the allowed range so that a
user (or the FMU log) can act on it directly.
"""


class BearingInputError(ValueError):
    """Bad input: ``parameter`` had ``value``, allowed is ``allowed`` (a human-readable range)."""

    def __init__(self, parameter: str, value, allowed: str, detail: str = ""):
        if hasattr(value, "item") and getattr(value, "shape", None) == ():
            value = value.item()            # numpy scalar: print 0.5, not np.float64(0.5)
        self.parameter = parameter
        self.value = value
        self.allowed = allowed
        msg = f"{parameter} = {value!r} is invalid; allowed: {allowed}"
        if detail:
            msg += f" ({detail})"
        super().__init__(msg)


class ConvergenceError(RuntimeError):
    """A nonlinear solve did not converge; the message says which solve, the residual and the inputs."""


def check_range(parameter: str, value, lo=None, hi=None, lo_incl=True, hi_incl=True, unit=""):
    """Raise BearingInputError unless ``lo <= value <= hi`` (bounds optional) and value is finite."""
    import math

    try:
        v = float(value)
    except (TypeError, ValueError):
        raise BearingInputError(parameter, value, _rng(lo, hi, lo_incl, hi_incl, unit), "not a number")
    if not math.isfinite(v):
        raise BearingInputError(parameter, value, _rng(lo, hi, lo_incl, hi_incl, unit), "not finite")
    bad = False
    if lo is not None:
        bad |= v < lo if lo_incl else v <= lo
    if hi is not None:
        bad |= v > hi if hi_incl else v >= hi
    if bad:
        raise BearingInputError(parameter, value, _rng(lo, hi, lo_incl, hi_incl, unit))
    return v


def _rng(lo, hi, lo_incl, hi_incl, unit):
    u = f" {unit}" if unit else ""
    if lo is not None and hi is not None:
        return f"{lo}{u} {'<=' if lo_incl else '<'} value {'<=' if hi_incl else '<'} {hi}{u}"
    if lo is not None:
        return f"value {'>=' if lo_incl else '>'} {lo}{u}"
    if hi is not None:
        return f"value {'<=' if hi_incl else '<'} {hi}{u}"
    return "a finite number"
