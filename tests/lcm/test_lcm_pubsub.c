/*
 * test_lcm_pubsub.c — LCM publish/subscribe smoke test with the gnc types (spec 00 §5.2, §5.3).
 *
 *   test_lcm_pubsub memq   one lcm_t shared by the "plant" and the "bridge" (memq is scoped to one
 *                          instance), lcm_handle_timeout alternated on a single thread
 *   test_lcm_pubsub udpm   two lcm_t on the URL in LCM_DEFAULT_URL (a private port per test from
 *                          fsw_lcm_url), still on one thread; exits 77 (CTest SKIP) with a message
 *                          naming the URL only if lcm_create returns NULL
 *
 * Messages are encoded into static buffers and sent with lcm_publish (never the generated
 * _publish, which allocates). Each node subscribes only to channels it does not publish.
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <lcm/lcm.h>

#include "gnc_actuator_cmd_t.h"
#include "gnc_sensor_frame_t.h"
#include "ut.h"

#define CH_SENSOR "GNC_SENSOR"
#define CH_CMD    "GNC_CMD"
#define N_EXCHANGE 200
#define RETX_MS 100          /* lock-step retransmission (spec 00 §5.2 step 3) */
#define DEADLINE_MS 5000     /* per exchange; far above any loopback latency */

static const char *url_;          /* transport under test */
static lcm_t *plant_, *bridge_;   /* same instance for memq */

/* Bridge side: decodes frame k into a static object, answers with command k. */
static uint8_t bridge_buf_[256];
static gnc_sensor_frame_t bridge_rx_;
static gnc_actuator_cmd_t bridge_tx_;
static int bridge_frames_, bridge_errors_;

static void on_sensor(const lcm_recv_buf_t *rbuf, const char *channel, void *user)
{
    int n, i;
    (void)channel;
    (void)user;
    if (gnc_sensor_frame_t_decode(rbuf->data, 0, (int)rbuf->data_size, &bridge_rx_) < 0) {
        ++bridge_errors_;
        return;
    }
    ++bridge_frames_;
    memset(&bridge_tx_, 0, sizeof bridge_tx_);
    bridge_tx_.utime = bridge_rx_.utime;
    bridge_tx_.seq = bridge_rx_.seq;
    bridge_tx_.n_counts = bridge_rx_.n_counts;
    for (i = 0; i < 16; ++i) {
        bridge_tx_.counts[i] = -bridge_rx_.counts[i];
    }
    bridge_tx_.fsw_mode = 2;
    bridge_tx_.fsw_health = (int32_t)bridge_rx_.seq;
    n = gnc_actuator_cmd_t_encode(bridge_buf_, 0, (int)sizeof bridge_buf_, &bridge_tx_);
    if (n < 0 || lcm_publish(bridge_, CH_CMD, bridge_buf_, (unsigned)n) != 0) {
        ++bridge_errors_;
    }
}

/* Plant side. */
static uint8_t plant_buf_[256];
static gnc_sensor_frame_t plant_tx_;
static gnc_actuator_cmd_t plant_rx_;
static int plant_got_, plant_errors_;

static void on_cmd(const lcm_recv_buf_t *rbuf, const char *channel, void *user)
{
    (void)channel;
    (void)user;
    if (gnc_actuator_cmd_t_decode(rbuf->data, 0, (int)rbuf->data_size, &plant_rx_) < 0) {
        ++plant_errors_;
        return;
    }
    if (plant_rx_.seq == plant_tx_.seq) {   /* a late duplicate of k-1 is ignored */
        plant_got_ = 1;
    }
}

static int publish_frame(void)
{
    int n = gnc_sensor_frame_t_encode(plant_buf_, 0, (int)sizeof plant_buf_, &plant_tx_);
    return (n < 0) ? -1 : lcm_publish(plant_, CH_SENSOR, plant_buf_, (unsigned)n);
}

/* Poll both nodes (one thread) until *flag or the deadline; returns retransmissions or -1. */
static int pump_until(const int *flag, int retransmit)
{
    int waited = 0, since = 0, retx = 0;
    while (!*flag) {
        int r = lcm_handle_timeout(plant_, 1);
        if (r < 0) {
            return -1;
        }
        if (bridge_ != plant_ && lcm_handle_timeout(bridge_, 1) < 0) {
            return -1;
        }
        if (r == 0) {
            waited += 1;
            since += 1;
        }
        if (waited > DEADLINE_MS) {
            return -1;
        }
        if (retransmit && since >= RETX_MS && !*flag) {
            since = 0;
            ++retx;
            if (publish_frame() != 0) {
                return -1;
            }
        }
    }
    return retx;
}

static int open_nodes(void)
{
    plant_ = lcm_create(url_);
    if (plant_ == NULL) {
        return -1;
    }
    if (strncmp(url_, "memq", 4) == 0) {
        bridge_ = plant_;                /* memq: one instance for both nodes */
    } else {
        bridge_ = lcm_create(url_);
        if (bridge_ == NULL) {
            lcm_destroy(plant_);
            return -1;
        }
    }
    return 0;
}

static void close_nodes(void)
{
    if (bridge_ != plant_) {
        lcm_destroy(bridge_);
    }
    lcm_destroy(plant_);
    plant_ = bridge_ = NULL;
}

