"""Interface of the impulse scheduler (mission RENDEZVOUS, spec 50-impulse): the single source of
its names and its telemetry block. Not flight code: `python -m tools.iface c` turns it into
imp_ids.h and imp_tlm.c (committed; CTest golden_iface_regen checks them) and the build turns it
into the host's tables; Python tools read it through tools.iface.
"""
from tools.iface.schema import Arg, Bit, Chan, Field, Module, enum, tc

AX = "xyz"
THR = ("px", "mx", "py", "my", "pz", "mz")   # thruster j = +x, -x, +y, -y, +z, -z
FAIL = enum("fail", "IMP_FAIL_", [
    ("NONE", 0), ("ITER", 1, "iteration limit"), ("DIVERGE", 2, "an iterate left (-tau_f, 2 tau_f)"),
    ("SINGULAR", 3, "|pivot| < pivot_min"), ("COND", 4, "smallest / largest pivot below 2^-pivot_ratio_sh"),
    ("FX", 5, "any other fx status bit in the attempt"), ("ORDER", 6, "converged, but not 0 <= T1 <= T2 <= tau_f"),
    ("N", 7, "number of causes")], "attempt failure causes (index of n_fail)")


def _tlm():
    f = [Field(n, "u32", "t->" + n) for n in ("plans", "plans_failed", "plans_late", "plans_skipped", "cmd_rej",
                                              "nav_rej", "cal_rej", "plans_kept")]
    f += [Field("fail_" + n.lower(), "u32", "t->n_fail[%du]" % v, note="attempt failures by cause")
          for n, v, _ in FAIL.values if n != "N"]
    for n, note in [("mode", "IMP_MODE_*"), ("rej_reason", "IMP_REJ_* of the last refused command"),
                    ("how_xy", "0 none 1 warm 2 rule 3 search"), ("how_z", ""), ("pattern", "polarity bits"),
                    ("iters_xy", ""), ("iters_z", ""), ("last_fail_xy", ""), ("last_fail_z", ""),
                    ("stuck_j", "0xFF: none"), ("stuck_off_mask", ""), ("job_active", "")]:
        f.append(Field(n, "u8", "t->" + n, note=note))
    f.append(Field("plan_units", "u16", "t->plan_units"))
    f.append(Field("plan_steps", "u16", "t->plan_steps"))
    f.append(Field("fres_xy", "i32", "t->fres_lsb[0u]", unit="LSB q28"))
    f.append(Field("fres_z", "i32", "t->fres_lsb[1u]", unit="LSB q28"))
    for n in ("t1", "t2"):
        f += [Field("%s_%s" % (n, AX[r]), "i32", "t->%s_q29[%du]" % (n, r), q=29, unit="rad (w t)") for r in range(3)]
    for n in ("on1_step", "on2_step", "on1_us", "on2_us"):
        f += [Field("%s_%s" % (n, AX[r]), "u32", "t->%s[%du]" % (n, r)) for r in range(3)]
    f += [Field("miss_" + s, "i32", "t->miss_q28[%du]" % k, q=28, note="predicted terminal error, nondimensional")
          for k, s in enumerate(("x", "xd", "y", "yd", "z", "zd"))]
    f.append(Field("round_xy", "u8", "t->round_choice[0u]"))
    f.append(Field("round_z", "u8", "t->round_choice[1u]"))
    for n in ("rho", "dv1", "dv2"):
        f += [Field("%s_%s" % (n, AX[r]), "i32", "t->%s_q28[%du]" % (n, r), q=28) for r in range(3)]
    for n in ("dv_cmd", "dv_used"):
        f += [Field("%s_%s" % (n, THR[j]), "i32", "t->%s_q28[%du]" % (n, j), q=28, unit="a_nom/w") for j in range(6)]
    f += [Field("alpha_" + THR[j], "i32", "t->alpha_q30[%du]" % j, q=30) for j in range(6)]
    f += [Field("cal_windows_" + THR[j], "u16", "t->cal_windows[%du]" % j) for j in range(6)]
    for n in ("nu", "exp_dr", "exp_dv"):
        f += [Field("%s_%s" % (n, AX[r]), "i32", "t->%s_q28[%du]" % (n, r), q=28) for r in range(3)]
    f += [Field(n, "u32", "t->" + n) for n in ("nav_age", "st_step", "st_sticky", "health_sticky", "revision")]
    return f


def _vec(name, n):
    return ["%s[%d]" % (name, i) for i in range(n)]


