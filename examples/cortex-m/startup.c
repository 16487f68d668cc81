// startup.c -- reset handler and vector table for a Cortex-M (no CMSIS needed).
// Reset: enable the FPU when compiled for one, copy .data from flash, zero .bss,
// call main(). Symbols come from cortex_m.ld.
#include <stdint.h>

int main(void);

extern uint32_t __sva_fw_stack_top;  // initial main stack pointer
extern uint32_t __data_load, __data_start, __data_end;
extern uint32_t __bss_start, __bss_end;

void Reset_Handler(void);
void Default_Handler(void);

void Default_Handler(void)
{
    for (;;) {
    }
}

void Reset_Handler(void)
{
#if defined(__ARM_FP)
    // CPACR: full access to coprocessors 10 and 11 (the FPU). The sva core never
    // touches it; a hard-float C library or the rest of the firmware may.
    volatile uint32_t* const cpacr = (volatile uint32_t*)0xE000ED88u;
    *cpacr |= (0xFu << 20);
#endif
    const uint32_t* src = &__data_load;
    for (uint32_t* dst = &__data_start; dst < &__data_end;) {
        *dst++ = *src++;
    }
    for (uint32_t* dst = &__bss_start; dst < &__bss_end;) {
        *dst++ = 0u;
    }
    (void)main();
    for (;;) {
    }
}

// The first 16 entries of every Cortex-M vector table; device interrupts follow on a
// real part. Entry 0 is the initial stack pointer, not a function.
typedef void (*fw_vector_t)(void);
__attribute__((section(".isr_vector"), used)) const fw_vector_t fw_vectors[16] = {
    (fw_vector_t)(uintptr_t)&__sva_fw_stack_top,
    Reset_Handler,
    Default_Handler,  // NMI
    Default_Handler,  // HardFault
    Default_Handler,  // MemManage
    Default_Handler,  // BusFault
    Default_Handler,  // UsageFault
    0,
    0,
    0,
    0,                // reserved
    Default_Handler,  // SVCall
    Default_Handler,  // DebugMonitor
    0,                // reserved
    Default_Handler,  // PendSV
    Default_Handler,  // SysTick
};
