"""Runner kinds: the computation behind each validation case.

A kind is a function ``kind(inputs: dict) -> dict`` that calls the bearing_core library with the case's
inputs and returns "ours": named scalars or lists whose names match the case's ``reference`` keys, plus
any series the case checks for a trend or plots. No published value lives here: references, tolerances
and verdict kinds are in the case files (bearing_validation/cases/*.json). Units: SI unless a key says
otherwise (``_rpm``, ``_deg``, ``_mm``...).
"""
from __future__ import annotations

import math

import numpy as np

RPM = math.pi / 30.0
KINDS = {}


def kind(fn):
    KINDS[fn.__name__] = fn
    return fn


def _steel_reduced_modulus(inputs):
    from bearing_core.contact import hertz as hz
    E, nu = inputs.get("E_Pa", 206e9), inputs.get("nu", 0.3)
    return hz.reduced_modulus(E, nu, E, nu)


# ------------------------------------------------------------------------------------------------
# Hertz contact
@kind
def hertz_table(inputs):
    """Harris's dimensionless a*, b*, delta* at each curvature difference F(rho), from the Hertz constants
    the library uses (hertz.hertz_exact: a = a_coef Q^(1/3), b = b_coef Q^(1/3), Q = K_load delta^1.5),
    by Harris & Kotzalas's definitions (Vol. 1 Ch. 6): a = a* (3Q/(E' sum_rho))^(1/3), same for b, and
    delta = delta* (3Q/(E' sum_rho))^(2/3) sum_rho/2."""
    from bearing_core.contact import hertz as hz
    Ep = _steel_reduced_modulus(inputs)
    s, Q = 150.0, 1000.0           # arbitrary curvature sum [1/m] and load [N]: the stars do not depend on them
    c = 3.0 * Q / (Ep * s)
    out = {"a_star": [], "b_star": [], "delta_star": []}
    for F in inputs["F_rho"]:
        hc = hz.hertz_exact(s, F, Ep)
        out["a_star"].append(hc.a_coef * Q ** (1 / 3) / c ** (1 / 3))
        out["b_star"].append(hc.b_coef * Q ** (1 / 3) / c ** (1 / 3))
        out["delta_star"].append((Q / hc.K_load) ** (2 / 3) / (c ** (2 / 3) * s / 2.0))
    out["F_rho"] = list(inputs["F_rho"])
    return out


@kind
def hertz_curvature(inputs):
    """Curvature sum [1/mm] and difference [-] at the inner and outer contacts (contact_curvature)."""
    from bearing_core.contact import hertz as hz
    D, dm, f = inputs["D_mm"] * 1e-3, inputs["dm_mm"] * 1e-3, inputs["r_groove_mm"] / inputs["D_mm"]
    al = math.radians(inputs.get("alpha_deg", 0.0))
    _, _, si, Fi = hz.contact_curvature(D, dm, f, al, True)
    _, _, so, Fo = hz.contact_curvature(D, dm, f, al, False)
    return {"sum_rho_i_per_mm": si * 1e-3, "F_rho_i": Fi, "sum_rho_o_per_mm": so * 1e-3, "F_rho_o": Fo}


# ------------------------------------------------------------------------------------------------
# quasi-static model
@kind
def quasistatic(inputs):
    """Jones-Harris quasi-static solution of one operating point; ball 0's speeds, angles and loads."""
    from bearing_core.bearing.geometry import load_preset
    from bearing_core.models.quasistatic import solve_quasistatic
    g = load_preset(inputs["bearing"])
    r = solve_quasistatic(g, inputs["speed_rpm"] * RPM, tuple(inputs["loads_N_Nm"]),
                          control=inputs.get("control", "outer"))
    return {"ball_spin_rpm": abs(float(r.omega_R[0])) / RPM, "orbital_rpm": float(r.omega_m[0]) / RPM,
            "alpha_i_deg": math.degrees(r.alpha_i[0]), "alpha_o_deg": math.degrees(r.alpha_o[0]),
            "Q_i_N": float(r.Q_i[0]), "Q_o_N": float(r.Q_o[0]), "spin_roll_i": float(r.spin_roll_i[0]),
            "residual": float(r.residual)}


@kind
def thrust_closed_form(inputs):
    """Zero-speed pure thrust: the 5-DOF model against Harris & Kotzalas's thrust equation
    Fa = Z Kn A^1.5 sin(a) (cos a0 / cos a - 1)^1.5 (Vol. 1 Ch. 7), Kn the series constant of the two
    contacts. Returns the relative differences in loaded contact angle and axial approach per load."""
    from scipy.optimize import brentq
    from bearing_core.bearing.geometry import load_preset
    from bearing_core.models.quasistatic import QuasiStaticModel
    g = load_preset(inputs["bearing"])
    m = QuasiStaticModel(g)
    A, a0 = g.A, g.alpha0
    da, dz_err, alpha = [], [], []
    for Fa in inputs["Fa_N"]:
        def f(a):
            Ki = m.hz.K(np.array([a]), True)[0]
            Ko = m.hz.K(np.array([a]), False)[0]
            Kn = (Ki ** (-2 / 3) + Ko ** (-2 / 3)) ** -1.5
            return g.Z * Kn * A ** 1.5 * math.sin(a) * (math.cos(a0) / math.cos(a) - 1) ** 1.5 - Fa
        a = brentq(f, a0 + 1e-9, math.radians(89))
        dz = A * math.cos(a0) * math.tan(a) - A * math.sin(a0)
        r = m.solve(0.0, (0, 0, Fa, 0, 0))
        da.append(abs(r.alpha_i[0] / a - 1))
        dz_err.append(abs(r.u[2] / dz - 1))
        alpha.append(math.degrees(r.alpha_i[0]))
    return {"alpha_rel_error": max(da), "axial_approach_rel_error": max(dz_err), "alpha_deg": alpha,
            "Fa_N": list(inputs["Fa_N"])}


