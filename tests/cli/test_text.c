// Unit tests of sva_text_escape() and sva_text_to_long() (port/json, sva/sva_text.h): what
// is kept, what is escaped, cuts that never split an escape or a character, escaping
// twice, and the integer option parser.
#include <stddef.h>
#include <stdint.h>
#include <string.h>

#include "unity.h"
#include <sva/sva_text.h>

static void expect(const char* in, const char* want)
{
    char out[256];
    TEST_ASSERT_EQUAL_PTR(out, sva_text_escape(out, sizeof out, in));
    TEST_ASSERT_EQUAL_STRING(want, out);
    // escaping the result again changes nothing
    char again[256];
    TEST_ASSERT_EQUAL_STRING(want, sva_text_escape(again, sizeof again, out));
}

void test_printable_ascii_and_utf8_are_kept(void)
{
    expect("plain name 42 \\ \"q\" ~", "plain name 42 \\ \"q\" ~");
    expect("\xc3\xa9t\xc3\xa9 \xe2\x82\xac \xf0\x9f\x9b\xb8",
           "\xc3\xa9t\xc3\xa9 \xe2\x82\xac \xf0\x9f\x9b\xb8");
    expect("\xc2\xa0", "\xc2\xa0");  // U+00A0, the first code point kept
    expect("", "");
}

void test_controls_are_escaped(void)
{
    expect("a\nb\rc\td", "a\\nb\\rc\\td");
    expect("\x1b[2J\x1b]0;title\x07", "\\x1b[2J\\x1b]0;title\\x07");
    expect("\x01\x1f\x7f", "\\x01\\x1f\\x7f");
    expect("\xc2\x9b"
           "31m",
           "\\xc2\\x9b31m");           // C1 CSI (U+009B)
    expect("\xc2\x85", "\\xc2\\x85");  // C1 NEL
}

void test_malformed_utf8_is_escaped_byte_by_byte(void)
{
    expect("\xc0\x80", "\\xc0\\x80");                    // overlong NUL
    expect("\xe0\x80\xaf", "\\xe0\\x80\\xaf");           // overlong '/'
    expect("\xed\xa0\x80", "\\xed\\xa0\\x80");           // surrogate U+D800
    expect("\xf4\x90\x80\x80", "\\xf4\\x90\\x80\\x80");  // above U+10FFFF
    expect("\xf5\xff\x80", "\\xf5\\xff\\x80");
    expect("a\xc3", "a\\xc3");           // truncated at the end
    expect("\xe2\x82z", "\\xe2\\x82z");  // truncated before ASCII
}

void test_null_text_is_empty(void)
{
    char out[4] = "xyz";
    TEST_ASSERT_EQUAL_STRING("", sva_text_escape(out, sizeof out, NULL));
}

void test_cuts_never_split_an_escape_or_a_character(void)
{
    char out[8];
    // "ab" + "\x1b" (4) = 6 chars fits in 8 with the NUL; the next escape does not
    TEST_ASSERT_EQUAL_STRING("ab\\x1b", sva_text_escape(out, sizeof out, "ab\x1b\x1b"));
    TEST_ASSERT_EQUAL_STRING("ab", sva_text_escape(out, 6, "ab\x1b"));
    TEST_ASSERT_EQUAL_STRING("ab",
                             sva_text_escape(out, 4, "ab\xe2\x82\xac"));  // euro sign: 3 bytes
    TEST_ASSERT_EQUAL_STRING("a\\n", sva_text_escape(out, 5, "a\n"));
    TEST_ASSERT_EQUAL_STRING("", sva_text_escape(out, 1, "abc"));
    // a full-size buffer always holds the escape
    const char* worst = "\x01\x02\x03";
    char fits[SVA_TEXT_ESCAPED_SIZE(3)];
    TEST_ASSERT_EQUAL_STRING("\\x01\\x02\\x03", sva_text_escape(fits, sizeof fits, worst));
}

// sva_text_to_long, the programs' integer option parser: whole decimal integers in
// [lo, hi] only; the error names the option, the range and the text, escaped.
void test_integer_options_are_whole_and_in_range(void)
{
    long v = 7;
    char err[200];
    TEST_ASSERT_EQUAL_INT(SVA_OK, sva_text_to_long("--n", "42", 0, 100, &v, err, sizeof err));
    TEST_ASSERT_EQUAL_INT(42, v);
    TEST_ASSERT_EQUAL_INT(SVA_OK, sva_text_to_long("--n", "-3", -5, 0, &v, NULL, 0));
    TEST_ASSERT_EQUAL_INT(-3, v);
    const char* bad[] = {"",    "1s", " 1", "+1",   "1 ",
                         "101", "-1", "-",  "0x10", "99999999999999999999999"};
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; ++i) {
        v = 7;
        TEST_ASSERT_EQUAL_INT(SVA_ERR_INVALID,
                              sva_text_to_long("--n", bad[i], 0, 100, &v, err, sizeof err));
        TEST_ASSERT_EQUAL_INT(7, v);  // untouched
    }
    TEST_ASSERT_EQUAL_INT(SVA_ERR_INVALID,
                          sva_text_to_long("--n", "x\n\x1b[31m", 0, 100, &v, err, sizeof err));
    TEST_ASSERT_EQUAL_STRING("--n: must be an integer in [0, 100], got \"x\\n\\x1b[31m\"", err);
    TEST_ASSERT_EQUAL_INT(SVA_ERR_ARGUMENT,
                          sva_text_to_long("--n", NULL, 0, 1, &v, err, sizeof err));
    TEST_ASSERT_EQUAL_INT(SVA_ERR_ARGUMENT,
                          sva_text_to_long("--n", "1", 0, 1, NULL, err, sizeof err));
}
