"""Cost of one contact evaluation: FASTSIM (Kalker) at several grids against the ellipse-integrated
Coulomb law, called from compiled code, for a 7218B-like contact (a = 1.15 mm, b = 0.17 mm, Q = 300 N).

    python bench/bench_fastsim.py [--json]
"""
import argparse
import json
import time

import numpy as np
from numba import njit

from bearing_core.contact_kernels import TRACTION_COULOMB, ellipse_quadrature, ellipse_traction, traction_params
from bearing_core.fastsim import PRESSURE_HERTZ, combined_elastic, fastsim_traction


@njit(cache=True)
def _loop_fastsim(n, a, b, Q, mu, G, nu, nx):
    s = 0.0
    for k in range(n):
        ft, fm, mn, p = fastsim_traction(a, b, Q, mu, G, nu, 3e-3 + 1e-9 * k, 1.4e-3, 16.5, -9.9, nx, nx,
                                         PRESSURE_HERTZ)
        s += ft
    return s


@njit(cache=True)
def _loop_ellipse(n, a, b, p, D, R, tp, qx, qwx, qy, qwy):
    s = 0.0
    for k in range(n):
        r = ellipse_traction(a, b, p, D, R, 3e-3 + 1e-9 * k, 1.4e-3, 16.5, 0.0, 0.0, -9.9, TRACTION_COULOMB, tp,
                             qx, qwx, qy, qwy)
        s += r[0]
    return s


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--json", action="store_true")
    a = ap.parse_args()
    G, nu = combined_elastic(206e9, 0.3, 206e9, 0.3)
    A, B, Q = 1.15e-3, 0.17e-3, 300.0
    p = 1.5 * Q / (np.pi * A * B)
    out = {}
    n = 20000
    for nx in (8, 12, 20, 40):
        _loop_fastsim(10, A, B, Q, 0.1, G, nu, nx)
        t0 = time.perf_counter()
        _loop_fastsim(n, A, B, Q, 0.1, G, nu, nx)
        out[f"fastsim_{nx}x{nx}_us"] = (time.perf_counter() - t0) / n * 1e6
    q = ellipse_quadrature(6, 2)
    tp = traction_params(0.1, 0.02)
    _loop_ellipse(10, A, B, p, 0.02223, 0.0116, tp, *q)
    t0 = time.perf_counter()
    _loop_ellipse(n, A, B, p, 0.02223, 0.0116, tp, *q)
    out["ellipse_coulomb_6x2_us"] = (time.perf_counter() - t0) / n * 1e6
    print(json.dumps(out) if a.json else "\n".join(f"{k}: {v:.2f}" for k, v in out.items()))


if __name__ == "__main__":
    main()
