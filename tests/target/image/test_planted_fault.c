// test_planted_fault.c -- a test image that faults (ctest target_tiny_planted_fault
// passes only when run_target.py reports the fault): proof that a crash on the target
// fails the label at once, not after a timeout.
#include "unity.h"

void setUp(void)
{
}
void tearDown(void)
{
}

void test_planted_fault(void)
{
    __asm__ volatile("udf #0");  // permanently undefined: a UsageFault
    TEST_FAIL_MESSAGE("not reached");
}
