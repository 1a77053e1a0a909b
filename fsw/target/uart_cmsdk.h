/*
 * uart_cmsdk.h — polled driver for the ARM CMSDK APB UART of the MPS2 images (spec 00 §6.2).
 *
 * No interrupts: the PIL loop polls RX between steps and waits on TXFULL. QEMU's model holds a
 * single RX byte and never overruns (the socket back-pressures), but a real board does, so
 * RXOVERRUN is still counted and cleared.
 */
#ifndef FSW_TARGET_UART_CMSDK_H
#define FSW_TARGET_UART_CMSDK_H

#include <stdint.h>
#include <stdbool.h>
#include <stddef.h>

/* cppcheck-suppress misra-c2012-2.5 ; board API: the PIL link (outside fsw/) uses UART0 */
#define CMSDK_UART0_BASE 0x40004000u
#define CMSDK_UART1_BASE 0x40005000u

#define CMSDK_UART_DATA     0x00u
#define CMSDK_UART_STATE    0x04u
#define CMSDK_UART_CTRL     0x08u
#define CMSDK_UART_INTSTAT  0x0Cu   /* INTSTATUS on read, INTCLEAR on write */
#define CMSDK_UART_BAUDDIV  0x10u

#define CMSDK_UART_STATE_TXFULL    (1u << 0)
#define CMSDK_UART_STATE_RXFULL    (1u << 1)
#define CMSDK_UART_STATE_TXOVERRUN (1u << 2)   /* write 1 to clear */
#define CMSDK_UART_STATE_RXOVERRUN (1u << 3)   /* write 1 to clear */

#define CMSDK_UART_CTRL_TXEN (1u << 0)
#define CMSDK_UART_CTRL_RXEN (1u << 1)

#define CMSDK_UART_BAUDDIV_MIN 16u   /* the hardware requires BAUDDIV >= 16 */

typedef struct {
    uint32_t base;          /* CMSDK_UART0_BASE or CMSDK_UART1_BASE */
    uint32_t rx_overruns;   /* RXOVERRUN events seen, saturating */
    uint32_t rx_bytes;      /* bytes received, saturating */
    uint32_t tx_bytes;      /* bytes sent, saturating */
} cmsdk_uart_t;

/* BAUDDIV for a baud rate from the APB clock, rounded to nearest, at least 16. */
uint32_t cmsdk_uart_bauddiv(uint32_t pclk_hz, uint32_t baud);
/* Disables, programs BAUDDIV (clamped to >= 16), clears stale status, enables TX and RX. */
void     cmsdk_uart_init(cmsdk_uart_t *u, uint32_t base, uint32_t bauddiv);
bool     cmsdk_uart_tx_full(const cmsdk_uart_t *u);
/* Non-blocking: false if the TX holding register is full. */
bool     cmsdk_uart_try_putc(cmsdk_uart_t *u, uint8_t b);
/* Blocking: waits while TXFULL. */
void     cmsdk_uart_putc(cmsdk_uart_t *u, uint8_t b);
void     cmsdk_uart_write(cmsdk_uart_t *u, const uint8_t *p, size_t n);
/* Non-blocking: true and *b set when a byte was waiting. Counts and clears RXOVERRUN. */
bool     cmsdk_uart_try_getc(cmsdk_uart_t *u, uint8_t *b);

#endif /* FSW_TARGET_UART_CMSDK_H */
