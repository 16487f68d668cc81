// Reads a SPEC section 3 mission file for the CAN node: the JSON layer
// (port/json, sva_json_load_mission) plus the CAN wire limits (sva_can_mission_check).
#ifndef SVA_CAN_MISSION_FILE_H
#define SVA_CAN_MISSION_FILE_H

#include <stdbool.h>
#include <stddef.h>

#include "sva/sva.h"
#include "sva/sva_can_mission_frame.h"
#include "sva/sva_json.h"

/// Parses `path` strictly (unknown keys, wrong types, missing keys, values outside
/// int32 or a list longer than its bound are errors), then runs sva_mission_validate()
/// and sva_can_mission_check(). name (may be NULL) receives the mission name.
/// Returns sva_json_load_mission's statuses: SVA_JSON_OK, SVA_JSON_ERR_INPUT (the file
/// cannot be opened, or the document, the mission or a CAN wire limit is broken) or
/// SVA_JSON_ERR_IO (a read failed), with a one-line message naming the field and the
/// rule in err.
sva_json_status_t sva_can_mission_load(const char* path, sva_mission_t* mission, char* name,
                                       size_t name_size, char* err, size_t err_size);

/// sva_can_mission_load that also returns the mission's frame (docs/flight-stack.md) in
/// its wire integers: *has_frame false when the mission has none.
sva_json_status_t sva_can_mission_load_frame(const char* path, sva_mission_t* mission, char* name,
                                             size_t name_size, sva_can_mission_frame_t* frame,
                                             bool* has_frame, char* err, size_t err_size);

#endif
