"""Numba kernels of the steady fidelity levels (bearing_core.session.fidelity): multilinear interpolation of an
operating map on its rectilinear grid, and the outputs of one communication point from the steady values with
the first-order lag of the cage speed.

Every index is an argument (maps built in Python from the output names), so the compiled, cached code does not
depend on the order of the outputs or of the map's variables.
"""
from __future__ import annotations

import math

from numba import njit

_exact = njit(cache=True, error_model="numpy")


@_exact
def cell_corner(c, idx, w, strides):
    """Corner c (bit d: the upper node along axis d) of the interpolation cell idx with weights w: its multilinear
    weight (the product over the axes of w[d] or 1 - w[d], 0 as soon as a factor makes it 0) and its flat index."""
    wt = 1.0
    off = 0
    for d in range(idx.shape[0]):
        if (c >> d) & 1:
            wt *= w[d]
            off += (idx[d] + 1) * strides[d]
        else:
            wt *= 1.0 - w[d]
            off += idx[d] * strides[d]
        if wt == 0.0:
            return 0.0, off
    return wt, off


@_exact
def interp_multilinear(axes, ptr, strides, values, speed_scaled, flags, x, idx, w, out):
    """Multilinear interpolation of all outputs of a map at the point x (one coordinate per axis).

    axes: the axes' coordinates concatenated (increasing along each axis), axis d in axes[ptr[d]:ptr[d + 1]];
    strides: flat-index stride of each axis in values (C order); values (n_points x n_out); speed_scaled
    (n_out, 0 / 1): the stored value is the output divided by x[0] (outputs proportional to the speed, which
    interpolate better per unit speed) and is multiplied back; flags (n_points, int): per-point validity bits,
    OR-ed over the corners of the cell that carry weight; idx, w: work arrays (n_axes). An axis with one
    value takes x[d] as given (the caller checks it). Writes out (n_out) and returns (-1, flags) or, if
    x[d] lies outside axis d, (d, 0): never extrapolates."""
    nd = x.shape[0]
    for d in range(nd):
        a0 = ptr[d]
        n = ptr[d + 1] - a0
        xd = x[d]
        if n == 1:
            idx[d] = 0
            w[d] = 0.0
            continue
        if not (xd >= axes[a0] and xd <= axes[a0 + n - 1]):
            return d, 0
        lo = 0
        hi = n - 1
        while hi - lo > 1:
            mid = (lo + hi) // 2
            if axes[a0 + mid] <= xd:
                lo = mid
            else:
                hi = mid
        idx[d] = lo
        w[d] = (xd - axes[a0 + lo]) / (axes[a0 + lo + 1] - axes[a0 + lo])
    nout = out.shape[0]
    for k in range(nout):
        out[k] = 0.0
    fl = 0
    for c in range(1 << nd):
        wt, off = cell_corner(c, idx, w, strides)
        if wt == 0.0:
            continue
        fl |= flags[off]
        for k in range(nout):
            out[k] += wt * values[off, k]
    for k in range(nout):
        if speed_scaled[k] != 0:
            out[k] *= x[0]
    return -1, fl


