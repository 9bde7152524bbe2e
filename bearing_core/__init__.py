"""bearing_core: angular-contact ball bearing models (Hertz contact, Jones-Harris quasi-statics, pure
rolling lines, Gupta-style tribo-dynamics in numba). SI units inside; see README.md.

The public face (imported on first use, so `import bearing_core` stays light):

    >>> import bearing_core as bc
    >>> m = bc.DynamicModel(bc.load_bearing("7218B"), bc.DynamicsOptions(traction="lubricated"))

Layers, each importing only those below it (pyproject.toml's import-linter contract): cli, postprocess ->
maps (sweeps) -> session (co-simulation) -> models (quasi-static, tribological, dynamics, skid, wear) ->
heat -> lubrication -> contact -> bearing (definition, presets, fits) -> numerics -> errors.
"""
from __future__ import annotations

import importlib

_API = {
    # bearing definition
    "BearingGeometry": "bearing.geometry", "load_bearing": "bearing.geometry", "load_preset": "bearing.geometry",
    "list_presets": "bearing.geometry", "RingFits": "bearing.ring_fits",
    # lubricants
    "get_oil": "lubrication.lubricants", "get_lubricant": "lubrication.lubricants",
    # models
    "QuasiStaticModel": "models.quasistatic", "solve_quasistatic": "models.quasistatic",
    "TriboQuasiStaticModel": "models.quasistatic_tribo", "solve_tribo_quasistatic": "models.quasistatic_tribo",
    "DynamicModel": "models.dynamics", "DynamicsOptions": "models.dynamics_setup",
    "simulate_profile": "models.dynamics", "read_profile": "models.dynamics", "advance_many": "models.dynamics",
    "life_at": "models.life", "rating_life": "models.life", "FatigueDamage": "models.life",
    "ThermalData": "heat.thermal",
    # co-simulation session
    "CoSimSession": "session.cosim", "CoSimParameters": "session.cosim", "StepRejected": "session.cosim",
    # operating maps
    "SweepSpec": "maps.sweep", "run_sweep": "maps.sweep", "write_results": "maps.sweep", "plot_maps": "maps.sweep",
    # errors
    "BearingInputError": "errors", "ConvergenceError": "errors",
}

__all__ = sorted(_API)


def __getattr__(name: str):
    mod = _API.get(name)
    if mod is None:
        raise AttributeError(f"module 'bearing_core' has no attribute {name!r}")
    value = getattr(importlib.import_module(f".{mod}", __name__), name)
    return value


def __dir__():
    return sorted(set(globals()) | set(__all__))
