"""Command-line interface: ``bearing <subcommand>``.

User-facing units are labelled: speeds in rpm, forces in N, moments in N m, lengths in the JSON keys'
units. Bad arguments exit with code 2 and a one-line reason on stderr.
"""
from __future__ import annotations

import argparse
import json
import math
import re
import sys
from pathlib import Path

import numpy as np

RPM = 2.0 * math.pi / 60.0  # rad/s per rpm


# argparse takes "-1e-3" for an option name (its negative-number pattern has no exponent): numbers in any
# float notation are values
_NEGATIVE_NUMBER = re.compile(r"^-(\d+\.?\d*|\.\d+)([eE][-+]?\d+)?$|^-(inf|nan)$", re.IGNORECASE)


class _Parser(argparse.ArgumentParser):
    def __init__(self, *args, **kw):
        super().__init__(*args, **kw)
        self._negative_number_matcher = _NEGATIVE_NUMBER

    def error(self, message):  # one-line reason, exit 2
        sys.stderr.write(f"{self.prog}: error: {message}\n")
        raise SystemExit(2)


def _finite(name):
    def conv(s):
        try:
            v = float(s)
        except ValueError:
            raise argparse.ArgumentTypeError(f"{name} must be a number, got {s!r}")
        if not math.isfinite(v):
            raise argparse.ArgumentTypeError(f"{name} must be finite, got {s!r}")
        return v
    return conv


def _add_loads(parser):
    """--fx --fy --fz [N] and --mx --my [N m]: loads on the inner ring."""
    for nm, unit in (("fx", "N"), ("fy", "N"), ("fz", "N"), ("mx", "N m"), ("my", "N m")):
        parser.add_argument(f"--{nm}", type=_finite(f"--{nm}"), default=0.0, help=f"load on the inner ring [{unit}]")


def build_parser() -> argparse.ArgumentParser:
    p = _Parser(prog="bearing", description="Angular-contact ball bearing tribo-dynamic model")
    sub = p.add_subparsers(dest="cmd", parser_class=_Parser)
    sub.required = True

    q = sub.add_parser("quasistatic", help="Jones-Harris 5-DOF quasi-static solution")
    q.add_argument("--bearing", required=True, help="preset name (see 'bearing presets')")
    q.add_argument("--speed-rpm", required=True, type=_finite("--speed-rpm"),
                   help="inner-ring speed [rpm], signed about +z (negative: turning the other way; the result is "
                        "the mirror image in the x-z plane of the positive-speed one under reflected loads)")
    q.add_argument("--outer-speed-rpm", type=_finite("--outer-speed-rpm"), default=0.0,
                   help="outer-ring speed [rpm], signed (default 0: fixed outer ring; Jones-Harris model only)")
    _add_loads(q)
    q.add_argument("--control", choices=("outer", "inner", "hybrid"), default="outer",
                   help="raceway control hypothesis (default outer)")
    q.add_argument("--traction", choices=("kalker", "coulomb", "lubricated"), default=None,
                   help="quasi-static TRIBOLOGICAL model with this traction (the dynamics' contact interface) "
                        "instead of Jones-Harris raceway control")
    q.add_argument("--mu", type=_finite("--mu"), default=0.1,
                   help="friction coefficient of --traction kalker / coulomb [-]")
    q.add_argument("--json", action="store_true", help="print one JSON object")
    q.set_defaults(func=cmd_quasistatic)

    _add_sweep_parser(sub)

    dy = sub.add_parser("dynamics", help="transient tribo-dynamic run through a speed profile: CSV, plots, "
                                          "summary JSON")
    dy.add_argument("--bearing", required=True)
    dy.add_argument("--profile", default="seed000",
                    help="'seed000' (1000 rpm to 0.5 s, 10,000 rpm/s to 10,000 rpm, held to 2 s) or a CSV "
                         "file with columns time_s, speed_rpm")
    _add_loads(dy)
    dy.add_argument("--traction", choices=("lubricated", "coulomb", "kalker"), default="lubricated")
    dy.add_argument("--mu", type=_finite("--mu"), default=0.1, help="Coulomb friction coefficient [-]")
    dy.add_argument("--mu-cage", type=_finite("--mu-cage"), default=0.1,
                    help="ball-pocket and cage-land friction coefficient [-]")
    dy.add_argument("--lubrication", choices=("auto", "oil", "solid", "dry"), default="auto",
                    help="lubrication regime of races and cage: oil (lubricated traction, oil-lubricated pocket "
                         "and land), solid (Kalker/Coulomb traction with --mu, dry cage with --mu-cage), dry "
                         "(Coulomb everywhere); auto: oil for --traction lubricated, else solid")
    dy.add_argument("--integrator", choices=("adaptive", "implicit", "auto", "rk4", "adaptive-rk4"), default="auto")
    dy.add_argument("--start", choices=("jones-harris", "tribological"), default="jones-harris",
                    help="initial state: Jones-Harris quasi-static or the quasi-static tribological model")
    dy.add_argument("--reduced", choices=("auto", "full", "axisymmetric"), default="auto")
    dy.add_argument("--record-dt", type=_finite("--record-dt"), default=1e-3, help="output interval [s]")
    dy.add_argument("--out", default="out", help="output folder (created)")
    dy.set_defaults(func=cmd_dynamics)

    ms = sub.add_parser("microslip", help="adhesion/slip picture of one contact (Kalker/FASTSIM) after a "
                                          "transient run at constant speed and load")
    ms.add_argument("--bearing", required=True)
    ms.add_argument("--speed-rpm", required=True, type=_finite("--speed-rpm"))
    _add_loads(ms)
    ms.add_argument("--time", type=_finite("--time"), default=0.02, help="instant of the picture [s]")
    ms.add_argument("--ball", type=int, default=0)
    ms.add_argument("--race", choices=("inner", "outer"), default="inner")
    ms.add_argument("--traction", choices=("kalker", "coulomb", "lubricated"), default="kalker",
                    help="traction law of the run (the picture is always FASTSIM)")
    ms.add_argument("--mu", type=_finite("--mu"), default=0.1)
    ms.add_argument("--out", default="out")
    ms.set_defaults(func=cmd_microslip)

    th = sub.add_parser("thermal", help="thermal steady state of the coupled dynamic-thermal model (seed 001): "
                                         "temperatures, losses by source, heat balance")
    th.add_argument("--bearing", required=True)
    th.add_argument("--speed-rpm", required=True, type=_finite("--speed-rpm"))
    _add_loads(th)
    th.add_argument("--oil", default="iso-vg32-mineral", help="oil name (bearing_core.lubrication.lubricants)")
    th.add_argument("--oil-fraction", type=_finite("--oil-fraction"), default=None,
                    help="oil volume fraction of the cavity's oil-air mixture [-], overriding the supply's "
                         "(default: from the supply; 0.05 without flow and method)")
    th.add_argument("--lubrication-method", choices=("jet", "oil-air", "bath", "grease"), default=None,
                    help="oil supply (bearing_core.lubrication.oil_supply); default jet when --oil-flow-lpm > 0")
    th.add_argument("--oil-level-mm", type=_finite("--oil-level-mm"), default=None,
                    help="bath: static oil level above the lowest point of the outer raceway [mm]")
    th.add_argument("--bath-model", choices=("skf", "geometric"), default=None,
                    help="bath: oil content from SKF's (2004) drag term (skf, default) or the submerged share of "
                         "the cavity (geometric)")
    th.add_argument("--ambient-c", type=_finite("--ambient-c"), default=35.0, help="ambient temperature [degC]")
    th.add_argument("--oil-inlet-c", type=_finite("--oil-inlet-c"), default=None,
                    help="oil supply temperature [degC] (default: ambient)")
    th.add_argument("--oil-flow-lpm", type=_finite("--oil-flow-lpm"), default=0.0,
                    help="circulating oil flow [L/min]")
    th.add_argument("--no-churning", action="store_true", help="leave out the churning torques")
    th.add_argument("--lubrication", choices=("auto", "oil", "solid"), default="auto",
                    help="lubrication regime (auto: oil, the lubricated traction of this command)")
    th.add_argument("--json", action="store_true")
    th.set_defaults(func=cmd_thermal)

    we = sub.add_parser("wear", help="raceway wear over a duty of hours (seed 003 modified Archard model, "
                                      "two time scales)")
    we.add_argument("--bearing", required=True)
    we.add_argument("--speed-rpm", required=True, type=_finite("--speed-rpm"))
    _add_loads(we)
    we.add_argument("--hours", type=_finite("--hours"), default=1000.0, help="duration [h]")
    we.add_argument("--json", action="store_true")
    we.set_defaults(func=cmd_wear)

    li = sub.add_parser("life", help="fatigue rating life: ISO 281 C_r, ISO/TS 16281 reference rating life L10r from "
                                      "the quasi-static load distribution, ISO 281 modified life L_nmr")
    li.add_argument("--bearing", required=True, help="preset name, catalogue designation or bearing JSON file")
    li.add_argument("--speed-rpm", type=_finite("--speed-rpm"), default=None,
                    help="inner-ring speed [rpm], 0 < speed <= 190000 (outer ring fixed); required without --duty")
    li.add_argument("--duty", default=None, metavar="CSV",
                    help="duty cycle of held levels: CSV with columns duration_s, speed_rpm and optionally Fx_N, Fy_N, "
                         "Fz_N, Mx_Nm, My_Nm (missing: the --fx ... values); Palmgren-Miner damage per cycle and the "
                         "equivalent lives")
    _add_loads(li)
    li.add_argument("--fixed-tilt", action="store_true",
                    help="inner ring held square by the shaft (Mx, My are reactions); default: free to tilt")
    li.add_argument("--oil", default="iso-vg32-mineral",
                    help="oil for the viscosity ratio kappa (default iso-vg32-mineral)")
    li.add_argument("--oil-temperature-c", type=_finite("--oil-temperature-c"), default=40.0,
                    help="operating oil temperature [degC] (default 40)")
    li.add_argument("--contamination", type=_finite("--contamination"), default=1.0,
                    help="contamination factor e_C of ISO 281 Table 13, 0..1 (default 1: extreme cleanliness)")
    li.add_argument("--reliability", type=_finite("--reliability"), default=90.0,
                    help="reliability [%%] for a_1, 90..99.95 (default 90)")
    li.add_argument("--json", action="store_true", help="print one JSON object")
    li.set_defaults(func=cmd_life)

    _add_build_map_parser(sub)
    pr = sub.add_parser("presets", help="list the bearing presets with their sources")
    pr.add_argument("--json", action="store_true")
    pr.set_defaults(func=cmd_presets)

    return p


