"""Interface of a bearing co-simulation session: input and output names, units, descriptions.
Pure data (no numba import), shared by bearing_core.session.cosim and the FMU slave in fmu_src/."""

INPUT_NAMES = ("shaft_speed", "Fx", "Fy", "Fz", "Mx", "My",
               "dx", "dy", "dz", "tx", "ty", "vx", "vy", "vz", "wx", "wy", "outer_ring_speed")
INPUT_UNITS = ("rad/s", "N", "N", "N", "N.m", "N.m", "m", "m", "m", "rad", "rad", "m/s", "m/s", "m/s",
               "rad/s", "rad/s", "rad/s")
OUTPUT_SPEC = (
    # name, unit, description
    ("reaction_Fx", "N", "force of the bearing on the shaft, x"),
    ("reaction_Fy", "N", "force of the bearing on the shaft, y"),
    ("reaction_Fz", "N", "force of the bearing on the shaft, z (axial)"),
    ("reaction_Mx", "N.m", "moment of the bearing on the shaft about x"),
    ("reaction_My", "N.m", "moment of the bearing on the shaft about y"),
    ("cage_speed", "rad/s", "cage angular speed"),
    ("cage_shaft_ratio", "1", "cage speed / shaft speed (CSR)"),
    ("cage_shaft_ratio_theory", "1", "seed 000 Eq. 26 CSR (spin-free, mean contact angles; not a raceway-"
                                     "control bound: see cage_speed_pure_rolling_outer / _inner)"),
    ("skid_ratio", "1", "1 - CSR / seed 000 Eq. 26 CSR (seed 000's measure; the skid classification uses "
                        "cage_slip_ratio)"),
    ("friction_torque", "N.m", "torque needed to drive the inner ring"),
    ("friction_torque_outer", "N.m", "torque needed to drive (or hold) the outer ring"),
    ("heat_flux_total", "W", "total dissipated power"),
    ("heat_flux_race_inner", "W", "ball-inner race traction (rolling, sliding, spin)"),
    ("heat_flux_race_outer", "W", "ball-outer race traction (rolling, sliding, spin)"),
    ("heat_flux_race_slide", "W", "ball-race losses from sliding of the contact centres (both races)"),
    ("heat_flux_race_spin", "W", "ball-race losses from spin about the contact normals (both races)"),
    ("heat_flux_race_diffslip", "W", "ball-race losses from differential slip across the contacts (both races)"),
    ("heat_flux_pocket", "W", "ball-pocket friction"),
    ("heat_flux_land", "W", "cage-land friction and hydrodynamic drag"),
    ("heat_flux_drag", "W", "ball drag in the oil-air mixture"),
    ("heat_flux_damping", "W", "contact and support damping"),
    ("heat_flux_churn_cage", "W", "oil churning of the cage (seed 001 Eq. 15; parameter churning)"),
    ("heat_flux_churn_ring", "W", "oil churning of the inner ring (seed 001 Eq. 17; parameter churning)"),
    ("ir_x", "m", "inner-ring displacement x"),
    ("ir_y", "m", "inner-ring displacement y"),
    ("ir_z", "m", "inner-ring displacement z"),
    ("ir_tx", "rad", "inner-ring tilt about x"),
    ("ir_ty", "rad", "inner-ring tilt about y"),
    ("ir_ax", "m/s2", "inner-ring acceleration x"),
    ("max_contact_pressure", "Pa", "largest Hertz pressure of all contacts"),
    ("alpha_i_mean", "rad", "mean inner contact angle of loaded balls"),
    ("alpha_o_mean", "rad", "mean outer contact angle of loaded balls"),
    ("Q_i_max", "N", "largest inner contact load"),
    ("Q_o_max", "N", "largest outer contact load"),
    ("ball0_omega_r", "rad/s", "ball 0 angular velocity, radial component"),
    ("ball0_omega_t", "rad/s", "ball 0 angular velocity, tangential component"),
    ("ball0_omega_z", "rad/s", "ball 0 angular velocity, axial component"),
    ("ball0_slide_roll_i", "1", "ball 0 slide-to-roll ratio, inner contact"),
    ("ball0_slide_roll_o", "1", "ball 0 slide-to-roll ratio, outer contact"),
    ("ball0_spin_roll_i", "1", "ball 0 spin-to-roll ratio, inner contact"),
    ("ball0_spin_roll_o", "1", "ball 0 spin-to-roll ratio, outer contact"),
    ("ball0_traction_i", "N", "ball 0 rolling-direction traction from the inner race (seed 000 Fig. 10)"),
    ("ball0_traction_o", "N", "ball 0 rolling-direction traction from the outer race"),
    ("temperature_ball", "K", "ball node temperature (thermal network; oil_temperature when thermal is off)"),
    ("temperature_outer_ring", "K", "outer ring / housing node temperature"),
    ("temperature_inner_ring", "K", "inner ring / shaft node temperature"),
    ("temperature_oil", "K", "oil and cage node temperature"),
    ("heat_to_ambient", "W", "heat rejected by the network to the ambient air"),
    ("heat_to_oil_flow", "W", "heat carried away by the circulating oil"),
    ("film_min_inner", "m", "smallest Hamrock-Dowson minimum film thickness of the inner contacts"),
    ("film_min_outer", "m", "smallest Hamrock-Dowson minimum film thickness of the outer contacts"),
    ("film_parameter_min", "1", "smallest film parameter Lambda = h_min / composite roughness"),
    ("cage_speed_pure_rolling_outer", "rad/s",
     "pure-rolling cage speed at the loaded balls' contact angles, outer-raceway control (bearing_core.models.skid)"),
    ("cage_speed_pure_rolling_inner", "rad/s",
     "pure-rolling cage speed at the loaded balls' contact angles, inner-raceway control (bearing_core.models.skid)"),
    ("cage_slip_ratio", "1", "1 - cage speed / cage_speed_pure_rolling_outer (> 0 skidding, < 0 over-skidding)"),
)
OUTPUT_SPEC += (
    ("drive_power", "W", "power supplied by the drives of both rings (friction torques x ring speeds)"),
)
# Energy-carrying outputs: their values are averages over the communication step (integral of the
# instantaneous value over the step / step, so that sum(value * h) is the energy); the value sampled at the
# communication point is the output 'instantaneous_<name>' (bearing_core.session.cosim; a prefix, so that sums over
# the 'heat_flux_' outputs keep counting each source once).
STEP_AVERAGED_NAMES = (
    "friction_torque", "friction_torque_outer", "drive_power", "heat_flux_total", "heat_flux_race_inner",
    "heat_flux_race_outer", "heat_flux_pocket", "heat_flux_land", "heat_flux_drag", "heat_flux_damping",
    "heat_flux_churn_cage", "heat_flux_churn_ring", "heat_flux_race_slide", "heat_flux_race_spin",
    "heat_flux_race_diffslip")
