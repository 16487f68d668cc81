// text.c -- user-supplied text made safe to print (see sva/sva_text.h).
#include <sva/sva_text.h>

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

// Length of the well-formed UTF-8 sequence at s that encodes a printable code point
// (U+00A0 and up, no surrogates, at most U+10FFFF); 0 for anything else.
static size_t printable_utf8(const unsigned char* s)
{
    size_t len;
    unsigned long cp;
    if (s[0] >= 0xc2U && s[0] <= 0xdfU) {
        len = 2;
        cp = s[0] & 0x1fU;
    } else if (s[0] >= 0xe0U && s[0] <= 0xefU) {
        len = 3;
        cp = s[0] & 0x0fU;
    } else if (s[0] >= 0xf0U && s[0] <= 0xf4U) {
        len = 4;
        cp = s[0] & 0x07U;
    } else {
        return 0;
    }
    for (size_t i = 1; i < len; ++i) {
        if ((s[i] & 0xc0U) != 0x80U) {  // also stops at the NUL
            return 0;
        }
        cp = (cp << 6) | (s[i] & 0x3fU);
    }
    static const unsigned long min_cp[5] = {0, 0, 0x80UL, 0x800UL, 0x10000UL};
    if (cp < min_cp[len] || cp < 0xa0UL || (cp >= 0xd800UL && cp <= 0xdfffUL) || cp > 0x10ffffUL) {
        return 0;
    }
    return len;
}

char* sva_text_escape(char* out, size_t size, const char* text)
{
    size_t used = 0;
    const unsigned char* s = (const unsigned char*)(text != NULL ? text : "");
    while (*s != '\0') {
        char piece[5];
        size_t n;
        size_t consumed = 1;
        if (*s >= 0x20U && *s < 0x7fU) {
            piece[0] = (char)*s;
            n = 1;
        } else if (*s == '\n' || *s == '\r' || *s == '\t') {
            piece[0] = '\\';
            piece[1] = (char)(*s == '\n' ? 'n' : (*s == '\r' ? 'r' : 't'));
            n = 2;
        } else if ((n = printable_utf8(s)) > 0) {
            memcpy(piece, s, n);
            consumed = n;
        } else {
            (void)snprintf(piece, sizeof piece, "\\x%02x", (unsigned)*s);
            n = 4;
        }
        if (used + n >= size) {
            break;
        }
        memcpy(out + used, piece, n);
        used += n;
        s += consumed;
    }
    out[used] = '\0';
    return out;
}

sva_status_t sva_text_to_long(const char* name, const char* text, long lo, long hi, long* out,
                              char* err, size_t err_size)
{
    if ((text == NULL) || (out == NULL)) {
        return SVA_ERR_ARGUMENT;
    }
    // Digits with an optional minus, nothing else (strtol alone would take spaces and '+').
    const char* digits = (text[0] == '-') ? &text[1] : text;
    const bool shaped = (digits[0] >= '0') && (digits[0] <= '9');
    char* end = NULL;
    errno = 0;
    const long v = shaped ? strtol(text, &end, 10) : 0L;
    if (shaped && (errno == 0) && (*end == '\0') && (v >= lo) && (v <= hi)) {
        *out = v;
        return SVA_OK;
    }
    if ((err != NULL) && (err_size > 0U)) {
        char shown[SVA_TEXT_ESCAPED_SIZE(256)];  // escaping cuts a longer text, never an escape
        (void)snprintf(err, err_size, "%s: must be an integer in [%ld, %ld], got \"%s\"",
                       (name != NULL) ? name : "value", lo, hi,
                       sva_text_escape(shown, sizeof shown, text));
    }
    return SVA_ERR_INVALID;
}