def quasistatic_dict(res) -> dict:
    """JSON-ready dict of a QuasiStaticResult (keys carry their units)."""
    g = res.geometry
    deg = np.degrees
    d = {
        "bearing": g.name,
        "speed_rpm": res.omega / RPM,
        "outer_speed_rpm": res.omega_outer / RPM,
        "control": res.control,
        "loads": dict(zip(("Fx_N", "Fy_N", "Fz_N", "Mx_Nm", "My_Nm"), map(float, res.loads))),
        "psi_deg": deg(res.psi).tolist(),
        "alpha_i_deg": deg(res.alpha_i).tolist(),
        "alpha_o_deg": deg(res.alpha_o).tolist(),
        "Q_i_N": res.Q_i.tolist(),
        "Q_o_N": res.Q_o.tolist(),
        "delta_i_m": res.delta_i.tolist(),
        "delta_o_m": res.delta_o.tolist(),
        "a_i_m": res.a_i.tolist(), "b_i_m": res.b_i.tolist(),
        "a_o_m": res.a_o.tolist(), "b_o_m": res.b_o.tolist(),
        "p_max_i_Pa": res.p_i.tolist(), "p_max_o_Pa": res.p_o.tolist(),
        "omega_m_rpm": (res.omega_m / RPM).tolist(),
        "omega_R_rpm": (res.omega_R / RPM).tolist(),
        "beta_deg": deg(res.beta).tolist(),
        "spin_roll_i": res.spin_roll_i.tolist(),
        "spin_roll_o": res.spin_roll_o.tolist(),
        "outer_control": res.outer_control.tolist(),
        "cage_speed_rpm": res.cage_speed / RPM,
        "displacement": dict(zip(("dx_m", "dy_m", "dz_m", "tx_rad", "ty_rad"), map(float, res.u))),
        "stiffness": None if res.stiffness is None else res.stiffness.tolist(),
        "stiffness_units": "rows Fx,Fy,Fz [N],Mx,My [N m]; columns dx,dy,dz [m],tx,ty [rad]",
        "equilibrium_residual_rel": res.residual,
    }
    return d


def cmd_quasistatic(a) -> int:
    from .bearing.geometry import load_preset
    from .models.quasistatic import solve_quasistatic

    for flag, v in (("--speed-rpm", a.speed_rpm), ("--outer-speed-rpm", a.outer_speed_rpm)):
        if not -190000.0 <= v <= 190000.0:
            raise _BadArg(f"{flag} = {v} is invalid; allowed: -190000 <= speed <= 190000 rpm")
    g = load_preset(a.bearing)
    if a.traction is not None:
        if a.outer_speed_rpm != 0.0:
            raise _BadArg(f"--outer-speed-rpm = {a.outer_speed_rpm} is invalid with --traction; allowed: 0 (the "
                          "tribological model has a fixed outer ring; use the Jones-Harris model or the dynamics)")
        g.require_two_point("tribological quasi-static model (--traction)")
        return _tribo_quasistatic(a, g)
    res = solve_quasistatic(g, a.speed_rpm * RPM, (a.fx, a.fy, a.fz, a.mx, a.my), control=a.control,
                            omega_outer=a.outer_speed_rpm * RPM)
    d = quasistatic_dict(res)
    if g.is_four_point:
        from .models.quasistatic import CONTACT_NAMES
        d["four_point"] = {
            "contacts": list(CONTACT_NAMES),
            "inner_groove_offset_mm": g.inner_groove_offset * 1e3,
            "outer_groove_offset_mm": g.outer_groove_offset * 1e3,
            "axial_play_mm": g.axial_play * 1e3, "radial_play_mm": g.radial_play * 1e3,
            "contact_angle_zero_clearance_deg": math.degrees(g.contact_angle_zero_clearance),
            "alpha_deg": np.degrees(res.alpha_c).tolist(), "Q_N": res.Q_c.tolist(),
            "delta_m": res.delta_c.tolist(), "a_m": res.a_c.tolist(), "b_m": res.b_c.tolist(),
            "p_max_Pa": res.p_c.tolist(), "contacts_per_ball": res.contacts_per_ball.tolist(),
        }
    if a.json:
        print(json.dumps(d))
        return 0
    print(f"bearing {g.name}  speed {a.speed_rpm:g} rpm" + (f"  outer ring {a.outer_speed_rpm:g} rpm"
                                                            if a.outer_speed_rpm else "") + f"  control {a.control}")
    print(f"loads  Fx {a.fx:g} N  Fy {a.fy:g} N  Fz {a.fz:g} N  Mx {a.mx:g} N m  My {a.my:g} N m")
    u = res.u
    print(f"displacement  dx {u[0]*1e6:.3f} um  dy {u[1]*1e6:.3f} um  dz {u[2]*1e6:.3f} um  "
          f"tx {u[3]*1e3:.4f} mrad  ty {u[4]*1e3:.4f} mrad")
    print(f"pure-rolling cage speed {d['cage_speed_rpm']:.1f} rpm   equilibrium residual {res.residual:.1e}")
    if g.is_four_point:
        fp = d["four_point"]
        print(f"four-point contact: groove offsets inner {fp['inner_groove_offset_mm']:.4f} mm, outer "
              f"{fp['outer_groove_offset_mm']:.4f} mm; axial play {fp['axial_play_mm']:.4f} mm, radial play "
              f"{fp['radial_play_mm']:.4f} mm, contact angle at zero clearance "
              f"{fp['contact_angle_zero_clearance_deg']:.2f} deg")
        print("contacts: i1/o1 = diagonal pair carrying +Fz on the inner ring, i2/o2 = its mirror image")
        nm = ("i1", "i2", "o1", "o2")
        hdr = f"{'ball':>4} {'psi':>6} " + " ".join(f"{'a_'+n:>7}" for n in nm) + " " + \
            " ".join(f"{'Q_'+n:>9}" for n in nm) + " " + " ".join(f"{'p_'+n:>6}" for n in nm) + f" {'w_m':>8}"
        print(hdr)
        print(f"{'':>4} {'deg':>6} " + " ".join(f"{'deg':>7}" for _ in nm) + " " + " ".join(f"{'N':>9}" for _ in nm)
              + " " + " ".join(f"{'GPa':>6}" for _ in nm) + f" {'rpm':>8}")
        for j in range(g.Z):
            print(f"{j:4d} {d['psi_deg'][j]:6.1f} " + " ".join(f"{np.degrees(x):7.3f}" for x in res.alpha_c[j]) + " "
                  + " ".join(f"{x:9.2f}" for x in res.Q_c[j]) + " " + " ".join(f"{x/1e9:6.3f}" for x in res.p_c[j])
                  + f" {d['omega_m_rpm'][j]:8.1f}")
        if res.stiffness is not None:
            print("stiffness matrix (rows Fx,Fy,Fz [N], Mx,My [N m]; cols dx,dy,dz [m], tx,ty [rad]):")
            for row in res.stiffness:
                print("  " + " ".join(f"{v:12.4e}" for v in row))
        return 0
    hdr = (f"{'ball':>4} {'psi':>6} {'a_i':>7} {'a_o':>7} {'Q_i':>9} {'Q_o':>9} {'p_i':>7} {'p_o':>7} "
           f"{'w_m':>8} {'w_R':>9} {'beta':>6} {'s/r_i':>7} {'s/r_o':>7}")
    print(hdr)
    print(f"{'':>4} {'deg':>6} {'deg':>7} {'deg':>7} {'N':>9} {'N':>9} {'GPa':>7} {'GPa':>7} "
          f"{'rpm':>8} {'rpm':>9} {'deg':>6} {'-':>7} {'-':>7}")
    for j in range(g.Z):
        print(f"{j:4d} {d['psi_deg'][j]:6.1f} {d['alpha_i_deg'][j]:7.3f} {d['alpha_o_deg'][j]:7.3f} "
              f"{res.Q_i[j]:9.2f} {res.Q_o[j]:9.2f} {res.p_i[j]/1e9:7.3f} {res.p_o[j]/1e9:7.3f} "
              f"{d['omega_m_rpm'][j]:8.1f} {d['omega_R_rpm'][j]:9.1f} {d['beta_deg'][j]:6.2f} "
              f"{d['spin_roll_i'][j]:7.4f} {d['spin_roll_o'][j]:7.4f}")
    if res.stiffness is not None:
        print("stiffness matrix (rows Fx,Fy,Fz [N], Mx,My [N m]; cols dx,dy,dz [m], tx,ty [rad]):")
        for row in res.stiffness:
            print("  " + " ".join(f"{v:12.4e}" for v in row))
    return 0


