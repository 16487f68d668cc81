// plan_check.h -- a plan in force from a document against its mission (private).
#ifndef SVA_JSON_PLAN_CHECK_H
#define SVA_JSON_PLAN_CHECK_H

#include <stddef.h>

#include <sva/sva_json.h>

/// Checks `plan` (routes only: uav_id, target_count, targets as indices into
/// mission->targets) against `mission`, a mission that passed sva_mission_validate():
/// one route per UAV in mission order with known targets, none twice (sva_live_init()'s
/// rules, worded as the core words them), then SPEC section 1: every visit reached by
/// its window's start, every route within its UAV's fuel (return leg and hover
/// included), every target served by exactly its `need` UAVs or by none.
/// Returns SVA_JSON_OK, or SVA_JSON_ERR_INPUT with one line in err, "plan." then the
/// route or field, the rule and the limit (the first broken rule: routes in mission
/// order, each its layout, visits in order and fuel; then targets in mission order).
/// Allocates nothing; O(U * R^2 + T) with R the longest route.
sva_json_status_t sva_json_check_plan(const sva_mission_t* mission, const sva_plan_t* plan,
                                      char* err, size_t err_size);

#endif  // SVA_JSON_PLAN_CHECK_H
