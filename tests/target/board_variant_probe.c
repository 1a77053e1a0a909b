/*
 * board_variant_probe.c — main for the non-semihosting board variant (fsw_board_mps2): console
 * on UART1 and exit by system reset. Run with QEMU's -no-reboot, the reset ends QEMU with 0.
 */
#include "board.h"

int main(void)
{
    board_console_write("mps2 variant: console on UART1\n");
    return 3;
}