def _read_duty(path, a) -> list:
    """Levels (duration_s, speed_rpm, loads) of a duty-cycle CSV (cmd_life --duty)."""
    import csv
    p = Path(path)
    if not p.is_file():
        raise _BadArg(f"--duty = {path!r} is invalid; allowed: an existing CSV file (file not found)")
    cols = ("Fx_N", "Fy_N", "Fz_N", "Mx_Nm", "My_Nm")
    default = (a.fx, a.fy, a.fz, a.mx, a.my)
    levels = []
    with p.open(newline="") as f:
        rd = csv.DictReader(f)
        need = {"duration_s", "speed_rpm"}
        if rd.fieldnames is None or not need.issubset(rd.fieldnames):
            raise _BadArg(f"--duty = {path!r} is invalid; allowed: a CSV with columns duration_s, speed_rpm "
                          f"[, {', '.join(cols)}] (got {rd.fieldnames})")
        for k, row in enumerate(rd, start=2):
            try:
                vals = [float(row["duration_s"]), float(row["speed_rpm"])] + \
                    [float(row[c]) if row.get(c) not in (None, "") else d for c, d in zip(cols, default)]
            except ValueError as e:
                raise _BadArg(f"--duty {path}: line {k} is invalid; allowed: numbers ({e})")
            if not all(math.isfinite(v) for v in vals):
                raise _BadArg(f"--duty {path}: line {k} = {vals} is invalid; allowed: finite numbers")
            levels.append((vals[0], vals[1], tuple(vals[2:])))
    if not levels:
        raise _BadArg(f"--duty = {path!r} is invalid; allowed: at least one level (the file has no rows)")
    return levels


def cmd_life(a) -> int:
    from .bearing.geometry import load_bearing
    from .models.life import duty_cycle_life, life_at

    if a.duty is not None:
        if a.speed_rpm is not None:
            raise _BadArg(f"--speed-rpm = {a.speed_rpm:g} is invalid with --duty; allowed: none (the speeds of the "
                          "duty CSV)")
        for flag, v, lo, hi in (("--contamination", a.contamination, 0.0, 1.0),
                                ("--reliability", a.reliability, 90.0, 99.95)):
            if not lo <= v <= hi:
                raise _BadArg(f"{flag} = {v:g} is invalid; allowed: {lo:g} <= value <= {hi:g}")
        g = load_bearing(a.bearing)
        dc = duty_cycle_life(g, _read_duty(a.duty, a), oil=a.oil, oil_temperature_c=a.oil_temperature_c,
                             e_C=a.contamination, reliability_pct=a.reliability, fixed_tilt=a.fixed_tilt)
        d = dc.to_dict()
        if a.json:
            print(json.dumps(d))
            return 0
        print(f"bearing {g.name}  duty cycle {a.duty}: {len(dc.levels)} levels, {d['cycle_s']:g} s per cycle" +
              ("  (inner ring held square)" if a.fixed_tilt else ""))
        print(f"{'level':>5} {'time':>9} {'speed':>8} {'Fx':>8} {'Fy':>8} {'Fz':>8} {'Mx':>7} {'My':>7} "
              f"{'L10r':>10} {'L_nmr':>10} {'damage L10r':>12}")
        print(f"{'':>5} {'s':>9} {'rpm':>8} {'N':>8} {'N':>8} {'N':>8} {'N m':>7} {'N m':>7} {'h':>10} {'h':>10} "
              f"{'-':>12}")
        for k, (t, rep) in enumerate(zip(dc.durations_s, dc.levels)):
            L = rep.loads
            print(f"{k:5d} {t:9.4g} {rep.speed_rpm:8.5g} {L[0]:8.5g} {L[1]:8.5g} {L[2]:8.5g} {L[3]:7.4g} "
                  f"{L[4]:7.4g} {rep.rating.L10r_h:10.4g} {rep.L_nmr_h:10.4g} "
                  f"{t / 3600.0 / rep.rating.L10r_h:12.4e}")
        print(f"Palmgren-Miner damage per cycle: {dc.damage_L10r:.4e} (L10r), {dc.damage_L_nmr:.4e} (L_nmr)")
        print(f"equivalent lives: L10r {dc.L10r_h:.4g} h, L_nmr {dc.L_nmr_h:.4g} h")
        return 0
    if a.speed_rpm is None:
        raise _BadArg("--speed-rpm is required (or --duty CSV); allowed: 0 < speed <= 190000 rpm")
    if not 0.0 < a.speed_rpm <= 190000.0:
        raise _BadArg(f"--speed-rpm = {a.speed_rpm:g} is invalid; allowed: 0 < speed <= 190000 rpm (the inner ring "
                      "turning in the positive sense; a rating life in hours needs rotation)")
    if not 0.0 <= a.contamination <= 1.0:
        raise _BadArg(f"--contamination = {a.contamination:g} is invalid; allowed: 0 <= e_C <= 1 (ISO 281 Table 13)")
    if not 90.0 <= a.reliability <= 99.95:
        raise _BadArg(f"--reliability = {a.reliability:g} is invalid; allowed: 90 <= reliability <= 99.95 %")
    g = load_bearing(a.bearing)
    rep = life_at(g, a.speed_rpm, (a.fx, a.fy, a.fz, a.mx, a.my), oil=a.oil, oil_temperature_c=a.oil_temperature_c,
                  e_C=a.contamination, reliability_pct=a.reliability, fixed_tilt=a.fixed_tilt)
    d = rep.to_dict()
    if a.json:
        print(json.dumps(d))
        return 0
    r = rep.rating
    fmt = lambda x: "infinite" if x is None else f"{x:.4g}"  # noqa: E731
    print(f"bearing {g.name}  speed {a.speed_rpm:g} rpm  loads Fx {a.fx:g} N  Fy {a.fy:g} N  Fz {a.fz:g} N  "
          f"Mx {a.mx:g} N m  My {a.my:g} N m" + ("  (inner ring held square)" if a.fixed_tilt else ""))
    print(f"C_r {rep.C_r/1e3:.2f} kN ({rep.C_r_source})   C_0 {rep.C_0/1e3:.2f} kN (ISO 76 basis)   "
          f"C_u {rep.C_u/1e3:.3f} kN (ISO 281 Annex B)")
    print(f"{'quantity':<44} {'value':>12}  unit")
    rows = [("equivalent ball load, inner ring Q_ei", r.Q_ei, "N"),
            ("equivalent ball load, outer ring Q_eo", r.Q_eo, "N"),
            ("inner raceway life L_i", d["L_inner_Mrev"], "10^6 rev"),
            ("outer raceway life L_o", d["L_outer_Mrev"], "10^6 rev"),
            ("reference rating life L10r", d["L10r_Mrev"], "10^6 rev"),
            ("reference rating life L10r", d["L10r_h"], "h"),
            ("equivalent reference load P = C_r L10r^-1/3", r.P_ref, "N"),
            (f"viscosity nu ({rep.oil} at {rep.oil_temperature_c:g} degC)", rep.nu_mm2s, "mm^2/s"),
            ("reference viscosity nu_1 (ISO 281)", rep.nu1_mm2s, "mm^2/s"),
            ("viscosity ratio kappa", rep.kappa, "-"),
            ("contamination factor e_C", rep.e_C, "-"),
            (f"a_1 (reliability {rep.reliability_pct:g} %)", rep.a1, "-"),
            ("a_ISO", rep.a_iso, "-"),
            ("modified rating life L_nmr", d["L_nmr_Mrev"], "10^6 rev"),
            ("modified rating life L_nmr", d["L_nmr_h"], "h")]
    for nm, v, u in rows:
        print(f"{nm:<44} {fmt(v):>12}  {u}")
    for note in rep.notes:
        print(f"note: {note}")
    return 0


