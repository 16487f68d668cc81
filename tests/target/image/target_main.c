// target_main.c -- main() of a Cortex-M test image (tests/target): runs the Unity
// runner of one tests/core file (generated with --main_name=sva_target_runner_main)
// on top of examples/cortex-m/startup.c, then reports over semihosting and exits
// with status 0 only if every test passed.
//
// Around the runner:
// - faults: the example's vector table parks every fault in a loop, which under qemu
//   only a timeout would end; this image installs its own table (VTOR) whose fault
//   handlers print the fault, the faulting pc and the fault status registers, and end
//   the run (status 3). Integer division by zero traps (CCR.DIV_0_TRP), as it does on
//   the host, instead of giving 0.
// - the stack: painted before the tests; afterwards the untouched part gives the
//   deepest use, and a stack that reached the end of .bss fails the run (status 4).
// - time: SysTick counts processor clock ticks (24 bits, wraps counted by its
//   interrupt). Under qemu -icount shift=0 the virtual clock advances 1 ns per
//   instruction, so ticks x 1e9 / clock = instructions executed (tests/target/run_target.py).
#include <stdint.h>
#include <stdio.h>

#include "semihost.h"
#include "target.h"

int sva_target_runner_main(void);

void Reset_Handler(void);  // examples/cortex-m/startup.c
void sva_target_fault(const uint32_t* frame);

extern uint32_t __bss_end;  // cortex_m.ld: the stack lies between these two
extern uint32_t __sva_fw_stack_top;

#define REG(addr)           (*(volatile uint32_t*)(addr))
#define SCB_VTOR            0xE000ED08u
#define SCB_CCR             0xE000ED14u
#define SCB_SHCSR           0xE000ED24u
#define SCB_CFSR            0xE000ED28u
#define SCB_HFSR            0xE000ED2Cu
#define SCB_MMFAR           0xE000ED34u
#define SCB_BFAR            0xE000ED38u
#define SYST_CSR            0xE000E010u
#define SYST_RVR            0xE000E014u
#define SYST_CVR            0xE000E018u
#define CCR_DIV_0_TRP       (1u << 4)
#define SHCSR_FAULTS_ENABLE (7u << 16)  // MemManage, BusFault, UsageFault handlers
#define SYST_RELOAD         0x00FFFFFFu
#define STACK_PAINT         0x5A5AA5A5u

enum { EXIT_FAULT = 3, EXIT_STACK = 4 };

static volatile uint32_t systick_wraps;

static void systick_handler(void)
{
    systick_wraps++;
}

static void put_hex(uint32_t v)
{
    char text[11] = "0x";
    for (int i = 0; i < 8; i++) {
        text[2 + i] = "0123456789abcdef"[(v >> (28 - 4 * i)) & 0xFu];
    }
    text[10] = '\0';
    sh_put_str(text);
}

// The exception frame the hardware stacked: r0-r3, r12, lr, pc, xpsr.
void sva_target_fault(const uint32_t* frame)
{
    static const char* const names[] = {"?",         "?",        "NMI",       "HardFault",
                                        "MemManage", "BusFault", "UsageFault"};
    uint32_t ipsr;
    __asm__ volatile("mrs %0, ipsr" : "=r"(ipsr));
    ipsr &= 0x1FFu;
    sva_target_flush();
    sh_put_str("sva target: fault ");
    sh_put_str(ipsr < 7u ? names[ipsr] : "?");
    sh_put_str(" pc=");
    put_hex(frame[6]);
    sh_put_str(" lr=");
    put_hex(frame[5]);
    sh_put_str(" cfsr=");
    put_hex(REG(SCB_CFSR));
    sh_put_str(" hfsr=");
    put_hex(REG(SCB_HFSR));
    sh_put_str(" mmfar=");
    put_hex(REG(SCB_MMFAR));
    sh_put_str(" bfar=");
    put_hex(REG(SCB_BFAR));
    sh_end_line();
    sh_exit(EXIT_FAULT);
}

