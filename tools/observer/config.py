"""Detumbling mission configuration -> observer flight table image (spec 10-observer §4).

    python -m tools.observer table --config CFG.yaml -o IMAGE.bin [--revision N]
    python -m tools.observer table --keys

A configuration is a YAML mapping of physical and design inputs (the keys, ranges and defaults
are the `ObserverConfig` model below; `--keys` prints them). The table is designed by the same
functions as the built-in boot tables (flight.yt_design, design.flight_table, ctable.table_c /
image._from_design), so the shipped tools/observer/configs/default.yaml reproduces
OBS_TBL_50HZ_PHYS bit for bit. Every key is checked (type, range, unknown keys, rules between
keys), the design must give a stable 12-state loop at its own design point, and the image's
fields must pass the flight loader's limits (fsw/observer/obs_table.c).
"""
import warnings
from typing import Annotated, Literal, Optional

import numpy as np
from pydantic import Field

from tools.table import config as tc

from . import ctable
from . import design as dz
from . import flight as fl
from . import image
from . import model as m
from . import paper as pp

HW = ctable.HW
SIGMA = {"M-phys": +1, "M-paper": -1}
Scale = Annotated[int, Field(ge=-20, le=0)]


class ObserverConfig(tc.Config):
    mission: Literal["detumble"] = tc.key(..., doc="the mission this table flies (the scenario's `mission:`)")
    description: str = tc.key("", doc="free text, not used")
    # plant model and rate
    model: Literal["M-phys", "M-paper"] = tc.key(
        ..., doc="plant model sign: M-phys (sigma +1, the physical one) or M-paper (sigma -1)")
    period_us: int = tc.key(..., 1000, 1_000_000, "us", "control period (= the scenario's period_us)")
    j_factor: Optional[float] = tc.key(None, 0.5, 2.0, "",
                                       "platform transverse inertia J / 1200 kg m^2 (the scenario's j_factor); "
                                       "default 1; give this or platform_inertia_kgm2")
    platform_inertia_kgm2: Optional[float] = tc.key(None, 600.0, 2400.0, "kg m^2",
                                                    "platform transverse inertia J; give this or j_factor")
    # gain design (spec 10 §4.2: Yang-Tits pole placement on the exact ZOH model)
    k2_design_per_s2: float = tc.key(m.K2_DESIGN, 0.005, 0.02, "1/s^2",
                                     "mount stiffness k^2 the gains are designed for")
    zeta_s: Optional[float] = tc.key(None, 0.0, 1.0, "",
                                     "M-phys only: damping of the sail pole pair (default 0.05)",
                                     lo_open=True, hi_open=True)
    # stiffness estimate (kappa = K-hat / 0.01 1/s^2)
    k_hat0_per_s2: float = tc.key(dz.KAPPA_INIT * m.K_REF, 0.001, 0.05, "1/s^2",
                                  "initial stiffness estimate K-hat(0) (inside the band)")
    k_hat_min_per_s2: float = tc.key(dz.BAND[0] * m.K_REF, 0.001, 0.05, "1/s^2",
                                     "lower clamp of K-hat (at most 0.01, the linearisation point)")
    k_hat_max_per_s2: float = tc.key(dz.BAND[1] * m.K_REF, 0.001, 0.05, "1/s^2",
                                     "upper clamp of K-hat (at least 0.01)")
    # EKF
    gyro_noise_radps: float = tc.key(0.0, 0.0, 0.01, "rad/s",
                                     "gyro white noise 1-sigma; R uses max(this, 1e-5 rad/s)")
    ekf_scale_log2: Optional[Annotated[list[Scale], Field(min_length=7, max_length=7)]] = tc.key(
        None, -20, 0, "", "EKF state scales S = 2^ls for w_y w_z mu_y mudot_y mu_z mudot_z kappa "
        "(default: the shipped table's for the model)", each=True)
    # sensors and actuators
    gyro_lsb_shift: int = tc.key(-HW.gyro_lsb_log2, 0, 29, "", "gyro count = 2^-gyro_lsb_shift rad/s "
                                 "(the scenario's gyro.lsb_shift)")
    gyro_max_cnt: int = tc.key(HW.gyro_max_cnt, 1, 2 ** 31 - 1, "counts",
                               "gyro full scale (the scenario's gyro.max_cnt)")
    gimbal_lsb_shift: int = tc.key(-HW.act_lsb_log2, 0, 29, "",
                                   "gimbal-rate count = 2^-gimbal_lsb_shift rad/s (the scenario's gimbal.lsb_shift)")
    gimbal_hw_limit_radps: float = tc.key(HW.bdot_hw, 0.0, 3.9, "rad/s",
                                          "gimbal-rate hardware clip (the scenario's gimbal.hw_limit_radps)",
                                          lo_open=True)
    bdot_max_radps: float = tc.key(HW.bdot_max, 0.0, 3.9, "rad/s",
                                   "command vector limit (<= gimbal_hw_limit_radps)", lo_open=True)
    # fault handling (spec 10 §7)
    n_lost: int = tc.key(HW.n_lost, 1, 65535, "samples", "bad samples in a row before MEAS_LOST")
    n_good: int = tc.key(HW.n_good, 1, 65535, "samples", "good samples in a row to recover")
    n_sat: int = tc.key(HW.n_sat, 1, 65535, "samples", "command-limited samples in a row before the flag")
    n_gap_max: int = tc.key(HW.n_gap_max, 1, 65535, "samples", "largest sequence gap bridged by prediction")
    d2_max: float = tc.key(HW.d2_max, 0.0, 32767.0, "", "innovation gate gamma^2 on d^2 = e^2 / S per gyro "
                           "channel (chi-square, 1 dof)", lo_open=True)
    d2_reject: bool = tc.key(bool(HW.d2_reject), doc="reject samples above d2_max (false: monitor only)")
    n_rej_safe: int = tc.key(HW.n_rej_safe, 1, 65535, "samples",
                             "gate rejections in a row on a channel before the observer's latched safe output")
    rej_leak_inc: int = tc.key(HW.rej_leak_inc, 1, 65535, "samples",
                               "leaky rejection level: added per rejected step (one drains per clean step)")
    rej_freeze_on: int = tc.key(HW.rej_freeze_on, 1, 65535, "samples",
                                "rejection level that freezes K-hat adaptation (until it drains to 0)")

    @property
    def sigma(self):
        return SIGMA[self.model]

    @property
    def J(self):
        if self.platform_inertia_kgm2 is not None:
            return self.platform_inertia_kgm2
        return m.J0 * (1.0 if self.j_factor is None else self.j_factor)

    @property
    def h(self):
        return self.period_us / 1e6

    def cross_checks(self):
        bad = []
        if self.j_factor is not None and self.platform_inertia_kgm2 is not None:
            bad.append("give j_factor (%s) or platform_inertia_kgm2 (%s), not both"
                       % (tc.range_text(type(self), "j_factor"), tc.range_text(type(self), "platform_inertia_kgm2")))
        if self.zeta_s is not None and self.model != "M-phys":
            bad.append("zeta_s applies to model M-phys only (M-paper places 6th-order Butterworth poles)")
        lo, hi = self.k_hat_min_per_s2, self.k_hat_max_per_s2
        if not lo <= m.K_REF <= hi or lo >= hi:
            bad.append("k_hat_min_per_s2 = %g and k_hat_max_per_s2 = %g 1/s^2 must bracket the linearisation point "
                       "%g 1/s^2 (min <= %g <= max, min < max)" % (lo, hi, m.K_REF, m.K_REF))
        if not lo <= self.k_hat0_per_s2 <= hi:
            bad.append("k_hat0_per_s2 = %g 1/s^2 is outside the band [k_hat_min_per_s2, k_hat_max_per_s2] = "
                       "[%g, %g] 1/s^2" % (self.k_hat0_per_s2, lo, hi))
        if self.bdot_max_radps > self.gimbal_hw_limit_radps:
            bad.append("bdot_max_radps = %g rad/s is above gimbal_hw_limit_radps = %g rad/s: allowed (0, "
                       "gimbal_hw_limit_radps]" % (self.bdot_max_radps, self.gimbal_hw_limit_radps))
        fs = self.gyro_max_cnt * 2.0 ** -self.gyro_lsb_shift
        if fs >= 4.0:
            bad.append("gyro_max_cnt = %d counts at gyro_lsb_shift = %d is a full scale of %g rad/s: the flight rate "
                       "format (q29) holds less than 4 rad/s" % (self.gyro_max_cnt, self.gyro_lsb_shift, fs))
        act = int(self.gimbal_hw_limit_radps * 2.0 ** self.gimbal_lsb_shift)
        if not 1 <= act < 2 ** 31:
            bad.append("gimbal_hw_limit_radps = %g rad/s is %d counts at gimbal_lsb_shift = %d: allowed [1, 2^31 - 1] "
                       "counts" % (self.gimbal_hw_limit_radps, act, self.gimbal_lsb_shift))
        return bad

    def hw(self):
        return ctable.Hw(gyro_lsb_log2=-self.gyro_lsb_shift, act_lsb_log2=-self.gimbal_lsb_shift,
                         gyro_max_cnt=self.gyro_max_cnt, bdot_hw=self.gimbal_hw_limit_radps,
                         bdot_max=self.bdot_max_radps, n_lost=self.n_lost, n_good=self.n_good, n_sat=self.n_sat,
                         n_gap_max=self.n_gap_max, d2_max=self.d2_max, d2_reject=int(self.d2_reject),
                         n_rej_safe=self.n_rej_safe, rej_leak_inc=self.rej_leak_inc,
                         rej_freeze_on=self.rej_freeze_on)

    def s_exp(self):
        if self.ekf_scale_log2 is not None:
            return list(self.ekf_scale_log2)
        return list(dz.S_EXP_PHYS if self.sigma > 0 else dz.S_EXP)


