"""Lubricant data: traction curves and a small database of named oils with their thermophysical
properties (SI inside: K, Pa s, m^2/s, kg/m^3, J/(kg K), W/(m K), 1/Pa).

1. Traction curves (seed 002): mu(s) = (A + B s) exp(-C s) + D, s = slide-to-roll ratio. Illustrative; used only
   by the traction model 'lubricated-curve'. The 'lubricated' model computes the traction from the oil's
   rheology (item 3, bearing_core.lubrication.ehl_traction); a curve name given as ``lubricant`` then only names its oil.

   The seeds give the form but no coefficients; both curves below are chosen, not fitted to a measurement.
   They keep mu(0) = A + D = 0 (no traction without slip) and stay inside the 0.03-0.08 range of EHL
   traction coefficients of mineral oils (Harris & Kotzalas, Rolling Bearing Analysis 5th ed., Vol. 2 Ch. 4).

   * ``generic-mineral-oil`` (default): B = 0, a limiting-shear-stress curve mu = D (1 - exp(-C s)), initial
     slope C D = 6, 90 % of the limit 0.06 at s = 2.3 %. Monotonic.
   * ``generic-mineral-oil-thermal``: B > 0 gives a maximum of 0.065 at s = 2.3 % and a falling branch to
     0.04 (thermal softening). The falling branch is a negative damping: in our runs of a 7218B at
     10000 rpm under pure thrust it drives a self-excited whirl of the inner ring when the ring has no other
     damping (as an undamped rotor model would give it). Use it with a damped rotor.

   Both generic curves take their viscosity/density data from the named oil ``iso-vg32-mineral``
   (``TRACTION_OIL``); their fixed ``density`` field (870 kg/m^3, used by the dynamics for ball drag) is
   that oil's density at 15 degC. Replace them with coefficients fitted to your oil's traction measurements.

   Temperature dependence, ``traction_curve_at(name, T)``: the EHL limiting shear stress
   tau_L = tau_0 + gamma p (Johnson & Tevaarwerk 1977) sets the plateau of the curve, and its
   pressure coefficient gamma falls with temperature (measured for a naphthenic oil and a PAO/diester from
   -20 to +110 degC: Wikstrom & Hoglund, ASME J. Tribol. 116(3) 612-620, 1994; also Bair & Winer 1979).
   None of our sources gives a slope we could transfer to these illustrative curves, so the ASSUMPTION is
   explicit and small: the whole curve (A, B, D) is scaled by f(T) = 1 - k_T (T - T_ref) with
   k_T = 0.003 1/K and T_ref = 313.15 K (40 degC; the generic curves are read as 40 degC curves), f clipped
   to [0.25, 1.5]; C (the slip scale of the rise) is kept. So mu(0) = 0 stays, and the plateau falls 30 %
   per 100 K. Set ``k_T = 0`` to switch it off.

2. Named oils (``OILS``; ``get_oil``): kinematic viscosity from the Walther / ASTM D341 equation through
   two published points, log10 log10(Z) = A - B log10(T), Z = nu + 0.7 + exp(-1.47 - 1.84 nu - 0.51 nu^2)
   (nu in mm^2/s = cSt, T in K; ASTM D341-09 Eqs. 1-2 and the inverse of its Eq. 3); density linear in
   temperature rho(T) = rho_15 [1 - beta_T (T - 288.15 K)] with beta_T = 6.4e-4 1/K (Hamrock, Fundamentals
   of Fluid Film Lubrication, NASA RP-1255, 1991, Ch. 4; = the value quoted for mineral oils); dynamic
   viscosity eta = rho nu; pressure-viscosity coefficient alpha(T) interpolated (log alpha piecewise linear
   in T, extrapolated with the end slopes) between tabulated points; specific heat and conductivity of
   petroleum oils from Cragoe (NBS Misc. Publ. 97, 1929), converted to SI:
       c_p = (1684.8 + 3.39 theta) / sqrt(d)   J/(kg K),   k = 0.1172 (1 - 5.4e-4 theta) / d   W/(m K)
   with theta the temperature in degC and d = rho_15 / 1000 (specific gravity). For the synthetic oils
   Cragoe's petroleum correlation is an approximation (typically within 10 %; said per oil).

   The oils and their sources (each record's ``source`` repeats this):

   * ``iso-vg32-mineral``, ``iso-vg68-mineral``: ISO 3448 mid-point kinematic viscosity at 40 degC
     (32 and 68 mm^2/s) and a viscosity at 100 degC typical of VI ~ 100 paraffinic turbine/hydraulic oils
     (5.4 and 8.6 mm^2/s; manufacturers' typical data, e.g. Shell Tellus S2 M 32 / 68); rho_15 = 870 / 886.
     alpha: no measurement for a generic oil; the mineral-oil row of Jones et al. (below) is used -- an
     assumption; paraffinic oils are typically 10-25 % lower.
   * ``mil-prf-23699-ester``: the 'formulated advanced ester' (a type II polyol-ester turbine oil of the
     MIL-L-23699 class) of Jones, Johnson, Winer & Sanborn, 'Pressure-viscosity measurements for several
     lubricants to 5.5e8 N/m^2 and 149 degC', ASLE Trans. 18(4) 249-262 (1975), as tabulated by Hamrock
     (NASA RP-1255, 1991, Ch. 4 tables of absolute viscosity and pressure-viscosity coefficient at
     38, 99 and 149 degC): eta = 27.6, 4.96, 2.15 mPa s; alpha = 1.37, 1.00, 0.874 x 1e-8 1/Pa.
     rho_15 = 1000 kg/m^3 (typical of pentaerythritol-ester turbine oils), used to convert eta to nu.
   * ``naphthenic-mineral``: Jones et al. (1975) super-refined naphthenic mineral oil: eta = 68.1, 6.86,
     2.74 mPa s; alpha = 2.51, 1.54, 1.27 x 1e-8 1/Pa; rho_15 = 900 kg/m^3 (assumed, typical).
   * ``synthetic-paraffinic``: Jones et al. (1975) synthetic paraffinic oil (lot 3; a PAO-type synthetic
     hydrocarbon of about ISO VG 460): eta = 414, 34.3, 10.9 mPa s; alpha = 1.77, 1.51, 1.09 x 1e-8 1/Pa;
     rho_15 = 850 kg/m^3 (assumed, typical of PAOs).
   * ``seed003-oil``: the oil of seed 003 (wear; Preprints 2026) section 3.1.1: eta_0 = 0.04 Pa s and
     xi = alpha = 2.2e-8 m^2/N, with no temperature given. Recorded as it is: temperature-independent
     (``kind='constant'``), rho = 870 kg/m^3 assumed.

   The three Jones et al. rows are fitted (Walther) through the 38 and 99 degC points; the 149 degC points
   are kept to check the fit (tests/test_lubricants.py). The tabulated numbers were transcribed from the
   reproduced tables and not re-checked against the 1975 original in this repository.

3. EHL rheology (``Oil`` fields tau0, tauL0, gamma_L, G_film, roelands_z; used by bearing_core.lubrication.ehl_traction
   through ``rheology_traction_params``): Eyring stress tau_0 [Pa] of the Ree-Eyring law, limiting shear
   stress tau_L = tau_L0 + gamma_L p (Bair & Winer 1979), shear modulus G of the film (Maxwell, Johnson &
   Tevaarwerk 1977), Roelands index z (0: the index equivalent to the oil's alpha at low pressure,
   z = alpha p_0 / (ln eta_0 + 9.67), Hamrock NASA RP-1255 Ch. 4). The temperature-viscosity coefficient
   beta = -d ln eta / dT comes from the Walther fit. gamma_L is read as a 40 degC value and falls with
   temperature by the ASSUMED factor traction_scale(T) (item 1's k_T = 0.003 1/K; no source gives a slope).
   Thermal conductivity: Cragoe (above). Each oil's
   ``rheology_source`` names where its numbers come from. Numbers marked 'recalled' were taken from memory
   of the cited papers and were not re-checked against them here; treat them as such.

   * Mineral oils (iso-vg32/68, naphthenic): tau_0 = 5 MPa, the middle of the 2-10 MPa that Evans &
     Johnson (Proc. IMechE 200C, 1986) and Johnson & Tevaarwerk (Proc. R. Soc. A 356, 1977) found for
     mineral oils (HVI 650, ...) at 0.5-2 GPa; gamma_L = 0.075 (Bair & Winer, J. Lubr. Technol. 101, 1979,
     and Hoglund & Jacobson, J. Tribol. 108, 1986: 0.07-0.09 near room temperature); G = 0.5 GPa (Johnson
     & Tevaarwerk 1977: 0.1-1 GPa). All recalled.
   * ``santotrac-50`` (Monsanto traction fluid, a synthetic cycloaliphatic hydrocarbon): viscosity and
     alpha of the 'synthetic hydrocarbon (traction fluid)' row of Jones et al. (1975) as tabulated by
     Hamrock (NASA RP-1255 Ch. 4): eta = 34.3 / 3.53 mPa s and alpha = 3.12 / 1.76 x 1e-8 1/Pa at 38 /
     99 degC (recalled); rho_15 = 900 kg/m^3 (typical, assumed); tau_0 = 8 MPa, gamma_L = 0.10, G = 0.5 GPa
     (traction fluids: higher Eyring and limiting stresses than mineral oils, Johnson & Tevaarwerk 1977,
     Bair & Winer 1979; recalled).
   * ``mil-prf-23699-ester``: tau_0 = 4 MPa, gamma_L = 0.06 (esters trace lower than mineral oils; recalled
     from the ester traction data summarised by Gupta, Advanced Dynamics of Rolling Elements, 1984).
   * ``synthetic-paraffinic`` (PAO): tau_0 = 4 MPa, gamma_L = 0.065 (recalled, as above).
   * ``seed003-oil``: the mineral-oil values.

Seed 001 (Gao et al., Friction 2022) names no oil and gives no viscosity.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, replace

import numpy as np
from numba import njit

from ..errors import BearingInputError, check_range

T_MIN = 233.0           # K, validity range of the property functions (-40 degC ...
T_MAX = 473.15          # ... 200 degC)
BETA_T = 6.4e-4         # 1/K, thermal expansion of oils (Hamrock, NASA RP-1255, Ch. 4)
T15 = 288.15            # K


# =============================================================================================
# traction curves
# =============================================================================================
@dataclass(frozen=True)
class TractionCurve:
    name: str
    A: float
    B: float
    C: float
    D: float
    density: float      # kg/m^3, for drag in the oil-air mixture
    source: str

    def mu(self, s):
        s = np.abs(s)
        return (self.A + self.B * s) * np.exp(-self.C * s) + self.D


LUBRICANTS = {
    "generic-mineral-oil": TractionCurve("generic-mineral-oil", -0.06, 0.0, 100.0, 0.06, 870.0,
                                         "illustrative, see module docstring"),
    "generic-mineral-oil-thermal": TractionCurve("generic-mineral-oil-thermal", -0.04, 6.0, 60.0, 0.04, 870.0,
                                                 "illustrative, see module docstring"),
}
TRACTION_OIL = {"generic-mineral-oil": "iso-vg32-mineral", "generic-mineral-oil-thermal": "iso-vg32-mineral"}
TRACTION_T_REF = 313.15     # K, the generic curves are read as 40 degC curves
TRACTION_K_T = 0.003        # 1/K, assumed fall of the traction plateau with temperature (see docstring)


def get_lubricant(name: str) -> TractionCurve:
    if name not in LUBRICANTS:
        raise BearingInputError("lubricant", name, "one of " + ", ".join(sorted(LUBRICANTS)))
    return LUBRICANTS[name]


def traction_scale(T: float, k_T: float = TRACTION_K_T, T_ref: float = TRACTION_T_REF) -> float:
    """Factor f(T) = 1 - k_T (T - T_ref), clipped to [0.25, 1.5], applied to A, B, D (assumption, see
    module docstring). T [K]."""
    check_range("T", T, T_MIN, T_MAX, unit="K")
    check_range("k_T", k_T, 0.0, 0.02, unit="1/K")
    return min(1.5, max(0.25, 1.0 - k_T * (T - T_ref)))


def traction_curve_at(name: str, T: float, k_T: float = TRACTION_K_T) -> TractionCurve:
    """The traction curve ``name`` at temperature T [K]: A, B, D scaled by traction_scale(T), C kept,
    density = that of the curve's oil (TRACTION_OIL) at T. At T_ref with the oil's density the curve's
    coefficients are returned unchanged."""
    c = get_lubricant(name)
    f = traction_scale(T, k_T)
    rho = density(TRACTION_OIL[name], T)
    return replace(c, name=f"{c.name}@{T:.2f}K", A=c.A * f, B=c.B * f, D=c.D * f, density=rho,
                   source=c.source + f"; scaled by {f:.4f} for T = {T:.2f} K (assumed k_T = {k_T} 1/K)")


# =============================================================================================
# Walther / ASTM D341 kernels (numba, floats only)
# =============================================================================================
@njit(cache=True)
def walther_z(nu_cst):
    """ASTM D341 Z(nu) = nu + 0.7 + exp(-1.47 - 1.84 nu - 0.51 nu^2), nu in mm^2/s."""
    return nu_cst + 0.7 + math.exp(-1.47 - 1.84 * nu_cst - 0.51 * nu_cst * nu_cst)


@njit(cache=True)
def walther_nu_from_z(z):
    """Inverse of walther_z (ASTM D341-09 Eq. 3): nu = (Z - 0.7) - exp(-0.7487 - 3.295 (Z-0.7)
    + 0.6119 (Z-0.7)^2 - 0.3193 (Z-0.7)^3), mm^2/s."""
    x = z - 0.7
    return x - math.exp(-0.7487 - 3.295 * x + 0.6119 * x * x - 0.3193 * x * x * x)


@njit(cache=True)
def walther_nu(wA, wB, T):
    """Kinematic viscosity [m^2/s] at T [K] from the Walther constants: log10 log10 Z = wA - wB log10 T."""
    z = 10.0 ** (10.0 ** (wA - wB * math.log10(T)))
    return walther_nu_from_z(z) * 1e-6


@njit(cache=True)
def oil_density(rho15, T):
    """rho(T) = rho_15 [1 - 6.4e-4 (T - 288.15)] [kg/m^3] (Hamrock NASA RP-1255 Ch. 4)."""
    return rho15 * (1.0 - 6.4e-4 * (T - 288.15))


@njit(cache=True)
def oil_eta(wA, wB, rho15, T):
    """Dynamic viscosity eta = rho(T) nu(T) [Pa s] at T [K] (Walther constants wA, wB)."""
    return oil_density(rho15, T) * walther_nu(wA, wB, T)


def walther_constants(T1: float, nu1: float, T2: float, nu2: float) -> tuple[float, float]:
    """Walther constants (A, B) through (T1 [K], nu1 [m^2/s]) and (T2, nu2)."""
    z1 = math.log10(math.log10(walther_z(nu1 * 1e6)))
    z2 = math.log10(math.log10(walther_z(nu2 * 1e6)))
    B = (z1 - z2) / (math.log10(T2) - math.log10(T1))
    return z1 + B * math.log10(T1), B


# =============================================================================================
# named oils
# =============================================================================================
_MINERAL_RHEOLOGY = ("mineral oil: tau_0 5 MPa (Evans & Johnson, Proc. IMechE 200C, 1986; Johnson & Tevaarwerk, "
                     "Proc. R. Soc. A 356, 1977), gamma_L 0.075 (Bair & Winer, J. Lubr. Technol. 101, 1979), "
                     "G 0.5 GPa (Johnson & Tevaarwerk 1977); recalled, check against the sources")


@dataclass(frozen=True)
class Oil:
    """A named oil. kind 'walther': two kinematic-viscosity points (T1, nu1), (T2, nu2) [K, m^2/s];
    kind 'constant': eta_const [Pa s] at every temperature. rho15: density at 15 degC [kg/m^3];
    alpha_T, alpha_v: temperatures [K] and pressure-viscosity coefficients [1/Pa] (one point = constant);
    check_points: further published (T [K], eta [Pa s]) points not used by the fit; cragoe_note: how
    well Cragoe's petroleum correlation applies."""

    name: str
    kind: str
    rho15: float
    alpha_T: tuple
    alpha_v: tuple
    source: str
    T1: float = 0.0
    nu1: float = 0.0
    T2: float = 0.0
    nu2: float = 0.0
    eta_const: float = 0.0
    check_points: tuple = ()
    cragoe_note: str = "petroleum oil: Cragoe's correlation applies"
    tau0: float = 5e6           # Pa, Eyring stress
    tauL0: float = 0.0          # Pa, limiting shear stress at zero pressure
    gamma_L: float = 0.075      # -, limiting shear stress pressure coefficient
    G_film: float = 0.5e9       # Pa, elastic shear modulus of the film
    roelands_z: float = 0.0     # -, 0: equivalent to alpha at low pressure
    rheology_source: str = _MINERAL_RHEOLOGY

    @property
    def walther(self) -> tuple[float, float]:
        return walther_constants(self.T1, self.nu1, self.T2, self.nu2)

    # property functions, T [K]
    def density(self, T):
        _T(T)
        return oil_density(self.rho15, T)

    def nu(self, T):
        """Kinematic viscosity [m^2/s]."""
        _T(T)
        if self.kind == "constant":
            return self.eta_const / self.density(T)
        A, B = self.walther
        return walther_nu(A, B, T)

    def eta(self, T):
        """Dynamic viscosity [Pa s] at atmospheric pressure."""
        _T(T)
        if self.kind == "constant":
            return self.eta_const
        return self.density(T) * self.nu(T)

    def alpha(self, T):
        """Pressure-viscosity coefficient [1/Pa]: log alpha piecewise linear in T through the tabulated
        points, end slopes outside."""
        _T(T)
        Ts = self.alpha_T
        la = [math.log(a) for a in self.alpha_v]
        if len(Ts) == 1:
            return self.alpha_v[0]
        k = 0
        while k < len(Ts) - 2 and T > Ts[k + 1]:
            k += 1
        w = (T - Ts[k]) / (Ts[k + 1] - Ts[k])
        return math.exp(la[k] + w * (la[k + 1] - la[k]))

    def beta(self, T):
        """Temperature-viscosity coefficient beta = -d ln eta / dT [1/K] at T (central difference of eta)."""
        _T(T)
        dT = 0.5
        lo, hi = max(T - dT, T_MIN), min(T + dT, T_MAX)
        return -(math.log(self.eta(hi)) - math.log(self.eta(lo))) / (hi - lo)

    def roelands(self, T):
        """Roelands pressure-viscosity index z [-] at T: the oil's own, or alpha(T) p_0 / (ln eta_0 + 9.67)."""
        if self.roelands_z > 0.0:
            return self.roelands_z
        lne = math.log(self.eta(T)) + 9.67
        return self.alpha(T) * 1.96e8 / lne

    def specific_heat(self, T):
        """c_p [J/(kg K)], Cragoe (1929) in SI."""
        _T(T)
        return (1684.8 + 3.39 * (T - 273.15)) / math.sqrt(self.rho15 / 1000.0)

    def conductivity(self, T):
        """Thermal conductivity [W/(m K)], Cragoe (1929) in SI."""
        _T(T)
        return 0.1172 * (1.0 - 5.4e-4 * (T - 273.15)) / (self.rho15 / 1000.0)


