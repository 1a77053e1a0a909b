"""Interface of the relay module (mission RELAY, spec 20-relay): the single source of its names,
enums, health bits and telemetry block. Not flight code: `python -m tools.iface c` turns it into
rly_ids.h and rly_tlm.c (committed; CTest golden_iface_regen checks them); Python tools read it
through tools.iface.
"""
from tools.iface.schema import Bit, Chan, Field, Module, enum, tc


def _vec(name, n):
    return ["%s_%d" % (name, i) for i in range(n)]


def _tlm():
    f = [Field("st", "u8", "t->st", note="law state (RLY_ST_*)"),
         Field("cmd", "u8", "t->cmd", note="level commanded this tick (RLY_LVL_*)"),
         Field("x", "i32", "t->x_q24", q=24, unit="rad", note="angle sample used (0 when invalid)"),
         Field("a", "u32", "t->a_q40", q=40, unit="rad", note="envelope estimate a = sum a_i (saturating)")]
    f += [Field("a_%d" % i, "u32", "t->ai_q40[%du]" % i, q=40, unit="rad", note="mode %d envelope" % (i + 1))
          for i in range(4)]
    f += [Field("kt", "u16", "t->kt_q16", q=16, note="k_t in force"),
          Field("n", "u32", "t->n", unit="tick", note="main-pulse timer"),
          Field("nb", "u32", "t->nb", unit="tick", note="brake countdown"),
          Field("tau1", "u32", "t->tau1", unit="tick", note="last main pulse"),
          Field("tau2", "u32", "t->tau2", unit="tick", note="last brake"),
          Field("n_r_main", "u32", "t->n_r_main", unit="count", note="entries into R_MAIN"),
          Field("n_l_main", "u32", "t->n_l_main", unit="count", note="entries into L_MAIN")]
    for n, note in (("x_invalid", "invalid samples"), ("x_range", "samples beyond x_max"),
                    ("lost", "entries into COAST"), ("tau_sat", "main-pulse timer saturations"),
                    ("kt_clamped", "k_t changes clamped to the limits"), ("env_sat", "anchor saturations"),
                    ("reinit", "re-initialisations of the copy"), ("env_high", "windows above env_alarm"),
                    ("windows", "windows closed")):
        f.append(Field("n_" + n, "u32", "t->n_" + n, unit="count", note=note))
    f += [Field("health_sticky", "u32", "t->health_sticky"),
          Field("seed", "u32", "t->seed", note="generator seed of the table"),
          Field("revision", "u32", "t->revision", note="table revision in use"),
          Field("win_j", "u32", "t->win.j", note="last window: index"),
          Field("win_s", "i64", "t->win_s", q=40, unit="rad tick", note="last window: S_j"),
          Field("win_abar", "u32", "t->win.abar_q40", q=40, unit="rad", note="last window: mean envelope"),
          Field("win_kt_in", "u16", "t->win.kt_in_q16", q=16, note="last window: k_t in force"),
          Field("win_kt_next", "u16", "t->win.kt_next_q16", q=16, note="last window: k_t next"),
          Field("win_phase", "u8", "t->win.phase", note="RLY_PH_* after the decision"),
          Field("win_event", "u8", "t->win.event", note="RLY_EV_*"),
          Field("win_sign", "i32", "t->win.sign", note="sign of the step"),
          Field("win_mag", "u32", "t->win.mag_q16", q=16, note="magnitude drawn"),
          Field("win_n_small", "u8", "t->win.n_small", unit="count"),
          Field("win_n_dec", "u32", "t->win.n_dec", unit="count"),
          Field("win_s_ref", "i64", "t->win_s_ref", q=40, unit="rad tick"),
          Field("win_rng", "u32", "t->win.rng", note="generator state after the decision"),
          Field("win_invalid", "u32", "t->win.n_invalid", unit="count", note="invalid samples in the window")]
    return f


