/// sva_json.h -- the JSON layer of sva (host only, jansson): SPEC section 3 missions
/// in, plans and transportation traces out. Used by the sva CLI, the CAN node and the
/// golden-plan runner; CMake target sva_json (alias sva::json).
///
/// Missions: the layer checks the shape of the document (object, keys, types, list
/// lengths, int32 range); every value rule (ranges, ids, windows) is the core's, so
/// callers run sva_mission_validate() afterwards (sva_json_load_mission() does).
/// A mission may carry a frame (docs/flight-stack.md): every reader here checks it
/// (shape, then sva_frame_from_units: "frame.cell_m: must be >= 0.1, got 0.05");
/// the *_frame functions also return it.
/// Messages follow SPEC section 4: "<json path>: <rule>", e.g.
///   targets[0]: missing key "need"
///   targets[0].need: must be an integer, got string
///   uavs: 65 entries exceed SVA_MAX_UAVS (64)     (formatted by sva_diag_format)
/// Every message is one printable line: user-supplied text in it (a path, a key) is
/// escaped with sva_text_escape() (sva/sva_text.h).
///
/// Memory: the mission reader allocates the document on the heap (at most
/// SVA_JSON_MAX_INPUT_BYTES) and frees it before returning; the mission itself lives
/// in the caller's sva_mission_t. Not thread-safe where it reads standard input.
#ifndef SVA_JSON_H
#define SVA_JSON_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>

#include <jansson.h>
#include <sva/sva_live.h>
#include <sva/sva_frame.h>
#include <sva/sva_text.h>