def tribo_quasistatic_dict(res) -> dict:
    """JSON-ready dict of a TriboQuasiStaticResult (keys carry their units); the Jones-Harris start for
    comparison under 'jones_harris'."""
    g = res.geometry
    deg = np.degrees
    jh = res.jones_harris
    return {
        "bearing": g.name, "model": "tribological", "traction": res.traction, "mu": res.mu,
        "speed_rpm": res.omega / RPM,
        "loads": dict(zip(("Fx_N", "Fy_N", "Fz_N", "Mx_Nm", "My_Nm"), map(float, res.loads))),
        "psi_deg": deg(res.psi).tolist(),
        "alpha_i_deg": deg(res.alpha_i).tolist(), "alpha_o_deg": deg(res.alpha_o).tolist(),
        "Q_i_N": res.Q_i.tolist(), "Q_o_N": res.Q_o.tolist(),
        "a_i_m": res.a_i.tolist(), "b_i_m": res.b_i.tolist(), "a_o_m": res.a_o.tolist(), "b_o_m": res.b_o.tolist(),
        "omega_m_rpm": (res.orbit_speed / RPM).tolist(),
        "ball_omega_rpm": (res.omega_ball / RPM).tolist(),
        "ball_omega_axes": "absolute angular velocity (radial, tangential, axial) in the ball's local frame",
        "attitude_deg": deg(res.attitude).tolist(), "yaw_deg": deg(res.yaw).tolist(),
        "slide_roll_i": res.slide_roll_i.tolist(), "slide_roll_o": res.slide_roll_o.tolist(),
        "spin_roll_i": res.spin_roll_i.tolist(), "spin_roll_o": res.spin_roll_o.tolist(),
        "Ft_i_N": res.Ft_i.tolist(), "Fm_i_N": res.Fm_i.tolist(), "Ft_o_N": res.Ft_o.tolist(),
        "Fm_o_N": res.Fm_o.tolist(),
        "cage_speed_rpm": res.cage_speed / RPM,
        "friction_torque_Nm": res.friction_torque,
        "losses_W": res.losses,
        "reaction": dict(zip(("Fx_N", "Fy_N", "Fz_N", "Mx_Nm", "My_Nm"), map(float, res.reaction))),
        "displacement": dict(zip(("dx_m", "dy_m", "dz_m", "tx_rad", "ty_rad"), map(float, res.u))),
        "equilibrium_residual_N": res.residual,
        "jones_harris": {"cage_speed_rpm": jh.cage_speed / RPM, "alpha_i_deg": deg(jh.alpha_i).tolist(),
                         "alpha_o_deg": deg(jh.alpha_o).tolist(), "beta_deg": deg(jh.beta).tolist(),
                         "omega_m_rpm": (jh.omega_m / RPM).tolist()},
    }


def _tribo_quasistatic(a, g) -> int:
    from .models.dynamics import DynamicsOptions
    from .models.quasistatic_tribo import solve_tribo_quasistatic
    if a.speed_rpm * RPM < 1.0:
        raise _BadArg(f"--speed-rpm = {a.speed_rpm} is invalid with --traction; allowed: 10 <= speed <= 190000 rpm "
                      "(the tribological model needs rolling in the positive sense; for a negative speed use the "
                      "Jones-Harris model, whose mirrored solution this command reports, or the dynamics)")
    opt = DynamicsOptions(traction=a.traction, mu=a.mu)
    res = solve_tribo_quasistatic(g, a.speed_rpm * RPM, (a.fx, a.fy, a.fz, a.mx, a.my), opt)
    d = tribo_quasistatic_dict(res)
    if a.json:
        print(json.dumps(d))
        return 0
    print(f"bearing {g.name}  speed {a.speed_rpm:g} rpm  quasi-static tribological model, {a.traction} traction "
          f"(mu {a.mu:g})")
    print(f"loads  Fx {a.fx:g} N  Fy {a.fy:g} N  Fz {a.fz:g} N  Mx {a.mx:g} N m  My {a.my:g} N m")
    u = res.u
    print(f"displacement  dx {u[0]*1e6:.3f} um  dy {u[1]*1e6:.3f} um  dz {u[2]*1e6:.3f} um  "
          f"tx {u[3]*1e3:.4f} mrad  ty {u[4]*1e3:.4f} mrad")
    print(f"cage speed (mean orbit) {d['cage_speed_rpm']:.1f} rpm (Jones-Harris {d['jones_harris']['cage_speed_rpm']:.1f})"
          f"   friction torque {res.friction_torque:.4f} N m   residual {res.residual:.1e} N")
    print(f"{'ball':>4} {'psi':>6} {'a_i':>7} {'a_o':>7} {'Q_i':>9} {'Q_o':>9} {'w_m':>8} {'att':>7} {'yaw':>8} "
          f"{'sl/r_i':>8} {'sl/r_o':>8} {'sp/r_i':>7} {'sp/r_o':>7}")
    print(f"{'':>4} {'deg':>6} {'deg':>7} {'deg':>7} {'N':>9} {'N':>9} {'rpm':>8} {'deg':>7} {'deg':>8} "
          f"{'-':>8} {'-':>8} {'-':>7} {'-':>7}")
    for j in range(g.Z):
        print(f"{j:4d} {d['psi_deg'][j]:6.1f} {d['alpha_i_deg'][j]:7.3f} {d['alpha_o_deg'][j]:7.3f} "
              f"{res.Q_i[j]:9.2f} {res.Q_o[j]:9.2f} {d['omega_m_rpm'][j]:8.1f} {d['attitude_deg'][j]:7.3f} "
              f"{d['yaw_deg'][j]:8.4f} {d['slide_roll_i'][j]:8.5f} {d['slide_roll_o'][j]:8.5f} "
              f"{d['spin_roll_i'][j]:7.4f} {d['spin_roll_o'][j]:7.4f}")
    return 0


