"""A rigid rotor on two bearing FMUs (displacement coupling) at 1 ms communication steps: the explicit exchange of
poses and reactions against a linear-implicit master that uses the bearings' Jacobian (fmi2GetDirectionalDerivative),
both against a reference at 1e-5 s steps.

    python ssp_examples/rotor_bearings/jacobian_master.py [--fmu dist/BearingFMU.fmu] [--t-end 0.1] \
        [--out ssp_examples/rotor_bearings/jacobian_coupling]          # -> .json; the plot: --plot
        [--plot docs/figures/jacobian_coupling.png]

The system. A rigid steel rotor, mass m = 5 kg, transverse moment of inertia It = 0.02 kg m^2 about its centre of
mass, polar Ip = 0.004 kg m^2, turning at Omega = 3000 rpm about +z, on two 7218B bearings (BearingFMU.fmu, fidelity
quasi-static, coupling displacement) at z_A = -0.075 m and z_B = +0.075 m from the centre of mass, both mounted the
same way round. The rotor's axial position is held (by a thrust bearing not modelled here): each bearing is held at
the axial pose of a 3000 N preload (the Jones-Harris pose of Fz = 3000 N, bearing_core.models.quasistatic) and the
rotor moves laterally and tilts: generalised coordinates q = (x, y, tx, ty) [m, m, rad, rad] of its centre of mass.
Bearing b sees the pose p_b = p0 + T_b q with (rigid body, small angles)

    dx = x + z_b ty,  dy = y - z_b tx,  dz = 0,  tx = tx,  ty = ty         (T_b: 5 x 4)

and returns its reaction R_b (Fx, Fy, Fz, Mx, My on the shaft), whose generalised forces are T_b^T R_b (virtual work:
the moment of the forces about the centre of mass is added to the bearing's own moment). Equations of motion
(Jeffcott-type rigid rotor, Genta, Dynamics of Rotating Systems, 2005, Ch. 4):

    M q'' + (C + Omega G) q' = sum_b T_b^T R_b(p_b) + f(t),
    M = diag(m, m, It, It), G: Ip on the tilts (It tx'' + Ip Omega ty' = Mx, It ty'' - Ip Omega tx' = My),
    f = (m e Omega^2 cos Omega t, m e Omega^2 sin Omega t - m g, 0, 0)   (static unbalance e = 20 um, gravity -y),

C: viscous damping of 2 % of critical on each rigid-body mode of the bearings' initial stiffness (external dampers;
the quasi-static bearing has no damping). The bearings' stiffness, dR_b/dp_b = -K_b (K_b = stiffness[i,j] of the
FMU, 1.5-2.5e8 N/m radially), makes the translational modes about 8000 rad/s: at h = 1 ms, omega h = 8.

Masters (one communication step h, inputs held over it; rotor integrated by the master):
  explicit    the pose of the rotor at t_n is sent, the bearings step, the rotor advances with their reactions
              held (symplectic Euler: v+ = v + h M^-1 (Q_n + f_n - (C + Omega G) v), q+ = q + h v+). Stable only
              for omega h < 2 (about 2.5e-4 s here);
  jacobian    the same exchange with the reactions extrapolated to the end of the step through the bearings'
              Jacobian J = -sum_b T_b^T K_b T_b (fmi2GetDirectionalDerivative of reaction_Fx..My in dx..ty at every
              communication point): the linear-implicit Euler step
              (M + h (C + Omega G) - h^2 J) v+ = M v + h (Q_n + f_{n+1}),  q+ = q + h v+,
              stable at any h for a positive definite stiffness (no new bearing call within the step).
  reference   explicit at h = 1e-5 s (omega h = 0.08).
Compared: the disk orbit x(t), y(t) and the bearing A reaction Fx over the last half of the run (the forced
response, after the start transient has decayed), the rms difference to the reference.
"""
from __future__ import annotations

import argparse
import json
import math
import sys
import time
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
ROOT = HERE.parents[1]
RPM = math.pi / 30.0

