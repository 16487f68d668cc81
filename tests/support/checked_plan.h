// checked_plan.h -- plan a mission and check the plan with the independent SPEC
// checker, the step most model-based tests repeat for every algorithm.
#ifndef SVA_CHECKED_PLAN_H
#define SVA_CHECKED_PLAN_H

#include <stddef.h>

#include "sva/sva.h"

/// Plans `mission` with `algorithm` into *plan; 0 when the planner succeeds and the
/// plan passes spec_check_plan, else non-zero with the reason in msg (the status and
/// the planner's diagnostic, or the first violation), prefixed by the algorithm name.
int checked_plan(sva_planner_t* planner, const sva_mission_t* mission, sva_algorithm_t algorithm,
                 sva_plan_t* plan, char* msg, size_t size);

#endif