def _T(T):
    check_range("T", T, T_MIN, T_MAX, unit="K")


def _C(c):
    return c + 273.15


_JONES = ("Jones, Johnson, Winer & Sanborn, ASLE Trans. 18(4) 249-262 (1975), as tabulated in Hamrock, "
          "Fundamentals of Fluid Film Lubrication, NASA RP-1255 (1991) Ch. 4")


def _jones(name, eta38, eta99, eta149, a38, a99, a149, rho15, note, cragoe, **rheology):
    """Oil from a Jones et al. row: absolute viscosities [mPa s] and alpha [1e-8 1/Pa] at 38/99/149 degC
    (eta149 / a149 None: not used)."""
    T1, T2, T3 = _C(37.78), _C(98.89), _C(148.89)     # 100, 210, 300 degF
    nu1 = eta38 * 1e-3 / oil_density(rho15, T1)
    nu2 = eta99 * 1e-3 / oil_density(rho15, T2)
    aT, av = ((T1, T2, T3), (a38 * 1e-8, a99 * 1e-8, a149 * 1e-8)) if a149 else ((T1, T2), (a38 * 1e-8, a99 * 1e-8))
    return Oil(name, "walther", rho15, aT, av,
               _JONES + "; " + note, T1=T1, nu1=nu1, T2=T2, nu2=nu2,
               check_points=((T3, eta149 * 1e-3),) if eta149 else (), cragoe_note=cragoe, **rheology)