/* Lock-step exchange: frame k out, command k back, N_EXCHANGE times, values echoed. */
UT_TEST(lockstep_exchange)
{
    lcm_subscription_t *s1, *s2;
    int k, i, retx = 0;
    UT_EQ(open_nodes(), 0);
    s1 = lcm_subscribe(bridge_, CH_SENSOR, on_sensor, NULL);
    s2 = lcm_subscribe(plant_, CH_CMD, on_cmd, NULL);
    UT_TRUE(s1 != NULL && s2 != NULL);
    bridge_frames_ = bridge_errors_ = plant_errors_ = 0;
    for (k = 0; k < N_EXCHANGE; ++k) {
        int r;
        memset(&plant_tx_, 0, sizeof plant_tx_);
        plant_tx_.utime = (int64_t)k * 20000;
        plant_tx_.seq = k;
        plant_tx_.period_us = 20000;
        plant_tx_.n_counts = 2;
        for (i = 0; i < 16; ++i) {
            plant_tx_.counts[i] = k * 1000 + i;
        }
        plant_tx_.status[1] = GNC_SENSOR_FRAME_T_STATUS_SAT;
        plant_got_ = 0;
        UT_EQ(publish_frame(), 0);
        r = pump_until(&plant_got_, 1);
        UT_TRUE(r >= 0);
        retx += r;
        UT_EQ(plant_rx_.seq, k);
        UT_EQ(plant_rx_.utime, (int64_t)k * 20000);
        UT_EQ(plant_rx_.counts[15], -(k * 1000 + 15));
        UT_EQ(plant_rx_.fsw_health, k);
    }
    UT_EQ(bridge_errors_ + plant_errors_, 0);
    UT_LE(N_EXCHANGE, bridge_frames_);
    printf("%s: %d exchanges, %d retransmission(s), bridge saw %d frame(s)\n", url_, N_EXCHANGE,
           retx, bridge_frames_);
    (void)lcm_unsubscribe(bridge_, s1);
    (void)lcm_unsubscribe(plant_, s2);
    close_nodes();
}

/* The generated _subscribe decodes fixed-size types into a stack object (no allocation). */
static gnc_sensor_frame_t typed_rx_;
static int typed_got_;

static void on_sensor_typed(const lcm_recv_buf_t *rbuf, const char *channel,
                            const gnc_sensor_frame_t *msg, void *user)
{
    (void)rbuf;
    (void)channel;
    (void)user;
    typed_rx_ = *msg;
    typed_got_ = 1;
}

UT_TEST(generated_subscribe)
{
    gnc_sensor_frame_t_subscription_t *s;
    UT_EQ(open_nodes(), 0);
    s = gnc_sensor_frame_t_subscribe(bridge_, CH_SENSOR, on_sensor_typed, NULL);
    UT_TRUE(s != NULL);
    memset(&plant_tx_, 0, sizeof plant_tx_);
    plant_tx_.utime = 123456789;
    plant_tx_.seq = 77;
    plant_tx_.counts[3] = -42;
    plant_tx_.status[3] = GNC_SENSOR_FRAME_T_STATUS_STALE;
    typed_got_ = 0;
    UT_EQ(publish_frame(), 0);
    UT_TRUE(pump_until(&typed_got_, 1) >= 0);
    UT_EQ(typed_rx_.seq, 77);
    UT_EQ(typed_rx_.utime, 123456789);
    UT_EQ(typed_rx_.counts[3], -42);
    UT_EQ(typed_rx_.status[3], GNC_SENSOR_FRAME_T_STATUS_STALE);
    (void)gnc_sensor_frame_t_unsubscribe(bridge_, s);
    close_nodes();
}

/* Why a node never subscribes to a channel it publishes: it hears its own messages. */
static int self_heard_;
static void on_self(const lcm_recv_buf_t *rbuf, const char *channel, void *user)
{
    (void)rbuf;
    (void)channel;
    (void)user;
    self_heard_ = 1;
}

UT_TEST(own_publications_come_back)
{
    lcm_subscription_t *s;
    static const uint8_t ping[4] = { 1, 2, 3, 4 };
    UT_EQ(open_nodes(), 0);
    s = lcm_subscribe(plant_, "GNC_SELF", on_self, NULL);
    UT_TRUE(s != NULL);
    self_heard_ = 0;
    UT_EQ(lcm_publish(plant_, "GNC_SELF", ping, (unsigned)sizeof ping), 0);
    UT_TRUE(pump_until(&self_heard_, 0) >= 0);
    (void)lcm_unsubscribe(plant_, s);
    close_nodes();
}

int main(int argc, char **argv)
{
    lcm_t *probe;
    UT_CASES(cases) = {
        UT_CASE(lockstep_exchange),
        UT_CASE(generated_subscribe),
        UT_CASE(own_publications_come_back),
    };
    if (argc != 2 || (strcmp(argv[1], "memq") != 0 && strcmp(argv[1], "udpm") != 0)) {
        fprintf(stderr, "usage: %s memq|udpm (udpm reads LCM_DEFAULT_URL)\n", argv[0]);
        return 2;
    }
    if (strcmp(argv[1], "memq") == 0) {
        url_ = "memq://";
    } else {
        url_ = getenv("LCM_DEFAULT_URL");
        if (url_ == NULL || strncmp(url_, "udpm://", 7) != 0) {
            fprintf(stderr, "udpm mode needs LCM_DEFAULT_URL=udpm://... (set by CTest)\n");
            return 2;
        }
    }
    probe = lcm_create(url_);
    if (probe == NULL) {
        printf("SKIP: lcm_create(\"%s\") returned NULL (no multicast route on loopback?)\n", url_);
        return 77;
    }
    lcm_destroy(probe);
    return UT_RUN(argv[1], cases);
}
