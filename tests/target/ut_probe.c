/*
 * ut_probe.c — deliberately misbehaving image that proves the board's exit codes
 * (spec 00 §6.2). The mode is the first guest argument (tools/qemu-run.sh <m> <elf> <mode>):
 *
 *   rc <n>      main returns n (checks clamping: > 127 gives 127)
 *   udf         undefined instruction: UsageFault escalated to HardFault -> 238
 *   bus         load from unmapped memory: BusFault escalated to HardFault -> 238
 *   invstate    branch to an even address (Thumb bit clear): INVSTATE -> 238
 *   svc         an exception nobody expects (SVCall) -> 238
 *   canary      overrun the whole stack region -> 236 at exit
 *   hang        spin forever -> 124 from timeout
 */
#include <stdint.h>
#include "board.h"

#ifndef UT_PROBE_STACK_SIZE
#error "UT_PROBE_STACK_SIZE (the board's stack size) must be defined"
#endif

static char probe_cmd[128];

static const char *probe_arg(const char *s, uint32_t idx)
{
    const char *p = s;
    uint32_t k;

    for (k = 0u; k <= idx; k++) {
        while ((*p != ' ') && (*p != '\0')) {
            p++;
        }
        while (*p == ' ') {
            p++;
        }
    }
    return p;
}

static int probe_is(const char *arg, const char *word)
{
    size_t i = 0u;
    while ((word[i] != '\0') && (arg[i] == word[i])) {
        i++;
    }
    return (word[i] == '\0') && ((arg[i] == '\0') || (arg[i] == ' '));
}

static int probe_atoi(const char *s)
{
    int v = 0;
    while ((*s >= '0') && (*s <= '9') && (v < 100000)) {
        v = (v * 10) + (*s - '0');
        s++;
    }
    return v;
}

/* Writes past the bottom of the stack region, like a runaway frame would. */
static void __attribute__((noinline)) probe_overrun(void)
{
    volatile uint32_t big[(UT_PROBE_STACK_SIZE + 4096) / 4];
    uint32_t i;

    for (i = 0u; i < (uint32_t)(sizeof(big) / sizeof(big[0])); i++) {
        big[i] = i;
    }
}

int main(void)
{
    const char *mode;
    volatile uintptr_t addr;

    if (board_cmdline(probe_cmd, (uint32_t)sizeof(probe_cmd)) < 0) {
        board_console_write("ut_probe: no command line\n");
        return 99;
    }
    mode = probe_arg(probe_cmd, 0u);
    board_console_write("ut_probe: ");
    board_console_write(mode);
    board_console_write("\n");

    if (probe_is(mode, "rc")) {
        return probe_atoi(probe_arg(mode, 0u));
    } else if (probe_is(mode, "udf")) {
        __asm__ volatile ("udf #0");
    } else if (probe_is(mode, "bus")) {
        addr = 0xF0000000u;
        (void)*(volatile const uint32_t *)addr;
    } else if (probe_is(mode, "invstate")) {
        addr = 0x00000100u;   /* even: the Thumb bit is clear */
        ((void (*)(void))addr)();
    } else if (probe_is(mode, "svc")) {
        __asm__ volatile ("svc #0");
    } else if (probe_is(mode, "canary")) {
        probe_overrun();
        board_console_write("ut_probe: overrun done, returning 0\n");
        return 0;
    } else if (probe_is(mode, "hang")) {
        for (;;) {
            __asm__ volatile ("" ::: "memory");
        }
    } else {
        board_console_write("ut_probe: unknown mode\n");
        return 98;
    }
    board_console_write("ut_probe: survived the fault\n");
    return 97;
}
