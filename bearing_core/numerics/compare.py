"""Exact comparison of a model point, compiled in strict IEEE arithmetic (the cheap test whether the state,
inputs and parameters of a model are unchanged since outputs were last computed)."""
from __future__ import annotations

from numba import njit

_exact = njit(cache=True, error_model="numpy")


@_exact
def same_point(t, y, U, P, kt, ky, kU, kP):
    """True if (t, y, U, P) equal (kt, ky, kU, kP) element by element (NaN never equal), same shapes."""
    if t != kt or y.shape[0] != ky.shape[0] or U.shape[0] != kU.shape[0] or P.shape[0] != kP.shape[0]:
        return False
    for i in range(y.shape[0]):
        if y[i] != ky[i]:
            return False
    for i in range(U.shape[0]):
        if U[i] != kU[i]:
            return False
    for i in range(P.shape[0]):
        if P[i] != kP[i]:
            return False
    return True
