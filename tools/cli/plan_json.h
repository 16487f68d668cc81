/// plan_json.h -- an sva_plan_t as SPEC section 3 plan JSON.
#ifndef SVA_PLAN_JSON_H
#define SVA_PLAN_JSON_H

#include <stdint.h>
#include <stdio.h>

#include <jansson.h>
#include <sva/sva.h>

#ifdef __cplusplus
extern "C" {
#endif

/// Builds the plan document of a successful sva_plan() (status complete or partial):
/// keys in SPEC order -- mission, algorithm, status, covered, uncovered (target ids,
/// mission order), cost, routes ({uav, targets (ids, visit order), distance,
/// fuel_used}, one per UAV in mission order), stranded (UAV ids), stats (solve_us,
/// then every sva_stats_t counter under its own name).
/// Returns a new reference (json_decref it), or NULL when memory runs out.
json_t* sva_json_plan(const sva_mission_t* mission, const char* name, const sva_plan_t* plan, int64_t solve_us);

/// Writes `plan` indented by 2, keys in insertion order, and a final newline.
/// Returns 0, or -1 when writing fails (errno tells why).
int sva_json_write_plan(FILE* out, const json_t* plan);

#ifdef __cplusplus
}
#endif

#endif  // SVA_PLAN_JSON_H
