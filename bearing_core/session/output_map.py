"""The session's output layout: which dynamics channels make each output of a communication point
(bearing_core.session.cosim, and the steady levels of bearing_core.session.fidelity that evaluate a steady state
through the same path), and that evaluation in one call (session_kernels.films_and_outputs)."""
from __future__ import annotations

import numpy as np

from ..models import dynamics_kernels as K
from ..models.skid import SKID_MIN_SPEED, SKID_TOL
from .cosim_spec import INT_OUTPUT_NAMES, LIFE_NAMES, OUTPUT_NAMES, STEP_AVERAGED_NAMES
from . import session_kernels as SK

HEAT_CHANNELS = {"race_inner": "P_race_inner", "race_outer": "P_race_outer", "pocket": "P_pocket",
                 "land": "P_land", "drag": "P_drag", "damping": "P_damping", "churn_cage": "P_churn_cage",
                 "churn_ring": "P_churn_ring"}
STEP_AVERAGED = (
    ("friction_torque", "friction_torque"), ("friction_torque_outer", "friction_torque_outer"),
    ("drive_power", "P_drive"), ("heat_flux_total", tuple(HEAT_CHANNELS.values())),
    *((f"heat_flux_{k}", v) for k, v in HEAT_CHANNELS.items()),
    ("heat_flux_race_slide", "P_race_slide"), ("heat_flux_race_spin", "P_race_spin"),
    ("heat_flux_race_diffslip", "P_race_diffslip"),
)
"""(output name, dynamics channel or channels summed): outputs averaged over each communication step."""
assert tuple(n for n, _ in STEP_AVERAGED) == STEP_AVERAGED_NAMES
CSR_MIN_SPEED = 1.0   # rad/s (9.5 rpm): below it |shaft speed| the cage/shaft ratios are reported as 0
ALL_OUTPUT_NAMES = OUTPUT_NAMES + INT_OUTPUT_NAMES
"""The session's output array (CoSimSession.values): the Real outputs, then the Integer ones."""
OUTPUT_INDEX = {n: i for i, n in enumerate(ALL_OUTPUT_NAMES)}


def _output_map():
    """(ptr, idx) of session_kernels.assemble_outputs: each output as the sum of entries of [instantaneous
    channels | step-averaged channels | session_kernels.EXTRA_NAMES]."""
    n = K.NOUT
    inst = {"reaction_Fx": "Fx", "reaction_Fy": "Fy", "reaction_Fz": "Fz", "reaction_Mx": "Mx", "reaction_My": "My",
            "cage_speed": "cage_speed", "heat_flux_race_slide": "P_race_slide", "heat_flux_race_spin": "P_race_spin",
            "heat_flux_race_diffslip": "P_race_diffslip", "ir_x": "ir_x", "ir_y": "ir_y", "ir_z": "ir_z",
            "ir_tx": "ir_tx", "ir_ty": "ir_ty", "ir_ax": "ir_ax", "max_contact_pressure": "p_max",
            "alpha_i_mean": "alpha_i_mean", "alpha_o_mean": "alpha_o_mean", "Q_i_max": "Q_i_max",
            "Q_o_max": "Q_o_max", "ball0_omega_r": "ball0_wr", "ball0_omega_t": "ball0_wt",
            "ball0_omega_z": "ball0_wz", "ball0_slide_roll_i": "ball0_slide_roll_i",
            "ball0_slide_roll_o": "ball0_slide_roll_o", "ball0_spin_roll_i": "ball0_spin_roll_i",
            "ball0_spin_roll_o": "ball0_spin_roll_o", "ball0_traction_i": "ball0_Ft_i",
            "ball0_traction_o": "ball0_Ft_o", "cage_speed_pure_rolling_outer": "cage_speed_pure_rolling_outer",
            "cage_speed_pure_rolling_inner": "cage_speed_pure_rolling_inner"}
    src = {name: [K.OUT_INDEX[c]] for name, c in inst.items()}
    for name, chans in STEP_AVERAGED:
        chans = chans if isinstance(chans, tuple) else (chans,)
        src["instantaneous_" + name] = [K.OUT_INDEX[c] for c in chans]
        src[name] = [n + K.OUT_INDEX[c] for c in chans]
    for k, name in enumerate(SK.EXTRA_NAMES):
        src[name] = [2 * n + k]
    for name in LIFE_NAMES:       # no source here (0): the session writes them after this kernel (CoSimSession)
        src[name] = []
    missing = set(ALL_OUTPUT_NAMES) - set(src)
    assert not missing, f"outputs without a source: {sorted(missing)}"
    ptr = np.zeros(len(ALL_OUTPUT_NAMES) + 1, dtype=np.int64)
    idx = []
    for i, name in enumerate(ALL_OUTPUT_NAMES):
        idx += src[name]
        ptr[i + 1] = len(idx)
    ch = np.array([K.OUT_INDEX[c] for c in ("shaft_speed", "cage_speed", "pure_rolling_cage_speed",
                                            "cage_speed_pure_rolling_outer", "outer_ring_speed")], dtype=np.int64)
    return ptr, np.array(idx, dtype=np.int64), ch

OUT_PTR, OUT_IDX, OUT_CH = _output_map()


def point_outputs(bd, geometry, film_parameters, diag, ext, films, x, out, q1=None, q0=None, h: float = 0.0) -> bool:
    """The outputs of a communication point into out (ALL_OUTPUT_NAMES order) in one kernel call
    (session_kernels.films_and_outputs): per-ball details bd and output channels diag at the instant, the film
    parameters (DynamicSetup.film_parameters), ext (session_kernels.N_EXT entries); step averages from the
    time integrals q1 at the end of a step of h [s] and q0 at its start (None: the instant stands for them).
    films, x: work arrays. Returns True if every output is finite."""
    if q0 is None:
        q1 = q0 = diag
        h = 0.0
    g = geometry
    return SK.films_and_outputs(bd, g.D, g.dm, g.fi, g.fo, *film_parameters, films, diag, q1, q0, h, ext, OUT_CH,
                                CSR_MIN_SPEED, SKID_TOL, SKID_MIN_SPEED, OUT_PTR, OUT_IDX, x, out)