DESIGN_KEYS = "model, period_us, j_factor/platform_inertia_kgm2, k2_design_per_s2, zeta_s"


def design(cfg, path="<config>"):
    """(design table dict as ctable renders it, figures dict) of a validated configuration;
    ConfigError if the design fails or its loop is not stable at the design point."""
    sigma, h, J, k2 = cfg.sigma, cfg.h, cfg.J, cfg.k2_design_per_s2
    zeta = fl.ZETA_S if cfg.zeta_s is None else cfg.zeta_s
    try:
        with warnings.catch_warnings(record=True) as caught:
            warnings.simplefilter("always")
            des = fl.yt_design(sigma, h, k2, zeta, J)
        tab = dz.flight_table("config", sigma, h, des, s_exp=cfg.s_exp(), J=J, k2_design=k2,
                              kappa_init=cfg.k_hat0_per_s2 / m.K_REF,
                              band=(cfg.k_hat_min_per_s2 / m.K_REF, cfg.k_hat_max_per_s2 / m.K_REF),
                              sigma_gyro=cfg.gyro_noise_radps, figures=False)
    except (ValueError, np.linalg.LinAlgError) as e:
        raise tc.ConfigError(path, ["the gain design failed for %s = (%s, %d us, %g kg m^2, %g 1/s^2%s): %s"
                                    % (DESIGN_KEYS, cfg.model, cfg.period_us, J, k2,
                                       (", %g" % zeta) if sigma > 0 else "", e)])
    fo = m.FirstOrder(sigma, h, J)
    Phi, G = m.zoh(k2, sigma, h, J)
    rho = m.specrad(fl.loop12(Phi, G, *fo.at(k2), des["D"], des["W6"]))
    Phi1, G1 = m.zoh(m.K2_TRUE, sigma, h, J)
    rho_true = m.specrad(fl.loop12(Phi1, G1, *fo.at(m.K2_TRUE), des["D"], des["W6"]))
    if not rho < 1.0:
        raise tc.ConfigError(path, ["the designed loop is not stable at its design point: rho = %.6f >= 1 (%s)"
                                    % (rho, DESIGN_KEYS)])
    notes = ["Yang-Tits: %s" % str(w.message).replace("\n", " ") for w in caught]
    return dz._clean(tab), {"rho_design": rho, "rho_k2_0.01": rho_true, "zeta_s": zeta if sigma > 0 else None,
                            "notes": notes}


