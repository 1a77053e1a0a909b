/*
 * board.h — board support for the MPS2 FPGA images AN385 (Cortex-M3) and AN386 (Cortex-M4),
 * as emulated by QEMU (spec 00 §6.2). fsw/target is the only place that touches hardware.
 *
 * The image starts in Reset_Handler (startup.c), which copies .data, clears .bss, paints the
 * stack, places the canary at the stack limit, calls `int main(void)` and passes its return
 * value to board_exit().
 *
 * Exit codes (spec 00 §6.2): 0 pass, 1..127 failed-test count (main's value, clamped),
 * BOARD_EXIT_CANARY when the stack canary is broken at exit, BOARD_EXIT_FAULT when any fault
 * or unexpected exception is taken. A hang is turned into 124 by the host's `timeout`.
 *
 * Variants: with BOARD_SEMIHOSTING=1 (the `qemu` variant) exit and console go through ARM
 * semihosting. Without it (a real board, where BKPT 0xAB would fault with no debugger
 * attached) the console is UART1 and exit requests a system reset.
 */
#ifndef FSW_TARGET_BOARD_H
#define FSW_TARGET_BOARD_H

#include <stdint.h>
#include <stdbool.h>
#include <stddef.h>

#define BOARD_EXIT_MAX_RC  127  /* main's value is clamped to [0, 127] */
#define BOARD_EXIT_CANARY  236  /* stack canary overwritten at exit */
#define BOARD_EXIT_FAULT   238  /* HardFault or any other unexpected exception */

#define BOARD_SYSCLK_HZ    25000000u  /* MPS2 SYSCLK; SysTick with CLKSOURCE = processor clock */

/*
 * A memory-mapped 32-bit register at a fixed address. This is the BSP's one integer-to-pointer
 * conversion (MISRA C:2012 11.4, advisory; deviation "hardware access", fsw/target only).
 */
static inline volatile uint32_t *board_reg32(uint32_t addr)
{
    /* cppcheck-suppress misra-c2012-11.4 ; hardware register at a fixed address */
    return (volatile uint32_t *)addr;
}

/* ---------------------------------------------------------------- exit and console */
/* Checks the stack canary, then exits with rc (clamped) or BOARD_EXIT_CANARY. Never returns. */
void board_exit(int rc) __attribute__((noreturn));
/* Raw exit without the canary check (used by the fault path). Never returns. */
void board_exit_raw(uint32_t code) __attribute__((noreturn));
/* Console output: semihosting on the qemu variant, UART1 otherwise. */
void board_console_write(const char *s);   /* NUL-terminated, no newline added */
void board_console_putc(char c);
void board_console_hex(uint32_t v);         /* "0x%08x", no libc: also used on the fault path */
/* System reset (SCB AIRCR SYSRESETREQ): the board starts again from its reset vector. Never returns. */
void board_reset(void) __attribute__((noreturn));
/* Host-supplied command line (qemu variant: "<elf> <args...>"); length, or -1 if none. */
int32_t board_cmdline(char *buf, uint32_t len);

/* ---------------------------------------------------------------- stack */
/* True while every canary word at the stack limit is intact. */
bool     board_stack_canary_ok(void);
/* Deepest stack use so far, in bytes, from the paint pattern (high-water mark). */
uint32_t board_stack_used(void);
/* Size of the stack region in bytes (linker symbol board_ld_stack_size). */
uint32_t board_stack_size(void);

/* ---------------------------------------------------------------- SysTick */
/*
 * SysTick runs free from the processor clock (25 MHz on MPS2), reload 0xFFFFFF, no interrupt.
 * It counts down; board_systick_elapsed() takes the modular 24-bit difference, valid for
 * brackets shorter than 2^24 ticks (about 0.67 s, or 84 M instructions under -icount shift=3).
 */
#define BOARD_SYSTICK_MASK 0x00FFFFFFu
void board_systick_start(void);
#define BOARD_SYST_CVR 0xE000E018u
static inline uint32_t board_systick_read(void)
{
    return *board_reg32(BOARD_SYST_CVR);
}
static inline uint32_t board_systick_elapsed(uint32_t start, uint32_t end)
{
    return (start - end) & BOARD_SYSTICK_MASK;
}

#endif /* FSW_TARGET_BOARD_H */