SWEEP_EPILOG = """\
points:
  Without --grid / --points-file: the speed grid 0 .. --speed-max-rpm in --points steps (the quasi-static speed
  sweep, also written as quasistatic_sweep_<bearing>.csv/.png). --grid VAR=START:STOP:NUM or VAR=A,B,C
  (repeatable; the Cartesian product, dims in the order given); --points-file CSV (one column per variable);
  --set VAR=VALUE fixes a variable for all points. Variables (units in the names):
    {variables}
models (--model): quasistatic (Jones-Harris), tribo (quasi-static tribological: traction, friction, ball drag in
  the oil-air mixture), dynamic (the dynamic model held at each point's speed and load until steady: between
  consecutive --window-s windows the window mean of the cage speed changes by less than --steady-tol and that of
  the friction torque by less than --torque-tol, at most --max-time-s simulated; column 'steady'), profile (the dynamic model through --profile), fmu (the FMU
  --fmu through fmpy: one instance per worker, reset between points, same steadiness criterion).

skid criterion:
  S = cage speed / pure-rolling cage speed, the pure-rolling value from Harris & Kotzalas (outer raceway control,
  pure rolling at both contact centres) at the model's own contact angles, averaged over the loaded balls.
  skidding: S < 1 - --skid-threshold; over-skidding: S > 1 + --overskid-threshold (defaults 0.05: an engineering
  tolerance, not a published constant). --min-preload SPEEDS finds, per speed, the smallest axial preload
  (constant-force, added to Fz) with S >= 1 - skid-threshold by bisection between --preload-range LO:HI
  (LO must skid, HI must not) to a relative width --preload-rtol.

execution:
  Dask distributed: a local cluster of single-threaded worker processes (--workers, default one per CPU), or
  --scheduler ADDRESS of an existing cluster. A point that raises is recorded (status 'failed', error) and the
  others go on; a task whose worker dies is retried (--retries). Finished points are cached in --cache (default
  OUT/sweep_cache) under the hash of the point, model, options and code version: re-running resumes.
  Each task carries a batch of points (--batch-size); the dynamic and profile models advance a batch's points
  together on --threads-per-worker threads, with the same results as one point at a time.
outputs (OUT/): sweep.csv, sweep.parquet, sweep.nc (grids), sweep_skid_map.png, sweep_torque_map.png,
  sweep_heat_map.png (grids over speed_rpm and a load), min_preload.csv/.png."""


def _add_sweep_parser(sub):
    from .maps.sweep import MODEL_NAMES, VARIABLES
    sw = sub.add_parser(
        "sweep", help="operating maps on Dask: grids or point lists over speed, loads, preload, oil, friction, "
                      "clearances, bearing; skid, torque and heat maps; minimum-preload curve",
        formatter_class=argparse.RawDescriptionHelpFormatter,
        epilog=SWEEP_EPILOG.format(variables="\n    ".join(f"{v.name}: {v.doc}" for v in VARIABLES.values())))
    sw.add_argument("--bearing", default=None, help="preset name or bearing JSON file (default: the points' or 7218B)")
    _add_loads(sw)
    sw.add_argument("--speed-max-rpm", type=_finite("--speed-max-rpm"), default=15000.0,
                    help="top of the default speed grid [rpm]")
    sw.add_argument("--points", type=int, default=16, help="number of speeds of the default speed grid")
    sw.add_argument("--control", choices=("outer", "inner", "hybrid"), default="outer",
                    help="raceway control of the quasistatic model")
    sw.add_argument("--out", default="out", help="output folder (created)")
    sw.add_argument("--model", choices=MODEL_NAMES, default="quasistatic", help="model evaluating each point")
    sw.add_argument("--grid", action="append", default=[], metavar="VAR=SPEC", help="grid dimension (repeatable)")
    sw.add_argument("--points-file", default=None, help="CSV list of points (columns: variable names)")
    sw.add_argument("--set", action="append", default=[], metavar="VAR=VALUE", help="fixed value of a variable")
    sw.add_argument("--speed-rpm", type=_finite("--speed-rpm"), default=None,
                    help="fixed speed when the grid does not vary speed_rpm [rpm]")
    sw.add_argument("--traction", choices=("lubricated", "coulomb", "kalker"), default=None)
    sw.add_argument("--mu", type=_finite("--mu"), default=None, help="ball-race friction coefficient [-]")
    sw.add_argument("--mu-cage", type=_finite("--mu-cage"), default=None, help="pocket/land friction coefficient [-]")
    sw.add_argument("--oil-fraction", type=_finite("--oil-fraction"), default=None,
                    help="oil volume fraction of the oil-air mixture [-]")
    sw.add_argument("--window-s", type=_finite("--window-s"), default=0.02, help="dynamic: window length [s]")
    sw.add_argument("--max-time-s", type=_finite("--max-time-s"), default=1.0, help="dynamic: longest run [s]")
    sw.add_argument("--steady-tol", type=_finite("--steady-tol"), default=2e-3,
                    help="dynamic: relative change between windows counted as steady [-]")
    sw.add_argument("--torque-tol", type=_finite("--torque-tol"), default=0.05,
                    help="dynamic: relative change of the window-mean friction torque counted as steady [-]")
    sw.add_argument("--start", choices=("jones-harris", "tribological"), default="jones-harris",
                    help="dynamic/profile: initial state")
    sw.add_argument("--integrator", choices=("adaptive", "implicit", "auto", "rk4"), default=None)
    sw.add_argument("--profile", default="seed000", help="profile model: 'seed000' or CSV time_s, speed_rpm")
    sw.add_argument("--fmu", default="dist/BearingFMU.fmu", help="fmu model: the FMU file")
    sw.add_argument("--skid-threshold", type=_finite("--skid-threshold"), default=0.05,
                    help="skidding when cage speed / pure-rolling cage speed < 1 - this [-]")
    sw.add_argument("--overskid-threshold", type=_finite("--overskid-threshold"), default=0.05,
                    help="over-skidding when cage speed / pure-rolling cage speed > 1 + this [-]")
    sw.add_argument("--min-preload", default=None, metavar="SPEEDS",
                    help="minimum-preload curve at these speeds [rpm]: START:STOP:NUM or A,B,C")
    sw.add_argument("--preload-range", default="1:5000", metavar="LO:HI", help="bisection bracket [N]")
    sw.add_argument("--preload-rtol", type=_finite("--preload-rtol"), default=0.02,
                    help="bisection ends when the bracket is narrower than this fraction [-]")
    sw.add_argument("--scheduler", default=None, metavar="ADDRESS", help="existing dask scheduler (tcp://host:port)")
    sw.add_argument("--workers", type=int, default=None, help="local cluster size (default: CPUs)")
    sw.add_argument("--retries", type=int, default=2, help="re-runs of a task whose worker failed")
    sw.add_argument("--batch-size", type=int, default=None,
                    help="points per Dask task (default: about 4 tasks per worker, at most 32 points; 1: one "
                         "task per point)")
    sw.add_argument("--threads-per-worker", type=int, default=1,
                    help="dynamic/profile: threads advancing a batch's points together in a worker (the local "
                         "cluster then starts CPUs / this many workers unless --workers is given)")
    sw.add_argument("--cache", default=None, help="cache folder (default OUT/sweep_cache)")
    sw.add_argument("--no-cache", action="store_true", help="neither read nor write the cache")
    sw.add_argument("--no-progress", action="store_true", help="no progress bar")
    sw.set_defaults(func=cmd_sweep)
    return sw


BUILD_MAP_EPILOG = """\
An operating map for the co-simulation's fidelity 'map' (docs/fidelity.md): the bearing's steady outputs (torque,
heat by source, cage speed, reactions, displacement, stiffness, contact angles and stresses, film parameter, skid
class, the cage speed's time constant) on a grid of speed_rpm, fx_N, fz_N (required) and optionally fy_N, my_Nm,
oil_temperature_C, written as NetCDF3 with provenance (bearing, oil, level, code version, grid).

levels (--level): dynamic (the dynamic model held at each point until steady, means of the last window; seconds
  per point), tribological (the quasi-static tribological model: free balls, centred cage; fast, no cage losses).
execution: as bearing sweep (Dask local cluster or --scheduler ADDRESS, --workers, cache in --cache for resume,
  progress bar).
example (7218B, oil-lubricated):
  bearing build-map --bearing 7218B --grid speed_rpm=500,1000,2000,4000,7000,12000 --grid fx_N=0,1500,3000 \\
      --grid fz_N=500,2000,5000,8000 --out maps/7218B_oil.nc
"""


