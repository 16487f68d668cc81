// Regression test: a core built with SVA_MAX_ROUTE_TARGETS below SVA_MAX_TARGETS
// (here 2; sva_config.h allows [1, SVA_MAX_TARGETS]) and asserts on. flow's rounding
// reads each relaxation route with a cap of SVA_MAX_ROUTE_TARGETS, and a relaxation
// route may be longer: sva_flow_route() asserted `n < cap` there, so a valid mission
// aborted the program (untrusted input reaching an assert). Now the route is cut, as
// flow_round.c intends, and branching splits it.
// Every algorithm must plan such missions with routes of at most 2 targets, each plan
// checked by the independent SPEC checker. Seeds are printed (SVA_TEST_SEED=...).
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>
#include "sva_unity.h"

#include "mission_gen.h"
#include "checked_plan.h"
#include "spec_checker.h"
#include "sva/sva.h"

static sva_planner_t planner;
static sva_mission_t mission;
static sva_plan_t plan;

static const sva_algorithm_t algorithms[] = {SVA_ALGO_SVA, SVA_ALGO_GA, SVA_ALGO_HGA, SVA_ALGO_BFA,
                                             SVA_ALGO_FLOW};

static void must_plan(sva_algorithm_t algorithm, uint64_t seed, int round)
{
    char why[320] = "";
    if (checked_plan(&planner, &mission, algorithm, &plan, why, sizeof(why)) != 0) {
        SVA_TEST_FAIL("seed %llu round %d %s", (unsigned long long)seed, round, why);
    }
    for (uint16_t u = 0U; u < plan.route_count; u++) {
        if (plan.routes[u].target_count > 2U) {
            SVA_TEST_FAIL("seed %llu round %d %s: route of UAV %d has %u targets",
                          (unsigned long long)seed, round, sva_algorithm_name(algorithm),
                          (int)plan.routes[u].uav_id, (unsigned)plan.routes[u].target_count);
        }
    }
}

void test_bound_is_two(void)
{
    TEST_ASSERT_EQUAL_INT(2, SVA_MAX_ROUTE_TARGETS);
    TEST_ASSERT_EQUAL_INT(2, sva_limits().max_route_targets);
}

void test_one_uav_three_chained_targets(void)
{
    // One UAV could serve A, B and C in turn (flow's relaxation route has 3 targets);
    // with routes of at most 2 the best plan serves A and B (40 cells).
    sva_mission_init(&mission);
    mission.uav_count = 1;
    mission.uavs[0] = (sva_uav_t){1, 0, 0, 1000, 0};
    mission.target_count = 3;
    mission.targets[0] = (sva_target_t){1, 10, 0, 20, 25, 1};
    mission.targets[1] = (sva_target_t){2, 20, 0, 40, 45, 1};
    mission.targets[2] = (sva_target_t){3, 30, 0, 60, 65, 1};
    for (size_t a = 0; a < sizeof(algorithms) / sizeof(algorithms[0]); a++) {
        must_plan(algorithms[a], 0U, 0);
        TEST_ASSERT_EQUAL_INT(2, plan.covered);
        TEST_ASSERT_EQUAL_INT(40, plan.cost);
    }
    TEST_ASSERT_TRUE(plan.stats.optimal);  // flow, last: proven under the route bound
}

void test_random_missions_keep_routes_short(void)
{
    const uint64_t seed = test_seed(0x5407A11ULL);
    test_rng_t rng;
    test_rng_seed(&rng, seed);
    for (int round = 0; round < 40; round++) {
        // Few UAVs, many chaining windows: long routes are what the planners want.
        const test_gen_params_t p = {10, 2, 20, 5, 10, 200, 1, 150, 400, 1, 1, 0, 0};
        test_gen_mission(&rng, &p, &mission);
        for (size_t a = 0; a < sizeof(algorithms) / sizeof(algorithms[0]); a++) {
            must_plan(algorithms[a], seed, round);
        }
    }
}

// Every test starts from a freshly initialised planner.
void setUp(void)
{
    TEST_ASSERT_EQUAL_INT(SVA_OK, sva_planner_init(&planner));
}