// Hands the stacked frame (main or process stack, by EXC_RETURN bit 2) to the C handler.
__attribute__((naked)) static void fault_entry(void)
{
    __asm__ volatile("tst lr, #4\n"
                     "ite eq\n"
                     "mrseq r0, msp\n"
                     "mrsne r0, psp\n"
                     "b sva_target_fault\n");
}

typedef void (*target_vector_t)(void);
// VTOR needs the table aligned to its size rounded up to a power of two, at least 128 B.
__attribute__((aligned(128))) static const target_vector_t vectors[16] = {
    0,  // the initial stack pointer: read at reset only, from the example's table
    Reset_Handler,
    fault_entry,  // NMI
    fault_entry,  // HardFault
    fault_entry,  // MemManage
    fault_entry,  // BusFault
    fault_entry,  // UsageFault
    0,
    0,
    0,
    0,
    fault_entry,  // SVCall: the tests make none
    fault_entry,  // DebugMonitor
    0,
    fault_entry,  // PendSV
    systick_handler,
};

static void install_vectors(void)
{
    REG(SCB_VTOR) = (uint32_t)(uintptr_t)vectors;
    REG(SCB_SHCSR) |= SHCSR_FAULTS_ENABLE;
    REG(SCB_CCR) |= CCR_DIV_0_TRP;
    __asm__ volatile("dsb\n isb" ::: "memory");
    REG(SYST_RVR) = SYST_RELOAD;
    REG(SYST_CVR) = 0u;
    REG(SYST_CSR) = 7u;  // processor clock, interrupt on wrap, enabled
}

static uint64_t systick_ticks(void)
{
    uint32_t wraps;
    uint32_t value;
    do {
        wraps = systick_wraps;
        value = REG(SYST_CVR);
    } while (wraps != systick_wraps);
    if (wraps == 0u && value == 0u) {
        return 0u;  // not reloaded yet: no tick since it was started
    }
    return ((uint64_t)wraps << 24) + (SYST_RELOAD - value);
}

static uint32_t* stack_bottom(void)
{
    return (uint32_t*)(((uintptr_t)&__bss_end + 7u) & ~(uintptr_t)7u);
}

__attribute__((noinline)) static void paint_stack(void)
{
    uintptr_t sp;
    __asm__ volatile("mov %0, sp" : "=r"(sp));
    for (uint32_t* p = stack_bottom(); (uintptr_t)p < sp - 64u; p++) {
        *p = STACK_PAINT;
    }
}

static uint32_t stack_used(void)
{
    const uint32_t* p = stack_bottom();
    while (p < &__sva_fw_stack_top && *p == STACK_PAINT) {
        p++;
    }
    return (uint32_t)((uintptr_t)&__sva_fw_stack_top - (uintptr_t)p);
}

int main(void)
{
    install_vectors();
    paint_stack();
    // Unbuffered: the tests' printf lines and Unity's output arrive in program order.
    (void)setvbuf(stdout, NULL, _IONBF, 0);
    const int failures = sva_target_runner_main();
    const uint64_t ticks = systick_ticks();
    (void)fflush(stdout);
    sva_target_flush();

    const uint32_t stack_size =
        (uint32_t)((uintptr_t)&__sva_fw_stack_top - (uintptr_t)stack_bottom());
    const uint32_t used = stack_used();
    sh_put_str("sva target: stack ");
    sh_put_int(used);
    sh_put_str(" of ");
    sh_put_int(stack_size);
    sh_put_str(" B, heap ");
    sh_put_int((int64_t)sva_target_heap_used());
    sh_put_str(" of ");
    sh_put_int((int64_t)sva_target_heap_size());
    sh_put_str(" B, systick ");
    sh_put_int((int64_t)ticks);
    sh_end_line();
    if (used >= stack_size) {
        sh_put_str("sva target: stack overflow (the stack reached the end of .bss)");
        sh_end_line();
        sh_exit(EXIT_STACK);
    }
    sh_exit(failures == 0 ? 0u : 1u);
    return 0;
}