M_ROTOR, IT, IP = 5.0, 0.02, 0.004            # kg, kg m^2, kg m^2
Z_B = (-0.075, 0.075)                          # m, bearings A and B from the centre of mass
SPEED = 3000.0 * RPM                           # rad/s
ECC, G0 = 20e-6, 9.81                          # m, m/s^2
PRELOAD = 3000.0                               # N, each bearing's axial load at its held axial pose
ZETA = 0.02
POSE = ("dx", "dy", "dz", "tx", "ty")
RATES = ("vx", "vy", "vz", "wx", "wy")
REACTIONS = ("reaction_Fx", "reaction_Fy", "reaction_Fz", "reaction_Mx", "reaction_My")


def t_matrix(zb: float) -> np.ndarray:
    """T_b (5 x 4): bearing pose (dx, dy, dz, tx, ty) per rotor coordinate (x, y, tx, ty) [m/m, m/rad, rad/rad]."""
    T = np.zeros((5, 4))
    T[0, 0], T[0, 3] = 1.0, zb
    T[1, 1], T[1, 2] = 1.0, -zb
    T[3, 2] = T[4, 3] = 1.0
    return T


class Bearing:
    """One BearingFMU instance (fmpy FMU2Slave) at fidelity quasi-static, coupling displacement."""

    def __init__(self, fmu: str, unzip: str, md, name: str, p0: np.ndarray):
        from fmpy.fmi2 import FMU2Slave
        self.vr = {v.name: v.valueReference for v in md.modelVariables}
        self.p0 = p0
        f = FMU2Slave(guid=md.guid, unzipDirectory=unzip, modelIdentifier=md.coSimulation.modelIdentifier,
                      instanceName=name)
        f.instantiate()
        f.setupExperiment(startTime=0.0)
        f.setString([self.vr["fidelity"], self.vr["coupling"]], ["quasi-static", "displacement"])
        f.enterInitializationMode()
        f.setReal([self.vr["shaft_speed"]] + [self.vr[k] for k in POSE], [SPEED] + p0.tolist())
        f.exitInitializationMode()
        self.f = f
        self._in = [self.vr[k] for k in POSE + RATES]
        self._out = [self.vr[k] for k in REACTIONS]
        self._pose = [self.vr[k] for k in POSE]

    def step(self, t: float, h: float, pose: np.ndarray, rate: np.ndarray) -> np.ndarray:
        """Send the pose and its rate, step [t, t + h]; the reaction (5) at t + h."""
        self.f.setReal(self._in, pose.tolist() + rate.tolist())
        self.f.doStep(currentCommunicationPoint=t, communicationStepSize=h)
        return np.array(self.f.getReal(self._out))

    def jacobian(self) -> np.ndarray:
        """d reaction / d pose (5 x 5) at the last communication point: fmi2GetDirectionalDerivative, one seed
        direction per pose coordinate (= -stiffness)."""
        J = np.empty((5, 5))
        for j, vr in enumerate(self._pose):
            J[:, j] = self.f.getDirectionalDerivative(self._out, [vr], [1.0])
        return J

    def close(self):
        try:
            self.f.terminate()
        except Exception:         # an instance that refused a step is in the error state: freed all the same
            pass
        self.f.freeInstance()