# ------------------------------------------------------------------------------------------------
# Kalker / FASTSIM
@kind
def kalker_nu_leave_one_out(inputs):
    """Kalker's nu = 0.25 column predicted from the nu = 0 and nu = 0.5 columns by the interpolation rule
    of fastsim (Lagrange in 1/C over nu), at the table rows g (a'/b' <= 1: case A, > 1: case B).
    Also the same prediction linear in C, for comparison."""
    from bearing_core.contact import fastsim as fs
    out = {}
    for k, name in enumerate(("C11", "C22", "C23")):
        pred, lin = [], []
        for r in inputs["a_over_b"]:
            c0 = fs._table_at_nu_node_r(r, 0, k)
            c2 = fs._table_at_nu_node_r(r, 2, k)
            pred.append(float(fs.inverse_lagrange_nu(0.25, np.array([0.0, 0.5]), np.array([c0, c2]))))
            lin.append(0.5 * (c0 + c2))
        out[name] = pred
        out[name + "_linear_in_C"] = lin
    out["a_over_b"] = list(inputs["a_over_b"])
    return out


@kind
def kalker_coefficients(inputs):
    """fastsim.kalker_coefficients at the given a'/b' and nu."""
    from bearing_core.contact import fastsim as fs
    C = [fs.kalker_coefficients(r, inputs["nu"]) for r in inputs["a_over_b"]]
    return {"C11": [c[0] for c in C], "C22": [c[1] for c in C], "C23": [c[2] for c in C],
            "a_over_b": list(inputs["a_over_b"])}


@kind
def kalker_asymptotes(inputs):
    """Relative difference of fastsim.kalker_coefficients from Kalker's slender-ellipse asymptotic
    expressions (Kalker 1967; closed forms as in CONTACT linrol) at very small / large a'/b'."""
    from bearing_core.contact import fastsim as fs
    err = 0.0
    for nu in inputs["nu"]:
        for r in inputs["a_over_b"]:
            got = np.array(fs.kalker_coefficients(r, nu))
            asym = np.array(fs._asymptotes(r, nu))
            err = max(err, float(np.max(np.abs(got / asym - 1))))
    return {"max_rel_difference": err}


@kind
def fastsim_linear_limit(inputs):
    """FASTSIM at a small creepage against Kalker's linear theory with the same coefficients:
    F_t = -G c^2 C11 xi, F_m = -G c^2 C22 eta, F_m = sign(u) G c^3 C23 phi. Returns FASTSIM / linear."""
    from bearing_core.contact import fastsim as fs
    G, nu = fs.combined_elastic(206e9, 0.3, 206e9, 0.3)
    Q, mu, n, u = inputs["Q_N"], inputs["mu"], inputs["grid"], inputs["u_roll_m_s"]
    out = {"Ft_over_linear": [], "Fm_over_linear": [], "spin_over_linear": []}
    for a_mm, b_mm in inputs["ellipses_a_b_mm"]:
        a, b = a_mm * 1e-3, b_mm * 1e-3
        C11, C22, C23 = fs.kalker_coefficients(b / a, nu)
        c = math.sqrt(a * b)
        xi = inputs["creepage"]
        Ft = fs.fastsim_traction(a, b, Q, mu, G, nu, xi * abs(u), 0.0, 0.0, u, n, n, fs.PRESSURE_PARABOLIC)[0]
        Fm = fs.fastsim_traction(a, b, Q, mu, G, nu, 0.0, xi * abs(u), 0.0, u, n, n, fs.PRESSURE_PARABOLIC)[1]
        phi = xi / c
        Fs = fs.fastsim_traction(a, b, Q, mu, G, nu, 0.0, 0.0, phi * abs(u), u, n, n, fs.PRESSURE_PARABOLIC)[1]
        out["Ft_over_linear"].append(Ft / (-G * c * c * C11 * xi))
        out["Fm_over_linear"].append(Fm / (-G * c * c * C22 * xi))
        out["spin_over_linear"].append(Fs / (math.copysign(1.0, u) * G * c ** 3 * C23 * phi))
    return out


@kind
def fastsim_case(inputs):
    """FASTSIM in Kalker's frame (fastsim_kalker): F_y/(mu F_n) and F_x/(mu F_n) for each traction bound."""
    from bearing_core.contact import fastsim as fs
    out = {}
    for name in inputs["pressures"]:
        p = fs.PRESSURE_PARABOLIC if name == "parabolic" else fs.PRESSURE_HERTZ
        Fx, Fy, _ = fs.fastsim_kalker(inputs["a_mm"] * 1e-3, inputs["b_mm"] * 1e-3, inputs["Fn_N"], inputs["mu"],
                                      inputs["G_Pa"], inputs["nu"], inputs["xi"], inputs["eta"],
                                      inputs["phi_rad_per_m"], inputs["grid"], inputs["grid"], p)
        out[f"Fy_over_muFn_{name}"] = Fy / (inputs["mu"] * inputs["Fn_N"])
        out[f"Fx_over_muFn_{name}"] = Fx / (inputs["mu"] * inputs["Fn_N"])
    return out


# ------------------------------------------------------------------------------------------------
# seed 004: pure rolling lines and spin torque
def _qs_rivera(alpha0_deg, rpm, Fz, control="outer"):
    from bearing_core.bearing.geometry import load_preset
    from bearing_core.models.quasistatic import solve_quasistatic
    g = load_preset("7008-rivera2021", alpha0=math.radians(alpha0_deg))
    return solve_quasistatic(g, rpm * RPM, (0, 0, Fz, 0, 0), control=control, stiffness=False)


@kind
def prl_c_values(inputs):
    """Houpert c-values of the pure rolling lines (spin_friction.analyse), in the paper's mirrored
    convention (c_paper = -c_ours, order swapped), every ball, inner then outer race."""
    from bearing_core.contact import spin_friction as sf
    s = sf.analyse(_qs_rivera(inputs["alpha0_deg"], inputs["speed_rpm"], inputs["Fz_N"]))
    c1 = np.concatenate([-s.c2_i, -s.c2_o])
    c2 = np.concatenate([-s.c1_i, -s.c1_o])
    return {"c1": c1.tolist(), "c2": c2.tolist()}


