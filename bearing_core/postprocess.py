"""Post-processing: CSV writing and plots (matplotlib, Agg backend, no display needed)."""
from __future__ import annotations

import csv
from pathlib import Path


def write_csv(path, rows: list[dict]):
    """Write a list of dicts (same keys) to CSV; column names carry their units."""
    path = Path(path)
    with path.open("w", newline="") as fh:
        w = csv.DictWriter(fh, fieldnames=list(rows[0].keys()))
        w.writeheader()
        w.writerows(rows)
    return path


def plot_quasistatic_sweep(rows: list[dict], path, title: str = ""):
    """Four panels over inner-ring speed: contact angles, contact loads, cage speed and ratio, spin-to-roll."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    n = [r["speed_rpm"] for r in rows]
    fig, ax = plt.subplots(2, 2, figsize=(10, 7), constrained_layout=True)
    ax[0, 0].plot(n, [r["alpha_i_deg"] for r in rows], label="inner")
    ax[0, 0].plot(n, [r["alpha_o_deg"] for r in rows], label="outer")
    ax[0, 0].set_ylabel("contact angle [deg]")
    ax[0, 1].plot(n, [r["Q_i_N"] for r in rows], label="inner")
    ax[0, 1].plot(n, [r["Q_o_N"] for r in rows], label="outer")
    ax[0, 1].set_ylabel("contact load, most loaded ball [N]")
    ax[1, 0].plot(n, [r["cage_speed_rpm"] for r in rows])
    ax[1, 0].set_ylabel("pure-rolling cage speed [rpm]")
    ax[1, 1].plot(n, [r["spin_roll_i"] for r in rows], label="inner")
    ax[1, 1].plot(n, [r["spin_roll_o"] for r in rows], label="outer")
    ax[1, 1].set_ylabel("spin-to-roll ratio [-]")
    for a in ax.flat:
        a.set_xlabel("inner-ring speed [rpm]")
        a.grid(True, alpha=0.3)
        if a.get_legend_handles_labels()[0]:
            a.legend()
    fig.suptitle(title)
    fig.savefig(path, dpi=110)
    plt.close(fig)
    return Path(path)


UNITS = {"t": "s", "shaft_speed": "rad/s", "shaft_accel": "rad/s2", "cage_speed": "rad/s", "cage_x": "m",
         "cage_y": "m", "Fx": "N", "Fy": "N", "Fz": "N", "Mx": "Nm", "My": "Nm", "ir_x": "m", "ir_y": "m",
         "ir_z": "m", "ir_tx": "rad", "ir_ty": "rad", "ir_vx": "m/s", "ir_vy": "m/s", "ir_vz": "m/s",
         "ir_ax": "m/s2", "ir_ay": "m/s2", "ir_az": "m/s2", "friction_torque": "Nm", "KE": "J",
         "U_elastic": "J", "alpha_i_mean": "rad", "alpha_o_mean": "rad", "Q_i_max": "N", "Q_o_max": "N",
         "Q_i_min": "N", "pure_rolling_cage_speed": "rad/s", "pure_rolling_cage_speed_jh": "rad/s",
         "ball0_wr": "rad/s", "ball0_wt": "rad/s", "ball0_wz": "rad/s", "ball0_orbit_speed": "rad/s",
         "ball0_alpha_i": "rad", "ball0_alpha_o": "rad", "ball0_Q_i": "N", "ball0_Q_o": "N",
         "ball0_Ft_i": "N", "ball0_Ft_o": "N", "p_max": "Pa"}


def unit_of(name: str) -> str:
    if name.startswith("P_"):
        return "W"
    return UNITS.get(name, "-")


def write_records_csv(path, rec, names):
    """Record array (rows = instants) to CSV with 'name [unit]' headers."""
    import numpy as np
    path = Path(path)
    header = ",".join(f"{n} [{unit_of(n)}]" for n in names)
    np.savetxt(path, rec, delimiter=",", header=header, comments="", fmt="%.9g")
    return path


def plot_dynamics(d: dict, path, title: str = ""):
    """Six panels over time: cage speed with its theoretical value, cage-shaft speed ratio, friction
    torque, dissipated power by source, reaction forces, ball 0 angular velocity (seed 000 Figs. 7-10)."""
    import math
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    import numpy as np

    t = d["t"]
    rpm = 30.0 / math.pi
    fig, ax = plt.subplots(3, 2, figsize=(12, 10), constrained_layout=True)
    a = ax[0, 0]
    a.plot(t, d["shaft_speed"] * rpm, label="shaft")
    a.plot(t, d["cage_speed"] * rpm, label="cage")
    a.plot(t, d["pure_rolling_cage_speed"] * rpm, "--", label="seed 000 Eq. 26 (spin-free, mean angles)")
    if "cage_speed_pure_rolling_outer" in d:    # raceway-control pure rolling at the balls' angles (skid.py)
        a.plot(t, d["cage_speed_pure_rolling_outer"] * rpm, "-.", label="pure rolling, outer-raceway control")
        a.plot(t, d["cage_speed_pure_rolling_inner"] * rpm, ":", label="pure rolling, inner-raceway control")
    a.set_ylabel("speed [rpm]")
    a = ax[0, 1]
    # ratios to the signed shaft speed; a gap in the curve below 1 rad/s (at rest or through zero: 0/0)
    w = np.where(np.abs(d["shaft_speed"]) >= 1.0, d["shaft_speed"], np.nan)
    a.plot(t, d["cage_speed"] / w, label="CSR")
    a.plot(t, d["pure_rolling_cage_speed"] / w, "--", label="seed 000 Eq. 26 CSR")
    if "cage_speed_pure_rolling_outer" in d:
        a.plot(t, d["cage_speed_pure_rolling_outer"] / w, "-.", label="outer-raceway control CSR")
    a.set_ylabel("cage / shaft speed [-]")
    a = ax[1, 0]
    a.plot(t, d["friction_torque"])
    a.set_ylabel("friction torque [N m]")
    a = ax[1, 1]
    for k, lab in (("P_race_inner", "ball-inner race"), ("P_race_outer", "ball-outer race"),
                   ("P_pocket", "ball-pocket"), ("P_land", "cage-land"), ("P_drag", "drag"),
                   ("P_damping", "contact damping")):
        a.plot(t, d[k], label=lab)
    a.plot(t, d["P_drive"], "k:", label="drive power")
    a.set_ylabel("heat flux by source [W]")
    a = ax[2, 0]
    for k in ("Fx", "Fy", "Fz"):
        a.plot(t, -d[k], label=f"-{k} (balls on ring)")
    a.set_ylabel("bearing reaction [N]")
    a = ax[2, 1]
    for k, lab in (("ball0_wr", "omega_r"), ("ball0_wt", "omega_t"), ("ball0_wz", "omega_z")):
        a.plot(t, d[k] * rpm, label=lab)
    a.set_ylabel("ball 0 angular velocity [rpm]")
    for a in ax.flat:
        a.set_xlabel("time [s]")
        a.grid(True, alpha=0.3)
        if a.get_legend_handles_labels()[0]:
            a.legend(fontsize=8)
    fig.suptitle(title)
    fig.savefig(path, dpi=100)
    plt.close(fig)
    return Path(path)


def microslip_map(model, ball: int = 0, race: str = "inner", n: int = 40, mu: float | None = None) -> dict:
    """Kalker/FASTSIM adhesion-slip map of one ball-race contact at the model's current state (seed 000
    Fig. 11): contact semi-axes and load from the dynamics, creepages and spin from its contact kinematics,
    friction limit mu (default options.mu), Hertz pressure bound. Returns fastsim_map's dict plus a, b, Q [m, N],
    the slips and 'adhesion_fraction'."""
    import numpy as np
    from .errors import BearingInputError
    from .contact.fastsim import PRESSURE_HERTZ, combined_elastic, fastsim_map

    if race not in ("inner", "outer"):
        raise BearingInputError("race", race, "inner | outer")
    d = model.ball_details()
    nb = len(d["Q_i"])
    if not (isinstance(ball, int) and 0 <= ball < nb):
        raise BearingInputError("ball", ball, f"integer 0..{nb - 1}")
    k = "i" if race == "inner" else "o"
    g = model.g
    G, nu = combined_elastic(g.ring_material.E, g.ring_material.nu, g.ball_material.E, g.ball_material.nu)
    sign = 1.0 if race == "inner" else -1.0    # entrainment direction at the inner / outer race (omega > 0)
    a, b, Q = d[f"a_{k}"][ball], d[f"b_{k}"][ball], d[f"Q_{k}"][ball]
    vs_t, vs_m, w = d[f"slip_{k}"][ball], d[f"slip_m_{k}"][ball], d[f"spin_{k}"][ball]
    u = sign * d[f"u_{k}"][ball]
    out = fastsim_map(a, b, Q, model.opt.mu if mu is None else mu, G, nu, vs_t, vs_m, w, u, n, n, PRESSURE_HERTZ)
    inside = (out["T"] / max(b, 1e-300)) ** 2 + (out["M"] / max(a, 1e-300)) ** 2 <= 1.0
    out.update(a=a, b=b, Q=Q, vs_t=vs_t, vs_m=vs_m, spin=w, u_roll=u, race=race, ball=ball,
               adhesion_fraction=float(np.mean(~out["slip"][inside])) if inside.any() else 0.0)
    return out


def plot_microslip(mp: dict, path, title: str = ""):
    """Contact ellipse with slip arrows (direction of the local slip, opposite to the shear on the ball)
    in the slip zone and the adhesion zone left blank (seed 000 Fig. 11)."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    import numpy as np

    a, b = mp["a"], mp["b"]
    fig, ax = plt.subplots(figsize=(6.5, 6), constrained_layout=True)
    th = np.linspace(0, 2 * np.pi, 200)
    ax.plot(np.cos(th), np.sin(th), "k-", lw=1)       # ellipse in coordinates normalised by a and b
    s = mp["slip"].copy()
    s[::2, :] = False                                   # every other row of arrows, for legibility
    s[:, ::2] = False
    mag = np.hypot(mp["Tm"] / a, mp["Tt"] / b)
    ok = s & (mag > 0)
    if ok.any():
        ax.quiver(mp["M"][ok] / a, mp["T"][ok] / b, -mp["Tm"][ok] / a / mag[ok], -mp["Tt"][ok] / b / mag[ok],
                  color="tab:red", scale=30, width=0.004)
    ax.set_aspect("equal")
    ax.set_xlabel(f"across the groove x / a  (a = {a * 1e3:.3f} mm)")
    ax.set_ylabel(f"rolling direction y / b  (b = {b * 1e3:.3f} mm)")
    ax.set_title(title or (f"{mp['race']} contact, ball {mp['ball']}: Q = {mp['Q']:.0f} N\nadhesion "
                           f"{100 * mp['adhesion_fraction']:.0f}% (blank), slip direction arrows"))
    fig.savefig(path, dpi=110)
    plt.close(fig)
    return Path(path)
