"""Interface of the observer module (mission DETUMBLE, spec 10-observer): the single source of its
names and its telemetry block. Not flight code: `python -m tools.iface c` turns it into
obs_ids.h and obs_tlm.c (committed; CTest golden_iface_regen checks them) and the build turns it
into the host's tables; Python tools read it through tools.iface.
"""
from tools.iface.schema import Bit, Chan, Field, Module

AX = ("y", "z")
X_NAMES = (("wy", "rad/s"), ("wz", "rad/s"), ("muy", "rad"), ("mudoty", "rad/s"), ("muz", "rad"),
           ("mudotz", "rad/s"))
COUNTERS = ("skip", "gap", "lost", "reinit", "clamp_lo", "clamp_hi", "limited", "innov", "cov_clip")


def _tlm():
    f = [Field("x_" + n, "i32", "t->x_q29[%du]" % i, q=29, unit=u, note="estimate")
         for i, (n, u) in enumerate(X_NAMES)]
    f.append(Field("kappa", "i32", "t->kappa_q28", q=28, unit="-", note="kappa = K / 0.01 s^-2"))
    f += [Field("u_" + a, "i32", "t->u_q29[%du]" % i, q=29, unit="rad/s",
                note="limited gimbal-rate command" if i == 0 else "") for i, a in enumerate(AX)]
    f += [Field("e_" + a, "i32", "t->e_q29[%du]" % i, q=29, unit="rad/s", note="innovation" if i == 0 else "")
          for i, a in enumerate(AX)]
    f += [Field("d2_" + a, "i32", "t->d2_q16[%du]" % i, q=16, unit="-",
                note="normalised innovation squared" if i == 0 else "") for i, a in enumerate(AX)]
    f.append(Field("pkk", "i32", "t->pkk_q30", q=30, unit="-",
                   note="scaled kappa variance: var(kappa) = pkk * 4^ls6, ls6 = table ls[6] (-1 in shipped tables)"))
    f.append(Field("health_sticky", "u32", "t->health_sticky"))
    f += [Field("n_" + c, "u32", "t->n_" + c, unit="count") for c in COUNTERS]
    f.append(Field("revision", "u32", "t->revision", note="observer table revision in use"))
    return f


def _vec(name, n):
    return ["%s[%d]" % (name, i) for i in range(n)]


MODULE = Module(
    module="observer",
    prefix="obs",
    doc="adaptive observer and B-dot-like gimbal-rate law of the sail platform (spec 10)",
    tlm_type="obs_tlm_t",
    tlm_layout=2,   # 2: the executive header gained n_tc, n_tc_rej (layout 1 had neither)
    tlm=_tlm(),
    sensors=[Chan("omega_BN_B_y", "2^-20 rad/s", "gyro y: body rate wrt inertial, body axes (range: table gyro_max_cnt)"),
             Chan("omega_BN_B_z", "2^-20 rad/s", "gyro z: body rate wrt inertial, body axes")],
    actuators=[Chan("act_cnt_y", "actuator count", "gimbal rate y command (2^-20 rad/s)"),
               Chan("act_cnt_z", "actuator count", "gimbal rate z command")],
    health=[
        Bit("NOT_INIT", 0x00000100, "no valid table at init"),
        Bit("MEAS_SKIP", 0x00000200, "an axis skipped this step (stale or saturated)"),
        Bit("MEAS_LOST", 0x00000400, "no valid axis for n_lost steps"),
        Bit("REINIT", 0x00000800, "re-initialised (gap or recovery)"),
        Bit("K_CLAMP_LO", 0x00001000, "kappa at its lower clamp"),
        Bit("K_CLAMP_HI", 0x00002000, "kappa at its upper clamp"),
        Bit("ADAPT_FROZEN", 0x00004000, "kappa adaptation frozen"),
        Bit("CMD_LIMITED", 0x00008000, "command vector limited this step"),
        Bit("CMD_LIMIT_PERSIST", 0x00010000, "command limited for n_sat steps"),
        Bit("INNOV_HIGH", 0x00020000, "normalised innovation above d2_max (rejected when d2_reject)"),
        Bit("COV_CLIP", 0x00040000, "covariance clipped to its floor or ceiling"),
        Bit("SEQ", 0x00080000, "sequence gap or repeat"),
        Bit("INNOV_PERSIST", 0x00100000, "a channel failed the innovation gate n_rej_safe times in a row"),
    ],
    why=[
        Bit("PERIOD", 0x001, "period"),
        Bit("ESTIMATOR", 0x002, "estimator selection"),
        Bit("FORMAT", 0x004, "a matrix Q below 16 fraction bits or above 40"),
        Bit("BAND", 0x008, "band must contain kappa0 and kappa_init, lo < hi"),
        Bit("LIMIT", 0x010, "bdot_max not in (0, hardware limit]"),
        Bit("COV", 0x020, "P0 <= 0, Q below 4 LSB, floor >= ceiling, R <= 0"),
        Bit("SCALE", 0x040, "scale exponents out of range"),
        Bit("FAULT", 0x080, "counters out of range"),
        Bit("SENSOR", 0x100, "gyro/actuator scaling out of range"),
    ],
    table_id=0x0B01,
    table_layout=2,   # 2: n_rej_safe, rej_leak_inc, rej_freeze_on appended (innovation gate)
    table_fields=(["period_us", "estimator", "gyro_cnt_shift", "act_cnt_shift", "d2_reject", "sigma",
                   "gyro_max_cnt", "act_max_cnt", "bdot_max_q29", "bdot_hw_q29", "q_phi0", "q_phik", "q_gam0",
                   "q_gamk", "q_d", "q_w", "n_lost", "n_good", "n_sat", "n_gap_max", "kappa0_q28",
                   "kappa_init_q28", "kappa_lo_q28", "kappa_hi_q28", "r_q30", "p_floor_q30", "p_ceil_q30",
                   "d2_max_q16"] + _vec("ls", 7) + _vec("p0_q30", 7) + _vec("qd_q30", 7)
                  + ["n_rej_safe", "rej_leak_inc", "rej_freeze_on"]),
)
