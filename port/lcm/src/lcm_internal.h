// lcm_internal.h -- what the adapter's files share (port/lcm/src/); not installed.
//
// The files call each other one way only, from the node down:
//   lcm_node.c (channels, subscriptions)
//     -> lcm_inputs.c (fleet, mission) -> lcm_reports.c (vehicle reports)
//     -> lcm_live.c (events, replans) -> lcm_plan.c (plans, the clock)
//     -> lcm_convert.c (core -> wire), lcm_hook.c (durable inputs)
//     -> lcm_checks.c (refusals and checks);
//   lcm_status.c (the status message) stands alone.
#ifndef SVA_LCM_INTERNAL_H
#define SVA_LCM_INTERNAL_H

#include "sva/sva_lcm.h"

#include <time.h>

// --- lcm_checks.c -----------------------------------------------------------------

/// Hands one line to the node's log callback (none: dropped).
void sva_lcm_log(sva_lcm_node_t* self, const char* line);

/// Counts a refused message under `reason` (logged once per reason); returns REJECTED.
sva_lcm_status_t sva_lcm_reject(sva_lcm_node_t* self, sva_lcm_reject_t reason, const char* what);

/// A refusal described by last_diag, prefixed with `channel`; returns REJECTED.
sva_lcm_status_t sva_lcm_reject_diag(sva_lcm_node_t* self, sva_lcm_reject_t reason,
                                     const char* channel);

/// Size and fingerprint, before the generated decoder sees the bytes: ACCEPTED when
/// the bytes may be decoded, else the refusal (counted).
sva_lcm_status_t sva_lcm_check_frame(sva_lcm_node_t* self, const char* channel, const void* data,
                                     size_t size, size_t want, int64_t fingerprint);

/// A decoded message's version field against the type's VERSION: false with *verdict
/// the refusal (naming both) when they differ.
bool sva_lcm_version_ok(sva_lcm_node_t* self, const char* channel, const char* type, int version,
                        int want, sva_lcm_status_t* verdict);

// --- lcm_hook.c -------------------------------------------------------------------

/// Hands an input the node took to input_hook (none: true). False when the hook failed:
/// the node is then halted and the caller publishes nothing.
bool sva_lcm_input_durable(sva_lcm_node_t* self, sva_lcm_input_t kind, bool restarts,
                           const void* data, size_t size);

// --- lcm_convert.c ----------------------------------------------------------------

/// A diagnostic into a plan message's diag_* fields.
void sva_lcm_plan_diag(sva_lcm_plan_t* p, const sva_diag_t* d);

/// Fills *p from a core plan over mission m; false when the routes need more than
/// MAX_ROUTE_ITEMS items (then the caller clears the routes).
bool sva_lcm_fill_plan(sva_lcm_plan_t* p, const sva_plan_t* plan, const sva_mission_t* m);

/// The residual mission as wire messages (stamped with the live revision).
void sva_lcm_fill_residual(sva_lcm_replan_t* r, const sva_mission_t* m, int64_t revision,
                           const sva_lcm_frame_t* frame);

// --- lcm_plan.c -------------------------------------------------------------------

/// The clock in microseconds (0 when it cannot be read).
int64_t sva_lcm_now_us(clockid_t clock);

/// Plans the fleet and mission in force, starts the live mission from the plan and
/// publishes the plan (or the refusal).
void sva_lcm_replan(sva_lcm_node_t* self);

// --- lcm_live.c -------------------------------------------------------------------

/// Every message a replan carries names its version, also when it is empty.
void sva_lcm_stamp_replan_versions(sva_lcm_replan_t* r);

/// Replans the live mission after applied events and publishes priv.replan_tx (whose
/// header the caller set).
void sva_lcm_replan_live(sva_lcm_node_t* self);

// --- lcm_reports.c ----------------------------------------------------------------

/// A fleet message while a live mission runs with fleet_reports set: each listed UAV
/// is a report through the core's rule; one replan if any applied.
void sva_lcm_fleet_report(sva_lcm_node_t* self);

#endif  // SVA_LCM_INTERNAL_H
