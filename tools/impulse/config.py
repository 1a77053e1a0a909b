"""Rendezvous mission configuration -> impulse flight table image (spec 50 §4.1, §5.7).

    python -m tools.impulse table --config CFG.yaml -o IMAGE.bin [--revision N]
    python -m tools.impulse table --keys

A configuration is a YAML mapping of physical inputs, each with its unit in its name (the keys,
ranges and defaults are the `ImpulseConfig` model below; `--keys` prints them). The table is
derived by the same function as the built-in boot tables (ctable.fields), so the shipped
tools/impulse/configs/default.yaml reproduces IMP_TBL_DEFAULT bit for bit. Every key is checked
(type, range, unknown keys, cross-field rules of imp_params_check), then the image's fields
against the flight loader's limits (fsw/impulse/imp_table.c).
"""
import dataclasses
import math
from typing import Annotated, Literal, Optional

from pydantic import Field

from tools.table import config as tc

from . import ctable
from . import image

MU_EARTH_M3PS2 = 3.986004418e14     # WGS-84 / EGM96 gravitational parameter
R_EARTH_M = 6378137.0               # WGS-84 equatorial radius
OMEGA_MIN, OMEGA_MAX = 8.0e-4, 1.2e-3   # spec 50 §4.2/§4.6 design span; the CW plant's cw.omega_radps range
D = ctable.DEFAULT
Alpha = Annotated[float, Field(ge=0.8, le=1.2)]


def omega_of_altitude(altitude_km):
    """Mean motion [rad/s] of a circular orbit at altitude_km above the equatorial radius."""
    r = R_EARTH_M + altitude_km * 1e3
    return math.sqrt(MU_EARTH_M3PS2 / r ** 3)