@_exact
def steady_level_outputs(ss, src, rot, cs, sn, wc0, h, tau, shaft, temps, inertia, shaft0, csr_min, skid_tol,
                         skid_min, ib, out):
    """Outputs of a communication point of a steady level into out (session output layout) from the steady
    values ss (the level's outputs at the held inputs); returns the cage speed at the end of the step.

    src[i] >= 0: output i is ss[src[i]]; -1: it holds 0 (outputs a steady level does not give). rot: pairs
    (i, j) of outputs forming an x-y vector turned by the angle (cs, sn) = (cos, sin) of the radial load
    direction (the map holds the bearing under a radial load along x; the bearing is axisymmetric). Cage
    speed: first-order lag towards its steady value over the step h [s] with time constant tau [s], exact
    for inputs held over the step: wc = wss + (wc0 - wss) exp(-h / tau) (h <= 0: the steady value). The
    quantities derived from the cage speed follow its lagged value as in session_kernels.assemble_outputs:
    cage/shaft ratios (0 below csr_min [rad/s]), skid ratio, cage slip ratio and skid state (tolerance
    skid_tol, 0/0 below skid_min [rad/s]). temps: T ball, outer, inner, oil [K], heat to ambient and to the
    oil flow [W], runaway flag.

    Acceleration of the rotating parts: the steady torque and drive power are those of a bearing at constant
    speed. While the shaft speed changes, the drive also supplies the change of the balls' and cage's kinetic
    energy KE = inertia wc^2 / 2 (inertia [kg m^2] referred to the cage speed, contact.kinematics.
    rotating_inertia; energy balance of the dynamic model: drive power = losses + dKE/dt, the outer ring
    fixed), with the cage at its steady ratio c = wss / shaft to the shaft: over a step from the shaft speed
    shaft0 [rad/s] of the previous step, dKE = inertia c^2 (shaft^2 - shaft0^2) / 2. It follows the inputs,
    not the cage speed's steady values, whose small jumps where a level re-solves would otherwise turn into
    torque spikes; a change of c with the loads is left out. dKE / h is added to drive_power and dKE / (h
    shaft) to friction_torque (0 below csr_min), and to their 'instantaneous_' twins. The heat (the losses) is
    unchanged.

    ib: output indices of cage_speed, cage_shaft_ratio, cage_shaft_ratio_theory, skid_ratio,
    cage_slip_ratio, skid_state, the Eq. 26 cage speed in ss, cage_speed_pure_rolling_outer, then the
    outputs of the 7 entries of temps, then of friction_torque, instantaneous_friction_torque, drive_power,
    instantaneous_drive_power."""
    n = out.shape[0]
    for i in range(n):
        out[i] = ss[src[i]] if src[i] >= 0 else 0.0
    for r in range(rot.shape[0]):
        i = rot[r, 0]
        j = rot[r, 1]
        a = out[i]
        b = out[j]
        out[i] = cs * a - sn * b
        out[j] = sn * a + cs * b
    wss = out[ib[0]]
    wc = wss
    if h > 0.0 and tau > 0.0:
        wc = wss + (wc0 - wss) * math.exp(-h / tau)
    out[ib[0]] = wc
    csr = 0.0
    csr_t = 0.0
    if abs(shaft) >= csr_min:
        csr = wc / shaft
        csr_t = ss[ib[6]] / shaft
    out[ib[1]] = csr
    out[ib[2]] = csr_t
    out[ib[3]] = 1.0 - csr / csr_t if csr_t > 0.0 else 0.0
    w_outer = out[ib[7]]
    s = 0.0
    state = 0.0
    if abs(w_outer) >= skid_min:
        s = (w_outer - wc) / w_outer
        if s > skid_tol:
            state = 1.0
        elif s < -skid_tol:
            state = -1.0
    out[ib[4]] = s
    out[ib[5]] = state
    nt = temps.shape[0]
    for k in range(nt):
        out[ib[8 + k]] = temps[k]
    if inertia > 0.0 and h > 0.0 and abs(shaft) >= csr_min:
        c = wss / shaft
        p_acc = 0.5 * inertia * c * c * (shaft * shaft - shaft0 * shaft0) / h
        for k in range(2):
            out[ib[10 + nt + k]] += p_acc
            out[ib[8 + nt + k]] += p_acc / shaft
    ok = True
    for i in range(n):
        if not math.isfinite(out[i]):
            ok = False
    return wc if ok else math.nan