_spec = {n: (u, d) for n, u, d in OUTPUT_SPEC}
OUTPUT_SPEC = tuple((n, u, d + (", averaged over the communication step" if n in STEP_AVERAGED_NAMES else ""))
                    for n, u, d in OUTPUT_SPEC) + tuple(
    ("instantaneous_" + n, _spec[n][0], _spec[n][1] + ", instantaneous value at the communication point")
    for n in STEP_AVERAGED_NAMES)
del _spec
OUTPUT_SPEC += (
    ("oil_fraction_used", "1", "oil volume fraction of the cavity's oil-air mixture that drag and churning use: "
                               "oil_fraction if > 0, else the oil supply's cavity oil content at the running speed "
                               "(bearing_core.lubrication.oil_supply)"),
)
# The bearing's 5 x 5 stiffness (docs/fidelity.md "Stiffness"), FMI 2 array-element names stiffness[i,j], i, j = 1..5:
# rows Fx, Fy, Fz [N], Mx, My [N m] (the load on the inner ring), columns dx, dy, dz [m], tx, ty [rad] (its pose).
# Sign: K[i,j] = d(load_i)/d(pose_j) = -d(reaction_i)/d(pose_j) (a restoring bearing has positive diagonal entries;
# the Jones-Harris convention of bearing_core.models.quasistatic). What each fidelity level gives: STIFFNESS_DESC.
STIFFNESS_ROWS = (("Fx", "N"), ("Fy", "N"), ("Fz", "N"), ("Mx", "N.m"), ("My", "N.m"))
STIFFNESS_COLS = (("dx", "m"), ("dy", "m"), ("dz", "m"), ("tx", "rad"), ("ty", "rad"))
STIFFNESS_NAMES = tuple(f"stiffness[{i + 1},{j + 1}]" for i in range(5) for j in range(5))
"""The 25 stiffness outputs, row-major (stiffness[i,j] at STIFFNESS_NAMES[5 (i - 1) + (j - 1)])."""
STIFFNESS_DESC = ("the levels' stiffness: dynamic, tangent of the reactions at the current contact state with the "
                  "balls held; quasi-static, the derivative of the level's reactions along its solution; map, the "
                  "map's Jones-Harris stiffness turned with the radial load")
