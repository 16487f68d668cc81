// semihost.c -- plan report and exit status over Arm semihosting, for running the
// image under a debugger or an emulator (qemu-system-arm -semihosting-config
// enable=on). Only built with SVA_FW_SEMIHOSTING=ON: on a part with no debugger
// attached, the BKPT instruction below would fault.
//
// No C library: a 64-bit integer formatter and two semihosting calls (SYS_WRITE0 and
// SYS_EXIT_EXTENDED), so the image still links no stdio, heap or syscall stub.
#include "semihost.h"

enum {
    SH_SYS_WRITE0 = 0x04,         // write a NUL-terminated string to the debug console
    SH_SYS_EXIT_EXTENDED = 0x20,  // exit with a status (semihosting v2; qemu has it)
};
#define SH_ADP_STOPPED_APPLICATION_EXIT 0x20026u

static uint32_t sh_call(uint32_t op, const void* arg)
{
    // The call: r0 = operation, r1 = argument, BKPT 0xAB (Thumb); result in r0.
    register uint32_t r0 __asm__("r0") = op;
    register const void* r1 __asm__("r1") = arg;
    __asm__ volatile("bkpt 0xab" : "+r"(r0) : "r"(r1) : "memory");
    return r0;
}

static char line[512];
static uint32_t used;

static void put_char(char c)
{
    if (used + 1u < sizeof(line)) {
        line[used] = c;
        used++;
    }
}

void sh_put_str(const char* s)
{
    for (const char* p = s; *p != '\0'; p++) {
        put_char(*p);
    }
}

void sh_put_int(int64_t v)
{
    char digits[20];
    uint32_t n = 0u;
    // Work on the negative magnitude so that INT64_MIN prints too.
    int64_t x = (v < 0) ? v : -v;
    do {
        digits[n] = (char)('0' - (int32_t)(x % 10));
        n++;
        x /= 10;
    } while (x != 0);
    if (v < 0) {
        put_char('-');
    }
    while (n > 0u) {
        n--;
        put_char(digits[n]);
    }
}

void sh_end_line(void)
{
    put_char('\n');
    line[used] = '\0';
    (void)sh_call(SH_SYS_WRITE0, line);
    used = 0u;
}

void sh_exit(uint32_t status)
{
    const uint32_t block[2] = {SH_ADP_STOPPED_APPLICATION_EXIT, status};
    (void)sh_call(SH_SYS_EXIT_EXTENDED, block);
    for (;;) {
        // not reached under a host that implements the call
    }
}