def run(fmu: str, h: float, t_end: float, scheme: str, blowup: float = 1e-3) -> dict:
    """One run of the master ('explicit' or 'jacobian'); returns its time series and wall time. A run whose rotor
    leaves |q| < blowup [m] (or whose bearing refuses a step) stops there: 'diverged_at' [s]."""
    from fmpy import extract, read_model_description
    from bearing_core.bearing.geometry import load_preset
    from bearing_core.models.quasistatic import QuasiStaticModel
    md = read_model_description(fmu)
    unzip = extract(fmu)
    g = load_preset("7218B")
    p0 = np.asarray(QuasiStaticModel(g, "outer").solve(SPEED, (0.0, 0.0, PRELOAD, 0.0, 0.0), stiffness=False).u,
                    dtype=float)
    bearings = [Bearing(fmu, unzip, md, f"bearing_{c}", p0) for c in "AB"]
    Ts = [t_matrix(z) for z in Z_B]
    Mm = np.diag([M_ROTOR, M_ROTOR, IT, IT])
    Gm = np.zeros((4, 4))
    Gm[2, 3], Gm[3, 2] = IP, -IP
    q = np.zeros(4)
    v = np.zeros(4)
    # the external dampers: 2 % of critical on the rigid-body modes of the initial stiffness
    # (modes of the symmetric part of the stiffness, mass-normalised: V^T M V = I, C = M V diag(2 zeta w) V^T M)
    from scipy.linalg import eigh
    K0 = sum(T.T @ -b.jacobian() @ T for b, T in zip(bearings, Ts))
    w2, V = eigh(0.5 * (K0 + K0.T), Mm)
    Cm = Mm @ V @ np.diag(2.0 * ZETA * np.sqrt(np.abs(w2))) @ V.T @ Mm
    A_damp = Cm + SPEED * Gm
    n = int(round(t_end / h))
    rec_every = max(1, int(round(1e-4 / h)))          # record every 0.1 ms (the 1 ms runs: every step)
    ts, qs, fa = [], [], []
    diverged = None
    t = 0.0
    w0 = time.perf_counter()
    try:
        R = [b.step(0.0, h, p0, np.zeros(5)) for b in bearings]     # reactions of the start pose
        t = h
        # (the first exchange: the start pose's reactions; the rotor starts at rest there)
        for k in range(1, n):
            def fext(tt):
                u = M_ROTOR * ECC * SPEED ** 2
                return np.array([u * math.cos(SPEED * tt), u * math.sin(SPEED * tt) - M_ROTOR * G0, 0.0, 0.0])
            Q = sum(T.T @ r for T, r in zip(Ts, R))
            if scheme == "explicit":
                v = v + h * np.linalg.solve(Mm, Q + fext(t) - A_damp @ v)
            else:
                J = sum(T.T @ b.jacobian() @ T for b, T in zip(bearings, Ts))
                v = np.linalg.solve(Mm + h * A_damp - h * h * J, Mm @ v + h * (Q + fext(t + h)))
            q = q + h * v
            if not np.all(np.abs(q[:2]) < blowup) or not np.all(np.isfinite(q)):
                diverged = t + h
                break
            R = [b.step(t, h, p0 + T @ q, T @ v) for b, T in zip(bearings, Ts)]
            t += h
            if k % rec_every == 0:
                ts.append(t)
                qs.append(q.copy())
                fa.append(R[0][0])
    except Exception as e:          # a bearing refusing the pose (contact pressure beyond the static limit ...)
        diverged = t
        print(f"{scheme} h={h:g}: stopped at t = {t:.6g} s: {type(e).__name__}: {str(e)[:200]}", file=sys.stderr)
    finally:
        for b in bearings:
            b.close()
    return {"scheme": scheme, "h": h, "t": np.array(ts), "q": np.array(qs).reshape(-1, 4), "Fx_A": np.array(fa),
            "wall_s": time.perf_counter() - w0, "diverged_at": diverged,
            "mode_frequencies_rad_s": sorted(np.sqrt(np.abs(w2)).tolist())}


