// Two additions to Unity that the C tests use:
//   SVA_TEST_FAIL(format, ...)  fails the running test with a printf-formatted message
//                               (Unity's TEST_FAIL_MESSAGE takes a fixed string), at the
//                               caller's line; longer messages are cut at 511 characters
//   SVA_TEST_ASSERT_EQUAL_BYTES(expected, actual, len)
//                               TEST_ASSERT_EQUAL_MEMORY for lengths that may be 0 (an
//                               empty route, an empty log): no bytes compare equal, where
//                               Unity fails a zero-length comparison as pointless
#ifndef SVA_UNITY_H
#define SVA_UNITY_H

#include <stdarg.h>
#include <stdio.h>

#include "unity.h"

#if defined(__GNUC__)
__attribute__((format(printf, 2, 3)))
#endif
static inline void
sva_test_fail_at(UNITY_LINE_TYPE line, const char* format, ...)
{
    static char text[512];
    va_list args;
    va_start(args, format);
    (void)vsnprintf(text, sizeof text, format, args);
    va_end(args);
    UNITY_TEST_FAIL(line, text);
}

#define SVA_TEST_FAIL(...) sva_test_fail_at((UNITY_LINE_TYPE)__LINE__, __VA_ARGS__)

#define SVA_TEST_ASSERT_EQUAL_BYTES(expected, actual, len)         \
    do {                                                           \
        if ((len) > 0U) {                                          \
            TEST_ASSERT_EQUAL_MEMORY((expected), (actual), (len)); \
        }                                                          \
    } while (0)

#endif
