/*
 * board_internal.h — symbols shared between the BSP translation units only.
 */
#ifndef FSW_TARGET_BOARD_INTERNAL_H
#define FSW_TARGET_BOARD_INTERNAL_H

#include <stdint.h>

/* Linker-script symbols (mps2.ld); only their addresses are meaningful. */
extern uint32_t board_ld_data_load;
extern uint32_t board_ld_data_start;
extern uint32_t board_ld_data_end;
extern uint32_t board_ld_bss_start;
extern uint32_t board_ld_bss_end;
extern uint32_t board_ld_stack_limit;
extern uint32_t board_ld_stack_top;

/*
 * Address of a linker symbol or object as an integer: the BSP's one pointer-to-integer
 * conversion (MISRA C:2012 11.4/11.6, advisory; deviation "hardware access").
 */
static inline uint32_t board_addr(const volatile void *p)
{
    /* cppcheck-suppress [misra-c2012-11.4, misra-c2012-11.6] ; linker symbols are addresses */
    return (uint32_t)(uintptr_t)p;
}

#define BOARD_RAM_BASE       0x20000000u
#define BOARD_STACK_PAINT    0xA5C3A5C3u   /* untouched stack word */
#define BOARD_CANARY_WORDS   4u            /* canary at the stack limit, 16 bytes */
#define BOARD_CANARY_BASE    0x5AFEC0DEu   /* word i holds BASE ^ i: a copy of one word is caught */

/* Entry points referenced by the vector table. */
void board_reset_handler(void) __attribute__((noreturn));
void board_fault_entry(void) __attribute__((noreturn));
void board_fault_report(const uint32_t *frame) __attribute__((noreturn, used));

/* Called once by the reset handler before main. */
void board_console_init(void);

#endif /* FSW_TARGET_BOARD_INTERNAL_H */