@kind
def prl_counts(inputs):
    """Number of pure rolling lines on the inner and outer race per speed (all balls must agree, else -1).
    E_model 'eq15': seed 004 Eq. 15 and Houpert's c-values; 'kinematic': exact spin-to-roll ratio and the
    zero crossings of the exact slip profile."""
    from bearing_core.contact import spin_friction as sf
    out = {"n_inner": [], "n_outer": [], "speed_rpm": list(inputs["speeds_rpm"])}
    for rpm in inputs["speeds_rpm"]:
        r = _qs_rivera(inputs["alpha0_deg"], rpm, inputs["Fz_N"], control=inputs.get("control", "outer"))
        if inputs["E_model"] == "eq15":
            s = sf.analyse(r, E_model="eq15")
            ni, no = s.nh_i, s.nh_o
        else:
            s = sf.analyse(r)
            ni, no = s.n_i, s.n_o
        out["n_inner"].append(int(ni[0]) if np.all(ni == ni[0]) else -1)
        out["n_outer"].append(int(no[0]) if np.all(no == no[0]) else -1)
    return out


@kind
def spin_torque_strip_vs_full(inputs):
    """Bearing spin torque (seed 004 Eq. 24) from the c-values (Eqs. 22-23) over the full integration
    (Eq. 19), minus 1, per speed; and both torques [N m]."""
    from bearing_core.contact import spin_friction as sf
    out = {"Ms_c_over_full_minus_1": [], "Ms_full_Nm": [], "Ms_c_Nm": [], "speed_rpm": list(inputs["speeds_rpm"])}
    for rpm in inputs["speeds_rpm"]:
        s = sf.analyse(_qs_rivera(inputs["alpha0_deg"], rpm, inputs["Fz_N"]), mu=inputs["mu"])
        out["Ms_c_over_full_minus_1"].append(s.Ms_c / s.Ms_full - 1)
        out["Ms_full_Nm"].append(s.Ms_full)
        out["Ms_c_Nm"].append(s.Ms_c)
    return out


# ------------------------------------------------------------------------------------------------
# seed 001 (churning, oils)
def _seed001_bearing(b):
    from bearing_core.bearing.geometry import from_dict
    return from_dict(dict(
        name="seed001-qj1044-estimate", ball_diameter_mm=b["ball_diameter_mm"], number_of_balls=b["number_of_balls"],
        pitch_diameter_mm=b["pitch_diameter_mm"], free_contact_angle_deg=b["free_contact_angle_deg"], fi=b["fi"],
        fo=b["fo"], width_mm=b["width_mm"], inner_ring_mass_kg=5.0, outer_ring_mass_kg=7.0,
        inner_ring_inertia_kg_mm2=1.5e5, inner_ring_tilt_inertia_kg_mm2=8e4,
        cage=dict(mass_kg=2.0, inertia_kg_mm2=4e4, guidance="outer", land_clearance_mm=1.0, material="brass")))


@kind
def churning_share(inputs):
    """Churning (cage + balls + inner ring, seed 001 Eqs. 12-17) over churning plus race spin loss (Coulomb
    spin moment 3/8 mu Q a E(e), Harris & Kotzalas Vol. 2) from the quasi-static model, per axial load."""
    from scipy.special import ellipe
    from bearing_core.lubrication import churning as ch
    from bearing_core.models.quasistatic import solve_quasistatic
    g = _seed001_bearing(inputs["bearing_estimate"])
    w = inputs["speed_rpm"] * RPM
    shares = []
    for Fa in inputs["Fa_N"]:
        r = solve_quasistatic(g, w, (inputs["Fr_N"], 0.0, Fa, 0.0, 0.0), control="outer", stiffness=False)
        c = ch.churning_losses(g, inputs["oil"], inputs["oil_temperature_C"] + 273.15, w, float(np.mean(r.omega_m)),
                               oil_fraction=inputs.get("oil_fraction", 1.0))
        churn = c["Q_ch_c"] + c["Q_ch_b"] + c["Q_ch_s"]
        spin = 0.0
        for Q, a, b, s in ((r.Q_i, r.a_i, r.b_i, r.spin_i), (r.Q_o, r.a_o, r.b_o, r.spin_o)):
            for q, aa, bb, ss in zip(Q, a, b, s):
                if q > 0:
                    spin += 3 / 8 * inputs["mu_spin"] * q * aa * ellipe(1 - (bb / aa) ** 2) * abs(ss)
        shares.append(churn / (churn + spin))
    return {"churning_share": shares, "min_churning_share": min(shares), "max_churning_share": max(shares),
            "Fa_N": list(inputs["Fa_N"])}


@kind
def oil_viscosity(inputs):
    """Dynamic viscosity [mPa s] of library oils at the given temperature [degC]."""
    from bearing_core.lubrication import lubricants as L
    return {"eta_mPa_s": [float(L.get_oil(n).eta(inputs["temperature_C"] + 273.15) * 1e3) for n in inputs["oils"]]}


@kind
def film_rolling_ball(inputs):
    """Hamrock-Dowson minimum film of a ball rolling down an inclined oiled plate (Stachowiak & Batchelor's
    conventions: R' = d/4 as Rx = Ry, U from v/2, E' = E/(1 - nu^2)); v = sqrt(10/7 g s sin(theta))."""
    from bearing_core.lubrication import film
    d, g = inputs["d_mm"] * 1e-3, 9.81
    th = math.radians(inputs["incline_deg"])
    W = inputs["rho_kg_m3"] * math.pi * d ** 3 / 6.0 * g * math.cos(th)
    Ep = inputs["E_Pa"] / (1.0 - inputs["nu"] ** 2)
    h = []
    for s in inputs["distance_m"]:
        v = math.sqrt(10.0 / 7.0 * g * s * math.sin(th))
        h.append(film.film_thickness(v / 2.0, inputs["eta0_Pa_s"], inputs["alpha_per_Pa"], d / 4.0, d / 4.0, Ep,
                                     W).h_min * 1e6)
    return {"h_min_um": h, "distance_m": list(inputs["distance_m"])}