@_exact
def map_step(u, i_speed, i_fx, i_fy, i_oring, zero_in, rotate, rpm, qkind, qidx, qval, qlo, qhi, qtol,
             axes, ptr, strides, values, speed_scaled, flags, x, idx, w, ss, i_tau,
             src, rot, wc0, h, temps, inertia, shaft0, csr_min, skid_tol, skid_min, ib, out, res):
    """One communication point of the map level in one call: the query of the inputs, the interpolation
    (interp_multilinear) and the outputs with the cage lag and the acceleration of the rotating parts (inertia
    [kg m^2], shaft0 the previous step's shaft speed [rad/s]; steady_level_outputs), the arithmetic of
    fidelity.MapLevel.query and SteadySession._evaluate.

    u: the inputs in cosim_spec.INPUT_NAMES order [SI]; i_speed, i_fx, i_fy, i_oring: their indices of shaft
    speed, Fx, Fy and outer ring speed; zero_in: indices of inputs the map does not vary (must be 0); rotate:
    the map is read at the radial load hypot(Fx, Fy) and its x-y outputs turned; rpm: rad/s per rpm. Per map
    axis d: qkind[d] 0 the fixed value qval[d], 1 the shaft speed in rpm, 2 the radial load (Fx unless
    rotate), 3 the input qidx[d]; range [qlo[d], qhi[d]] with tolerance qtol[d] (values within it are
    clamped). Returns 0 with res = (cage speed at the end of the step [rad/s], validity flags of the cell)
    and the outputs in out; 1 if anything is refused or not finite (an input not finite or not allowed,
    outside the map, a failed grid point): the caller then takes the checked path, which names the
    reason."""
    for i in range(u.shape[0]):
        if not math.isfinite(u[i]):
            return 1
    if u[i_oring] != 0.0:
        return 1
    cs = 1.0
    sn = 0.0
    fx = u[i_fx]
    if rotate:
        fr = math.sqrt(u[i_fx] * u[i_fx] + u[i_fy] * u[i_fy])   # as MapLevel.query (bit for bit)
        if fr > 0.0:
            cs = u[i_fx] / fr
            sn = u[i_fy] / fr
        fx = fr
    for k in range(zero_in.shape[0]):
        if u[zero_in[k]] != 0.0:
            return 1
    for d in range(x.shape[0]):
        kind = qkind[d]
        if kind == 0:
            v = qval[d]
        elif kind == 1:
            v = u[i_speed] / rpm
        elif kind == 2:
            v = fx
        else:
            v = u[qidx[d]]
        lo = qlo[d]
        hi = qhi[d]
        if not (lo - qtol[d] <= v and v <= hi + qtol[d]):
            return 1
        x[d] = lo if v < lo else (hi if v > hi else v)
    d, fl = interp_multilinear(axes, ptr, strides, values, speed_scaled, flags, x, idx, w, ss)
    if d >= 0:
        return 1
    wc = steady_level_outputs(ss, src, rot, cs, sn, wc0, h, ss[i_tau], u[i_speed], temps, inertia, shaft0,
                              csr_min, skid_tol, skid_min, ib, out)
    if not math.isfinite(wc):
        return 1
    res[0] = wc
    res[1] = fl
    return 0


