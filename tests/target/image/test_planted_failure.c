// test_planted_failure.c -- a test image that must fail (ctest target_tiny_planted_failure
// passes only when run_target.py reports the failed test): proof that a failing
// assertion on the target fails the label.
#include "unity.h"

void setUp(void)
{
}
void tearDown(void)
{
}

void test_passes(void)
{
    TEST_ASSERT_EQUAL_INT(2, 1 + 1);
}

void test_planted_failure(void)
{
    volatile int two = 2;
    TEST_ASSERT_EQUAL_INT_MESSAGE(3, two, "planted failure");
}
