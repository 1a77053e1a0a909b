"""Interface of the pd module (mission HOLD): the single source of its names and its
telemetry block. Not flight code: `python -m tools.iface c` turns it into pd_ids.h and
pd_tlm.c (committed; CTest golden_iface_regen checks them), the build turns it into the
host's tables, and Python tools read it through tools.iface (tools/iface/schema.py documents
every constructor; fsw/impulse/imp_iface.py shows enums and telecommands with arguments).
"""
from tools.iface.schema import Bit, Chan, Field, Module, tc


def _tlm():
    return [Field("rate", "i32", "t->rate_cnt", unit="2^-20 rad/s", note="body rate of the last step"),
            Field("u", "i32", "t->u_cnt", unit="2^-16 N m", note="torque command of the last step"),
            Field("n_skip", "u32", "t->n_skip", unit="count", note="steps without a valid rate"),
            Field("n_limited", "u32", "t->n_limited", unit="count", note="steps with the command at its limit"),
            Field("health_sticky", "u32", "t->health_sticky"),
            Field("revision", "u32", "t->revision", note="table revision in use")]


MODULE = Module(
    module="pd",
    prefix="pd",
    doc="HOLD: single-axis rate damper (module template)",
    tlm_type="pd_tlm_t",
    tlm_layout=1,
    tlm=_tlm(),
    sensors=[Chan("omega_BN_B_x", "2^-20 rad/s", "rate gyro x: body rate wrt inertial, body axes")],
    actuators=[Chan("tau_cmd_B_x", "2^-16 N m", "torque command about body x")],
    health=[
        Bit("MEAS_SKIP", 0x00000100, "no valid rate this step: zero torque"),
        Bit("CMD_LIMITED", 0x00000200, "command at its limit this step"),
        Bit("CMD_LIMIT_PERSIST", 0x00000400, "command limited for n_sat steps"),
    ],
    why=[
        Bit("PERIOD", 0x01, "period (zero, or not the executive's)"),
        Bit("GAIN", 0x02, "gain outside (0, 2^24]"),
        Bit("LIMIT", 0x04, "torque limit outside (0, 2^24]"),
        Bit("SENSOR", 0x08, "gyro full scale not positive"),
        Bit("FAULT", 0x10, "n_sat zero"),
    ],
    commands=[tc("RESET_COUNTERS", 1, "clear the step counters and the sticky health of the module")],
    table_id=0x0B07,
    table_layout=1,
    table_fields=["period_us", "rate_max_cnt", "gain_q16", "u_max_cnt", "n_sat", "spare"],
)