OUTPUT_SPEC += tuple(
    (STIFFNESS_NAMES[5 * i + j], f"{ru}/{cu}",
     f"bearing stiffness d({rn} load on the inner ring)/d({cn}) = -d(reaction_{rn})/d({cn}) ({STIFFNESS_DESC})")
    for i, (rn, ru) in enumerate(STIFFNESS_ROWS) for j, (cn, cu) in enumerate(STIFFNESS_COLS))
# Fatigue (bearing_core.models.life; docs/life.md "In a co-simulation"): the ISO/TS 16281 reference rating life at
# the current state (per-ball contact loads and operating contact angles, inner ring rotating) and the Palmgren-Miner
# damage of the run, sum over the communication steps of h / L10r_h (0 at the start; part of the session's state).
LIFE_CAP_H = 1.0e12
"""h: the life reported where it is infinite (no loaded ball, standstill); such a step adds no damage."""
LIFE_NAMES = ("life_L10r_h", "fatigue_damage")
OUTPUT_SPEC += (
    ("life_L10r_h", "h", "ISO/TS 16281 reference rating life L10r at the current state (per-ball contact loads and "
                         "operating contact angles, inner ring rotating; infinite life, no loaded ball or standstill, "
                         f"reported as {LIFE_CAP_H:g} h; fidelity map: 0 where the map has no "
                         "fatigue_damage_rate, unknown)"),
    ("fatigue_damage", "1", "Palmgren-Miner damage of the run: sum over the communication steps of h / L10r (0 at the "
                            "start; part of the FMU state)"),
)
OUTPUT_NAMES = tuple(n for n, _, _ in OUTPUT_SPEC)

# Integer outputs (FMI Integer variables)
INT_OUTPUT_SPEC = (
    ("skid_state", "1", "cage skid state: 1 skidding, 0 pure rolling (|cage_slip_ratio| <= 1 %), -1 over-skidding"),
    ("thermal_runaway", "1", "1 once a thermal-network temperature passed the oil's limit (the step is "
                             "then discarded), else 0"),
)
INT_OUTPUT_NAMES = tuple(n for n, _, _ in INT_OUTPUT_SPEC)


P_LIMIT = 4.2e9
"""Pa: the ISO 76 static-capacity contact stress of ball bearings; beyond it every fidelity level refuses the
loads."""


def parse_inputs(inputs: dict) -> dict:
    """The inputs by name (INPUT_NAMES; missing ones 0.0) as finite floats, in their units (INPUT_UNITS);
    raises bearing_core.errors.BearingInputError naming an unknown input or a value that is not a finite
    number."""
    import math
    from ..errors import BearingInputError
    u = {n: 0.0 for n in INPUT_NAMES}
    for k, v in inputs.items():
        if k not in u:
            raise BearingInputError("input", k, ", ".join(INPUT_NAMES))
        try:
            v = float(v)
        except (TypeError, ValueError):
            raise BearingInputError(k, v, "a finite number")
        if not math.isfinite(v):
            raise BearingInputError(k, v, "a finite number")
        u[k] = v
    return u
