"""Seed 000 Table 3: what sets our inner-ring vibration floor at 100 % MOL, against the quasi-static
varying-compliance (VC) vibration and the paper's numbers (0.022 / 0.141 at 100 % MOL, no unit given).

7218B at 10,000 rpm (the end of the seed 000 ramp), MOL from the validation loads (Fr 20 kN, Fa 40 kN)
and the Fx 1 kN / Fz 3 kN set of docs/kalker.md:

  vc       quasi-static VC vibration: the Jones-Harris equilibrium solved with the ball set turned through
           one ball spacing (16 positions); x(phi) turned into an acceleration at the ball-pass rate,
           a = d2x/dt2 with phi = omega_cage t (Fourier series). This is the ring vibration a model
           makes with no dynamics other than the balls passing (no impacts, no ring resonance).
  fn       natural frequency of the inner ring on its balls, sqrt(K_xx / m_ring) / 2 pi, K_xx from the
           quasi-static stiffness matrix.
  steady   the dynamics held at 10,000 rpm from the tribological quasi-static start: peak and RMS of
           a_x over 0.1-0.2 s, the force that RMS means on the ring (m_ring a_rms), and where the
           spectrum has its energy; for Kalker / Coulomb / lubricated traction and more contact damping.
           At 25 % MOL (no quasi-static equilibrium with Fr tan(alpha0) > Fa) the run starts from the
           50 % MOL equilibrium and the axial load is stepped down at t = 0. Where the tribological
           start does not converge the run starts from Jones-Harris (the "start" key says which).

    python studies/seed000_table3_floor.py [--quick]

Writes docs/figures/seed000_table3_floor.json and docs/figures/seed000_table3_floor_psd.png.
One process, about 4 min (--quick: VC only and one 0.05 s run).
"""
from __future__ import annotations

import argparse
import json
import math
import time
from pathlib import Path

import numpy as np
from scipy import signal

from bearing_core.models.dynamics import DynamicModel, DynamicsOptions, records_to_dict
from bearing_core.errors import ConvergenceError
from bearing_core.bearing.geometry import load_preset
from bearing_core.models.quasistatic import QuasiStaticModel

RPM = math.pi / 30
ROOT = Path(__file__).resolve().parents[1]
SPEED = 10000 * RPM
PAPER_TABLE3 = {"mu0.001": {"25%": 11.620, "50%": 0.042, "100%": 0.022},
                "mu0.1": {"25%": 10.498, "50%": 1.088, "100%": 0.141}}
LOADS = {"V 100% (Fr 20 kN, Fa 40 kN)": (20000.0, 40000.0), "V 50%": (20000.0, 20000.0),
         "V 25%": (20000.0, 10000.0), "K 100% (Fx 1 kN, Fz 3 kN)": (1000.0, 3000.0),
         "K 50%": (1000.0, 1500.0), "K 25%": (1000.0, 750.0)}


def vc_vibration(g, fr, fa, fixed_tilt, npos=16):
    """Quasi-static VC vibration [m/s^2]: equilibria with the ball set at npos positions over one ball
    spacing; returns peak |a_x|, peak-to-peak x [m], cage speed [rad/s], K_xx [N/m] (or None: no equilibrium)."""
    m = QuasiStaticModel(g, "outer", fixed_tilt=fixed_tilt)
    base = m.psi.copy()
    xs, u0, r = [], None, None
    try:
        r0 = m.solve(SPEED, (fr, 0.0, fa, 0.0, 0.0), stiffness=True)
        kxx = float(r0.stiffness[0, 0])
        for k in range(npos):
            m.psi = base + 2 * np.pi / g.Z * k / npos
            r = m.solve(SPEED, (fr, 0.0, fa, 0.0, 0.0), u0=u0, stiffness=False)
            u0 = r.u.copy()
            xs.append(r.u[0])
    except ConvergenceError as e:
        return {"error": f"no quasi-static equilibrium ({e})"[:200]}
    xs = np.array(xs)
    wc = r.cage_speed
    X = np.fft.rfft(xs)
    h = np.arange(X.size)
    acc = np.fft.irfft(-(g.Z * wc * h) ** 2 * X, npos)      # x(phi(t)), phi = wc t, period 2 pi / Z
    return {"peak_abs_ax_m_s2": float(np.abs(acc).max()), "ptp_x_nm": float(np.ptp(xs) * 1e9),
            "cage_rpm": wc / RPM, "ball_pass_Hz": g.Z * wc / (2 * np.pi), "K_xx_N_per_m": kxx,
            "fn_ring_on_balls_Hz": math.sqrt(kxx / g.inner_ring_mass) / (2 * np.pi), "min_Q_i_N": float(r.Q_i.min())}