MODULE = Module(
    module="impulse",
    prefix="imp",
    doc="impulse scheduler: terminal rendezvous with six on/off thrusters (spec 50)",
    tlm_type="imp_tlm_t",
    tlm_layout=1,
    tlm=_tlm(),
    # frame R is spec 50 §2.1's: x forward (along-track), y towards the Earth, z = orbit normal
    sensors=([Chan("r_CT_R_" + a, "1 mm", "chaser position wrt target, R " + a) for a in "xyz"] +
             [Chan("v_CT_R_" + a, "10 um/s", "chaser velocity wrt target, R " + a) for a in "xyz"] +
             [Chan("nav_step", "step", "the sample's step index (the plant's k)")]),
    actuators=([Chan("act_start_" + THR[j], "us", "on-window start in the step") for j in range(6)] +
               [Chan("act_len_" + THR[j], "us", "on-window length") for j in range(6)] +
               [Chan("act_mask", "bit set", "bit j: thruster j on")]),
    health=[
        Bit("MODE", 0x00000F00, "IMP_MODE_* of this step"),
        Bit("INFEASIBLE", 0x00001000), Bit("NO_SOLUTION", 0x00002000), Bit("MARGINAL", 0x00004000),
        Bit("NAV_STALE", 0x00008000), Bit("THRUST_LEVEL", 0x00010000), Bit("EXPECTED_MISS", 0x00020000),
        Bit("INTERLOCK", 0x00040000),
        Bit("STUCK_OFF", 0x00380000, "STUCK_OFF of axis r: bit 19 + r"),
        Bit("STUCK_ON", 0x01C00000, "STUCK_ON of axis r: bit 22 + r"),
        Bit("CMD_REJ", 0x02000000, "a command was refused in this step (reason in tlm)"),
    ],
    why=[
        Bit("PERIOD", 0x001, "period, t_min, rounding weight"),
        Bit("ITER", 0x002, "max_iter, plan_iter_per_step, re-plan timing"),
        Bit("TOL", 0x004, "r_tol, pivot_min, pivot ratio"),
        Bit("RHO", 0x008, "0 < rho_warn <= rho_reject <= 1"),
        Bit("ALPHA", 0x010, "alpha_j outside [0.8, 1.2]"),
        Bit("SCALE", 0x020, "count / tick scale constants inconsistent"),
        Bit("TAU", 0x040, "tau_f limits outside [0.2, 2.0]"),
        Bit("LEAD", 0x080, "plan_lead < ceil(worst plan / plan_iter_per_step)"),
        Bit("GRID", 0x100, "sub-tick grid or its scale constants"),
        Bit("CAL", 0x200, "calibration and expected-miss parameters"),
        Bit("FD", 0x400, "stuck-valve monitor parameters"),
        Bit("NAV", 0x800, "nav timeout and outlier gate"),
    ],
    enums=[
        enum("mode", "IMP_MODE_", [
            ("IDLE", 0), ("PLANNING", 1), ("ARMED", 2), ("FIRING", 3), ("FINAL", 4), ("DONE", 5),
            ("INFEASIBLE", 6), ("NO_SOLUTION", 7), ("ABORTED", 8), ("FAULT", 9)],
            "scheduler modes (spec 50 §5.1; health bits 8..11)"),
        FAIL,
        enum("rej", "IMP_REJ_", [
            ("NONE", 0), ("MODE", 1, "START outside a terminal mode, or an unknown command"),
            ("TIME", 2, "t0 < now + plan_lead, or t_f <= t0"), ("TAU", 3, "tau_f outside [tauf_min, tauf_max]"),
            ("NO_NAV", 4, "no accepted nav sample within nav_timeout"),
            ("TARGET", 5, "target (or nav state) beyond the q28 range")],
            "reason of the last refused command (imp_tlm_t.rej_reason)"),
        enum("how", "IMP_HOW_", [("NONE", 0), ("WARM", 1), ("RULE", 2), ("SEARCH", 3)],
             "how the polarities were found"),
    ],
    commands=[
        tc("START", 1, "plan and fly a rendezvous to the target at t_f", args=[
            Arg("t0_s", kind="steps", lo=0.0, hi=1.0e6, required=True, unit="step"),
            Arg("tf_s", kind="steps", lo=0.0, hi=1.0e6, required=True, unit="step"),
            Arg("target_pos_m", scale=1000.0, lo=-1.0e6, hi=1.0e6, n=3, unit="1 mm"),
            Arg("target_vel_mps", scale=1.0e5, lo=-100.0, hi=100.0, n=3, unit="10 um/s")]),
        tc("ABORT", 2, "every thruster off, ABORTED"),
        tc("CLEAR_FAULTS", 3, "clear the scheduler's faults (back to IDLE)"),
    ],
    table_id=0x0B04,
    table_layout=1,
    table_fields=(["period_us", "subtick_us", "t_min_us", "plan_lead", "replan_period", "t_stop", "nav_timeout",
                   "max_iter", "plan_iter_per_step", "pivot_ratio_sh", "k_tau_sh", "r_tol_lsb", "pivot_min_q26",
                   "rho_warn_q28", "rho_reject_q28", "dv_tie_q28", "tauf_min_q29", "tauf_max_q29", "w_v_q28"] +
                  _vec("alpha_q30", 6) +
                  ["k_pos_m", "k_pos_sh", "k_vel_sh", "k_tick_sh", "spare", "k_vel_m", "k_tau_m", "k_tick_m",
                   "omega_nradps", "a_nom_umps2", "k_gtau_m", "k_gtick_m", "k_gtau_sh", "k_gtick_sh", "cal_enable",
                   "cal_pool", "dv_cal_min_q28", "cal_gate_q30", "u_uncal_q30", "u_cal_q30", "miss_flag_q28",
                   "fd_window", "fd_frac_q30", "fd_persist"] + _vec("spare2", 3) +
                  ["nav_gate_pos_q28", "nav_gate_vel_q28", "nav_gate_acc_q28", "replan_gain_q30"]),
)