# ------------------------------------------------------------------------------------------------
# seed 003 wear trends
@kind
def wear_speed_sweep(inputs):
    """Wear coefficient k and h_min per loaded ball against speed (wear.operating_point_wear), and the
    largest contact-centre sliding speed. Monotonicity flags over the balls loaded at every speed."""
    from bearing_core.models import wear
    from bearing_core.bearing.geometry import load_preset
    g = load_preset(inputs["bearing"])
    ks = {"inner": [], "outer": []}
    hs = {"inner": [], "outer": []}
    qs = {"inner": [], "outer": []}
    vmax = {"inner": [], "outer": []}
    for n in inputs["speeds_rpm"]:
        op = wear.operating_point_wear(g, n * RPM, tuple(inputs["loads_N_Nm"]))
        for race in ks:
            ks[race].append(op[race].k)
            hs[race].append(op[race].h_min)
            qs[race].append(op[race].states.Q)
            s = op[race].states
            vmax[race].append(float(np.max(np.hypot(s.vs_t, s.vs_m))))
    out = {"speed_rpm": list(inputs["speeds_rpm"])}
    for race in ks:
        loaded = np.all(np.array(qs[race]) > 0, axis=0)
        dk = np.diff(np.array(ks[race])[:, loaded], axis=0)
        dh = np.diff(np.array(hs[race])[:, loaded], axis=0)
        out[f"k_{race}_falls_with_speed"] = bool(np.all(dk < 0))
        out[f"hmin_{race}_rises_with_speed"] = bool(np.all(dh > 0))
        out[f"k_{race}_mean"] = [float(np.mean(np.array(k)[loaded])) for k in ks[race]]
        out[f"sliding_{race}_max_m_s"] = vmax[race]
        out[f"loaded_balls_{race}"] = int(loaded.sum())
    out["inner_sliding_above_outer"] = bool(all(a > b for a, b in zip(vmax["inner"], vmax["outer"])))
    return out


@kind
def wear_radial_force_sweep(inputs):
    """Seed 003 Fig. 6 quantities: k at the force direction and opposite, per radial force; the number of
    local minima of k_i around the ring; its depth (max - min)."""
    from bearing_core.models import wear
    from bearing_core.bearing.geometry import load_preset
    g = load_preset(inputs["bearing"])
    runs = [wear.operating_point_wear(g, inputs["speed_rpm"] * RPM, (F, 0, inputs["Fz_N"], 0, 0))
            for F in inputs["Fx_N"]]
    psi = np.degrees(runs[0]["qs"].psi)
    j0 = int(np.argmin(np.abs(((psi - 0.0) + 180) % 360 - 180)))
    j180 = int(np.argmin(np.abs(((psi - 180.0) + 180) % 360 - 180)))
    ki = np.array([r["inner"].k for r in runs])
    ko = np.array([r["outer"].k for r in runs])
    minima = [int(np.sum((x < np.roll(x, 1)) & (x < np.roll(x, -1)))) for x in ki]
    return {"Fx_N": list(inputs["Fx_N"]), "k_inner_at_force": ki[:, j0].tolist(),
            "k_outer_at_force": ko[:, j0].tolist(), "k_outer_opposite": ko[:, j180].tolist(),
            "k_inner_local_minima": minima, "k_inner_depth": [float(np.ptp(x)) for x in ki],
            "k_max_at_force_direction": [bool(int(np.argmax(ki[i])) == j0 and int(np.argmax(ko[i])) == j0)
                                         for i in range(len(runs))]}


@kind
def wear_moment_zones(inputs):
    """Seed 003 Fig. 7: local maxima (bearing zones) of k_i around the ring under a moment M_y."""
    from bearing_core.models import wear
    from bearing_core.bearing.geometry import load_preset
    g = load_preset(inputs["bearing"])
    runs = [wear.operating_point_wear(g, inputs["speed_rpm"] * RPM, (0, 0, inputs["Fz_N"], 0, M))
            for M in inputs["My_Nm"]]
    psi = np.degrees(runs[0]["qs"].psi)
    ki = np.array([r["inner"].k for r in runs])
    x = ki[-1]
    peaks = np.where((x >= np.roll(x, 1)) & (x > np.roll(x, -1)))[0]
    dist = np.abs(((psi[peaks][:, None] - np.array([0.0, 180.0])[None, :]) + 180) % 360 - 180)
    jmax = int(np.argmax(x))
    return {"bearing_zones": int(len(peaks)), "zone_azimuths_deg": psi[peaks].tolist(),
            "zones_within_one_pitch_of_0_and_180": bool(np.all(dist.min(axis=1) < 360.0 / g.Z)),
            "k_inner_max": ki[:, jmax].tolist(), "My_Nm": list(inputs["My_Nm"])}


@kind
def wear_ellipse_sliding(inputs):
    """Seed 003 Fig. 12: asymmetry of the strip wear q(x) along the major axis, inner and outer race
    (max |q(x) - q(-x)| / max q over the balls)."""
    from bearing_core.models import wear
    from bearing_core.bearing.geometry import load_preset
    g = load_preset(inputs["bearing"])
    op = wear.operating_point_wear(g, inputs["speed_rpm"] * RPM, tuple(inputs["loads_N_Nm"]))
    asym = {}
    for race in ("inner", "outer"):
        vals = [float(np.max(np.abs(q - q[::-1])) / np.max(q)) for q in op[race].q if np.max(q) > 0]
        asym[race] = vals
    return {"inner_min_asymmetry": min(asym["inner"]), "outer_max_asymmetry": max(asym["outer"])}


# ------------------------------------------------------------------------------------------------
# dynamics (slow: full run only)
def _seed000_profile(t_end):
    from bearing_core.models.dynamics import SEED000_PROFILE
    ts = [p[0] for p in SEED000_PROFILE]
    ns = [p[1] for p in SEED000_PROFILE]
    return [p for p in SEED000_PROFILE if p[0] < t_end] + [(t_end, float(np.interp(t_end, ts, ns)))]


