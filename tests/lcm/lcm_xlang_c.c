/*
 * lcm_xlang_c.c — C side of the cross-language check (driven by lcm_xlang_check.py).
 *
 *   lcm_xlang_c write <log>   write one event per gnc type (channel = type name, encoded by the
 *                             generated C into a static buffer) in the standard LCM event-log
 *                             format, through liblcm's lcm_eventlog_write_event (spec 00 §5.3)
 *   lcm_xlang_c check <log>   read a log written by Python and check that every type decodes
 *                             with the C binding to exactly the shared pattern (lcm_pattern.h)
 *
 * Exit status 0 on success; failures are printed.
 */
#include <stdio.h>
#include <string.h>

#include <lcm/eventlog.h>

#include "lcm_types.h"

static uint8_t buf_[PAT_SIZE_MAX];
static lcm_any_t ref_, got_;
static char chan_[64];

static int write_log(const char *path)
{
    lcm_eventlog_t *log = lcm_eventlog_create(path, "w");
    size_t i;
    if (log == NULL) {
        fprintf(stderr, "cannot create event log %s\n", path);
        return 1;
    }
    for (i = 0; i < LCM_N_TYPES; ++i) {
        const lcm_type_ops_t *t = &lcm_types[i];
        lcm_eventlog_event_t ev;
        int n;
        t->fill(&ref_);
        n = t->enc(buf_, 0, (int)sizeof buf_, &ref_);
        if (n != t->encoded_len) {
            fprintf(stderr, "%s: encode returned %d\n", t->name, n);
            lcm_eventlog_destroy(log);
            return 1;
        }
        (void)snprintf(chan_, sizeof chan_, "%s", t->name);
        memset(&ev, 0, sizeof ev);
        ev.eventnum = (int64_t)i;
        ev.timestamp = 1000000 + (int64_t)i;   /* fixed: the log is reproducible */
        ev.channellen = (int32_t)strlen(chan_);
        ev.datalen = n;
        ev.channel = chan_;
        ev.data = buf_;
        if (lcm_eventlog_write_event(log, &ev) != 0) {
            fprintf(stderr, "%s: lcm_eventlog_write_event failed\n", t->name);
            lcm_eventlog_destroy(log);
            return 1;
        }
    }
    lcm_eventlog_destroy(log);
    printf("wrote %u events to %s\n", (unsigned)LCM_N_TYPES, path);
    return 0;
}

static int check_log(const char *path)
{
    lcm_eventlog_t *log = lcm_eventlog_create(path, "r");
    unsigned seen = 0, bad = 0;
    lcm_eventlog_event_t *ev;
    if (log == NULL) {
        fprintf(stderr, "cannot open event log %s\n", path);
        return 1;
    }
    while ((ev = lcm_eventlog_read_next_event(log)) != NULL) {
        size_t i;
        int found = 0;
        for (i = 0; i < LCM_N_TYPES; ++i) {
            const lcm_type_ops_t *t = &lcm_types[i];
            if (strlen(t->name) != (size_t)ev->channellen ||
                memcmp(t->name, ev->channel, (size_t)ev->channellen) != 0) {
                continue;
            }
            found = 1;
            t->fill(&ref_);
            memset(&got_, 0, sizeof got_);
            if (ev->datalen != t->encoded_len ||
                t->dec(ev->data, 0, ev->datalen, &got_) != t->encoded_len ||
                memcmp(&ref_, &got_, t->size) != 0) {
                fprintf(stderr, "%s: Python-encoded event does not decode to the pattern\n", t->name);
                ++bad;
            } else {
                seen |= 1u << i;
            }
        }
        if (!found) {
            fprintf(stderr, "unexpected channel %.*s\n", (int)ev->channellen, ev->channel);
            ++bad;
        }
        lcm_eventlog_free_event(ev);
    }
    lcm_eventlog_destroy(log);
    if (seen != (1u << LCM_N_TYPES) - 1u) {
        fprintf(stderr, "missing types: mask 0x%x\n", seen);
        ++bad;
    }
    printf("%s: C decoded %s: %u error(s)\n", bad == 0u ? "PASS" : "FAIL", path, bad);
    return bad == 0u ? 0 : 1;
}

int main(int argc, char **argv)
{
    if (argc == 3 && strcmp(argv[1], "write") == 0) {
        return write_log(argv[2]);
    }
    if (argc == 3 && strcmp(argv[1], "check") == 0) {
        return check_log(argv[2]);
    }
    fprintf(stderr, "usage: %s write|check <log>\n", argc > 0 ? argv[0] : "lcm_xlang_c");
    return 2;
}
