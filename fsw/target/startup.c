/*
 * startup.c — vector table, reset handler, the single fault handler and the stack canary
 * for MPS2 AN385/AN386 (spec 00 §6.2).
 *
 * Every exception other than reset is unexpected in this polled design (no interrupt is ever
 * taken: the PIL image enables UART0's RX interrupt only to end a WFI, with PRIMASK set), so all of them — the faults, SVCall, PendSV, SysTick and every IRQ — go to one
 * handler that reports and exits with BOARD_EXIT_FAULT.
 */
#include "board.h"
#include "board_internal.h"

extern int main(void);

typedef void (*board_isr_t)(void);

#define BOARD_NUM_IRQ      32u   /* external interrupts of the AN385/AN386 images */
#define BOARD_NUM_SYS_EXC  15u   /* Reset .. SysTick */

typedef struct {
    /* cppcheck-suppress unusedStructMember ; read by the core at reset */
    uint32_t *initial_sp;
    /* cppcheck-suppress unusedStructMember ; read by the core on exception entry */
    board_isr_t vector[BOARD_NUM_SYS_EXC + BOARD_NUM_IRQ];
} board_vectors_t;

#define BOARD_F_ board_fault_entry
#define BOARD_F4_ BOARD_F_, BOARD_F_, BOARD_F_, BOARD_F_
#define BOARD_F16_ BOARD_F4_, BOARD_F4_, BOARD_F4_, BOARD_F4_

/* Placed at address 0 by mps2.ld (VTOR resets to 0); `used` because nothing references it. */
__attribute__((section(".vectors"), used))
static const board_vectors_t board_vectors = {
    &board_ld_stack_top,
    {
        board_reset_handler,   /* 1 Reset */
        BOARD_F4_,             /* 2 NMI, 3 HardFault, 4 MemManage, 5 BusFault */
        BOARD_F4_,             /* 6 UsageFault, 7..9 reserved */
        BOARD_F4_,             /* 10 reserved, 11 SVCall, 12 DebugMonitor, 13 reserved */
        BOARD_F_, BOARD_F_,    /* 14 PendSV, 15 SysTick */
        BOARD_F16_, BOARD_F16_ /* IRQ 0..31 */
    }
};

#define SCB_CPACR  0xE000ED88u
#define SCB_CPACR_CP10_CP11_FULL 0x00F00000u
#define SCB_CFSR   0xE000ED28u
#define SCB_HFSR   0xE000ED2Cu
#define SCB_MMFAR  0xE000ED34u
#define SCB_BFAR   0xE000ED38u

/*
 * RAM set-up runs through board_reg32 (volatile word accesses at computed addresses): the
 * regions are delimited by linker symbols, not by C objects, and volatile keeps GCC from
 * turning these loops into calls to memcpy/memset before anything is initialised.
 */
static void board_fill(uint32_t begin, uint32_t end, uint32_t value)
{
    uint32_t a;

    for (a = begin; a < end; a += 4u) {
        *board_reg32(a) = value;
    }
}

static void board_stack_prepare(void)
{
    uint32_t limit = board_addr(&board_ld_stack_limit);
    uint32_t sp;
    uint32_t i;

    __asm__ volatile ("mov %0, sp" : "=r"(sp));
    /* Stop short of the reset handler's own frame: painting it would corrupt the caller. */
    board_fill(limit + (4u * BOARD_CANARY_WORDS), (sp - 64u) & ~3u, BOARD_STACK_PAINT);
    for (i = 0u; i < BOARD_CANARY_WORDS; i++) {
        *board_reg32(limit + (4u * i)) = BOARD_CANARY_BASE ^ i;
    }
}

bool board_stack_canary_ok(void)
{
    uint32_t limit = board_addr(&board_ld_stack_limit);
    uint32_t bad = 0u;
    uint32_t i;

    for (i = 0u; i < BOARD_CANARY_WORDS; i++) {
        bad |= *board_reg32(limit + (4u * i)) ^ (BOARD_CANARY_BASE ^ i);
    }
    return bad == 0u;
}

uint32_t board_stack_size(void)
{
    return board_addr(&board_ld_stack_top) - board_addr(&board_ld_stack_limit);
}

uint32_t board_stack_used(void)
{
    uint32_t top = board_addr(&board_ld_stack_top);
    uint32_t a = board_addr(&board_ld_stack_limit) + (4u * BOARD_CANARY_WORDS);

    while ((a < top) && (*board_reg32(a) == BOARD_STACK_PAINT)) {
        a += 4u;
    }
    return top - a;
}

void board_reset_handler(void)
{
    uint32_t src = board_addr(&board_ld_data_load);
    uint32_t dst = board_addr(&board_ld_data_start);
    uint32_t end = board_addr(&board_ld_data_end);

#if defined(__ARM_FP)
    /* Hard-float ABI: code outside fsw/ (tests, runners) may use VFP registers, and with CP10/CP11
     * disabled the first such instruction would take a NOCP UsageFault. */
    *board_reg32(SCB_CPACR) |= SCB_CPACR_CP10_CP11_FULL;
    __asm__ volatile ("dsb\n\tisb" ::: "memory");
#endif
    while (dst < end) {
        *board_reg32(dst) = *board_reg32(src);
        dst += 4u;
        src += 4u;
    }
    board_fill(board_addr(&board_ld_bss_start), board_addr(&board_ld_bss_end), 0u);
    board_stack_prepare();
    board_systick_start();
    board_console_init();
    board_exit(main());
}

/* The exception frame is read from MSP before any prologue moves it. */
__attribute__((naked))
void board_fault_entry(void)
{
    __asm__ volatile (
        "mrs r0, msp\n\t"
        "b board_fault_report\n\t");
}

void board_fault_report(const uint32_t *frame)
{
    uint32_t ipsr;
    uint32_t f = board_addr(frame);

    __asm__ volatile ("mrs %0, ipsr" : "=r"(ipsr));
    board_console_write("\n*** FAULT exception ");
    board_console_hex(ipsr & 0x1FFu);
    /* A frame outside RAM (a wild SP) is not dereferenced: that would fault inside the handler. */
    if ((f >= BOARD_RAM_BASE) && ((f + 32u) <= board_addr(&board_ld_stack_top)) && ((f & 3u) == 0u)) {
        board_console_write(" pc ");
        board_console_hex(frame[6]);
        board_console_write(" lr ");
        board_console_hex(frame[5]);
        board_console_write(" xpsr ");
        board_console_hex(frame[7]);
    }
    board_console_write(" cfsr ");
    board_console_hex(*board_reg32(SCB_CFSR));
    board_console_write(" hfsr ");
    board_console_hex(*board_reg32(SCB_HFSR));
    board_console_write(" mmfar ");
    board_console_hex(*board_reg32(SCB_MMFAR));
    board_console_write(" bfar ");
    board_console_hex(*board_reg32(SCB_BFAR));
    if (!board_stack_canary_ok()) {
        /* The likely cause: a stack overflow ran into whatever faulted. */
        board_console_write(" (stack canary broken)");
    }
    board_console_write("\n");
    board_exit_raw(BOARD_EXIT_FAULT);
}
