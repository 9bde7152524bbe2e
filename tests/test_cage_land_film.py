"""Film force of the flooded guiding land (dynamics_kernels._cage_flooded_land) against the short-bearing
Reynolds solution integrated numerically over its half-Sommerfeld (pi) film, for a cage centre at rest and,
with land_film = 'moving', for a whirling and approaching one (Ocvirk's short bearing; the dh/dt of a moving
journal: Childs, 'Turbomachinery Rotordynamics', 1993, Sec. 3.6)."""
import math

import numpy as np
import pytest

from bearing_core.errors import BearingInputError
from bearing_core.models import dynamics_kernels as K
from bearing_core.models.dynamics import DynamicsOptions

ETA, C, R, B = 0.03, 3.0e-4, 0.075, 6.0e-3          # Pa s, radial clearance, land radius and width [m]


def params(moving):
    P = np.zeros(K.NPAR)
    P[K.P_RLAND], P[K.P_WLAND], P[K.P_GUIDE], P[K.P_EPSMAX] = R, B, 0.0, 0.995     # outer-land guided
    P[K.P_LANDFILM] = 1.0 if moving else 0.0
    return P


def kernel_force(moving, e, phi, edot, phid, wc, wo=0.0):
    """Film force on the cage [N] from the kernel, the centre at e (direction phi) moving at (edot, e phid)."""
    xc, yc = e * math.cos(phi), e * math.sin(phi)
    vx = edot * math.cos(phi) - e * phid * math.sin(phi)
    vy = edot * math.sin(phi) + e * phid * math.cos(phi)
    out = K._cage_flooded_land(ETA, e, C, xc, yc, vx, vy, wc, 0.0, wo, params(moving), 0.0, 0.0, 0.0, 0.0, 0.0,
                               0.0, 0.0, 0.0, 0.0, 0.0)
    return np.array([out[0], out[1]])


def reynolds_force(e, phi, edot, phid, ws, n=20001):
    """Short-bearing Reynolds solution d/dz (h^3 dp/dz) = 6 eta ws dh/dalpha + 12 eta dh/dt with p = 0 at the
    land's edges, h = c - e cos(alpha - phi); the pi film is the half on which the rotation term alone gives
    positive pressure (the film the kernel takes). Force on the cage (the inner surface) [N]."""
    # the pi film: sin(alpha - phi) < 0 where the rotation and whirl term (ws - 2 phid) is positive
    th = np.linspace(-math.pi, 0.0, n) if ws - 2.0 * phid >= 0.0 else np.linspace(0.0, math.pi, n)
    a = phi + th
    h = C - e * np.cos(th)
    dh_da = e * np.sin(th)
    dh_dt = -edot * np.cos(th) - e * phid * np.sin(th)
    S = 6.0 * ETA * ws * dh_da + 12.0 * ETA * dh_dt
    # p(z) = S / (2 h^3) (z^2 - B^2 / 4): its integral over the width is -S B^3 / (12 h^3)
    pz = -S * B ** 3 / (12.0 * h ** 3)
    da = th[1] - th[0]
    # pressure on the cage's outer surface pushes it inwards: F = -int p n R dalpha
    return np.array([-np.trapezoid(pz * np.cos(a), dx=da) * R, -np.trapezoid(pz * np.sin(a), dx=da) * R])


@pytest.mark.parametrize("eps", [0.2, 0.6, 0.9])
def test_centre_at_rest_is_the_short_bearing_film(eps):
    """A centre at rest: both films are seed 001's Eq. 4, the integrated Reynolds solution within 1e-4."""
    e, phi, wc = eps * C, 0.7, 600.0
    ref = reynolds_force(e, phi, 0.0, 0.0, wc)
    for moving in (False, True):
        np.testing.assert_allclose(kernel_force(moving, e, phi, 0.0, 0.0, wc), ref, rtol=1e-4,
                                   atol=1e-4 * np.linalg.norm(ref))


@pytest.mark.parametrize("eps,edot,phid", [(0.3, 0.0, 150.0), (0.6, 0.05, 0.0), (0.6, -0.05, 200.0),
                                           (0.85, 0.02, 400.0), (0.5, 0.0, -300.0)])
def test_moving_centre_is_the_reynolds_film_of_a_moving_journal(eps, edot, phid):
    """Whirl (phid [rad/s]) and approach (edot [m/s]) of the centre: the 'moving' film is the Reynolds
    solution with dh/dt within 1e-4 of the force; the 'stationary' film is not (it ignores the motion)."""
    e, phi, wc = eps * C, -1.1, 600.0
    ref = reynolds_force(e, phi, edot, phid, wc)
    got = kernel_force(True, e, phi, edot, phid, wc)
    np.testing.assert_allclose(got, ref, rtol=1e-4, atol=1e-4 * np.linalg.norm(ref))
    assert np.linalg.norm(kernel_force(False, e, phi, edot, phid, wc) - ref) > 0.05 * np.linalg.norm(ref)


def test_half_speed_whirl_carries_no_film_force():
    """A circular whirl at half the sum of the surface speeds (the classic half-frequency oil whirl): the
    film carries no force at all; faster whirls are opposed by it, slower ones driven. The stationary film
    pushes every whirl forward."""
    e, phi, wc = 0.7 * C, 0.3, 600.0
    t = np.array([-math.sin(phi), math.cos(phi)])           # the whirl's direction of travel
    assert np.linalg.norm(kernel_force(True, e, phi, 0.0, 0.5 * wc, wc)) < 1e-9
    assert kernel_force(True, e, phi, 0.0, 0.8 * wc, wc) @ t < 0.0
    assert kernel_force(True, e, phi, 0.0, 0.2 * wc, wc) @ t > 0.0
    for phid in (0.2 * wc, 0.8 * wc, 2.0 * wc):
        assert kernel_force(False, e, phi, 0.0, phid, wc) @ t > 0.0


def test_land_film_option_is_checked():
    with pytest.raises(BearingInputError, match="land_film = 'rotating'.*stationary \\| moving"):
        DynamicsOptions(land_film="rotating").validate()
