// lcm_internal.h -- what the adapter's files share (port/lcm/src/); not installed.
#ifndef SVA_LCM_INTERNAL_H
#define SVA_LCM_INTERNAL_H

#include "sva/sva_lcm.h"

/// Counts a refused message under `reason` (logged once per reason); returns REJECTED.
sva_lcm_verdict_t sva_lcm_reject(sva_lcm_node_t* self, sva_lcm_reject_t reason, const char* what);

/// Size and fingerprint, before the generated decoder sees the bytes: ACCEPTED when
/// the bytes may be decoded, else the refusal (counted).
sva_lcm_verdict_t sva_lcm_check_frame(sva_lcm_node_t* self, const char* channel, const void* data,
                                      size_t size, size_t want, int64_t fingerprint);

/// A decoded message's version field against the type's VERSION: false with *verdict
/// the refusal (naming both) when they differ.
bool sva_lcm_version_ok(sva_lcm_node_t* self, const char* channel, const char* type, int version,
                        int want, sva_lcm_verdict_t* verdict);

/// Every message a replan carries names its version, also when it is empty.
void sva_lcm_stamp_replan_versions(sva_lcm_replan_t* r);

/// Hands an input the node took to input_hook (none: true). False when the hook failed:
/// the node is then halted and the caller publishes nothing.
bool sva_lcm_input_durable(sva_lcm_node_t* self, sva_lcm_input_t kind, bool restarts,
                           const void* data, size_t size);

/// Replans the live mission after applied events and publishes priv.replan_tx (whose
/// header the caller set).
void sva_lcm_replan_live(sva_lcm_node_t* self);

/// A fleet message while a live mission runs with fleet_reports set (lcm_reports.c):
/// each listed UAV is a report through the core's rule; one replan if any applied.
void sva_lcm_fleet_report(sva_lcm_node_t* self);

#endif  // SVA_LCM_INTERNAL_H
