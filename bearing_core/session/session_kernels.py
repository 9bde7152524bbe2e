"""Numba kernels of the co-simulation session (bearing_core.session.cosim): the outputs at a communication point
assembled into one float64 array in one call, and the cheap test whether a model point is unchanged.

The kernels take every index as an argument (maps built in Python from the channel and output names), so
their compiled, cached code does not depend on the order of dynamics_kernels.OUT_NAMES or of the FMU's
outputs.
"""
from __future__ import annotations

import math

from numba import njit

from ..numerics.compare import same_point  # noqa: F401  (the session's cheap unchanged-point test)
from ..models.dynamics_kernels import contact_films
from .cosim_spec import STIFFNESS_NAMES

# Strict IEEE arithmetic here (no fastmath): with the reciprocal flag LLVM computes a division as a
# multiplication by the reciprocal in a vectorised loop body but divides in its scalar remainder, so which
# elements round which way would depend on the arrays' alignment in memory, and two identical runs could
# give step averages differing in the last bit. These kernels are not on the integration's hot path.
_exact = njit(cache=True, error_model="numpy")

# derived quantities the output kernel computes, after the 2 x NOUT channels (instantaneous, step-averaged)
EXTRA_NAMES = ("cage_shaft_ratio", "cage_shaft_ratio_theory", "skid_ratio", "film_min_inner", "film_min_outer",
               "film_parameter_min", "cage_slip_ratio", "skid_state",
               # copied from the ext argument (thermal network or isothermal oil, runaway flag)
               "temperature_ball", "temperature_outer_ring", "temperature_inner_ring", "temperature_oil",
               "heat_to_ambient", "heat_to_oil_flow", "thermal_runaway", "oil_fraction_used") + STIFFNESS_NAMES
N_EXT = 8 + len(STIFFNESS_NAMES)
"""Entries of the ext argument: T ball, outer ring, inner ring, oil [K], heat to ambient, to the oil flow [W],
thermal runaway flag (0 / 1), cavity oil fraction used [-], then the 5 x 5 stiffness row-major (ext[EXT_STIFFNESS:],
cosim_spec.STIFFNESS_NAMES: N/m, N/rad, N m/m, N m/rad)."""
EXT_STIFFNESS = 8
# positions in the ch argument of the channels the derived quantities need
CH_SHAFT, CH_CAGE, CH_CAGE_EQ26, CH_CAGE_PR_OUTER, CH_OUTER = range(5)


@_exact
def assemble_outputs(diag, q1, q0, dt, films, lam, ext, ch, csr_min, skid_tol, skid_min, ptr, idx, x, out):
    """Outputs of a communication point into out (float64, one entry per output):
    out[i] = sum of x[idx[ptr[i]:ptr[i + 1]]] over the source vector x = [diag (NOUT channels at the
    instant) | the channels averaged over the step, (q1 - q0) / dt from their time integrals at its end and
    start (dt <= 0: diag stands for them) | derived quantities (EXTRA_NAMES)].

    Derived: cage / shaft speed ratios (0 below csr_min [rad/s] of |shaft speed|, where they are 0/0),
    skid ratio 1 - CSR / CSR_theory, smallest minimum film of the loaded inner and outer contacts (films:
    4 x nb from dynamics_kernels.contact_films, 0 if none is loaded), smallest film parameter lam (0 if not
    finite), and the cage slip ratio and skid state of bearing_core.models.skid.classify_skid (outer-raceway
    control, in the outer ring's frame; tolerance skid_tol, 0/0 below skid_min [rad/s]): +1 skidding,
    0 pure rolling, -1 over-skidding. ch: indices in diag of shaft speed, cage speed, seed 000 Eq. 26 cage
    speed, pure-rolling cage speed (outer control), outer-ring speed. Returns True if every output is finite."""
    n = diag.shape[0]
    for i in range(n):
        x[i] = diag[i]
        x[n + i] = (q1[i] - q0[i]) / dt if dt > 0.0 else diag[i]
    e = 2 * n
    w = diag[ch[CH_SHAFT]]
    wc = diag[ch[CH_CAGE]]
    csr = 0.0
    csr_t = 0.0
    if abs(w) >= csr_min:
        csr = wc / w
        csr_t = diag[ch[CH_CAGE_EQ26]] / w
    x[e] = csr
    x[e + 1] = csr_t
    x[e + 2] = 1.0 - csr / csr_t if csr_t > 0.0 else 0.0
    for r in range(2):
        hm = math.inf
        for j in range(films.shape[1]):
            v = films[2 * r + 1, j]
            if v > 0.0 and v < hm:
                hm = v
        x[e + 3 + r] = hm if hm < math.inf else 0.0
    x[e + 5] = lam if math.isfinite(lam) else 0.0
    # bearing_core.models.skid.classify_skid
    w_outer = diag[ch[CH_CAGE_PR_OUTER]]
    d = w_outer - diag[ch[CH_OUTER]]
    state = 0.0
    s = 0.0
    if abs(d) >= skid_min and math.isfinite(wc):
        s = (w_outer - wc) / d
        if s > skid_tol:
            state = 1.0
        elif s < -skid_tol:
            state = -1.0
    x[e + 6] = s
    x[e + 7] = state
    for k in range(ext.shape[0]):
        x[e + 8 + k] = ext[k]
    ok = True
    for i in range(out.shape[0]):
        acc = 0.0
        for k in range(ptr[i], ptr[i + 1]):
            acc += x[idx[k]]
        out[i] = acc
        if not math.isfinite(acc):
            ok = False
    return ok


@_exact
def films_and_outputs(bd, D, dm, fi, fo, eta0, alpha, Ep, s_ball, s_race, films, diag, q1, q0, dt, ext, ch, csr_min,
                      skid_tol, skid_min, ptr, idx, x, out):
    """The films of every ball-race contact into films (dynamics_kernels.contact_films: per-ball details bd,
    geometry D, dm [m], conformities fi, fo, oil eta0 [Pa s], alpha [1/Pa], reduced modulus Ep [Pa], rms
    roughness [m]) and then the outputs of the communication point into out (assemble_outputs), in one call.
    Returns True if every output is finite."""
    lam = contact_films(bd, D, dm, fi, fo, eta0, alpha, Ep, s_ball, s_race, films)
    return assemble_outputs(diag, q1, q0, dt, films, lam, ext, ch, csr_min, skid_tol, skid_min, ptr, idx, x, out)