def _settle_time(t, cage, tol=0.01):
    """First time after which the cage speed stays within tol of its mean over the last 0.1 s."""
    final = cage[t > t[-1] - 0.1].mean()
    bad = np.where(np.abs(cage / final - 1) > tol)[0]
    return float(t[bad[-1]]) if len(bad) else float(t[0])


@kind
def seed000_profile(inputs):
    """Seed 000 acceleration profile (1000 rpm to 0.5 s, 10,000 rpm/s to 10,000 rpm at 1.4 s, held), full
    16-ball model, per axial load: cage speed at the end, settle time (1 % band), CSR over the spin-free
    theoretical CSR (Eq. 26) at the end and its minimum after 0.5 s, peak |a_x| of the inner ring in the
    ramp (0.5-1.4 s); plus the cage-speed curves for the plot."""
    from bearing_core.models.dynamics import DynamicModel, DynamicsOptions, records_to_dict, simulate_profile
    from bearing_core.bearing.geometry import load_preset
    mu = inputs["mu"]
    t_end = inputs.get("t_end_s", 2.0)
    out = {"Fz_N": list(inputs["Fz_N"]), "cage_end_rpm": [], "settle_time_s": [], "csr_over_theory_end": [],
           "min_csr_over_theory_after_ramp_start": [], "peak_ir_ax_ramp_m_s2": [], "curves": {}}
    for fz in inputs["Fz_N"]:
        opts = dict(traction=inputs["traction"], mu=mu, mu_pocket=mu, mu_land=mu, reduced="full")
        opts.update(inputs.get("options", {}))
        m = DynamicModel(load_preset(inputs["bearing"]), DynamicsOptions(**opts))
        m.initialize(inputs["start_rpm"] * RPM, (inputs["Fx_N"], 0.0, fz, 0.0, 0.0))
        d = records_to_dict(simulate_profile(m, _seed000_profile(t_end), record_dt=2e-3))
        t = d["t"]
        tail = t > t[-1] - 0.1
        ramp = t > 0.5
        out["cage_end_rpm"].append(float(d["cage_speed"][tail].mean() / RPM))
        out["settle_time_s"].append(_settle_time(t, d["cage_speed"]))
        theo = d["pure_rolling_cage_speed"]
        out["csr_over_theory_end"].append(float((d["cage_speed"][tail] / theo[tail]).mean()))
        out["min_csr_over_theory_after_ramp_start"].append(float(np.min(d["cage_speed"][ramp] / theo[ramp])))
        win = (t > 0.5) & (t < 1.4)
        out["peak_ir_ax_ramp_m_s2"].append(float(np.max(np.abs(d["ir_ax"][win]))))
        out["curves"][f"Fz {fz:g} N"] = {"t_s": t[::5].tolist(), "cage_rpm": (d["cage_speed"][::5] / RPM).tolist()}
    out["cage_end_rpm_first"] = out["cage_end_rpm"][0]
    out["settle_time_s_first"] = out["settle_time_s"][0]
    out["settled_before_end"] = [s < t_end - 0.15 for s in out["settle_time_s"]]
    out["peak_ir_ax_growth_last_over_first"] = out["peak_ir_ax_ramp_m_s2"][-1] / out["peak_ir_ax_ramp_m_s2"][0]
    return out


@kind
def held_speed_vibration(inputs):
    """7218B held at a constant speed (Seed 000 Table 3 analogue): RMS inner-ring x acceleration over the
    second half of the run and the share of time ball 0's inner contact is open, per axial load
    (25 % stepped down from a higher-load equilibrium where given)."""
    from bearing_core.models.dynamics import DynamicModel, DynamicsOptions, records_to_dict
    from bearing_core.bearing.geometry import load_preset
    mu = inputs["mu"]
    out = {"preload_pct": list(inputs["preload_pct"]), "rms_ir_ax_m_s2": [], "ball0_inner_open_share": []}
    for pct, start_pct in zip(inputs["preload_pct"], inputs["start_pct"]):
        fz = inputs["MOL_Fz_N"] * pct / 100.0
        fz0 = inputs["MOL_Fz_N"] * start_pct / 100.0
        m = DynamicModel(load_preset(inputs["bearing"]),
                         DynamicsOptions(traction=inputs["traction"], mu=mu, mu_pocket=mu, mu_land=mu,
                                         reduced="full", integrator="auto"))
        m.initialize(inputs["speed_rpm"] * RPM, (inputs["Fx_N"], 0.0, fz0, 0.0, 0.0), start="jones-harris")
        if fz0 != fz:
            m.set_inputs(loads=(inputs["Fx_N"], 0.0, fz, 0.0, 0.0))
        T = inputs["t_end_s"]
        d = records_to_dict(m.advance(T, record_dt=1e-5))
        w = d["t"] >= T / 2
        out["rms_ir_ax_m_s2"].append(float(d["ir_ax"][w].std()))
        out["ball0_inner_open_share"].append(float(np.mean(d["ball0_Q_i"][w] <= 0.0)))
    r = out["rms_ir_ax_m_s2"]
    out["growth_lowest_over_full_preload"] = r[0] / r[-1]
    out["inner_open_share_lowest"] = out["ball0_inner_open_share"][0]
    out["inner_open_share_full"] = out["ball0_inner_open_share"][-1]
    return out


@kind
def microslip(inputs):
    """Adhesion / slip map of ball 0's contact after a short transient with Kalker traction
    (postprocess.microslip_map): adhesion fraction, and whether the stick zone lies at the leading edge."""
    from bearing_core.models.dynamics import DynamicModel, DynamicsOptions
    from bearing_core.bearing.geometry import load_preset
    from bearing_core.postprocess import microslip_map
    m = DynamicModel(load_preset(inputs["bearing"]), DynamicsOptions(traction="kalker", mu=inputs["mu"], rtol=1e-6))
    m.initialize(inputs["speed_rpm"] * RPM, tuple(inputs["loads_N_Nm"]))
    m.advance(inputs["t_end_s"])
    out = {}
    for race in ("outer", "inner"):
        mp = microslip_map(m, 0, race)
        lead = -np.sign(mp["u_roll"])
        inside = (mp["T"] / mp["b"]) ** 2 + (mp["M"] / mp["a"]) ** 2 < 1
        stick = mp["T"][inside & ~mp["slip"]] * lead
        slip = mp["T"][inside & mp["slip"]] * lead
        out[f"adhesion_fraction_{race}"] = float(mp["adhesion_fraction"])
        out[f"stick_at_leading_edge_{race}"] = bool(len(stick) > 0 and len(slip) > 0 and stick.mean() > slip.mean())
    return out


