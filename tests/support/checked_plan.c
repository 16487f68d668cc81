// checked_plan.c -- see checked_plan.h.
#include "checked_plan.h"

#include <stdio.h>

#include "spec_checker.h"

int checked_plan(sva_planner_t* planner, const sva_mission_t* mission, sva_algorithm_t algorithm,
                 sva_plan_t* plan, char* msg, size_t size)
{
    sva_diag_t diag;
    char why[256] = "";
    const sva_status_t st = sva_plan(planner, mission, algorithm, plan, &diag);
    if (st != SVA_OK) {
        sva_diag_format(&diag, why, sizeof(why));
        snprintf(msg, size, "%s: status %d (%s)", sva_algorithm_name(algorithm), (int)st, why);
        return 1;
    }
    if (spec_check_plan(mission, plan, why, sizeof(why)) != 0) {
        snprintf(msg, size, "%s: %s", sva_algorithm_name(algorithm), why);
        return 1;
    }
    return 0;
}
