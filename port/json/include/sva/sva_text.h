/// sva_text.h -- user-supplied text made safe to print outside JSON (host tools and
/// nodes), and the programs' integer option parser. Part of the sva_json library
/// (sva::json); needs nothing but the C library and sva.h's status codes.
///
/// A mission name, a file name or a command-line argument may hold a newline or a
/// terminal escape sequence (ESC [ ...). Printed raw, it forges output lines or
/// drives the terminal. sva_text_escape() turns such text into visible characters:
///   - printable ASCII (0x20..0x7e) is kept, backslash included;
///   - \n, \r, \t become the two characters \n, \r, \t;
///   - any other control byte (0x00..0x1f, 0x7f) becomes \xHH (ESC is \x1b);
///   - a well-formed UTF-8 sequence of a code point from U+00A0 up is kept;
///   - every byte of anything else (C1 controls U+0080..U+009F such as CSI,
///     overlong forms, surrogates, stray or truncated bytes) becomes \xHH.
/// So the result holds no byte below 0x20, no 0x7f and only well-formed UTF-8, and
/// escaping it again changes nothing (the helper may be applied at every layer).
/// Backslashes are kept as they are: the result is for reading, not for decoding.
#ifndef SVA_TEXT_H
#define SVA_TEXT_H

#include <stddef.h>

#include <sva/sva.h>

#ifdef __cplusplus
extern "C" {
#endif

/// Room that always holds the escape of `n` input bytes, with the NUL (an escaped
/// byte takes at most 4 characters).
#define SVA_TEXT_ESCAPED_SIZE(n) ((4U * (size_t)(n)) + 1U)

/// Writes the escape of the NUL-terminated `text` into `out` (`size` bytes, NUL
/// included). Output that does not fit is cut before the first character (or escape)
/// that would overflow, never inside one. Returns `out`, so a call can be an argument
/// of printf. Preconditions: out != NULL, size >= 1; text == NULL is written as "".
/// Complexity O(strlen(text)); allocates nothing; thread-safe.
char* sva_text_escape(char* out, size_t size, const char* text);

/// The integer option parser of every program (the CLI, the nodes, the bridge): reads
/// `text` as a whole decimal integer (digits with an optional leading minus) in [lo, hi]
/// into *out and returns SVA_OK. Returns SVA_ERR_INVALID, *out untouched, when it is not
/// one (empty, spaces, a plus, other characters, beyond long) or lies outside [lo, hi], with
/// "<name>: must be an integer in [lo, hi], got
/// \"<text, escaped>\"" in err (when err is not NULL and err_size > 0); SVA_ERR_ARGUMENT
/// for a NULL text or out. Allocates nothing; O(strlen(text) + err_size); thread-safe.
SVA_NODISCARD sva_status_t sva_text_to_long(const char* name, const char* text, long lo, long hi,
                                            long* out, char* err, size_t err_size);

#ifdef __cplusplus
}
#endif

#endif  // SVA_TEXT_H