def _add_build_map_parser(sub):
    bm = sub.add_parser("build-map", help="operating map of steady outputs over speed and loads for the 'map' "
                        "fidelity level (NetCDF, on Dask)", formatter_class=argparse.RawDescriptionHelpFormatter,
                        epilog=BUILD_MAP_EPILOG)
    bm.add_argument("--bearing", default="7218B", help="preset name or bearing JSON file")
    bm.add_argument("--grid", action="append", default=[], metavar="VAR=SPEC",
                    help="axis: speed_rpm, fx_N, fz_N (required), fy_N, my_Nm, oil_temperature_C; START:STOP:NUM or "
                         "A,B,C (repeatable)")
    bm.add_argument("--set", action="append", default=[], metavar="VAR=VALUE",
                    help="fixed sweep variable (traction, mu, mu_cage, oil, oil_fraction, oil_temperature_C, ...)")
    bm.add_argument("--traction", choices=("lubricated", "coulomb", "kalker"), default=None,
                    help="ball-race traction (lubricated: oil-lubricated; kalker / coulomb: solid-lubricated)")
    bm.add_argument("--level", choices=("dynamic", "tribological"), default="dynamic", help="steady level")
    bm.add_argument("--out", required=True, help="map file to write (.nc)")
    bm.add_argument("--window-s", type=_finite("--window-s"), default=0.04, help="dynamic: window length [s]")
    bm.add_argument("--max-time-s", type=_finite("--max-time-s"), default=1.0, help="dynamic: longest run [s]")
    bm.add_argument("--steady-tol", type=_finite("--steady-tol"), default=2e-3,
                    help="dynamic: relative change of the window-mean cage speed counted as steady [-]")
    bm.add_argument("--torque-tol", type=_finite("--torque-tol"), default=0.02,
                    help="dynamic: relative change of the window-mean friction torque counted as steady [-]")
    bm.add_argument("--integrator", choices=("adaptive", "implicit", "auto", "rk4"), default="auto")
    bm.add_argument("--scheduler", default=None, metavar="ADDRESS", help="existing dask scheduler (tcp://host:port)")
    bm.add_argument("--workers", type=int, default=None, help="local cluster size (default: CPUs)")
    bm.add_argument("--batch-size", type=int, default=None, help="points per Dask task (default: automatic)")
    bm.add_argument("--cache", default=None, help="cache folder (default: <out>_cache next to the map)")
    bm.add_argument("--no-cache", action="store_true", help="neither read nor write the cache")
    bm.add_argument("--no-progress", action="store_true", help="no progress bar")
    bm.set_defaults(func=cmd_build_map)
    return bm


def cmd_build_map(a) -> int:
    import time
    from .maps.build_map import build_map, map_summary, write_map
    from .maps.sweep import parse_assignment, parse_values
    from .errors import BearingInputError
    grid, base = {}, {"bearing": a.bearing}
    for s in a.grid:
        k, v = parse_assignment(s)
        if k in grid:
            raise BearingInputError("--grid", k, "each variable once")
        grid[k] = parse_values(k, v)
    for s in a.set:
        k, v = parse_assignment(s)
        vals = parse_values(k, v)
        if len(vals) != 1:
            raise BearingInputError(f"--set {k}", v, "one value")
        base[k] = vals[0]
    if a.traction:
        base["traction"] = a.traction
    if a.workers is not None and not 1 <= a.workers <= 512:
        raise _BadArg(f"--workers = {a.workers} is invalid; allowed: 1 <= workers <= 512")
    out = Path(a.out)
    out.parent.mkdir(parents=True, exist_ok=True)
    cache = None if a.no_cache else (Path(a.cache) if a.cache else out.with_name(out.stem + "_cache"))
    opts = dict(window_s=a.window_s, max_time_s=a.max_time_s, steady_tol=a.steady_tol, torque_tol=a.torque_tol,
                integrator=a.integrator)
    t0 = time.perf_counter()
    ds, df = build_map(grid, base, a.level, opts, command="bearing build-map " + " ".join(sys.argv[2:]),
                       cache_dir=cache, scheduler=a.scheduler, workers=a.workers, progress=not a.no_progress,
                       batch_size=a.batch_size)
    write_map(ds, out)
    wall = time.perf_counter() - t0
    n = int(df.attrs.get("computed", len(df)))
    print(f"wrote {out}: {map_summary(ds)}")
    print(f"{len(df)} points ({n} computed, {len(df) - n} from the cache) in {wall:.1f} s wall"
          + (f", {60.0 * n / wall:.1f} computed points per minute" if n else ""))
    for _, r in df[df["status"] != "ok"].head(5).iterrows():
        print(f"  point {r['point_index']} failed: {r['error']}")
    return 0


def sweep_spec_from_args(a):
    """SweepSpec of the `bearing sweep` arguments (validated later, before any work)."""
    from .maps.sweep import SweepSpec, parse_assignment, parse_values, read_points_csv, VARIABLES
    from .errors import BearingInputError
    base = {}
    if a.bearing is not None:
        base["bearing"] = a.bearing
    for nm, key in (("fx", "fx_N"), ("fy", "fy_N"), ("fz", "fz_N"), ("mx", "mx_Nm"), ("my", "my_Nm")):
        if getattr(a, nm) != 0.0:
            base[key] = getattr(a, nm)
    for nm, key in (("traction", "traction"), ("mu", "mu"), ("mu_cage", "mu_cage"), ("oil_fraction", "oil_fraction"),
                    ("speed_rpm", "speed_rpm")):
        if getattr(a, nm) is not None:
            base[key] = getattr(a, nm)
    for s in a.set:
        k, v = parse_assignment(s)
        vals = parse_values(k, v)
        if len(vals) != 1:
            raise BearingInputError(f"--set {k}", v, "one value")
        base[k] = vals[0]
    grid = {}
    for s in a.grid:
        k, v = parse_assignment(s)
        if k in grid:
            raise BearingInputError("--grid", k, "each variable once")
        grid[k] = parse_values(k, v)
    if a.points_file and grid:
        raise BearingInputError("--points-file", a.points_file, "either --grid or --points-file, not both")
    pts = read_points_csv(a.points_file) if a.points_file else None
    legacy = not grid and pts is None and a.min_preload is None
    if legacy:
        if not (0 <= a.speed_max_rpm <= 190000):
            raise _BadArg(f"--speed-max-rpm = {a.speed_max_rpm} is invalid; allowed: 0 <= value <= 190000 rpm")
        if not (2 <= a.points <= 1000):
            raise _BadArg(f"--points = {a.points} is invalid; allowed: 2 <= points <= 1000")
        grid = {"speed_rpm": np.linspace(0.0, a.speed_max_rpm, a.points).tolist()}
    for k in grid:
        if k in base:
            raise BearingInputError(k, base[k], "set either by --grid or as a fixed value, not both")
    opts = {}
    if a.model == "quasistatic":
        opts["control"] = a.control
    if a.model in ("dynamic", "fmu"):
        opts.update(window_s=a.window_s, max_time_s=a.max_time_s, steady_tol=a.steady_tol, torque_tol=a.torque_tol)
    if a.model in ("dynamic", "profile"):
        opts["start"] = a.start
        if a.integrator:
            opts["integrator"] = a.integrator
    if a.model == "profile":
        opts["profile"] = a.profile
    if a.model == "fmu":
        opts["fmu"] = str(Path(a.fmu).resolve())
    return SweepSpec(model=a.model, base=base, grid=grid, points_list=pts, options=opts), legacy