@kind
def seed002_unloaded_zone(inputs):
    """7008-ma2023 under a radial plus axial load (tilt held): does an unloaded inner-contact zone open
    (minimum inner load exactly 0 over the late half), per radial load; reaction errors."""
    from bearing_core.models.dynamics import DynamicModel, DynamicsOptions, records_to_dict
    from bearing_core.bearing.geometry import load_preset
    out = {"Fr_N": list(inputs["Fr_N"]), "unloaded_zone": [], "reaction_rel_error": []}
    for fr in inputs["Fr_N"]:
        m = DynamicModel(load_preset(inputs["bearing"]), DynamicsOptions(traction="lubricated", fixed_tilt=True))
        m.initialize(inputs["speed_rpm"] * RPM, (fr, 0.0, inputs["Fa_N"], 0.0, 0.0))
        d = records_to_dict(m.advance(inputs["t_end_s"], record_dt=1e-4))
        late = d["t"] > d["t"][-1] / 2
        out["unloaded_zone"].append(bool(np.all(d["Q_i_min"][late] == 0.0)))
        out["reaction_rel_error"].append(float(max(abs(-d["Fx"][late].mean() / fr - 1),
                                                   abs(-d["Fz"][late].mean() / inputs["Fa_N"] - 1))))
    out["max_reaction_rel_error"] = max(out["reaction_rel_error"])
    return out


@kind
def seed002_sliding_in_oil(inputs):
    """7008-ma2023 with ball drag in an oil-air mixture and churning: inner contact-centre slip [mm/s] of
    ball 0 after a fixed time, per axial load."""
    from bearing_core.models.dynamics import DynamicModel, DynamicsOptions
    from bearing_core.bearing.geometry import load_preset
    slip = []
    for fz in inputs["Fa_N"]:
        m = DynamicModel(load_preset(inputs["bearing"]),
                         DynamicsOptions(churning=True, oil_fraction=inputs["oil_fraction"]))
        m.initialize(inputs["speed_rpm"] * RPM, (0.0, 0.0, fz, 0.0, 0.0))
        m.advance(inputs["t_end_s"])
        slip.append(float(abs(m.ball_details()["slip_i"][0]) * 1e3))
    return {"Fa_N": list(inputs["Fa_N"]), "slip_inner_mm_s": slip,
            "slip_ratio_lightest_over_heaviest": slip[0] / slip[-1]}


