"""Interface of the pd module (mission HOLD, spec 40): the single source of its names and its
telemetry block. Not flight code: `python -m tools.iface c` turns it into pd_ids.h and pd_tlm.c
(committed; CTest golden_iface_regen checks them), the build turns it into the host's tables, and
Python tools read it through tools.iface (tools/iface/schema.py documents every constructor).

Three channels (k = yaw, roll, pitch), one law instance each (pd.h). The telemetry block carries
each channel's sample; the health word of the mission is the OR of the three channels' words.
"""
from tools.iface.schema import Arg, Bit, Chan, Field, Module, enum, tc

CHANNELS = ("yaw", "roll", "pitch")


def _tlm():
    f = []
    for k, ch in enumerate(CHANNELS):
        c = "t->ch[%du]." % k
        f += [Field("%s_y" % ch, "i32", c + "y_q30", q=30, unit="rad", note="attitude sample in use"),
              Field("%s_dy" % ch, "i32", c + "dy_q30", q=30, unit="rad", note="y_k - y_k-1 (0 after a restart)"),
              Field("%s_m" % ch, "i32", c + "m_q28", q=28, unit="N m", note="gimbal torque command"),
              Field("%s_k2" % ch, "u32", c + "k2_q22", q=22, unit="s", note="derivative gain in use"),
              Field("%s_health" % ch, "u32", c + "health", note="the channel's health word of the last sample"),
              Field("%s_health_sticky" % ch, "u32", c + "health_sticky", note="OR since init or RESET_COUNTERS"),
              Field("%s_miss" % ch, "u32", c + "miss_cnt", unit="count", note="samples missing (invalid or stale)"),
              Field("%s_stale" % ch, "u32", c + "stale_cnt", unit="count", note="samples refused as frozen"),
              Field("%s_range_rej" % ch, "u32", c + "range_rej", unit="count", note="|y| > y_lim or saturated"),
              Field("%s_rate_rej" % ch, "u32", c + "rate_rej", unit="count", note="|dy| > dy_max"),
              Field("%s_period_rej" % ch, "u32", c + "period_rej", unit="count",
                    note="control periods with > n_bad_max invalid samples"),
              Field("%s_trq_sat" % ch, "u32", c + "trq_sat_cnt", unit="count", note="samples at +-M_max"),
              Field("%s_beta_lim" % ch, "u32", c + "beta_lim_cnt", unit="count",
                    note="samples with |beta| >= beta_lim (outward torque zeroed)"),
              Field("%s_fest_f" % ch, "u32", c + "fest_f_q32", q=32, unit="Hz",
                    note="estimator: published f_hat (0 while the channel is not ADAPTIVE)"),
              Field("%s_fest" % ch, "u32", c + "fest_word",
                    note="estimator: state 0..3 = ACQUIRE/TRACK/HOLD/FAULT (bits 0..1), confident (bit 2), "
                         "gate open (bit 3), last fault reasons PD_FEST_F_* (bits 8..15)"),
              Field("%s_fest_p" % ch, "u32", c + "fest_p_a_q30", q=30, note="estimator: RLS P of the notch"),
              Field("%s_fest_att" % ch, "u32", c + "fest_att_q16", q=16, note="estimator: notch rms(out)/rms(in)"),
              Field("%s_fest_resets" % ch, "u32", c + "fest_resets", unit="count",
                    note="estimator FAULTs since init")]
    f += [Field("revision", "u32", "t->revision", note="table revision in use")]
    return f