def compare(run_: dict, ref: dict, t0: float) -> dict:
    """rms differences to the reference over t >= t0 (the reference interpolated at the run's instants)."""
    if run_["diverged_at"] is not None or len(run_["t"]) == 0:
        return {"diverged_at_s": run_["diverged_at"]}
    sel = run_["t"] >= t0
    out = {}
    for name, a, b in (("x", run_["q"][:, 0], ref["q"][:, 0]), ("y", run_["q"][:, 1], ref["q"][:, 1]),
                       ("Fx_A", run_["Fx_A"], ref["Fx_A"])):
        rb = np.interp(run_["t"][sel], ref["t"], b)
        amp = 0.5 * (rb.max() - rb.min())
        out[f"{name}_rms_diff"] = float(np.sqrt(np.mean((a[sel] - rb) ** 2)))
        out[f"{name}_ref_half_range"] = float(amp)
    return out


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--fmu", default=str(ROOT / "dist" / "BearingFMU.fmu"))
    ap.add_argument("--t-end", type=float, default=0.1)
    ap.add_argument("--out", default=str(HERE / "jacobian_coupling"))
    ap.add_argument("--plot", default=str(HERE.parents[1] / "docs" / "figures" / "jacobian_coupling.png"),
                    help="the plot (PNG; the manual shows docs/figures/jacobian_coupling.png)")
    ap.add_argument("--explicit-steps", default="1e-3,5e-4,2.5e-4,1.25e-4",
                    help="communication steps of the explicit runs [s], comma-separated")
    a = ap.parse_args(argv)
    if not 1e-3 <= a.t_end <= 10.0:
        ap.error(f"--t-end {a.t_end}: allowed 1e-3 <= value <= 10 s")
    if not Path(a.fmu).is_file():
        sys.path.insert(0, str(ROOT))
        from build_fmu import build
        a.fmu = str(build(Path(a.fmu).parent))
    runs = {"reference": run(a.fmu, 1e-5, a.t_end, "explicit"), "jacobian_1ms": run(a.fmu, 1e-3, a.t_end, "jacobian")}
    for hs in a.explicit_steps.split(","):
        h = float(hs)
        runs[f"explicit_{h:g}"] = run(a.fmu, h, a.t_end, "explicit")
    ref = runs["reference"]
    t0 = 0.5 * a.t_end
    summary = {"t_end_s": a.t_end, "compared_from_s": t0,
               "mode_frequencies_rad_s": ref["mode_frequencies_rad_s"], "runs": {}}
    for k, r in runs.items():
        summary["runs"][k] = {"h_s": r["h"], "scheme": r["scheme"], "wall_s": round(r["wall_s"], 3),
                              "diverged_at_s": r["diverged_at"], **(compare(r, ref, t0) if k != "reference" else {})}
    out = Path(a.out)
    out.parent.mkdir(parents=True, exist_ok=True)
    out.with_suffix(".json").write_text(json.dumps(summary, indent=1))
    print(json.dumps(summary, indent=1))
    plot(runs, Path(a.plot), t0)


def plot(runs: dict, path: Path, t0: float):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(3, 1, figsize=(9, 9.5))
    ref = runs["reference"]
    styles = {"reference": dict(color="k", lw=1.0, label="reference, explicit, h = 1e-5 s"),
              "jacobian_1ms": dict(color="tab:blue", lw=0, marker="o", ms=3.5,
                                   label="Jacobian (linear-implicit), h = 1 ms")}
    colors = iter(["tab:red", "tab:orange", "tab:green", "tab:purple"])
    for k, r in runs.items():
        if k.startswith("explicit"):
            lab = f"explicit, h = {r['h'] * 1e3:g} ms" + (
                f" (diverged at {r['diverged_at'] * 1e3:.3g} ms)" if r["diverged_at"] is not None else "")
            styles[k] = dict(color=next(colors), lw=0.9, ls="--", label=lab)
    for k, r in runs.items():
        if len(r["t"]) == 0:
            ax[0].plot([], [], **styles[k])
            continue
        ax[0].plot(r["t"] * 1e3, r["q"][:, 1] * 1e6, **styles[k])
        ax[2].plot(r["t"] * 1e3, r["Fx_A"], **styles[k])
    ax[0].set_ylim(-0.6, 0.1)
    ax[0].set_ylabel("rotor y [um]")
    ax[0].set_title("rigid rotor (5 kg) on two 7218B bearing FMUs (quasi-static, displacement coupling), 3000 rpm")
    ax[0].legend(fontsize=7, loc="lower right")
    # the forced orbit, last half
    for k in ("reference", "jacobian_1ms"):
        r = runs[k]
        sel = r["t"] >= t0
        ax[1].plot(r["q"][sel, 0] * 1e9, r["q"][sel, 1] * 1e9, **styles[k])
    ax[1].set_xlabel("x [nm]")
    ax[1].set_ylabel("y [nm]")
    ax[1].set_title(f"orbit of the centre of mass, t >= {t0 * 1e3:g} ms")
    ax[1].set_aspect("equal", adjustable="datalim")
    lo, hi = np.percentile(ref["Fx_A"], [1, 99])
    ax[2].set_ylim(lo - 0.5 * (hi - lo), hi + 0.5 * (hi - lo))
    ax[2].set_xlabel("t [ms]")
    ax[2].set_ylabel("bearing A reaction Fx [N]")
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    print(f"wrote {path}")


if __name__ == "__main__":
    main()