#ifdef __cplusplus
extern "C" {
#endif

/// Longest mission name in bytes (UTF-8, without the NUL).
#define SVA_JSON_NAME_MAX 63
/// Room for any message this layer writes.
#define SVA_JSON_ERROR_SIZE 512
/// Largest mission document read (bigger input is rejected as bad input).
#define SVA_JSON_MAX_INPUT_BYTES (16L * 1024L * 1024L)

/// What a function of this layer that can fail returns (DESIGN.md section 10): 0 on
/// success, a negative error otherwise, with one line in the caller's err buffer (the
/// core has no words for a file or JSON syntax; a broken core rule is worded by
/// sva_diag_format). The sva CLI maps these to its exit statuses (docs/cli.md).
typedef enum {
    SVA_JSON_OK = 0,
    SVA_JSON_ERR_INPUT = -1,  ///< the document or the mission is wrong, or cannot be opened
    SVA_JSON_ERR_IO = -2,     ///< reading or writing failed, or memory ran out
} sva_json_status_t;

/// Parses `len` bytes of JSON text into *mission (reset with sva_mission_init first)
/// and its name. The name is copied as the document gives it and may hold any
/// character JSON allows (control characters too): pass it through sva_text_escape()
/// before printing it outside JSON. `source` names the input in syntax-error messages
/// ("<source>:<line>:<column>: invalid JSON: ..."). Checks the document's shape only,
/// not the core's value rules. On error writes one line (no "sva: error: " prefix, no
/// newline) into err and returns SVA_JSON_ERR_INPUT.
sva_json_status_t sva_json_parse_mission(const char* text, size_t len, const char* source,
                                         sva_mission_t* mission, char name[SVA_JSON_NAME_MAX + 1],
                                         char* err, size_t err_size);

/// The mission object `root` (an already parsed document) into *mission and its name,
/// as sva_json_parse_mission() does for text; the core's value rules are not checked.
sva_json_status_t sva_json_mission_from(const json_t* root, sva_mission_t* mission,
                                        char name[SVA_JSON_NAME_MAX + 1], char* err,
                                        size_t err_size);

/// The optional "frame" of the mission object `root`: *present false when it has none,
/// else the frame in integers (sva_frame_from_units). On error (frame unchanged, present
/// false) one line in err naming the field, the rule and the limit, and
/// SVA_JSON_ERR_INPUT.
sva_json_status_t sva_json_mission_frame(const json_t* root, sva_frame_t* frame, bool* present,
                                         char* err, size_t err_size);

/// A frame as the mission JSON writes it: lat, lon, alt_m, cell_m, tick_s (numbers at
/// their stored resolution) and t0 (sva_frame_format_utc). New reference, or NULL when
/// memory runs out or t0 is out of range.
json_t* sva_json_frame(const sva_frame_t* frame);

/// One target object (SPEC section 3 keys) into *target; `prefix` names it in messages
/// ("events[2].target"). False with one line in err when the shape is wrong.
bool sva_json_target_from(const json_t* object, const char* prefix, sva_target_t* target, char* err,
                          size_t err_size);

/// A target as its SPEC section 3 object. New reference, or NULL when memory runs out.
json_t* sva_json_target(const sva_target_t* target);

/// A mission as its SPEC section 3 document (change_penalty only when not 0), for
/// missions the tools make, such as a live mission's residual mission. New reference,
/// or NULL when memory runs out.
json_t* sva_json_mission(const sva_mission_t* mission, const char* name);

/// sva_json_mission with the mission's frame last (none when frame is NULL).
json_t* sva_json_mission_framed(const sva_mission_t* mission, const char* name,
                                const sva_frame_t* frame);

/// Reads the mission at `path` ("-" for standard input), parses it and runs
/// sva_mission_validate(). Returns SVA_JSON_OK, SVA_JSON_ERR_INPUT (unreadable
/// path, empty or oversized input, malformed document, broken rule) or
/// SVA_JSON_ERR_IO (a read failing after the file was opened), with a message in err.
sva_json_status_t sva_json_load_mission(const char* path, sva_mission_t* mission,
                                        char name[SVA_JSON_NAME_MAX + 1], char* err,
                                        size_t err_size);

/// sva_json_load_mission that also returns the mission's frame (*present false when it
/// has none).
sva_json_status_t sva_json_load_mission_frame(const char* path, sva_mission_t* mission,
                                              char name[SVA_JSON_NAME_MAX + 1], sva_frame_t* frame,
                                              bool* present, char* err, size_t err_size);

/// How input read from standard input is named in messages.
#define SVA_JSON_STDIN_NAME "<stdin>"

// ---------------------------------------------------------------------------------
// Plans out.

/// Builds the plan document of a successful sva_plan() (status complete or partial):
/// keys in SPEC order -- mission, algorithm, status, covered, uncovered (target ids,
/// mission order), cost, routes ({uav, targets (ids, visit order), distance,
/// fuel_used}, one per UAV in mission order), stranded (UAV ids), stats (solve_us,
/// then every sva_stats_t counter under its own name).
/// Returns a new reference (json_decref it), or NULL when memory runs out.
json_t* sva_json_plan(const sva_mission_t* mission, const char* name, const sva_plan_t* plan,
                      int64_t solve_us);

/// Writes `plan` indented by 2, keys in insertion order, reals with 15 significant
/// digits (a frame's values come back as written), and a final newline.
/// Returns SVA_JSON_OK, or SVA_JSON_ERR_IO when writing fails (errno tells why).
sva_json_status_t sva_json_write_plan(FILE* out, const json_t* plan);

// ---------------------------------------------------------------------------------
// Transportation problems as JSON Lines (sva plan --trace FILE).
//
// One compact JSON object per problem, in solving order:
//   {"algorithm":"sva","source_uavs":[..],"supply":[..],"sink_targets":[..],
//    "demand":[..],"dropped":[..],"cost":[[..]],"flow":[[..]],
//    "cost_total":N,"covered":K,"pivots":P}
// source_uavs holds the id of the first (lowest-index) UAV of each source group,
// sink_targets the target ids; cost and flow are source-major matrices with null
// for a pair that is no arc (SVA_TP_NO_ARC).

/// State of one trace: where lines go and the mission that maps indices to ids.
typedef struct {
    FILE* out;
    const sva_mission_t* mission;
    unsigned long problems;  ///< lines written
    bool failed;             ///< a write or an allocation failed; later lines are skipped
} sva_trace_t;

/// The problem as a JSON object (new reference), or NULL when memory runs out.
json_t* sva_json_transport(const sva_mission_t* mission, const sva_tp_view_t* problem);

/// An sva_tp_observer_t: `user` is an sva_trace_t. Writes one line per problem.
void sva_trace_observer(void* user, const sva_tp_view_t* problem);

/// Points planner->on_transport at sva_trace_observer with *trace.
void sva_trace_attach(sva_trace_t* trace, sva_planner_t* planner, FILE* out,
                      const sva_mission_t* mission);

// ---------------------------------------------------------------------------------
// Live missions (docs/SPEC.md, live missions)

/// Most events a LIVE.json document may hold.
#define SVA_JSON_MAX_EVENTS 100000L

/// A LIVE.json document: the mission as planned at tick 0, the plan in force then (when
/// has_plan), the events in order (heap: sva_json_live_free() releases them) and the
/// tick to replan at (the last event's when the document gives none).
typedef struct {
    sva_mission_t mission;
    char name[SVA_JSON_NAME_MAX + 1];
    bool has_plan;
    sva_plan_t plan;
    sva_event_t* events;
    size_t event_count;
    int32_t now_ticks;
    bool has_now;
    bool has_frame;     ///< the mission has a frame (docs/flight-stack.md)
    sva_frame_t frame;  ///< valid when has_frame
} sva_json_live_t;

/// Reads and checks the shape of a LIVE.json document at `path` ("-": standard input);
/// the mission is also checked against the core's rules, and the plan in force against
/// the mission: one route per UAV in mission order, known targets none twice, and SPEC
/// section 1 (every visit reached by its window's start, every route within its UAV's
/// fuel, every target served by exactly its need or by none), each refused with a
/// message starting "plan." that names the route or field, the rule and the limit.
/// Event rules (ids, ticks) are the core's, checked when sva_live_apply() takes each
/// event. Returns SVA_JSON_OK, or SVA_JSON_ERR_INPUT / SVA_JSON_ERR_IO with one line
/// in err (nothing to free then).
sva_json_status_t sva_json_load_live(const char* path, sva_json_live_t* live, char* err,
                                     size_t err_size);

/// Frees the events of a loaded live document.
void sva_json_live_free(sva_json_live_t* live);

/// The plan document of a replan (sva_json_plan() over the residual mission) with two
/// more keys: "changes" ({dropped, added: [[uav id, target id], ...], count, penalty})
/// and "live" ({now, revision, kept, covered, under_way: [target ids], targets: [{id,
/// state}]}). New reference, or NULL when memory runs out.
json_t* sva_json_replan(const sva_live_t* live, const sva_live_result_t* result, const char* name,
                        int64_t solve_us);

#ifdef __cplusplus
}
#endif

#endif  // SVA_JSON_H