class ImpulseConfig(tc.Config):
    mission: Literal["rendezvous"] = tc.key(..., doc="the mission this table flies (the scenario's `mission:`)")
    description: str = tc.key("", doc="free text, not used")
    # orbit and thrusters
    omega_radps: Optional[float] = tc.key(None, OMEGA_MIN, OMEGA_MAX, "rad/s",
                                          "orbit rate; give this or altitude_km")
    altitude_km: Optional[float] = tc.key(None, 150.0, 2000.0, "km",
                                          "circular-orbit altitude, omega = sqrt(mu/(R+h)^3) with WGS-84 mu and R; "
                                          "give this or omega_radps")
    a_nom_mps2: float = tc.key(..., 1e-4, 10.0, "m/s^2", "nominal acceleration of one thruster")
    # valve timing
    period_us: int = tc.key(..., 1000, 10_000_000, "us", "valve tick = flight software period")
    subtick_us: int = tc.key(D.subtick_us, 0, 10_000_000, "us",
                             "valve grid inside a tick (0: whole ticks); divides period_us, at most 1000 per tick")
    t_min_us: int = tc.key(D.t_min_us, 0, 10_000_000, "us", "minimum valve on-time (<= period_us)")
    # navigation sensor counts
    nav_pos_lsb_m: float = tc.key(D.nav_pos_lsb_m, 1e-6, 1.0, "m", "relative-navigation position count")
    nav_vel_lsb_mps: float = tc.key(D.nav_vel_lsb_mps, 1e-8, 1e-2, "m/s", "relative-navigation velocity count")
    # planning
    plan_lead_s: float = tc.key(D.plan_lead_s, 0.0, 1e4, "s",
                                "a plan is applied this long after its epoch (whole ticks; long enough for "
                                "the worst plan)")
    replan_period_s: float = tc.key(D.replan_period_s, 0.0, 1e5, "s",
                                    "re-plan epochs (whole ticks; 0: never; else > plan_lead_s and >= nav_timeout_s)")
    t_stop_s: float = tc.key(D.t_stop_s, 0.0, 1e5, "s", "no re-plan applied later than this before t_f (whole ticks)")
    nav_timeout_s: float = tc.key(D.nav_timeout_s, 0.0, 1e5, "s",
                                  "oldest nav sample a re-plan uses (whole ticks, at least one)", lo_open=True)
    # thrust-level calibration and expected miss (spec 50 §5.5)
    cal_enable: bool = tc.key(D.cal_enable, doc="thrust-level calibration on/off")
    cal_pool: bool = tc.key(D.cal_pool, doc="thrusters without a window take the pooled mean of the others")
    dv_cal_min_mps: float = tc.key(D.dv_cal_min_mps, 0.0, 100.0, "m/s",
                                   "smallest commanded dv of a thruster in a calibration window")
    cal_gate: float = tc.key(D.cal_gate, 0.0, 0.5, "", "largest |alpha - 1| a window may estimate", lo_open=True)
    u_uncal: float = tc.key(D.u_uncal, 0.0, 0.5, "", "thrust-level uncertainty before calibration")
    u_cal: float = tc.key(D.u_cal, 0.0, 0.5, "", "thrust-level uncertainty after calibration (<= u_uncal)")
    miss_flag_m: float = tc.key(D.miss_flag_m, 0.0, 1e5, "m", "EXPECTED_MISS threshold", lo_open=True)
    alpha_init: Annotated[list[Alpha], Field(min_length=6, max_length=6)] = tc.key(
        list(D.alpha_init), 0.8, 1.2, "", "initial thrust factors of +x -x +y -y +z -z", each=True)
    # stuck-valve monitor (spec 50 §8)
    fd_window_s: float = tc.key(D.fd_window_s, 0.0, 60.0, "s", "stuck-valve monitor window (whole ticks)",
                                lo_open=True)
    fd_frac: float = tc.key(D.fd_frac, 0.0, 1.0, "", "fraction of the expected dv that counts as fired",
                            lo_open=True, hi_open=True)
    fd_persist: int = tc.key(D.fd_persist, 1, 255, "windows", "windows in a row before a stuck valve is declared")
    # navigation gates
    nav_gate_pos_m: float = tc.key(D.nav_gate_pos_m, 0.0, 1e5, "m", "nav position innovation gate", lo_open=True)
    nav_gate_vel_mps: float = tc.key(D.nav_gate_vel_mps, 0.0, 100.0, "m/s", "nav velocity innovation gate",
                                     lo_open=True)
    nav_gate_acc: float = tc.key(D.nav_gate_acc, 0.0, 7.9, "a_nom", "nav acceleration gate, in units of a_nom_mps2")
    replan_gain: float = tc.key(D.replan_gain, 0.0, 1.0, "",
                                "a re-plan replaces the timeline only if it cuts the predicted cost by this "
                                "fraction", hi_open=True)

    @property
    def omega(self):
        return self.omega_radps if self.omega_radps is not None else omega_of_altitude(self.altitude_km)

    def cross_checks(self):
        """Rules between keys (imp_params_check's invariants, in configuration terms)."""
        bad = []
        if (self.omega_radps is None) == (self.altitude_km is None):
            bad.append("give exactly one of omega_radps (%s) or altitude_km (%s)%s"
                       % (tc.range_text(type(self), "omega_radps"), tc.range_text(type(self), "altitude_km"),
                          "" if self.omega_radps is None else ", not both"))
        per = self.period_us
        if self.t_min_us > per:
            bad.append("t_min_us = %d us is longer than period_us = %d us: allowed [0, period_us] us"
                       % (self.t_min_us, per))
        if self.subtick_us:
            if self.subtick_us > per or per % self.subtick_us:
                bad.append("subtick_us = %d us does not divide period_us = %d us" % (self.subtick_us, per))
            elif per // self.subtick_us > 1000:
                bad.append("subtick_us = %d us gives %d sub-ticks per tick: at most 1000 (IMP_G_MAX)"
                           % (self.subtick_us, per // self.subtick_us))
        if self.u_cal > self.u_uncal:
            bad.append("u_cal = %g is above u_uncal = %g: allowed [0, u_uncal]" % (self.u_cal, self.u_uncal))
        steps = {}
        for k, lo in (("plan_lead_s", 2), ("replan_period_s", 0), ("t_stop_s", 0), ("nav_timeout_s", 1),
                      ("fd_window_s", 1)):
            steps[k] = tc.whole_steps(getattr(self, k), per, k, bad, lo)
        if bad:
            return bad
        if steps["replan_period_s"] and (steps["replan_period_s"] <= steps["plan_lead_s"]
                                         or steps["nav_timeout_s"] > steps["replan_period_s"]):
            bad.append("replan_period_s = %g s must be longer than plan_lead_s = %g s and at least nav_timeout_s "
                       "= %g s (or 0: never)" % (self.replan_period_s, self.plan_lead_s, self.nav_timeout_s))
        pips = ctable.plan_iter_per_step(steps["plan_lead_s"], D.max_iter)
        if pips is None:
            need = max(math.ceil(ctable.worst_units(D.max_iter) / 255) + 1, math.ceil(ctable.WORST_ITER / 255))
            bad.append("plan_lead_s = %g s is %d ticks: the worst plan needs at least %d ticks at 255 work units "
                       "per tick (%g s at period_us = %d us)"
                       % (self.plan_lead_s, steps["plan_lead_s"], need, need * per * 1e-6, per))
        return bad

    def inputs(self):
        """ctable.Inputs of this configuration (the solver numerics keep their flight defaults)."""
        kw = {f.name: getattr(self, f.name) for f in dataclasses.fields(ctable.Inputs) if f.name in type(self).model_fields}
        kw["omega_radps"] = self.omega
        kw["alpha_init"] = tuple(self.alpha_init)
        return dataclasses.replace(ctable.DEFAULT, **kw)


# Image fields -> the configuration keys they are derived from (for the loader-limit messages).
_ORBIT = ("omega_radps or altitude_km", "a_nom_mps2")
SOURCES = {
    "period_us": ("period_us",), "subtick_us": ("subtick_us",), "t_min_us": ("t_min_us",),
    "plan_lead": ("plan_lead_s", "period_us"), "replan_period": ("replan_period_s", "period_us"),
    "t_stop": ("t_stop_s", "period_us"), "nav_timeout": ("nav_timeout_s", "period_us"),
    "plan_iter_per_step": ("plan_lead_s", "period_us"),
    "k_pos_m": ("nav_pos_lsb_m",) + _ORBIT, "k_vel_m": ("nav_vel_lsb_mps",) + _ORBIT,
    "k_tau_m": ("omega_radps or altitude_km", "period_us"), "k_tick_m": ("omega_radps or altitude_km", "period_us"),
    "k_gtau_m": ("omega_radps or altitude_km", "subtick_us"), "k_gtick_m": ("omega_radps or altitude_km", "subtick_us"),
    "omega_nradps": ("omega_radps or altitude_km",), "a_nom_umps2": ("a_nom_mps2",),
    "w_v_q28": ("omega_radps or altitude_km",), "dv_tie_q28": _ORBIT,
    "alpha_q30": ("alpha_init",), "cal_enable": ("cal_enable",), "cal_pool": ("cal_pool",),
    "dv_cal_min_q28": ("dv_cal_min_mps",) + _ORBIT, "cal_gate_q30": ("cal_gate",), "u_uncal_q30": ("u_uncal",),
    "u_cal_q30": ("u_cal",), "miss_flag_q28": ("miss_flag_m",) + _ORBIT, "fd_window": ("fd_window_s", "period_us"),
    "fd_frac_q30": ("fd_frac",), "fd_persist": ("fd_persist",), "nav_gate_pos_q28": ("nav_gate_pos_m",) + _ORBIT,
    "nav_gate_vel_q28": ("nav_gate_vel_mps",) + _ORBIT, "nav_gate_acc_q28": ("nav_gate_acc",),
    "replan_gain_q30": ("replan_gain",),
}


def params(cfg):
    """Raw imp_params_t integers (image field dict) of a validated configuration."""
    inp = cfg.inputs()
    vals = [(f, image._c_value(v)) for f, v, _ in ctable.fields(inp.period_us, inp.subtick_us, inp.omega_radps,
                                                                inp.a_nom_mps2, inp)]
    p = dict(vals)
    p.pop("revision")
    return p


def build(path, revision=1):
    """(image bytes, configuration, params) of a configuration file; ConfigError if it is invalid
    or its table would not pass the flight loader's limits."""
    cfg = tc.load(path, ImpulseConfig)
    p = params(cfg)
    bad = image.LAYOUT.check_limits(p, SOURCES)
    if bad:
        raise tc.ConfigError(path, bad)
    return image.LAYOUT.build(p, revision), cfg, p


def main(a):
    if a.keys:
        print(tc.keys_table(ImpulseConfig))
        return 0
    if not a.config or not a.o:
        raise SystemExit("table: give --config CFG.yaml and -o IMAGE.bin (or --keys)")
    try:
        img, cfg, p = build(a.config, a.revision)
    except tc.ConfigError as e:
        print("table: invalid configuration\n%s" % e)
        return 2
    with open(a.o, "wb") as fh:
        fh.write(img)
    hdr, _ = image.decode(img)
    w, an = cfg.omega, cfg.a_nom_mps2
    print("%s: rendezvous table from %s, %d bytes, table_id 0x%04X layout %d revision %d crc 0x%08X"
          % (a.o, a.config, len(img), hdr["table_id"], hdr["layout_version"], hdr["revision"], hdr["crc"]))
    print("  omega %.9e rad/s (1/omega %.2f s), a_nom %g m/s^2: L = %.2f m, V = %.4f m/s; tick %g s%s, "
          "plan lead %d ticks, %d work units per tick, calibration %s"
          % (w, 1 / w, an, an / w ** 2, an / w, cfg.period_us * 1e-6,
             (", grid %g ms" % (cfg.subtick_us * 1e-3)) if cfg.subtick_us else "", p["plan_lead"],
             p["plan_iter_per_step"], "on" if cfg.cal_enable else "off"))
    print("  scenario: cw: {omega_radps: %r, a_nom_mps2: %r, t_min_us: %d%s}, period_us: %d"
          % (w, an, cfg.t_min_us, (", subtick_us: %d" % cfg.subtick_us) if cfg.subtick_us else "", cfg.period_us))
    return 0