_A_MINERAL = ((_C(37.78), _C(98.89), _C(148.89)), (2.51e-8, 1.54e-8, 1.27e-8))

OILS = {
    "iso-vg32-mineral": Oil(
        "iso-vg32-mineral", "walther", 870.0, *_A_MINERAL,
        "ISO 3448 VG 32 mid-point 32 mm^2/s at 40 degC; 5.4 mm^2/s at 100 degC typical of VI~100 paraffinic "
        "oils (e.g. Shell Tellus S2 M 32 typical data); alpha: naphthenic mineral oil of " + _JONES
        + " (assumed, paraffinic oils are lower)",
        T1=_C(40.0), nu1=32e-6, T2=_C(100.0), nu2=5.4e-6),
    "iso-vg68-mineral": Oil(
        "iso-vg68-mineral", "walther", 886.0, *_A_MINERAL,
        "ISO 3448 VG 68 mid-point 68 mm^2/s at 40 degC; 8.6 mm^2/s at 100 degC typical of VI~100 paraffinic "
        "oils (e.g. Shell Tellus S2 M 68 typical data); alpha: naphthenic mineral oil of " + _JONES
        + " (assumed)",
        T1=_C(40.0), nu1=68e-6, T2=_C(100.0), nu2=8.6e-6),
    "mil-prf-23699-ester": _jones(
        "mil-prf-23699-ester", 27.6, 4.96, 2.15, 1.37, 1.00, 0.874, 1000.0,
        "'formulated advanced ester' (type II polyol ester, MIL-L-23699 class); rho_15 typical of such oils",
        "synthetic ester: Cragoe's petroleum correlation is an approximation (~10 %)",
        tau0=4e6, gamma_L=0.06,
        rheology_source="ester: tau_0 4 MPa, gamma_L 0.06, G 0.5 GPa; recalled (see module docstring)"),
    "naphthenic-mineral": _jones(
        "naphthenic-mineral", 68.1, 6.86, 2.74, 2.51, 1.54, 1.27, 900.0,
        "super-refined naphthenic mineral oil; rho_15 assumed", "petroleum oil: Cragoe's correlation applies"),
    "synthetic-paraffinic": _jones(
        "synthetic-paraffinic", 414.0, 34.3, 10.9, 1.77, 1.51, 1.09, 850.0,
        "synthetic paraffinic oil (lot 3), PAO-type; rho_15 assumed",
        "synthetic hydrocarbon: Cragoe's petroleum correlation is an approximation (~10 %)",
        tau0=4e6, gamma_L=0.065,
        rheology_source="PAO: tau_0 4 MPa, gamma_L 0.065, G 0.5 GPa; recalled (see module docstring)"),
    "santotrac-50": _jones(
        "santotrac-50", 34.3, 3.53, None, 3.12, 1.76, None, 900.0,
        "'synthetic hydrocarbon (traction fluid)' row (Santotrac 50); values recalled, check against the "
        "source; rho_15 assumed",
        "synthetic hydrocarbon: Cragoe's petroleum correlation is an approximation (~10 %)",
        tau0=8e6, gamma_L=0.10,
        rheology_source="traction fluid: tau_0 8 MPa, gamma_L 0.10, G 0.5 GPa (Johnson & Tevaarwerk, Proc. R. "
                        "Soc. A 356, 1977; Bair & Winer, J. Lubr. Technol. 101, 1979); recalled, check against "
                        "the sources"),
    "seed003-oil": Oil(
        "seed003-oil", "constant", 870.0, (_C(40.0),), (2.2e-8,),
        "seed 003 (Preprints 2026) section 3.1.1: eta_0 = 0.04 Pa s, xi = 2.2e-8 m^2/N, no temperature given;"
        " rho assumed 870 kg/m^3", eta_const=0.04),
}


