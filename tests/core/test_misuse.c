// API misuse and budget exhaustion, against a core built with SVA_ENABLE_ASSERT=0,
// SVA_BFA_MAX_NODES=1000 and SVA_MAX_PIVOTS=16 (sva_core_misuse in CMakeLists.txt):
// NULL pointers and enum values out of range return SVA_ERR_ARGUMENT instead of
// asserting; bfa's node budget is SVA_ERR_LIMIT naming it; the pivot budget is
// SVA_ERR_SOLVER. Every failure leaves the plan empty (all-or-nothing).
#include <stddef.h>
#include <stdint.h>
#include <string.h>
#include "unity.h"

#include "sva/sva.h"

#if SVA_ENABLE_ASSERT != 0 || SVA_BFA_MAX_NODES != 1000 || SVA_MAX_PIVOTS != 16
#    error "test_misuse.c needs the sva_core_misuse build of the core"
#endif

static sva_planner_t planner;
static sva_mission_t mission;
static sva_plan_t plan;

void test_null_and_enum_misuse_is_an_argument_error(void)
{
    sva_diag_t d;
    sva_mission_init(&mission);
    TEST_ASSERT_EQUAL_INT(SVA_ERR_ARGUMENT, sva_planner_init(NULL));
    TEST_ASSERT_EQUAL_INT(SVA_OK, sva_planner_init(&planner));
    TEST_ASSERT_EQUAL_INT(SVA_ERR_ARGUMENT, sva_mission_validate(NULL, &d));
    TEST_ASSERT_EQUAL_INT(SVA_ERR_ARGUMENT, sva_plan(NULL, &mission, SVA_ALGO_SVA, &plan, &d));
    TEST_ASSERT_EQUAL_INT(SVA_ERR_ARGUMENT, sva_plan(&planner, NULL, SVA_ALGO_SVA, &plan, &d));
    TEST_ASSERT_EQUAL_INT(SVA_ERR_ARGUMENT, sva_plan(&planner, &mission, SVA_ALGO_SVA, NULL, &d));
    TEST_ASSERT_EQUAL_INT(SVA_ERR_ARGUMENT,
                          sva_plan(&planner, &mission, SVA_ALGO_COUNT_, &plan, &d));
    TEST_ASSERT_EQUAL_INT(SVA_ERR_ARGUMENT,
                          sva_plan(&planner, &mission, (sva_algorithm_t)-1, &plan, &d));
    sva_algorithm_t algo = SVA_ALGO_HGA;
    TEST_ASSERT_EQUAL_INT(SVA_ERR_ARGUMENT, sva_algorithm_from_name(NULL, &algo));
    TEST_ASSERT_EQUAL_INT(SVA_ERR_ARGUMENT, sva_algorithm_from_name("sva", NULL));
    TEST_ASSERT_EQUAL_INT(SVA_ALGO_HGA, algo);
    char buf[8] = "xyz";
    TEST_ASSERT_EQUAL_INT(0, sva_diag_format(NULL, buf, sizeof buf));
    TEST_ASSERT_EQUAL_INT(0, sva_diag_format(&d, NULL, 4));
    sva_diag_clear(NULL);  // must not crash
    TEST_ASSERT_EQUAL_STRING("xyz", buf);
}

// Ten targets in consecutive windows, five UAVs at the depot: far more than 1000
// search nodes.
void test_bfa_node_budget_is_a_limit_error(void)
{
    sva_mission_init(&mission);
    for (int i = 0; i < 5; i++) {
        mission.uavs[i] =
            (sva_uav_t){.id = i + 1, .x = 0, .y = 0, .fuel = 100000, .ready_at_ticks = 0};
    }
    for (int i = 0; i < 10; i++) {
        mission.targets[i] = (sva_target_t){.id = i + 1,
                                            .x = 3 * (i % 4),
                                            .y = 2 * (i % 3),
                                            .start_ticks = 20 + 30 * i,
                                            .end_ticks = 40 + 30 * i,
                                            .need = 1 + (i % 2)};
    }
    mission.uav_count = 5;
    mission.target_count = 10;
    TEST_ASSERT_EQUAL_INT(SVA_OK, sva_planner_init(&planner));
    sva_diag_t d;
    TEST_ASSERT_EQUAL_INT(SVA_ERR_LIMIT, sva_plan(&planner, &mission, SVA_ALGO_BFA, &plan, &d));
    TEST_ASSERT_EQUAL_INT(SVA_PLAN_NONE, plan.status);
    TEST_ASSERT_EQUAL_INT(0, plan.route_count);
    TEST_ASSERT_EQUAL_INT(SVA_RULE_ALGO_LIMIT, d.rule);
    TEST_ASSERT_NOT_NULL(d.limit_name);
    TEST_ASSERT_EQUAL_STRING("SVA_BFA_MAX_NODES", d.limit_name);
    // The same mission within bfa's size limits plans with the other algorithms.
    TEST_ASSERT_EQUAL_INT(SVA_OK, sva_plan(&planner, &mission, SVA_ALGO_GA, &plan, &d));
}

// Twenty UAVs at distinct positions and twenty targets in one window: the tableau needs
// at least one pivot per served sink, more than the 16 allowed.
void test_pivot_budget_is_a_solver_error(void)
{
    sva_mission_init(&mission);
    const int n = (SVA_MAX_UAVS < 20) ? SVA_MAX_UAVS : 20;
    for (int i = 0; i < n; i++) {
        mission.uavs[i] =
            (sva_uav_t){.id = i + 1, .x = i, .y = 0, .fuel = 100000, .ready_at_ticks = 0};
        mission.targets[i] = (sva_target_t){
            .id = i + 1, .x = i, .y = 5, .start_ticks = 100, .end_ticks = 110, .need = 1};
    }
    mission.uav_count = (uint16_t)n;
    mission.target_count = (uint16_t)n;
    TEST_ASSERT_EQUAL_INT(SVA_OK, sva_planner_init(&planner));
    sva_diag_t d;
    TEST_ASSERT_EQUAL_INT(SVA_ERR_SOLVER, sva_plan(&planner, &mission, SVA_ALGO_SVA, &plan, &d));
    TEST_ASSERT_EQUAL_INT(SVA_PLAN_NONE, plan.status);
    TEST_ASSERT_EQUAL_INT(0, plan.route_count);
}