def cmd_sweep(a) -> int:
    from .maps.sweep import min_preload_curve, parse_values, plot_maps, plot_min_preload, run_sweep, write_results
    from .errors import check_range
    from .postprocess import write_csv, plot_quasistatic_sweep

    spec, legacy = sweep_spec_from_args(a)
    check_range("--skid-threshold", a.skid_threshold, 0.0, 1.0)
    check_range("--overskid-threshold", a.overskid_threshold, 0.0, 10.0)
    if a.workers is not None and not 1 <= a.workers <= 512:
        raise _BadArg(f"--workers = {a.workers} is invalid; allowed: 1 <= workers <= 512")
    if not 0 <= a.retries <= 20:
        raise _BadArg(f"--retries = {a.retries} is invalid; allowed: 0 <= retries <= 20")
    if a.batch_size is not None and not 1 <= a.batch_size <= 100000:
        raise _BadArg(f"--batch-size = {a.batch_size} is invalid; allowed: 1 <= batch size <= 100000")
    if not 1 <= a.threads_per_worker <= 512:
        raise _BadArg(f"--threads-per-worker = {a.threads_per_worker} is invalid; allowed: 1 <= threads <= 512")
    skid = (a.skid_threshold, a.overskid_threshold)
    out = Path(a.out)
    cache = None if a.no_cache else (Path(a.cache) if a.cache else out / "sweep_cache")
    run = dict(cache_dir=cache, scheduler=a.scheduler, workers=a.workers, retries=a.retries,
               progress=not a.no_progress, skid=skid)
    if a.min_preload is not None:
        speeds = parse_values("speed_rpm", a.min_preload)
        try:
            lo, hi = (float(x) for x in a.preload_range.split(":"))
        except ValueError:
            raise _BadArg(f"--preload-range = {a.preload_range!r} is invalid; allowed: LO:HI in N")
        df = min_preload_curve(spec, speeds, lo, hi, a.preload_rtol, **run)
        out.mkdir(parents=True, exist_ok=True)
        df.to_csv(out / "min_preload.csv", index=False)
        png = plot_min_preload(df, out / "min_preload.png",
                               title=f"{spec.model}, skidding when cage speed ratio < {1 - skid[0]:g}")
        print(f"wrote {out / 'min_preload.csv'} and {png}; {df.attrs['computed']} speeds computed, "
              f"{int((df['status'] != 'ok').sum())} not bracketed or failed")
        return 0
    df = run_sweep(spec, batch_size=a.batch_size, threads_per_worker=a.threads_per_worker, **run)
    paths = write_results(df, spec, out)
    paths += plot_maps(df, spec, out, skid=skid)
    nfail = int((df["status"] != "ok").sum())
    if legacy and spec.model == "quasistatic":
        keys = ("speed_rpm", "cage_speed_rpm", "cage_shaft_ratio", "alpha_i_deg", "alpha_o_deg", "Q_i_N", "Q_o_N",
                "omega_R_rpm", "spin_roll_i", "spin_roll_o", "p_max_i_Pa", "dz_m", "dx_m")
        ok = df[df["status"] == "ok"]
        if len(ok):
            from .maps.sweep import resolve_geometry
            name = resolve_geometry(spec.points()[0]).name
            rows = [{k: float(r[k]) for k in keys} for _, r in ok.iterrows()]
            loads = tuple(float(x) for x in (a.fx, a.fy, a.fz, a.mx, a.my))
            csv = write_csv(out / f"quasistatic_sweep_{name}.csv", rows)
            png = plot_quasistatic_sweep(rows, out / f"quasistatic_sweep_{name}.png", title=f"{name}, loads {loads}")
            paths = [csv, png] + paths
    print("wrote " + ", ".join(str(p) for p in paths))
    print(f"{len(df)} points ({df.attrs['computed']} computed, {len(df) - df.attrs['computed']} from the cache), "
          f"{nfail} failed")
    if nfail:
        for _, r in df[df["status"] != "ok"].head(5).iterrows():
            print(f"  point {r['point_index']} failed: {r['error']}")
    return 0


def cmd_dynamics(a) -> int:
    import time
    from pathlib import Path
    from .models.dynamics import DynamicModel, DynamicsOptions, records_to_dict, simulate_profile
    from .models.dynamics_kernels import OUT_NAMES
    from .bearing.geometry import load_preset
    from .postprocess import plot_dynamics, write_records_csv

    from .models.dynamics import read_profile
    t_prof, n_prof, prof_loads = read_profile(a.profile)
    prof_loads = dict(prof_loads or {})
    n_outer = prof_loads.pop("outer_speed_rpm", None)
    if prof_loads:
        raise _BadArg(f"--profile {a.profile}: load columns are read by 'bearing simulate'; here the loads "
                      "are --fx ... --my")
    prof = list(zip(t_prof.tolist(), n_prof.tolist()))
    if n_outer is not None:           # outer-ring speed [rpm], held over each segment
        prof = [(t, n, no) for (t, n), no in zip(prof, n_outer.tolist())]
    if not (1e-5 <= a.record_dt <= 1.0):
        raise _BadArg(f"--record-dt = {a.record_dt} is invalid; allowed: 1e-5 <= value <= 1 s")
    g = load_preset(a.bearing)
    opt = DynamicsOptions(traction=a.traction, mu=a.mu, mu_pocket=a.mu_cage, mu_land=a.mu_cage,
                          integrator=a.integrator, reduced=a.reduced, record_dt=a.record_dt,
                          lubrication=a.lubrication)
    m = DynamicModel(g, opt)
    loads = (a.fx, a.fy, a.fz, a.mx, a.my)
    m.initialize(prof[0][1] * RPM, loads, t0=prof[0][0], start=a.start,
                 **({"omega_outer": prof[0][2] * RPM} if n_outer is not None else {}))
    t0 = time.perf_counter()

    def progress(t, t_end):
        sys.stderr.write(f"\r  simulated {t:7.3f} / {t_end:.3f} s   wall {time.perf_counter() - t0:6.1f} s")
        sys.stderr.flush()

    rec = simulate_profile(m, prof, record_dt=a.record_dt, progress=progress)
    sys.stderr.write("\n")
    wall = time.perf_counter() - t0
    out = Path(a.out)
    out.mkdir(parents=True, exist_ok=True)
    stem = f"dynamics_{g.name}"
    csv_path = write_records_csv(out / f"{stem}.csv", rec, OUT_NAMES)
    png = plot_dynamics(records_to_dict(rec), out / f"{stem}.png",
                        title=f"{g.name}, loads {loads} N/N m, {a.traction} traction (mu {a.mu:g})")
    d = records_to_dict(rec)
    tail = d["t"] >= d["t"][-1] - 0.1
    summary = {
        "bearing": g.name, "loads": dict(zip(("Fx_N", "Fy_N", "Fz_N", "Mx_Nm", "My_Nm"), loads)),
        "traction": a.traction, "mu": a.mu, "integrator": a.integrator, "reduced_model": bool(m.axisym),
        "start": a.start,
        "simulated_s": float(d["t"][-1] - d["t"][0]), "wall_s": wall,
        "final_speed_rpm": float(d["shaft_speed"][-1] / RPM),
        "final_cage_speed_rpm": float(d["cage_speed"][tail].mean() / RPM),
        "final_pure_rolling_cage_speed_rpm": float(d["pure_rolling_cage_speed"][tail].mean() / RPM),
        "final_friction_torque_Nm": float(d["friction_torque"][tail].mean()),
        "final_reaction_N": {k: float(d[k][tail].mean()) for k in ("Fx", "Fy", "Fz")},
        "rhs_calls": int(m.stats[2]),
        "lubrication": opt.regime, "race_traction": opt.race_traction,
    }
    # kinematic reference at the loaded balls' contact angles and the skid classification (bearing_core.models.skid)
    from .models.skid import SKID_LABELS, SKID_TOL, classify_skid
    wo = float(d["cage_speed_pure_rolling_outer"][tail].mean())
    state, slip = classify_skid(summary["final_cage_speed_rpm"] * RPM, wo)
    summary.update({
        "final_cage_speed_pure_rolling_outer_rpm": wo / RPM,
        "final_cage_speed_pure_rolling_inner_rpm": float(d["cage_speed_pure_rolling_inner"][tail].mean() / RPM),
        "final_cage_slip_ratio": slip, "skid_state": state, "skid_label": SKID_LABELS[state],
        "skid_tolerance": SKID_TOL,
    })
    (out / f"{stem}_summary.json").write_text(json.dumps(summary, indent=1))
    print(f"wrote {csv_path}, {png} and {out / (stem + '_summary.json')}")
    print(f"final cage speed {summary['final_cage_speed_rpm']:.1f} rpm; pure rolling at the loaded balls' "
          f"angles {summary['final_cage_speed_pure_rolling_outer_rpm']:.1f} rpm (outer-raceway control) / "
          f"{summary['final_cage_speed_pure_rolling_inner_rpm']:.1f} rpm (inner); seed 000 Eq. 26 (spin-free, "
          f"mean angles) {summary['final_pure_rolling_cage_speed_rpm']:.1f} rpm")
    print(f"cage {summary['skid_label']} (slip {100 * slip:+.1f} % against outer-raceway control, tolerance "
          f"{100 * SKID_TOL:g} %), friction torque {summary['final_friction_torque_Nm']:.3f} N m; "
          f"{summary['simulated_s']:.3f} s simulated in {wall:.1f} s")
    return 0