def get_oil(name: str) -> Oil:
    """Named oil (see OILS) or the oil behind a traction curve name (TRACTION_OIL)."""
    if isinstance(name, Oil):
        return name
    key = TRACTION_OIL.get(name, name)
    if key not in OILS:
        raise BearingInputError("oil", name, "one of " + ", ".join(sorted(OILS) + sorted(TRACTION_OIL)))
    return OILS[key]


def list_oils() -> list[str]:
    return sorted(OILS)


# module-level convenience functions, T [K]
def eta(oil: str, T: float) -> float:
    """Dynamic viscosity [Pa s] of ``oil`` at T [K] (atmospheric pressure)."""
    return get_oil(oil).eta(T)


def nu(oil: str, T: float) -> float:
    """Kinematic viscosity [m^2/s]."""
    return get_oil(oil).nu(T)


def alpha(oil: str, T: float) -> float:
    """Pressure-viscosity coefficient [1/Pa]."""
    return get_oil(oil).alpha(T)


def density(oil: str, T: float) -> float:
    """Density [kg/m^3]."""
    return get_oil(oil).density(T)


def specific_heat(oil: str, T: float) -> float:
    """Specific heat [J/(kg K)]."""
    return get_oil(oil).specific_heat(T)


def thermal_conductivity(oil: str, T: float) -> float:
    """Thermal conductivity [W/(m K)]."""
    return get_oil(oil).conductivity(T)


