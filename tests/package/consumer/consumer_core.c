// Installed-tree consumer of sva::core: it must see the bound profile the library was
// built with (sva_build_config.h, through CMake's SVA_CONFIG_HEADER or pkg-config's
// SVA_BUILD_CONFIG) and plan a small mission completely.
#include <stdio.h>

#include "sva/sva.h"

#ifndef SVA_BUILD_CONFIG_H  // the include guard of sva_build_config.h
#    error "sva_build_config.h did not reach this consumer (the installed package must export it)"
#endif

static sva_planner_t planner;
static sva_mission_t mission;
static sva_plan_t plan;

static int check(int ok, const char* what)
{
    if (!ok) {
        fprintf(stderr, "consumer_core: %s\n", what);
    }
    return ok ? 0 : 1;
}

int main(void)
{
    const sva_limits_t lim = sva_limits();
    int bad = 0;
    sva_diag_t diag;

    bad += check(lim.max_uavs == SVA_MAX_UAVS, "SVA_MAX_UAVS differs from the library's");
    bad += check(lim.max_targets == SVA_MAX_TARGETS, "SVA_MAX_TARGETS differs from the library's");
    bad += check(lim.mission_bytes == sizeof(sva_mission_t), "sizeof(sva_mission_t) differs");
    bad += check(lim.plan_bytes == sizeof(sva_plan_t), "sizeof(sva_plan_t) differs");
    bad += check(lim.planner_bytes == sizeof(sva_planner_t), "sizeof(sva_planner_t) differs");

    sva_mission_init(&mission);
    mission.uavs[0] = (sva_uav_t){.id = 1, .x = 0, .y = 0, .fuel = 100, .ready_at_ticks = 0};
    mission.uavs[1] = (sva_uav_t){.id = 2, .x = 0, .y = 0, .fuel = 100, .ready_at_ticks = 0};
    mission.uav_count = 2;
    mission.targets[0] =
        (sva_target_t){.id = 1, .x = 3, .y = 4, .start_ticks = 10, .end_ticks = 30, .need = 2};
    mission.target_count = 1;
    bad += check(sva_planner_init(&planner) == SVA_OK, "sva_planner_init failed");
    bad += check(sva_plan(&planner, &mission, SVA_ALGO_SVA, &plan, &diag) == SVA_OK,
                 "sva_plan failed");
    bad += check(plan.status == SVA_PLAN_COMPLETE && plan.covered == 1, "the plan is not complete");
    // Both UAVs fly depot -> (3,4) -> depot: 7 + 7 cells each.
    bad += check(plan.cost == 28, "the plan's cost is not 28");
    if (bad == 0) {
        printf("consumer_core: sva %d.%d.%d, plan cost %lld\n", SVA_VERSION_MAJOR,
               SVA_VERSION_MINOR, SVA_VERSION_PATCH, (long long)plan.cost);
    }
    return bad == 0 ? 0 : 1;
}