def cmd_microslip(a) -> int:
    from pathlib import Path
    from .models.dynamics import DynamicModel, DynamicsOptions
    from .bearing.geometry import load_preset
    from .postprocess import microslip_map, plot_microslip

    if not (0.0 < a.time <= 10.0):
        raise _BadArg(f"--time = {a.time} is invalid; allowed: 0 < time <= 10 s")
    if not (0.0 <= a.mu <= 1.0):
        raise _BadArg(f"--mu = {a.mu} is invalid; allowed: 0 <= mu <= 1")
    if a.speed_rpm < 0:
        raise _BadArg(f"--speed-rpm = {a.speed_rpm} is invalid; allowed: >= 0 rpm")
    m = DynamicModel(load_preset(a.bearing), DynamicsOptions(traction=a.traction, mu=a.mu,
                                                             rtol=1e-6 if a.traction == "kalker" else 1e-4))
    m.initialize(a.speed_rpm * RPM, (a.fx, a.fy, a.fz, a.mx, a.my))
    m.advance(a.time)
    mp = microslip_map(m, a.ball, a.race)
    out = Path(a.out)
    out.mkdir(parents=True, exist_ok=True)
    png = plot_microslip(mp, out / f"microslip_{m.g.name}_{a.race}_ball{a.ball}.png")
    summary = {k: float(mp[k]) for k in ("a", "b", "Q", "vs_t", "vs_m", "spin", "u_roll", "F_t", "F_m", "M_n",
                                         "adhesion_fraction")}
    print(json.dumps(dict(summary, png=str(png))))
    return 0


def cmd_thermal(a) -> int:
    import math
    from .models.dynamics import DynamicModel, DynamicsOptions
    from .bearing.geometry import load_preset
    from .heat.thermal import ThermalData

    T_amb = a.ambient_c + 273.15
    T_in = (a.oil_inlet_c if a.oil_inlet_c is not None else a.ambient_c) + 273.15
    from .errors import BearingInputError
    from .lubrication.oil_supply import OilSupply
    from .heat.thermal import ThermalRunaway
    flow = a.oil_flow_lpm / 60000.0
    method = a.lubrication_method or ("jet" if flow > 0 else None)
    supply = None
    if a.bath_model is not None and method != "bath":
        raise BearingInputError("--bath-model", a.bath_model, "only with --lubrication-method bath")
    if method is not None:
        supply = OilSupply(method, flow, T_in, None if a.oil_level_mm is None else a.oil_level_mm * 1e-3,
                           bath_model=a.bath_model or "skf").validate()
    elif a.oil_level_mm is not None:
        raise BearingInputError("--oil-level-mm", a.oil_level_mm, "only with --lubrication-method bath")
    X = a.oil_fraction if a.oil_fraction is not None else (0.0 if supply is not None else 0.05)
    td = ThermalData(T_amb=T_amb, T_in=T_in, flow_rate=flow)
    opts = DynamicsOptions(oil=a.oil, oil_fraction=X, churning=not a.no_churning, thermal=True,
                           thermal_data=td, oil_temperature=T_in, lubrication=a.lubrication, oil_supply=supply)
    m = DynamicModel(load_preset(a.bearing), opts)
    m.initialize(a.speed_rpm * math.pi / 30, (a.fx, a.fy, a.fz, a.mx, a.my))
    cav = m.cavity_oil()
    oil_used = {"oil_fraction": m.oil_fraction_used(), "method": method or "none",
                "formula": cav.formula if cav is not None else "given (--oil-fraction)" if a.oil_fraction is not None
                else "default 0.05 (no oil supply given)",
                "extrapolated": bool(cav.extrapolated) if cav is not None else False,
                "note": cav.note if cav is not None else ""}
    try:
        r = m.thermal_equilibrium()
    except ThermalRunaway as e:
        if a.json:
            print(json.dumps({"bearing": a.bearing, "speed_rpm": a.speed_rpm, "thermal_runaway": True,
                              "temperatures_K": e.temperatures, "T_max_K": e.T_max, "oil": e.oil,
                              "node": e.node, "cause": e.cause, "cavity_oil": oil_used, "message": str(e)}))
        sys.stderr.write(f"bearing thermal: THERMAL RUNAWAY: {e}\n")
        return EXIT_THERMAL_RUNAWAY
    out = {"bearing": a.bearing, "speed_rpm": a.speed_rpm, "thermal_runaway": False, "loads_N": [a.fx, a.fy, a.fz],
           "moments_Nm": [a.mx, a.my], "oil": a.oil, "lubrication_method": method or "none",
           "oil_fraction": oil_used["oil_fraction"], "cavity_oil": oil_used,
           "ambient_temperature_K": T_amb, "oil_inlet_temperature_K": T_in,
           "oil_flow_m3_per_s": td.flow_rate,
           "temperatures_K": r["temperatures_K"],
           "cage_temperature_K": r["temperatures_K"]["oil"],       # cage and cavity oil are one node
           "heat_to_ambient_W": m.thermal.heat_to_ambient(), "heat_to_oil_flow_W": m.thermal.heat_to_oil_flow(), "losses_W": {k: float(v) for k, v in r["losses_W"].items()},
           "heat_generated_W": float(r["heat_generated_W"]), "heat_rejected_W": float(r["heat_rejected_W"]),
           "heat_balance": float(r["balance"]), "drive_power_W": r["drive_power_W"],
           "friction_torque_Nm": r["friction_torque_Nm"], "cage_speed_rpm": r["cage_speed_rad_s"] * 30 / math.pi,
           "iterations": r["iterations"]}
    film = m.film()
    out["film_min_inner_m"] = float(film["h_min_i"][film["h_min_i"] > 0].min()) if (film["h_min_i"] > 0).any() else 0.0
    out["film_min_outer_m"] = float(film["h_min_o"][film["h_min_o"] > 0].min()) if (film["h_min_o"] > 0).any() else 0.0
    out["film_parameter_min"] = film["Lambda_min"]
    if a.json:
        print(json.dumps(out))
    else:
        print(f"{a.bearing} at {a.speed_rpm:g} rpm, loads {out['loads_N']} N, oil {a.oil}, supply "
              f"{out['lubrication_method']} (cavity oil fraction {out['oil_fraction']:.3g}: {oil_used['formula']})")
        for k, v in r["temperatures_K"].items():
            print(f"  T_{k:6s} {v - 273.15:7.1f} degC" + ("  (oil and cage)" if k == "oil" else ""))
        for k, v in out["losses_W"].items():
            print(f"  {k:7s} {v:9.2f} W")
        print(f"  generated {out['heat_generated_W']:.2f} W, rejected {out['heat_rejected_W']:.2f} W "
              f"(ambient {out['heat_to_ambient_W']:.2f} W, oil flow {out['heat_to_oil_flow_W']:.2f} W) "
              f"(balance {out['heat_balance']:+.2e}); friction torque {out['friction_torque_Nm']:.4f} N m; "
              f"Lambda_min {out['film_parameter_min']:.2f}")
    return 0


def cmd_wear(a) -> int:
    from .models.wear import wear_report

    r = wear_report(a.bearing, a.speed_rpm, a.fx, a.fz, a.hours, fy=a.fy, mx=a.mx, my=a.my)
    if a.json:
        print(json.dumps(r, default=lambda o: o.tolist() if hasattr(o, "tolist") else str(o)))
    else:
        for k, v in r.items():
            if not isinstance(v, (list, tuple, dict)) and not hasattr(v, "__len__") or isinstance(v, str):
                print(f"{k:40s} {v}")
    return 0


def cmd_presets(a) -> int:
    from .bearing.geometry import list_presets, preset_data

    rows = [{"name": n, "source": preset_data(n).get("source", "")} for n in list_presets()]
    if a.json:
        print(json.dumps(rows))
    else:
        for r in rows:
            print(f"{r['name']:18s} {r['source']}")
    return 0


class _BadArg(Exception):
    pass


EXIT_THERMAL_RUNAWAY = 4   # exit status of 'bearing thermal' when the bearing runs away thermally


def main(argv=None) -> int:
    from .errors import BearingInputError, ConvergenceError

    parser = build_parser()
    a = parser.parse_args(argv)
    try:
        return a.func(a)
    except (BearingInputError, _BadArg) as e:
        sys.stderr.write(f"bearing {a.cmd}: error: {e}\n")
        return 2
    except ConvergenceError as e:
        sys.stderr.write(f"bearing {a.cmd}: solver failed: {e}\n")
        return 3


if __name__ == "__main__":
    sys.exit(main())
