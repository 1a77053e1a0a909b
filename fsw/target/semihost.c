/*
 * semihost.c — ARM semihosting for the qemu board variant (spec 00 §6.2).
 */
#include "semihost.h"

#if !defined(BOARD_SEMIHOSTING) || (BOARD_SEMIHOSTING != 1)
#error "semihost.c belongs to the qemu board variant only (BKPT 0xAB faults on a real board)"
#endif

/* cppcheck-suppress misra-c2012-2.7 ; op and arg are asm operands, which the addon does not see */
uint32_t semihost_call(uint32_t op, const void *arg)
{
    uint32_t ret;

    /* r0/r1 are clobbered, so the compiler never allocates op or arg to them. */
    __asm__ volatile (
        "mov r0, %1\n\t"
        "mov r1, %2\n\t"
        "bkpt 0xAB\n\t"
        "mov %0, r0\n\t"
        : "=r"(ret)
        : "r"(op), "r"(arg)
        : "r0", "r1", "memory");
    return ret;
}

void semihost_write0(const char *s)
{
    (void)semihost_call(SEMIHOST_SYS_WRITE0, s);
}

void semihost_writec(char c)
{
    (void)semihost_call(SEMIHOST_SYS_WRITEC, &c);
}

void semihost_exit(uint32_t code)
{
    const uint32_t block[2] = { SEMIHOST_ADP_APP_EXIT, code };

    (void)semihost_call(SEMIHOST_SYS_EXIT_EXTENDED, block);
    /* Only reached under a debugger without SYS_EXIT_EXTENDED: hang, which the host's
     * timeout reports (124), rather than exit with a status that could read as a pass. */
    for (;;) {
    }
}

int32_t semihost_get_cmdline(char *buf, uint32_t len)
{
    struct {
        char *buf;
        uint32_t len;
    } block;
    int32_t rc = -1;

    block.buf = buf;
    block.len = len;
    if ((len > 0u) && (semihost_call(SEMIHOST_SYS_GET_CMDLINE, &block) == 0u)) {
        rc = (int32_t)block.len;
    }
    return rc;
}
