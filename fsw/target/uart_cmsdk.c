/*
 * uart_cmsdk.c — polled CMSDK APB UART driver.
 */
#include "uart_cmsdk.h"
#include "board.h"

static volatile uint32_t *cmsdk_reg(const cmsdk_uart_t *u, uint32_t off)
{
    return board_reg32(u->base + off);
}

static void cmsdk_cnt_inc(uint32_t *c)
{
    if (*c != UINT32_MAX) {
        *c += 1u;
    }
}

uint32_t cmsdk_uart_bauddiv(uint32_t pclk_hz, uint32_t baud)
{
    uint32_t div = CMSDK_UART_BAUDDIV_MIN;

    if (baud != 0u) {
        div = (pclk_hz + (baud / 2u)) / baud;
    }
    return (div < CMSDK_UART_BAUDDIV_MIN) ? CMSDK_UART_BAUDDIV_MIN : div;
}

void cmsdk_uart_init(cmsdk_uart_t *u, uint32_t base, uint32_t bauddiv)
{
    u->base = base;
    u->rx_overruns = 0u;
    u->rx_bytes = 0u;
    u->tx_bytes = 0u;
    *cmsdk_reg(u, CMSDK_UART_CTRL) = 0u;
    *cmsdk_reg(u, CMSDK_UART_BAUDDIV) = (bauddiv < CMSDK_UART_BAUDDIV_MIN) ? CMSDK_UART_BAUDDIV_MIN : bauddiv;
    *cmsdk_reg(u, CMSDK_UART_STATE) = CMSDK_UART_STATE_TXOVERRUN | CMSDK_UART_STATE_RXOVERRUN;
    *cmsdk_reg(u, CMSDK_UART_INTSTAT) = 0xFu;
    *cmsdk_reg(u, CMSDK_UART_CTRL) = CMSDK_UART_CTRL_TXEN | CMSDK_UART_CTRL_RXEN;
}

/* cppcheck-suppress misra-c2012-8.7 ; board API, also used by images outside fsw/ */
bool cmsdk_uart_tx_full(const cmsdk_uart_t *u)
{
    return (*cmsdk_reg(u, CMSDK_UART_STATE) & CMSDK_UART_STATE_TXFULL) != 0u;
}

/* cppcheck-suppress misra-c2012-8.7 ; board API, also used by images outside fsw/ */
bool cmsdk_uart_try_putc(cmsdk_uart_t *u, uint8_t b)
{
    bool ok = false;

    if (!cmsdk_uart_tx_full(u)) {
        *cmsdk_reg(u, CMSDK_UART_DATA) = (uint32_t)b;
        cmsdk_cnt_inc(&u->tx_bytes);
        ok = true;
    }
    return ok;
}

void cmsdk_uart_putc(cmsdk_uart_t *u, uint8_t b)
{
    while (!cmsdk_uart_try_putc(u, b)) {
    }
}

void cmsdk_uart_write(cmsdk_uart_t *u, const uint8_t *p, size_t n)
{
    size_t i;

    for (i = 0u; i < n; i++) {
        cmsdk_uart_putc(u, p[i]);
    }
}

bool cmsdk_uart_try_getc(cmsdk_uart_t *u, uint8_t *b)
{
    uint32_t state = *cmsdk_reg(u, CMSDK_UART_STATE);
    bool got = false;

    if ((state & CMSDK_UART_STATE_RXOVERRUN) != 0u) {
        *cmsdk_reg(u, CMSDK_UART_STATE) = CMSDK_UART_STATE_RXOVERRUN;
        cmsdk_cnt_inc(&u->rx_overruns);
    }
    if ((state & CMSDK_UART_STATE_RXFULL) != 0u) {
        *b = (uint8_t)(*cmsdk_reg(u, CMSDK_UART_DATA) & 0xFFu);
        cmsdk_cnt_inc(&u->rx_bytes);
        got = true;
    }
    return got;
}
