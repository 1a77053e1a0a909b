/*
 * board_io.c — exit, console and SysTick for both board variants.
 *
 * qemu variant (BOARD_SEMIHOSTING=1): console = SYS_WRITE0/SYS_WRITEC, which QEMU writes to
 * its stderr (or the -semihosting-config chardev); exit = SYS_EXIT_EXTENDED, so QEMU's exit
 * status is the code.
 * board variant: console = UART1 (UART0 is the PIL link); exit = message, then system reset.
 */
#include "board.h"
#include "board_internal.h"

#if defined(BOARD_SEMIHOSTING) && (BOARD_SEMIHOSTING == 1)
#include "semihost.h"
#else
#include "uart_cmsdk.h"
#define BOARD_CONSOLE_BAUD 115200u
static cmsdk_uart_t board_console_uart;   /* BSP state: console UART counters */
#endif
#define SCB_AIRCR 0xE000ED0Cu
#define SCB_AIRCR_SYSRESETREQ 0x05FA0004u

#define SYST_CSR 0xE000E010u
#define SYST_RVR 0xE000E014u
#define SYST_CSR_ENABLE    (1u << 0)
#define SYST_CSR_CLKSOURCE (1u << 2)   /* processor clock; TICKINT stays 0 */

void board_systick_start(void)
{
    *board_reg32(SYST_CSR) = 0u;
    *board_reg32(SYST_RVR) = BOARD_SYSTICK_MASK;
    *board_reg32(BOARD_SYST_CVR) = 0u;   /* any write clears the counter */
    *board_reg32(SYST_CSR) = SYST_CSR_CLKSOURCE | SYST_CSR_ENABLE;
}

void board_reset(void)
{
    *board_reg32(SCB_AIRCR) = SCB_AIRCR_SYSRESETREQ;
    __asm__ volatile ("dsb" ::: "memory");
    for (;;) {
        /* the reset takes effect within a few cycles */
    }
}

void board_console_hex(uint32_t v)
{
    static const char digits[16] = {
        '0', '1', '2', '3', '4', '5', '6', '7', '8', '9', 'a', 'b', 'c', 'd', 'e', 'f'
    };
    char buf[11];
    uint32_t i;

    buf[0] = '0';
    buf[1] = 'x';
    for (i = 0u; i < 8u; i++) {
        buf[2u + i] = digits[(v >> (28u - (4u * i))) & 0xFu];
    }
    buf[10] = '\0';
    board_console_write(buf);
}

void board_exit(int rc)
{
    uint32_t code = ((rc < 0) || (rc > BOARD_EXIT_MAX_RC)) ? (uint32_t)BOARD_EXIT_MAX_RC : (uint32_t)rc;

    if (!board_stack_canary_ok()) {
        board_console_write("\n*** stack canary broken at ");
        board_console_hex(board_addr(&board_ld_stack_limit));
        board_console_write("\n");
        code = BOARD_EXIT_CANARY;
    }
    board_exit_raw(code);
}

#if defined(BOARD_SEMIHOSTING) && (BOARD_SEMIHOSTING == 1)

void board_console_init(void)
{
}

void board_console_write(const char *s)
{
    semihost_write0(s);
}

void board_console_putc(char c)
{
    semihost_writec(c);
}

int32_t board_cmdline(char *buf, uint32_t len)
{
    return semihost_get_cmdline(buf, len);
}

void board_exit_raw(uint32_t code)
{
    semihost_exit(code);
}

#else /* real board */

void board_console_init(void)
{
    cmsdk_uart_init(&board_console_uart, CMSDK_UART1_BASE,
                    cmsdk_uart_bauddiv(BOARD_SYSCLK_HZ, BOARD_CONSOLE_BAUD));
}

/* cppcheck-suppress misra-c2012-8.7 ; board API (board.h), used by images outside fsw/ */
void board_console_putc(char c)
{
    /* Before board_console_init (a very early fault) TXEN is clear and the byte is dropped. */
    if (board_console_uart.base != 0u) {
        cmsdk_uart_putc(&board_console_uart, (uint8_t)c);
    }
}

void board_console_write(const char *s)
{
    const char *p = s;

    while (*p != '\0') {
        board_console_putc(*p);
        p++;
    }
}

int32_t board_cmdline(char *buf, uint32_t len)
{
    (void)buf;
    (void)len;
    return -1;
}

void board_exit_raw(uint32_t code)
{
    board_console_write("\n*** exit ");
    board_console_hex(code);
    board_console_write(", reset\n");
    board_reset();
}

#endif
