/// mission_json.h -- read a SPEC section 3 mission from JSON text into sva_mission_t.
///
/// The JSON layer checks the shape of the document (object, keys, types, list
/// lengths, int32 range); every value rule (ranges, ids, windows) is the core's, so
/// callers run sva_mission_validate() afterwards (sva_json_load_mission() does).
/// Messages follow SPEC section 4: "<json path>: <rule>", e.g.
///   targets[0]: missing key "need"
///   targets[0].need: must be an integer, got string
///   uavs: 65 entries exceed SVA_MAX_UAVS (64)     (formatted by sva_diag_format)
#ifndef SVA_MISSION_JSON_H
#define SVA_MISSION_JSON_H

#include <stddef.h>

#include <sva/sva.h>

#ifdef __cplusplus
extern "C" {
#endif

/// Longest mission name in bytes (UTF-8, without the NUL).
#define SVA_JSON_NAME_MAX 63
/// Room for any message this layer writes.
#define SVA_JSON_ERROR_SIZE 512
/// Largest mission document read (bigger input is rejected as bad input).
#define SVA_JSON_MAX_INPUT_BYTES (16L * 1024L * 1024L)

typedef enum {
    SVA_JSON_OK = 0,
    SVA_JSON_BAD_INPUT = 2,  ///< the document or the mission is wrong (CLI exit 2)
    SVA_JSON_IO_ERROR = 1,   ///< the input could not be read (CLI exit 1)
} sva_json_result_t;

/// Parses `len` bytes of JSON text into *mission (reset with sva_mission_init first)
/// and its name. `source` names the input in syntax-error messages
/// ("<source>:<line>:<column>: invalid JSON: ..."). Checks the document's shape only,
/// not the core's value rules. On error writes one line (no "sva: error: " prefix, no
/// newline) into err and returns SVA_JSON_BAD_INPUT.
sva_json_result_t sva_json_parse_mission(const char* text,
                                         size_t len,
                                         const char* source,
                                         sva_mission_t* mission,
                                         char name[SVA_JSON_NAME_MAX + 1],
                                         char* err,
                                         size_t err_size);

/// Reads the mission at `path` ("-" for standard input), parses it and runs
/// sva_mission_validate(). Returns SVA_JSON_OK, SVA_JSON_BAD_INPUT (unreadable
/// path, empty or oversized input, malformed document, broken rule) or
/// SVA_JSON_IO_ERROR (a read failing after the file was opened), with a message in err.
sva_json_result_t sva_json_load_mission(const char* path,
                                        sva_mission_t* mission,
                                        char name[SVA_JSON_NAME_MAX + 1],
                                        char* err,
                                        size_t err_size);

#ifdef __cplusplus
}
#endif

#endif  // SVA_MISSION_JSON_H
