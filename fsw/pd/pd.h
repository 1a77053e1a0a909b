/*
 * pd.h — pd: the flight algorithm of the HOLD mission. Generated from the module
 * template (tools/new_module.py): a single-axis rate damper, the smallest closed loop that has
 * everything a module needs (a table, a state, health bits, telemetry). Replace the law with
 * your module's and keep the shape: params (the table), state, in, out; init/check/step on
 * caller-owned memory; no globals, no floating point, every loop bounded.
 *
 * The law, on integer counts (the channel units of pd_iface.py):
 *   rate   omega_BN_B_x = omega [rad/s] * 2^20      sensor channel 0
 *   torque tau_cmd_B_x  = tau [N m] * 2^16          actuator channel 0
 *   u = -round(gain_q16 * rate / 2^16), clamped to [-u_max_cnt, u_max_cnt]
 * i.e. tau = -K omega with K = gain_q16 * 2^-16 * 2^-16 / 2^-20 = gain_q16 / 2^12 N m s.
 * A step without a valid rate commands zero torque (the safe value) and is counted.
 */
#ifndef FSW_PD_H
#define FSW_PD_H

#include <stdint.h>
#include <stdbool.h>
#include "fx.h"
#include "fx_rc.h"
#include "pd_ids.h"

#define PD_GAIN_MAX_Q16 ((int32_t)16777216)   /* 2^24: K <= 4096 N m s; gain * rate within int64 */
#define PD_U_MAX_CNT    ((int32_t)16777216)   /* 2^24 counts = 256 N m */

typedef struct {
    uint32_t period_us;     /* the step period the table was designed for */
    int32_t  rate_max_cnt;  /* |rate| >= rate_max_cnt is the gyro's full scale: not accepted */
    int32_t  gain_q16;      /* K: torque counts per rate count, q16 */
    int32_t  u_max_cnt;     /* torque command limit, counts */
    uint16_t n_sat;         /* limited steps in a row before CMD_LIMIT_PERSIST */
    uint32_t revision;      /* table revision (the image header's) */
} pd_params_t;

/* The telemetry block (its wire layout: pd_iface.py -> pd_tlm.c). */
typedef struct {
    int32_t  rate_cnt;      /* rate of the last step (0 without a valid one) */
    int32_t  u_cnt;         /* torque command of the last step */
    uint32_t n_skip;        /* steps without a valid rate */
    uint32_t n_limited;     /* steps with the command at its limit */
    uint32_t health_sticky; /* OR of the health words since init */
    uint32_t revision;      /* table revision in use */
} pd_tlm_t;

typedef struct {
    uint32_t sat_run;       /* limited steps in a row */
    pd_tlm_t tlm;
} pd_state_t;

typedef struct {
    int32_t rate_cnt;
    bool    valid;          /* the executive accepted channel 0 this step */
} pd_in_t;

typedef struct {
    int32_t  u_cnt;
    uint32_t health;        /* bits 0..7 fx status of the step, 8.. PD_H_* */
} pd_out_t;

/* FSW_OK when p can fly; else FSW_ERR_ARG / FSW_ERR_RANGE and *why = PD_WHY_* bits. */
fsw_rc_t pd_params_check(const pd_params_t *p, uint32_t *why);
void     pd_init(pd_state_t *s, const pd_params_t *p);
void     pd_step(pd_state_t *s, const pd_params_t *p, const pd_in_t *in,
                       pd_out_t *out);

#endif /* FSW_PD_H */