# ------------------------------------------------------------------------------------------------
# Whole-bearing friction torque of the oil-lubricated dynamics against SKF's and Palmgren's models
@kind
def friction_torque_vs_skf(inputs):
    """Steady friction torque [N m] of the oil-lubricated dynamics (mean of the second half of t_end_s from
    the Jones-Harris start) at every oil x (Fr, Fa) x speed, and its ratio to the SKF (2004) and Palmgren
    models at the same oil viscosity (bearing_core.lubrication.friction_models)."""
    from bearing_core.models.dynamics import DynamicModel, DynamicsOptions, records_to_dict
    from bearing_core.lubrication.friction_models import iso76_static_rating, palmgren_friction, skf_friction
    from bearing_core.bearing.geometry import load_preset
    from bearing_core.lubrication.lubricants import get_oil
    g = load_preset(inputs["bearing"])
    C0 = iso76_static_rating(g)
    T = inputs["oil_temperature_C"] + 273.15
    out = {"M_Nm": [], "M_skf_Nm": [], "M_palmgren_Nm": [], "ratio_skf": [], "ratio_palmgren": [],
           "ratio_skf_above_1000rpm": [], "case": []}
    for oil in inputs["oils"]:
        nu = get_oil(oil).nu(T) * 1e6
        for Fr, Fa in inputs["loads_N"]:
            for rpm in inputs["speeds_rpm"]:
                m = DynamicModel(g, DynamicsOptions(oil=oil, oil_temperature=T, integrator="auto",
                                                    fixed_tilt=bool(inputs.get("fixed_tilt", False))))
                m.initialize(rpm * RPM, (Fr, 0.0, Fa, 0.0, 0.0))
                d = records_to_dict(m.advance(inputs["t_end_s"], record_dt=1e-3))
                M = float(d["friction_torque"][len(d["t"]) // 2:].mean())
                skf = skf_friction(inputs["bore_mm"], inputs["outer_diameter_mm"], rpm, nu, Fr, Fa)["M"]
                pal = palmgren_friction(g.dm * 1e3, rpm, nu, Fr, Fa, C0)["M"]
                out["M_Nm"].append(M)
                out["M_skf_Nm"].append(skf)
                out["M_palmgren_Nm"].append(pal)
                out["ratio_skf"].append(M / skf)
                out["ratio_palmgren"].append(M / pal)
                if rpm > 1000.0:
                    out["ratio_skf_above_1000rpm"].append(M / skf)
                out["case"].append(f"{oil} Fr {Fr:g} N Fa {Fa:g} N {rpm:g} rpm")
    return out


@kind
def power_loss_load_sensitivity(inputs):
    """Steady power loss [W] of the oil-lubricated quasi-static tribological model (solve_tribo_quasistatic,
    traction 'lubricated': EHL traction, mixed lubrication, EHL rolling resistance, ball drag; no cage) at
    each speed under a base axial load Fa, with a radial load Fr added, and with the axial load raised by
    dFa. Returns the power at the base load per speed, the relative effects of Fr and of dFa on it, their
    ratio, and whether the operating points lie inside a stated range: N dm [mm rpm] and the largest load
    over the ISO 76 static rating C0 (friction_models.iso76_static_rating)."""
    from bearing_core.models.dynamics import DynamicsOptions
    from bearing_core.lubrication.friction_models import iso76_static_rating
    from bearing_core.bearing.geometry import load_preset
    from bearing_core.models.quasistatic_tribo import solve_tribo_quasistatic
    g = load_preset(inputs["bearing"])
    kw = {}
    if inputs.get("oil"):
        kw["oil"] = inputs["oil"]
    if inputs.get("oil_temperature_C") is not None:
        kw["oil_temperature"] = inputs["oil_temperature_C"] + 273.15
    opt = DynamicsOptions(traction="lubricated", integrator="auto", **kw)
    Fa, Fr, dFa = inputs["Fa_N"], inputs["Fr_N"], inputs["dFa_N"]
    out = {"speed_rpm": [], "P_base_W": [], "P_radial_W": [], "P_axial_W": [], "radial_effect": [],
           "axial_effect": [], "abs_radial_over_axial": []}
    for rpm in inputs["speeds_rpm"]:
        P = [solve_tribo_quasistatic(g, rpm * RPM, loads, opt).losses["P_drive"]
             for loads in ((0.0, 0.0, Fa, 0.0, 0.0), (Fr, 0.0, Fa, 0.0, 0.0), (0.0, 0.0, Fa + dFa, 0.0, 0.0))]
        out["speed_rpm"].append(rpm)
        out["P_base_W"].append(P[0])
        out["P_radial_W"].append(P[1])
        out["P_axial_W"].append(P[2])
        out["radial_effect"].append(P[1] / P[0] - 1.0)
        out["axial_effect"].append(P[2] / P[0] - 1.0)
        out["abs_radial_over_axial"].append(abs(P[1] - P[0]) / (P[2] - P[0]))
    C0 = iso76_static_rating(g)
    out["C0_N"] = C0
    out["max_load_over_C0"] = max(math.hypot(Fr, Fa), Fa + dFa) / C0
    out["max_ndm_mm_rpm"] = g.dm * 1e3 * max(inputs["speeds_rpm"])
    out["inside_stated_range"] = bool(out["max_load_over_C0"] <= inputs["max_load_over_C0"]
                                      and out["max_ndm_mm_rpm"] <= inputs["max_ndm_mm_rpm"])
    return out


# ------------------------------------------------------------------------------------------------
# thermal network and oil supply
@kind
def thermal_contact_resistance(inputs):
    """Resistance [K/W] from a circular contact of radius a to the bulk of a steel half-space at rest
    (thermal.moving_source_resistance at U = 0), times k a (dimensionless), and the ratio of the resistances
    at two rolling speeds (the moving-source asymptote R ~ U^-1/2 at high Peclet number)."""
    from bearing_core.heat.thermal import moving_source_resistance
    k, kappa, a = inputs["k_W_mK"], inputs["kappa_m2_s"], inputs["a_m"]
    R0 = moving_source_resistance(k, kappa, a, 0.0)
    U1, U2 = inputs["speeds_m_s"]
    return {"R0_k_a": R0 * k * a,
            "R_ratio_speeds": moving_source_resistance(k, kappa, a, U1) / moving_source_resistance(k, kappa, a, U2),
            "Pe_low": U1 * a / (2 * kappa)}


@kind
def jet_bearing_thermal(inputs):
    """Coupled dynamic-thermal steady state (DynamicModel.thermal_equilibrium) of a jet-lubricated bearing
    at each speed: cavity oil content from the supply (oil_supply, Parker), heat generated [W], ring / ball /
    oil temperature rise above the oil inlet [K], runaway flag; speed exponent of the heat between the
    first and last speed."""
    from bearing_core.models.dynamics import DynamicModel, DynamicsOptions
    from bearing_core.bearing.geometry import from_dict
    from bearing_core.lubrication.oil_supply import OilSupply
    from bearing_core.heat.thermal import ThermalData, ThermalRunaway
    g = from_dict(inputs["bearing_definition"])
    T_in = inputs["oil_inlet_K"]
    flow = inputs["oil_flow_lpm"] / 60000.0
    out = {"speed_rpm": [], "heat_W": [], "oil_fraction": [], "outer_rise_K": [], "inner_rise_K": [],
           "ball_rise_K": [], "oil_rise_K": [], "runaway": []}
    for rpm in inputs["speeds_rpm"]:
        opts = DynamicsOptions(oil=inputs["oil"], churning=True, thermal=True, oil_temperature=T_in,
                               thermal_data=ThermalData(T_amb=inputs.get("ambient_K", 308.15), T_in=T_in,
                                                        flow_rate=flow),
                               oil_supply=OilSupply("jet", flow, T_in))
        m = DynamicModel(g, opts)
        m.initialize(rpm * RPM, (inputs.get("Fr_N", 0.0), 0.0, inputs["Fa_N"], 0.0, 0.0))
        out["speed_rpm"].append(rpm)
        out["oil_fraction"].append(m.oil_fraction_used())
        try:
            r = m.thermal_equilibrium()
        except ThermalRunaway:
            out["runaway"].append(True)
            for key in ("heat_W", "outer_rise_K", "inner_rise_K", "ball_rise_K", "oil_rise_K"):
                out[key].append(float("nan"))
            continue
        T = r["temperatures_K"]
        out["runaway"].append(False)
        out["heat_W"].append(float(r["heat_generated_W"]))
        for key, node in (("outer_rise_K", "outer"), ("inner_rise_K", "inner"), ("ball_rise_K", "ball"),
                          ("oil_rise_K", "oil")):
            out[key].append(T[node] - T_in)
    out["no_runaway"] = not any(out["runaway"])
    h, n = out["heat_W"], out["speed_rpm"]
    out["heat_speed_exponent"] = (math.log(h[-1] / h[0]) / math.log(n[-1] / n[0])
                                  if out["no_runaway"] else float("nan"))
    return out


@kind
def skf_bath_drag(inputs):
    """Drag torque [N m] of a ball bearing in an oil bath, ours against SKF's (2004) drag term: our drag is the
    ball drag plus cage and inner-ring churning (churning.churning_losses, cd 0.5, orbit and cage at the
    kinematic speed w (1 - gamma)/2 with the outer ring fixed) in the oil-air mixture of the GEOMETRIC bath
    fraction (oil_supply.bath_fraction: submerged share of the cavity annulus, not the SKF-equivalent one);
    SKF's is friction_models.skf_drag_torque with V_M(H/dm). Returns both torques and their ratio for every
    oil level x speed."""
    from bearing_core.bearing.geometry import load_preset
    from bearing_core.lubrication.churning import churning_losses
    from bearing_core.lubrication.friction_models import bearing_envelope_mm, skf_drag_torque
    from bearing_core.lubrication.oil_supply import bath_fraction
    g = load_preset(inputs["bearing"])
    d_mm, D_mm, how = bearing_envelope_mm(g)
    gam = g.D * math.cos(g.alpha0) / g.dm
    T = inputs["oil_temperature_C"] + 273.15
    out = {"H_over_D_ball": [], "speed_rpm": [], "oil_fraction": [], "M_ours_Nm": [], "M_skf_Nm": [],
           "ratio_to_skf": [], "envelope": how}
    for h in inputs["oil_level_over_ball_diameter"]:
        H = h * g.D
        X = bath_fraction(H, 0.5 * g.inner_raceway_diameter, 0.5 * g.outer_raceway_diameter)
        for rpm in inputs["speeds_rpm"]:
            w = rpm * RPM
            wc = 0.5 * w * (1.0 - gam)
            c = churning_losses(g, inputs["oil"], T, w, wc, wc, cd=0.5, oil_fraction=X)
            M = (c["Q_ch_b"] + c["Q_ch_c"] + c["Q_ch_s"]) / w
            M_skf = skf_drag_torque(d_mm, D_mm, rpm, H * 1e3)
            out["H_over_D_ball"].append(h)
            out["speed_rpm"].append(rpm)
            out["oil_fraction"].append(X)
            out["M_ours_Nm"].append(M)
            out["M_skf_Nm"].append(M_skf)
            out["ratio_to_skf"].append(M / M_skf)
    return out


# ------------------------------------------------------------------------------------------------
# fatigue rating life (bearing_core.bearing.ratings, bearing_core.models.life)
@kind
def lundberg_palmgren_fc(inputs):
    """Lundberg-Palmgren f_c (bearing_core.bearing.ratings.lundberg_palmgren_fc, conformities 0.52 / 0.53 of
    ISO 281's basis) at each gamma = D cos(alpha) / dm of the case."""
    from bearing_core.bearing.ratings import lundberg_palmgren_fc as fc
    fi, fe = inputs.get("fi", 0.52), inputs.get("fe", 0.53)
    return {"f_c": [fc(g, fi, fe) for g in inputs["gamma"]], "gamma": list(inputs["gamma"])}


def _bearing_from_balls(b):
    """A bearing definition from the ball set of a case (Z, D_mm, dm_mm, alpha_deg, fi, fo); the masses and the
    cage are placeholders (no rating depends on them)."""
    from bearing_core.bearing.geometry import from_dict
    return from_dict({"name": b["name"], "number_of_balls": b["Z"], "ball_diameter_mm": b["D_mm"],
                      "pitch_diameter_mm": b["dm_mm"], "free_contact_angle_deg": b.get("alpha_deg", 0.0),
                      "fi": b.get("fi", 0.52), "fo": b.get("fo", 0.53), "width_mm": 10.0,
                      "inner_ring_mass_kg": 0.1, "outer_ring_mass_kg": 0.1, "inner_ring_inertia_kg_mm2": 10.0,
                      "inner_ring_tilt_inertia_kg_mm2": 10.0, "cage": {"mass_kg": 0.01, "inertia_kg_mm2": 1.0}})


@kind
def iso281_load_ratings(inputs):
    """ISO 281:2007 C_r (BearingGeometry.iso281_dynamic_load_rating) and the ISO 76-basis C_0
    (friction_models.iso76_static_rating: 4200 MPa at the inner contact) of each ball set, in kN."""
    from bearing_core.lubrication.friction_models import iso76_static_rating
    out = {"C_r_kN": [], "C_0_kN": [], "bearing": []}
    for b in inputs["bearings"]:
        g = _bearing_from_balls(b)
        out["C_r_kN"].append(g.iso281_dynamic_load_rating / 1e3)
        out["C_0_kN"].append(iso76_static_rating(g) / 1e3)
        out["bearing"].append(b["name"])
    return out


@kind
def iso281_a1(inputs):
    """Life modification factor for reliability a_1 (models.life.a1_reliability: the Weibull relation behind
    ISO 281 Table 12) at each reliability [%] of the case."""
    from bearing_core.models.life import a1_reliability
    return {"a1": [a1_reliability(R) for R in inputs["reliability_pct"]],
            "reliability_pct": list(inputs["reliability_pct"])}


@kind
def axial_life_vs_iso281_y(inputs):
    """Pure axial load: the dynamic equivalent reference load P = C_r L10r^(-1/3) of the ISO/TS 16281-style
    life from the quasi-static load distribution (models.life.life_at), as P / Fa for each bearing (in the
    case's order) and each axial load, against ISO 281's P = Y Fa (Fr = 0)."""
    from bearing_core.bearing.geometry import load_preset
    from bearing_core.models.life import life_at
    out = {"P_over_Fa": [], "alpha_i_deg": [], "bearing": [], "Fa_N": []}
    for name in inputs["bearings"]:
        g = load_preset(name)
        for Fa in inputs["Fa_N"]:
            r = life_at(g, inputs["speed_rpm"], (0.0, 0.0, Fa, 0.0, 0.0))
            out["P_over_Fa"].append(r.rating.P_ref / Fa)
            out["alpha_i_deg"].append(math.degrees(float(np.mean(r.result.alpha_i))))
            out["bearing"].append(name)
            out["Fa_N"].append(Fa)
    return out