def steady(g, fr, fa, t_end=0.2, start_fa=None, **kw):
    o = DynamicsOptions(**{"traction": "kalker", "mu": 0.001, "mu_pocket": 0.001, "mu_land": 0.001,
                           "reduced": "full", "integrator": "auto", **kw})
    m = DynamicModel(g, o)
    start = "tribological"
    try:
        m.initialize(SPEED, (fr, 0.0, start_fa or fa, 0.0, 0.0), start=start)
    except ConvergenceError:      # outside the tribological model's convergence domain (bench_tribo_qs)
        start = "jones-harris"
        m.initialize(SPEED, (fr, 0.0, start_fa or fa, 0.0, 0.0), start=start)
    if start_fa:
        m.set_inputs(loads=(fr, 0.0, fa, 0.0, 0.0))
    t0 = time.perf_counter()
    d = records_to_dict(m.advance(t_end, record_dt=1e-5))
    wall = time.perf_counter() - t0
    w = d["t"] >= t_end / 2
    a = d["ir_ax"][w] - d["ir_ax"][w].mean()
    f, P = signal.welch(a, fs=1e5, nperseg=min(4096, a.size))
    band = {f"{lo}-{hi} Hz": float(P[(f >= lo) & (f < hi)].sum() / P.sum())
            for lo, hi in ((0, 1000), (1000, 3000), (3000, 6000), (6000, 50000))}
    return {"peak_abs_ax_m_s2": float(np.abs(a).max()), "rms_ax_m_s2": float(a.std()),
            "rms_force_N": float(a.std() * g.inner_ring_mass), "psd_peak_Hz": float(f[np.argmax(P)]),
            "psd_share": band, "min_Q_i_N": float(d["Q_i_min"][w].min()),
            "inner_open_share_ball0": float(np.mean(d["ball0_Q_i"][w] <= 0.0)), "wall_s": wall,
            "window_s": [t_end / 2, t_end], "start": start, "options": kw}, (f, P)


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--quick", action="store_true")
    ap.add_argument("--out", default=str(ROOT / "docs" / "figures"))
    a = ap.parse_args(argv)
    g = load_preset("7218B")
    res = {"paper_table3": PAPER_TABLE3, "inner_ring_mass_kg": g.inner_ring_mass, "speed_rpm": 10000, "vc": {}}
    for name, (fr, fa) in LOADS.items():
        for tilt in (False, True):
            key = f"{name}, {'tilt held' if tilt else 'free tilt'}"
            res["vc"][key] = vc_vibration(g, fr, fa, tilt)
            print(key, json.dumps(res["vc"][key]), flush=True)
    MU01 = {"mu": 0.1, "mu_pocket": 0.1, "mu_land": 0.1}
    runs = [("V 100%, kalker", 20000.0, 40000.0, None, {}),
            ("V 100%, coulomb", 20000.0, 40000.0, None, {"traction": "coulomb"}),
            ("V 100%, lubricated", 20000.0, 40000.0, None, {"traction": "lubricated"}),
            ("V 100%, kalker, zeta 0.2", 20000.0, 40000.0, None, {"zeta": 0.2}),
            ("V 100%, kalker mu 0.1", 20000.0, 40000.0, None, MU01),
            ("V 50%, kalker", 20000.0, 20000.0, None, {}),
            ("V 25%, kalker", 20000.0, 10000.0, 20000.0, {}),
            ("K 100%, kalker", 1000.0, 3000.0, None, {}),
            ("K 50%, kalker", 1000.0, 1500.0, None, {}),
            ("K 25%, kalker", 1000.0, 750.0, 1500.0, {}),
            ("K 100%, kalker mu 0.1", 1000.0, 3000.0, None, MU01),
            ("K 50%, kalker mu 0.1", 1000.0, 1500.0, None, MU01),
            ("K 25%, kalker mu 0.1", 1000.0, 750.0, 1500.0, MU01)]
    if a.quick:
        runs = runs[:1]
    res["steady"], psd = {}, {}
    for name, fr, fa, sfa, kw in runs:
        try:
            res["steady"][name], psd[name] = steady(g, fr, fa, 0.05 if a.quick else 0.2, sfa, **kw)
        except (ConvergenceError, FloatingPointError) as e:
            res["steady"][name] = {"error": f"{type(e).__name__}: {e}"[:300]}
        print(name, json.dumps(res["steady"][name]), flush=True)
    out = Path(a.out)
    out.mkdir(parents=True, exist_ok=True)
    (out / "seed000_table3_floor.json").write_text(json.dumps(res, indent=1))
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(figsize=(8, 4.5), constrained_layout=True)
    for name, (f, P) in psd.items():
        ax.semilogy(f / 1e3, P, lw=0.8, label=name)
    fn = res["vc"]["V 100% (Fr 20 kN, Fa 40 kN), free tilt"].get("fn_ring_on_balls_Hz")
    if fn:
        ax.axvline(fn / 1e3, color="k", ls=":", lw=1, label=f"ring on balls, QS: {fn:.0f} Hz (V 100%)")
    ax.set_xlim(0, 10)
    ax.set_xlabel("frequency [kHz]")
    ax.set_ylabel("PSD of inner-ring a_x [(m/s2)^2/Hz]")
    ax.set_title("7218B held at 10,000 rpm: inner-ring x acceleration (0.1-0.2 s)")
    ax.grid(alpha=0.3, which="both")
    ax.legend(fontsize=7)
    fig.savefig(out / "seed000_table3_floor_psd.png", dpi=90)
    plt.close(fig)


if __name__ == "__main__":
    main()