def eta_pressure(oil: str, T: float, p: float) -> float:
    """Barus viscosity eta(T) exp(alpha(T) p) [Pa s] at gauge pressure p [Pa] (Hamrock RP-1255 Ch. 4);
    meant for the inlet zone of EHL contacts, not for Hertz pressures above ~0.5 GPa."""
    check_range("p", p, 0.0, 5e9, unit="Pa")
    o = get_oil(oil)
    return o.eta(T) * math.exp(o.alpha(T) * p)


# =============================================================================================
# EHL rheology parameters for the traction kernels
# =============================================================================================
STEEL_RHO_C_K = 7850.0 * 470.0 * 46.0   # rho c k of bearing steel [J^2/(m^4 K^2 s)]: 7850 kg/m^3, 470 J/(kg K),
#                                          46 W/(m K) (AISI 52100, e.g. Harris & Kotzalas Vol. 1 App.)
MU_BOUNDARY = 0.15    # boundary friction coefficient of an additive-containing oil: SKF's mu_bl (SKF rolling
#                       bearings catalogue, 'The SKF model for calculating the frictional moment', 2018)
V_BOUNDARY = 1e-3     # m/s, regularisation of the boundary friction direction


def rheology_traction_params(base, oil, T: float, E_prime: float, GsC11: float, Rq: float,
                             mu_bl: float = MU_BOUNDARY, rolling_resistance: bool = True, thermal: bool = True,
                             rck: float = STEEL_RHO_C_K, v_bl: float = V_BOUNDARY):
    """Traction parameter array (contact_kernels layout) of the rheology-based EHL model for ``oil`` at the
    inlet temperature T [K]: ``base`` from traction_params.traction_params (mu0, v_reg, u_min), a copy is
    returned with the model set to traction_params.TRACTION_EHL and the rheology slots filled.

    E_prime [Pa] = 2 / ((1 - nu1^2)/E1 + (1 - nu2^2)/E2); GsC11 [Pa]: combined shear modulus of the solids
    times Kalker's C11 at the contact's b/a (the tangential compliance in series with the film); Rq [m]:
    composite rms roughness sqrt(Rq1^2 + Rq2^2) (0: smooth, no asperity contact); mu_bl [-]: boundary
    friction coefficient; rolling_resistance: EHL rolling-resistance moment on/off; thermal: shear heating
    on/off; rck: rho c k of the solids (flash temperature)."""
    from ..contact import traction_params as E
    o = get_oil(oil)
    check_range("T", T, T_MIN, T_MAX, unit="K")
    check_range("E_prime", E_prime, 1e9, 1e13, unit="Pa")
    check_range("Rq", Rq, 0.0, 1e-5, unit="m")
    check_range("mu_bl", mu_bl, 0.0, 1.0)
    p = np.array(base, dtype=float).copy()
    eta0 = o.eta(T)
    p[E.R_LUBMODEL] = 2.0
    p[E.R_ETA0] = eta0
    p[E.R_LNE] = math.log(eta0) + 9.67
    p[E.R_Z] = o.roelands(T)
    p[E.R_ALPHA] = o.alpha(T)
    p[E.R_BETA] = o.beta(T)
    p[E.R_TAU0] = o.tau0
    p[E.R_TAUL0] = o.tauL0
    # limiting shear stress coefficient at the inlet temperature, and its relative fall with the film's
    # heating (ehl_traction item 7; the same assumed k_T = TRACTION_K_T as traction_scale)
    g_in = o.gamma_L * traction_scale(T)
    p[E.R_GAML] = g_in
    p[E.R_KGAM] = TRACTION_K_T * o.gamma_L / g_in if thermal else 0.0
    p[E.R_GFILM] = o.G_film
    p[E.R_KOIL] = o.conductivity(T)
    p[E.R_EPRIME] = E_prime
    p[E.R_GSC11] = GsC11
    p[E.R_RCK] = rck
    p[E.R_RQ] = Rq
    p[E.R_MUBL] = mu_bl
    p[E.R_VBL] = v_bl
    p[E.R_RR] = 1.0 if rolling_resistance else 0.0
    p[E.R_THERMAL] = 1.0 if thermal else 0.0
    return p