# Image fields -> the configuration keys they come from (for the loader-limit messages).
SOURCES = {
    "period_us": ("period_us",), "sigma": ("model",), "gyro_cnt_shift": ("gyro_lsb_shift",),
    "act_cnt_shift": ("gimbal_lsb_shift",), "gyro_max_cnt": ("gyro_max_cnt",),
    "act_max_cnt": ("gimbal_hw_limit_radps", "gimbal_lsb_shift"), "bdot_max_q29": ("bdot_max_radps",),
    "bdot_hw_q29": ("gimbal_hw_limit_radps",), "kappa_init_q28": ("k_hat0_per_s2",),
    "kappa_lo_q28": ("k_hat_min_per_s2",), "kappa_hi_q28": ("k_hat_max_per_s2",), "r_q30": ("gyro_noise_radps",),
    "d2_max_q16": ("d2_max",), "ls": ("ekf_scale_log2",), "p0_q30": ("ekf_scale_log2", "k_hat0_per_s2"),
    "qd_q30": ("ekf_scale_log2",), "n_lost": ("n_lost",), "n_good": ("n_good",), "n_sat": ("n_sat",),
    "n_gap_max": ("n_gap_max",), "n_rej_safe": ("n_rej_safe",), "rej_leak_inc": ("rej_leak_inc",),
    "rej_freeze_on": ("rej_freeze_on",),
}
for _f in ("q_phi0", "q_phik", "q_gam0", "q_gamk", "q_d", "q_w"):
    SOURCES[_f] = (DESIGN_KEYS,)