MODULE = Module(
    module="pd",
    prefix="pd",
    doc="HOLD: gyrodine PD channels with a scheduled derivative gain (spec 40)",
    tlm_type="pd_tlm_t",
    tlm_layout=3,
    tlm=_tlm(),
    sensors=[Chan("psi_BN_yaw", "2^-26 rad", "attitude, yaw channel"),
             Chan("phi_BN_roll", "2^-26 rad", "attitude, roll channel"),
             Chan("theta_BN_pitch", "2^-26 rad", "attitude, pitch channel"),
             Chan("beta_g_yaw", "2^-24 rad", "gimbal encoder, yaw gyrodine"),
             Chan("beta_g_roll", "2^-24 rad", "gimbal encoder, roll gyrodine"),
             Chan("beta_g_pitch", "2^-24 rad", "gimbal encoder, pitch gyrodine")],
    actuators=[Chan("m_g_yaw", "2^-20 N m", "gimbal torque command, yaw gyrodine"),
               Chan("m_g_roll", "2^-20 N m", "gimbal torque command, roll gyrodine"),
               Chan("m_g_pitch", "2^-20 N m", "gimbal torque command, pitch gyrodine")],
    health=[
        Bit("LAW", 0x00000300, "law mode (PD_LAW_*)"),
        Bit("SRC", 0x00000C00, "gain source (PD_SRC_*)"),
        Bit("FEST", 0x00003000, "estimator state (ACQUIRE 0, TRACK 1, HOLD 2, FAULT 3) while SRC is ADAPTIVE, else 0"),
        Bit("STALE", 0x00004000, "no usable sample this step (missing, stale, rejected): torque held, then zero"),
        Bit("FROZEN", 0x00008000, "attitude bit-identical for n_frozen samples under torque: refused"),
        Bit("TRQ_SAT", 0x00010000, "command clamped to +-M_max (the designated saturation point)"),
        Bit("BETA_WARN", 0x00020000, "|beta| > beta_warn: the linear model is strained"),
        Bit("BETA_LIM", 0x00040000, "|beta| >= beta_lim: outward torque zeroed"),
        Bit("FEST_FAULT", 0x00080000, "estimator in FAULT this period (k2_cold applied)"),
        Bit("FALLBACK_GAIN", 0x00100000, "k2 is k2_cold"),
        Bit("RETUNE", 0x00200000, "k2 changed at this sample (pulse)"),
        Bit("TABLE_DEFAULT", 0x00400000, "flying the boot table"),
        Bit("REJECT", 0x00800000, "this sample was refused (range or rate)"),
        Bit("COAST", 0x01000000, "missing for more than n_hold samples: zero torque"),
        Bit("PERIOD_BAD", 0x02000000, "averaged modes: the last control period had too many invalid samples"),
    ],
    why=[
        Bit("PERIOD", 0x01, "period: zero, not the executive's, or 1/Ty not within 1 LSB of n_div period_us"),
        Bit("GAIN", 0x02, "gain: k0 k1 >= 2^10, k0 k2_max / Ty >= 2^16, or k2 order (min <= nom, cold <= max)"),
        Bit("LIMIT", 0x04, "torque or sensor limit out of range"),
        Bit("MODE", 0x08, "law or gain source unknown, ADAPTIVE on a channel whose estimator block pd_fest_check "
                         "refuses or with Ty != 0.25 s, or schedule law != law"),
        Bit("SCHED", 0x10, "schedule: node above k2_max, table increasing in f, or node spacing zero"),
        Bit("NY", 0x20, "n_y not a power of two in [2, 64], or n_bad_max >= n_y"),
        Bit("CAP", 0x40, "roll k2_max above its sampled-mode cap (150 s)"),
        Bit("FAULT", 0x80, "fault thresholds: n_hold, n_frozen or beta limits"),
    ],
    enums=[
        enum("law", "PD_LAW_", [("FAST", 0, "P and D on every sample (shipped)"),
                                ("FAST_AVGP", 1, "P on the last period's mean, D every sample"),
                                ("LITERAL", 2, "the source's averaged law, held T0 (demonstration only)")],
             "law mode (spec 40 §3)"),
        enum("src", "PD_SRC_", [("FIXED", 0, "k2_nom of the table or SET_K2"),
                                ("GROUND", 1, "the schedule at the commanded f"),
                                ("ADAPTIVE", 2, "the schedule at the on-board estimate (pitch, roll; yaw refused)")],
             "gain source (spec 40 §4.2)"),
    ],
    commands=[
        tc("RESET_COUNTERS", 1, "clear the channels' counters and sticky health"),
        tc("SET_SOURCE", 2, "gain source FIXED (0), GROUND (1) or ADAPTIVE (2: on the channels with a usable "
                           "estimator, pitch and roll; a cold start at k2_cold); takes effect at the next sample", args=[
            Arg("src", scale=1.0, lo=0.0, hi=2.0, required=True, unit="PD_SRC_*")]),
        tc("SET_F", 3, "GROUND at this commanded f_min", args=[
            Arg("f_hz", scale=1.0e6, lo=0.0, hi=0.5, required=True, unit="1e-6 Hz")]),
        tc("SET_K2", 4, "FIXED at these k2 (yaw, roll, pitch), each limited to [k2_min, k2_max]", args=[
            Arg("k2_s", scale=256.0, lo=0.0, hi=1023.0, n=3, required=True, unit="2^-8 s")]),
    ],
    table_id=0x0B07,
    table_layout=3,
    table_fields=(["period_us", "inv_ty_q22", "law", "src", "sched_law", "ch_mask", "n_y", "n_bad_max", "n_div",
                   "n_hold", "n_frozen", "y_lim_q30", "dy_max_q30", "m_max_q28", "m_frozen_q28", "beta_warn_q24",
                   "beta_lim_q24", "f0_q32", "df_inv_q16", "f_ground_q32"] +
                  ["%s_%s" % (ch, n) for ch in CHANNELS
                   for n in ("k0_q22", "k1_q22", "k2_nom_q22", "k2_cold_q22", "k2_min_q22", "k2_max_q22",
                             "fest_n_sec", "fest_n_reg")]),
)