@_exact
def quasistatic_step(u, i_speed, i_oring, ring_idx, ring_ok, check_ring, w_lo, w_hi, t_oil, p0, y0, sens, tol, sc,
                     i_power, i_heat, pred, ss0, speed_scaled, race_split, i_race, i_torque, i_torque_outer, i_pmax,
                     i_cage, i_pure, x, y, ss, i_tau, src, rot, wc0, h, temps, inertia, shaft0, csr_min, skid_tol,
                     skid_min, ib, out, res):
    """One communication point of the quasi-static level in one call where its inputs stay inside the trust
    region of its last solution: the arithmetic of fidelity.QuasiStaticLevel.query and steady_into on the
    tracker's first-order update (models.quasistatic_cage.QuasiStaticTracker.at) and of steady_level_outputs.

    u: the inputs in cosim_spec.INPUT_NAMES order [SI]; i_speed, i_oring: shaft and outer-ring speed; ring_idx:
    the 5 ring inputs (Fx..My, or dx..ty in displacement coupling); check_ring 1: they must equal ring_ok, the
    values the session's load checks last passed (the checks themselves run on the Python path); shaft speed
    within [w_lo, w_hi] [rad/s]; t_oil [K]. The last solution: inputs p0 (7), outputs y0, d outputs / d inputs
    sens, per-input trust scales tol (inf: none), sc = (trust radius, its energy imbalance, the allowed change
    of it, its shaft speed, cage time constant [s], contact pressure limit [Pa], gross-skid slip, 1 if valid, the
    solution's validity flags, the shaft's rate [rad/s^2] at an accelerating solution (0: a steady one),
    and the tracker's accel_min, accel_max [1/s] and accel_rel: an accelerating solution holds while the
    shaft's rate over the step, (shaft - shaft0) / h, continues its ramp (QuasiStaticTracker.in_ramp and
    same_rate));
    i_power, i_heat: drive power and heat in the outputs. The level's steady values at the solution ss0 and
    their update: pred (pairs: index in ss, index in y), speed_scaled (scale with the shaft speed),
    race_split (scale with the race losses i_race), i_torque_outer (scales with i_torque); i_pmax, i_cage,
    i_pure. Writes x (7, the query point) and y (the updated outputs). Returns 0 with res = (cage speed at the
    end of the step [rad/s], validity flags) and the outputs in out; 1 (nothing to use) where anything needs
    the Python path: an input not finite or out of range, ring inputs not yet checked, a point outside the
    trust region or one whose update breaks the energy balance (a re-solve), a ramp that ended or changed its
    rate, a contact pressure above the limit."""
    if sc[7] == 0.0:
        return 1
    for i in range(u.shape[0]):
        if not math.isfinite(u[i]):
            return 1
    if u[i_oring] != 0.0:
        return 1
    w = u[i_speed]
    if not (w_lo <= w and w <= w_hi):
        return 1
    x[0] = w
    for k in range(5):
        v = u[ring_idx[k]]
        if check_ring != 0 and v != ring_ok[k]:
            return 1
        x[1 + k] = v
    x[6] = t_oil
    r0 = sc[9]
    if r0 != 0.0:
        if not h > 0.0:
            return 1
        rate = (w - shaft0) / h
        s = rate / w
        if not (sc[10] <= abs(s) and abs(s) <= sc[11] and s * r0 > 0.0 and abs(rate - r0) <= sc[12] * abs(r0)):
            return 1
    d = 0.0
    for j in range(7):
        if math.isfinite(tol[j]):
            dn = abs(x[j] - p0[j]) / tol[j]
            if dn > d:
                d = dn
    if not d <= sc[0]:
        return 1
    ny = y0.shape[0]
    for i in range(ny):
        acc = y0[i]
        for j in range(7):
            acc += sens[i, j] * (x[j] - p0[j])
        y[i] = acc
    pd = y[i_power]
    hb = y[i_heat]
    m = max(abs(pd), abs(hb), 1e-9)
    if not abs((pd - hb) / m - sc[1]) <= sc[2]:
        return 1
    for i in range(ss0.shape[0]):
        ss[i] = ss0[i]
    for r in range(pred.shape[0]):
        ss[pred[r, 0]] = ss0[pred[r, 0]] + (y[pred[r, 1]] - y0[pred[r, 1]])
    f = x[0] / sc[3]
    for k in range(speed_scaled.shape[0]):
        ss[speed_scaled[k]] = ss0[speed_scaled[k]] * f
    r0 = ss0[i_race[0]] + ss0[i_race[1]]
    if r0 > 0.0:
        fr = (ss[i_race[0]] + ss[i_race[1]]) / r0
        for k in range(race_split.shape[0]):
            ss[race_split[k]] = ss0[race_split[k]] * fr
    if ss0[i_torque] != 0.0:
        ss[i_torque_outer] = ss0[i_torque_outer] * ss[i_torque] / ss0[i_torque]
    if not ss[i_pmax] <= sc[5]:
        return 1
    tau = sc[4]
    ss[i_tau] = tau if math.isfinite(tau) and tau > 0.0 else 0.0
    pure = ss[i_pure]
    fl = int(sc[8])                 # the solution's own flags (cage instability)
    if pure > 0.0 and 1.0 - ss[i_cage] / pure > sc[6]:
        fl |= 1
    wc = steady_level_outputs(ss, src, rot, 1.0, 0.0, wc0, h, ss[i_tau], w, temps, inertia, shaft0, csr_min,
                              skid_tol, skid_min, ib, out)
    if not math.isfinite(wc):
        return 1
    res[0] = wc
    res[1] = fl
    return 0


# ---- the map level's stiffness outputs: an addition of its own (map_step and steady_level_outputs unchanged) ----