def build(path, revision=1):
    """(image bytes, configuration, params, figures) of a configuration file; ConfigError if it is
    invalid, its design fails, or its table would not pass the flight loader's limits."""
    cfg = tc.load(path, ObserverConfig)
    tab, fig = design(cfg, path)
    p = image.params_of("config", tab, cfg.hw())
    bad = image.LAYOUT.check_limits(p, SOURCES)
    if bad:
        raise tc.ConfigError(path, bad)
    return image.LAYOUT.build(p, revision), cfg, p, fig


def main(a):
    if a.keys:
        print(tc.keys_table(ObserverConfig))
        return 0
    if not a.config or not a.o:
        raise SystemExit("table: give --config CFG.yaml and -o IMAGE.bin (or --keys)")
    try:
        img, cfg, p, fig = build(a.config, a.revision)
    except tc.ConfigError as e:
        print("table: invalid configuration\n%s" % e)
        return 2
    with open(a.o, "wb") as fh:
        fh.write(img)
    hdr, _ = image.decode(img)
    print("%s: detumble table from %s, %d bytes, table_id 0x%04X layout %d revision %d crc 0x%08X"
          % (a.o, a.config, len(img), hdr["table_id"], hdr["layout_version"], hdr["revision"], hdr["crc"]))
    print("  %s (sigma %+d), h = %g s, J = %g kg m^2 (j_factor %.6g), k2_design %.7g 1/s^2%s: rho %.6f at the design "
          "point, %.6f at k2 = 0.01; q phi0/phik/gam0/gamk/d/w = %d/%d/%d/%d/%d/%d"
          % (cfg.model, cfg.sigma, cfg.h, cfg.J, cfg.J / m.J0, cfg.k2_design_per_s2,
             (", zeta_s %g" % fig["zeta_s"]) if fig["zeta_s"] is not None else "", fig["rho_design"],
             fig["rho_k2_0.01"], p["q_phi0"], p["q_phik"], p["q_gam0"], p["q_gamk"], p["q_d"], p["q_w"]))
    for n in fig["notes"]:
        print("  note: %s (the poles are placed; their robustness is not optimised)" % n)
    print("  scenario: model: %s, sigma: %d, j_factor: %r, period_us: %d, gyro: {lsb_shift: %d, max_cnt: %d}, "
          "gimbal: {lsb_shift: %d, hw_limit_radps: %r}"
          % (cfg.model, cfg.sigma, cfg.J / m.J0, cfg.period_us, cfg.gyro_lsb_shift, cfg.gyro_max_cnt,
             cfg.gimbal_lsb_shift, cfg.gimbal_hw_limit_radps))
    return 0
