// input.h -- read a whole mission document from a file or standard input; the names
// of JSON types in messages; which of our file kinds a document is (private).
#ifndef SVA_JSON_INPUT_H
#define SVA_JSON_INPUT_H

#include <stddef.h>

#include <sva/sva_json.h>

/// Reads all of `path` ("-" for standard input) into a new NUL-terminated buffer
/// (*text, to be freed with free(); *len excludes the NUL). At most
/// SVA_JSON_MAX_INPUT_BYTES are accepted.
/// Returns SVA_JSON_OK; SVA_JSON_ERR_INPUT when the path cannot be opened, is a
/// directory or holds too much; SVA_JSON_ERR_IO when reading fails or memory runs
/// out. On error *text is NULL and err holds one printable line naming the path.
sva_json_status_t sva_json_read_input(const char* path, char** text, size_t* len, char* err,
                                      size_t err_size);

/// Writes one printf-style error line into err (when size > 0) and returns
/// SVA_JSON_ERR_INPUT: the one way a document's rule is refused.
#if defined(__GNUC__) || defined(__clang__)
__attribute__((format(printf, 3, 4)))
#endif
sva_json_status_t
sva_json_refuse(char* err, size_t size, const char* fmt, ...);

/// The SPEC section 4 name of a JSON value's type: object, array, string, integer,
/// real, boolean or null.
const char* sva_json_type_name(const json_t* value);

/// Names a document of another of our kinds (mission, plan, live mission, scenario,
/// flight log; told apart by their top-level keys) given where an `expected` one was
/// ("mission" or "live mission"): "a scenario (mission, events, change_penalty):
/// sva-tools sim takes it", or NULL when `root` is of the expected kind or of none.
const char* sva_json_other_kind(const json_t* root, const char* expected);

#endif  // SVA_JSON_INPUT_H