MODULE = Module(
    module="relay",
    prefix="rly",
    doc="RELAY: relay-logic law with envelope estimator and k_t adaptation (spec 20)",
    tlm_type="rly_tlm_t",
    tlm_layout=1,
    tlm=_tlm(),
    sensors=[Chan("x_B_rad", "2^-24 rad", "attitude angle about the controlled axis (rigid + modes)")],
    actuators=[Chan("m_cmd_B", "enum", "relay level RLY_LVL_* (0 OFF, +-m_eps, +-m_u)")],
    health=[
        Bit("X_INVALID", 0x00000100, "no valid sample this tick: level tests skipped"),
        Bit("X_RANGE", 0x00000200, "|x| > x_max: sample refused"),
        Bit("SENSOR_LOST", 0x00000400, "lost_ticks invalid samples in a row: COAST"),
        Bit("TAU_SAT", 0x00000800, "main-pulse timer at tau_max_ticks"),
        Bit("KT_CLAMPED", 0x00001000, "k_t change clamped to [kt_min, kt_max]"),
        Bit("ENV_SAT", 0x00002000, "an envelope anchor saturated (sticky)"),
        Bit("REINIT", 0x00004000, "the copy was re-initialised"),
        Bit("ENV_HIGH", 0x00008000, "window mean above env_alarm"),
        Bit("WIN_DONE", 0x00010000, "a window closed this tick (the packet is new)"),
    ],
    why=[
        Bit("PERIOD", 0x001, "period (zero, or not the executive's)"),
        Bit("GEOM", 0x002, "epsilon, gamma, x_max: 2 <= gamma < epsilon <= x_max"),
        Bit("KT", 0x004, "1 <= kt_min <= kt0 <= kt_max, 1 <= dk <= (kt_max - kt_min) / 4"),
        Bit("SEED", 0x008, "generator seed zero"),
        Bit("WIN", 0x010, "win_ticks outside [1, 2^21], tmin_windows or tau_max zero"),
        Bit("MODES", 0x020, "n_modes > 4, |C| > 2^29 or |q0|, |p0| > 2^30"),
        Bit("PHASE", 0x040, "dphi >= 2^62, or not round(f h 2^64) within 1 LSB"),
        Bit("ADAPT", 0x080, "adaptation mode or ratios (num, den in 1..255; delta0 < 1 < cliff, unfreeze)"),
        Bit("LOST", 0x100, "lost_ticks zero"),
    ],
    enums=[
        enum("st", "RLY_ST_", [("W_POS", 0), ("R_MAIN", 1), ("R_BRAKE", 2), ("W_NEG", 3), ("L_MAIN", 4),
                                ("L_BRAKE", 5), ("COAST", 6)], "law states (spec 20 §3.2)"),
        enum("lvl", "RLY_LVL_", [("OFF", 0), ("WEAK_POS", 1), ("WEAK_NEG", 2), ("FULL_POS", 3), ("FULL_NEG", 4)],
             "actuator levels: the command is an enum, never a number (spec 20 §2.4)"),
        enum("adapt", "RLY_ADAPT_", [("OFF", 0), ("PAPER", 1), ("IMPROVED", 2), ("IMPROVED_UP", 3)], "k_t adaptation modes"),
        enum("ph", "RLY_PH_", [("SEARCH", 0), ("PROBE", 1), ("FROZEN", 2)], "adaptation phases"),
        enum("ev", "RLY_EV_", [("NONE", 0), ("STEP", 1), ("PROBE_START", 2), ("FREEZE_SETTLED", 3),
                                ("FREEZE_CLIFF", 4), ("UNFREEZE", 5), ("SKIPPED", 6)],
             "window events"),
    ],
    commands=[tc("RESET_COUNTERS", 1, "clear the module's counters and sticky health")],
    table_id=0x0B05,
    table_layout=1,
    table_fields=(["period_us", "x_max_q24", "eps_q24", "gamma_q24", "tau_max_ticks", "win_ticks", "seed",
                   "env_alarm_q40", "lost_ticks", "tmin_windows", "dk_q16", "kt0_q16", "kt_min_q16", "kt_max_q16",
                   "n_modes", "adapt_mode", "delta0_num", "delta0_den", "n_small", "n_ignore", "count_before_tmin",
                   "learn_after_tmin", "gate_dk", "probe_settle", "cliff_num", "cliff_den", "retreat_dk",
                   "unfreeze_num", "unfreeze_den", "unfreeze_windows"] +
                  _vec("dphi_lo", 4) + _vec("dphi_hi", 4) + _vec("f_lo", 4) + _vec("f_hi", 4) +
                  _vec("cu_q40", 4) + _vec("ce_q40", 4) + _vec("q0_q40", 4) + _vec("p0_q40", 4)),
)