@_exact
def map_stiffness(strides, kvals, idx, w, cs, sn, kbuf, i_k, out):
    """The map level's 5 x 5 stiffness into out[i_k:i_k + 25] (row-major; rows Fx, Fy, Fz, Mx, My, columns dx, dy,
    dz, tx, ty; K = d(load)/d(pose) [N/m, N/rad, N m/m, N m/rad]; docs/fidelity.md "Stiffness"), after
    interp_multilinear at the same map coordinates, whose cell idx and weights w it takes:

    1. K0 = the multilinear interpolation of the map's variables stiffness_<row><col> (kvals: n_points x 25,
       row-major; the Jones-Harris stiffness at the grid point's speed and loads, bearing_core.maps.build_map) on
       that cell, corner by corner as interp_multilinear (the same corner order, weights and skip of zero
       weights; no entry is speed-scaled); kbuf (25) a work array;
    2. turned with the radial load's direction (cs, sn) = (cos, sin) (a map without fy_N and my_Nm axes is read
       along x; cs = 1, sn = 0 otherwise): K = R K0 R^T with R = diag(Rz, 1, Rz), Rz = [[cs, -sn], [sn, cs]],
       on the (x, y) and (tx, ty) index pairs: the stiffness of the axisymmetric bearing seen turned by the load
       angle, as steady_level_outputs turns the x-y outputs (out_x = cs a - sn b, out_y = sn a + cs b).
    Returns False (out unchanged) if an entry is not finite."""
    nd = idx.shape[0]
    for k in range(25):
        kbuf[k] = 0.0
    for c in range(1 << nd):
        wt, off = cell_corner(c, idx, w, strides)
        if wt == 0.0:
            continue
        for k in range(25):
            kbuf[k] += wt * kvals[off, k]
    # K R^T (columns), then R (K R^T) (rows): index pairs (0, 1) and (3, 4) turn, index 2 stays
    for i in range(5):
        for p in (0, 3):
            a = kbuf[5 * i + p]
            b = kbuf[5 * i + p + 1]
            kbuf[5 * i + p] = cs * a - sn * b
            kbuf[5 * i + p + 1] = sn * a + cs * b
    for j in range(5):
        for p in (0, 3):
            a = kbuf[5 * p + j]
            b = kbuf[5 * (p + 1) + j]
            kbuf[5 * p + j] = cs * a - sn * b
            kbuf[5 * (p + 1) + j] = sn * a + cs * b
    for k in range(25):
        if not math.isfinite(kbuf[k]):
            return False
    for k in range(25):
        out[i_k + k] = kbuf[k]
    return True


@_exact
def map_step_stiffness(u, i_speed, i_fx, i_fy, i_oring, zero_in, rotate, rpm, qkind, qidx, qval, qlo, qhi, qtol,
                       axes, ptr, strides, values, speed_scaled, flags, x, idx, w, kvals, kbuf, i_k,
                       ss, i_tau, src, rot, wc0, h, temps, inertia, shaft0, csr_min, skid_tol, skid_min, ib, out, res):
    """map_step (unchanged: its arguments, outputs and return value), then the stiffness outputs (map_stiffness on
    the cell idx, w that map_step's interpolation left; kvals, kbuf, i_k its arguments), the radial load's
    direction from the inputs u as map_step computes it (bit for bit). One call per communication point (a second
    kernel call would cost about as much as the map level's whole step). Returns map_step's code, or 1 if the
    stiffness is not finite (the checked path then names the point)."""
    rc = map_step(u, i_speed, i_fx, i_fy, i_oring, zero_in, rotate, rpm, qkind, qidx, qval, qlo, qhi, qtol,
                  axes, ptr, strides, values, speed_scaled, flags, x, idx, w, ss, i_tau,
                  src, rot, wc0, h, temps, inertia, shaft0, csr_min, skid_tol, skid_min, ib, out, res)
    if rc != 0:
        return rc
    cs = 1.0
    sn = 0.0
    if rotate:
        fr = math.sqrt(u[i_fx] * u[i_fx] + u[i_fy] * u[i_fy])
        if fr > 0.0:
            cs = u[i_fx] / fr
            sn = u[i_fy] / fr
    if not map_stiffness(strides, kvals, idx, w, cs, sn, kbuf, i_k, out):
        return 1
    return 0


# ---- the map level's fatigue outputs: an addition of its own (map_step and steady_level_outputs unchanged) ----

@_exact
def map_fatigue(ss, i_rate, damage0, h, life_cap, i_life, i_damage, out):
    """The map level's fatigue outputs into out[i_life] (life_L10r_h [h]) and out[i_damage] (fatigue_damage [-]),
    after the interpolation that left the steady values ss (interp_multilinear, map_step):

    r = ss[i_rate] [1/s], the map's fatigue_damage_rate (fidelity.MAP_FATIGUE_RATE: 1 / (3600 L10r_h) at each grid
    point, the ISO/TS 16281 reference rating life of its steady state; interpolated per unit speed and multiplied
    back by the speed, as the other speed-scaled values), held over the step h [s] like the inputs;
        life_L10r_h    = min(1 / (3600 r), life_cap)   if r > 0, else life_cap (an infinite life)
        fatigue_damage = damage0 + r h                  if r > 0, else damage0
    damage0 [-]: the damage of the run before the step (0 at the start, h = 0). Palmgren-Miner: the step's damage is
    its time over the life in seconds, h / (3600 L10r_h) = r h."""
    r = ss[i_rate]
    d = damage0
    if r > 0.0:
        L = 1.0 / (3600.0 * r)
        out[i_life] = L if L < life_cap else life_cap
        d = d + r * h
    else:
        out[i_life] = life_cap
    out[i_damage] = d
