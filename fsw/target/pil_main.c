/*
 * pil_main.c — the PIL board image fsw_pil.elf (spec 00 §6.1, §6.2, §6.4): the flight software of
 * every configured mission behind the serial link on UART0, polled.
 *
 * Between bytes the core sleeps in WFI, woken by UART0's RX interrupt, which is enabled but never
 * taken (PRIMASK set: no handler, the vector table unchanged). Busy polling kept QEMU's vCPU busy
 * while its main loop delivers the next byte, one byte per turn: with WFI a 32-byte ping round trip
 * under -icount shift=3 is 1.7 x faster (5.4 -> 3.2 ms, both images measured alternately; the
 * emulator's absolute rate varies with the host's load), and a real board idles instead of spinning.
 * The instruction counts are unchanged: WFI lies outside the bracket.
 *
 * The session logic (boot from a host-sent configuration and image, sequence rules, duplicate
 * cache, payloads) is fsw/app/fsw_pil.c, the same code the host harness runs; this file is only
 * the board around it: the UART, the SysTick bracket around fsw_step, the stack watch and the end.
 *
 * Instruction count: under QEMU -icount shift=3 one instruction is 8 ns of virtual time and the
 * MPS2 SysTick counts at 25 MHz, so one tick is 5 instructions; TLM carries ticks x 5 (the
 * bracket's own few instructions included, a resolution of 5). The UART waits lie outside the
 * bracket, and SysTick is restarted just before it (its phase reset), so the count does not depend
 * on host timing.
 */
#include "board.h"
#include "uart_cmsdk.h"
#include "fsw_pil.h"

#ifndef FSW_PIL_BOARD_ID
#define FSW_PIL_BOARD_ID FSW_PIL_BOARD_AN385
#endif
#ifndef FSW_PIL_BUILD_ID
#define FSW_PIL_BUILD_ID 0u
#endif
#define PIL_BAUD 921600u          /* a real board's link rate; QEMU ignores BAUDDIV timing */
#define PIL_INSN_PER_TICK 5u      /* -icount shift=3 at 25 MHz SysTick */

/* BSP state: the board's one session and its UART (fsw/target may hold globals; fsw/ may not). */
static fsw_pil_board_t pil_board;
static cmsdk_uart_t pil_uart;

#define NVIC_ISER0 0xE000E100u
#define NVIC_ICPR0 0xE000E280u
#define PIL_UART0_RX_IRQ_BIT 1u   /* MPS2 AN385/AN386: UART0 RX is IRQ 0 */
#define CMSDK_UART_CTRL_RXINTEN (1u << 3)
#define CMSDK_UART_INT_RX (1u << 1)

/* Sleeps until UART0 has a byte. The RX interrupt is enabled in the UART and the NVIC but PRIMASK
   is set, so it is never taken (no handler, the vector table is unchanged): it only ends the WFI. */
static void pil_wait_rx(void)
{
    *board_reg32(CMSDK_UART0_BASE + CMSDK_UART_INTSTAT) = CMSDK_UART_INT_RX;
    *board_reg32(NVIC_ICPR0) = PIL_UART0_RX_IRQ_BIT;
    if ((*board_reg32(CMSDK_UART0_BASE + CMSDK_UART_STATE) & CMSDK_UART_STATE_RXFULL) == 0u) {
        __asm__ volatile ("wfi" ::: "memory");
    }
}

static void pil_send(void)
{
    cmsdk_uart_write(&pil_uart, pil_board.tx, pil_board.tx_len);
    fsw_pil_board_sent(&pil_board);
}

int main(void)
{
    bool done = false;

    cmsdk_uart_init(&pil_uart, CMSDK_UART0_BASE, cmsdk_uart_bauddiv(BOARD_SYSCLK_HZ, PIL_BAUD));
    __asm__ volatile ("cpsid i" ::: "memory");
    *board_reg32(CMSDK_UART0_BASE + CMSDK_UART_CTRL) |= CMSDK_UART_CTRL_RXINTEN;
    *board_reg32(NVIC_ISER0) = PIL_UART0_RX_IRQ_BIT;
    fsw_pil_board_init(&pil_board, (uint16_t)FSW_PIL_BOARD_ID, FSW_PIL_BUILD_ID);
    pil_board.st.stack_size = board_stack_size();
    pil_send();
    /* The session's loop: it ends on the host's MODE_CMD END or on a broken stack canary. */
    while (!done) {
        uint8_t byte = 0u;
        if (!cmsdk_uart_try_getc(&pil_uart, &byte)) {
            pil_wait_rx();
        } else {
            const fsw_pil_rx_t act = fsw_pil_board_rx(&pil_board, byte);
            if (act == FSW_PIL_RX_STEP) {
                /* Restarting SysTick resets its phase: without it the bracket's start falls anywhere
                   in a 5-instruction tick, depending on how long the UART was polled, and the count
                   varies by one tick between identical runs. */
                board_systick_start();
                const uint32_t t0 = board_systick_read();
                fsw_pil_board_step(&pil_board);
                const uint32_t t1 = board_systick_read();
                fsw_pil_board_finish(&pil_board, board_systick_elapsed(t0, t1) * PIL_INSN_PER_TICK);
                pil_board.st.stack_used = board_stack_used();
                pil_board.st.uart_overruns = pil_uart.rx_overruns;
                done = !board_stack_canary_ok();
            } else if (act == FSW_PIL_RX_END) {
                done = true;
            } else if (act == FSW_PIL_RX_RESET) {
                pil_send();        /* the ack first, then the reset the host asked for */
                board_reset();
            } else {
                /* NONE or SEND */
            }
            if (pil_board.tx_len > 0u) {
                pil_send();
            }
        }
    }
    /* board_exit checks the canary again: 236 when broken, else 0. */
    return 0;
}
