// Edge cases of the flow planner (core/src/flow/) that the random tests do not
// reach, each on a hand-built mission whose answer is known:
// - a route over its fuel is branched on while an earlier UAV is stranded (the
//   stranded UAV is skipped; the plan equals bfa's optimum, proven);
// - needs whose least common multiple does not fit the exact rewards: flow says so
//   (SVA_FLOW_INCOMPLETE_REWARD, not optimal) and its plan is still checked and no worse than
//   sva's; the same mission with need 1 everywhere is exact;
// - needs summed past SVA_FLOW_MAX_COPIES: the fallback (SVA_FLOW_OVER_COPIES, bound 0).
// Every plan passes the independent SPEC checker (tests/support/spec_checker.c).
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>
#include "sva_unity.h"

#include "checked_plan.h"
#include "spec_checker.h"
#include "sva/sva.h"

static sva_planner_t planner;
static sva_mission_t mission;
static sva_plan_t plan;
static sva_plan_t other;

static void must_plan(sva_algorithm_t algorithm, sva_plan_t* out)
{
    char why[320] = "";
    if (checked_plan(&planner, &mission, algorithm, out, why, sizeof(why)) != 0) {
        SVA_TEST_FAIL("%s", why);
    }
}

void test_route_branch_skips_a_stranded_uav(void)
{
    // UAV 1 cannot get home (100 cells, fuel 10): stranded, listed first. UAV 2 could
    // chain A -> B -> C in time, but that route needs 60 cells + 3 x 10 hover = 90 >
    // 80 fuel, so the root relaxation breaks the fuel rule and flow branches on the
    // route. Best plan: two targets; A and B cost the least (40 cells).
    sva_mission_init(&mission);
    mission.hover_fuel = 10;
    mission.uav_count = 2;
    mission.uavs[0] = (sva_uav_t){1, 50, 50, 10, 0};
    mission.uavs[1] = (sva_uav_t){2, 0, 0, 80, 0};
    mission.target_count = 3;
    mission.targets[0] = (sva_target_t){1, 10, 0, 20, 25, 1};
    mission.targets[1] = (sva_target_t){2, 20, 0, 40, 45, 1};
    mission.targets[2] = (sva_target_t){3, 30, 0, 60, 65, 1};
    must_plan(SVA_ALGO_FLOW, &plan);
    TEST_ASSERT_TRUE(plan.routes[0].stranded);
    TEST_ASSERT_EQUAL_INT(1, plan.stranded_count);
    TEST_ASSERT_EQUAL_INT(2, plan.covered);
    TEST_ASSERT_EQUAL_INT(40, plan.cost);
    TEST_ASSERT_TRUE(plan.stats.search_nodes > 1U);  // it branched
    TEST_ASSERT_TRUE(plan.stats.optimal);
    TEST_ASSERT_EQUAL_INT(40, plan.stats.lower_bound);
    must_plan(SVA_ALGO_BFA, &other);  // the exhaustive optimum agrees
    TEST_ASSERT_EQUAL_INT(plan.covered, other.covered);
    TEST_ASSERT_EQUAL_INT(plan.cost, other.cost);
}

// Seven targets with distinct prime needs (their lcm is about 5.8e11) at the far
// corner of the grid, which makes W large, in one shared window (no copy chains into
// another, so the graph stays small); plus one need-1 target near the depot that the
// two UAVs can serve. With need_one true every need is 1 instead.
static void build_prime_needs(bool need_one)
{
    static const int32_t primes[] = {37, 41, 43, 47, 53, 59, 61};
    sva_mission_init(&mission);
    mission.uav_count = 2;
    mission.uavs[0] = (sva_uav_t){1, 0, 0, 1000000, 0};
    mission.uavs[1] = (sva_uav_t){2, 0, 0, 1000000, 0};
    mission.target_count = 8;
    mission.targets[0] = (sva_target_t){1, 3, 4, 10, 20, 1};
    for (int32_t k = 0; k < 7; k++) {
        mission.targets[k + 1] =
            (sva_target_t){k + 2, 32767, 32767 - k, 100000, 100010, need_one ? 1 : primes[k]};
    }
}

void test_needs_past_exact_rewards_are_reported(void)
{
    if (SVA_MAX_UAVS < 61 || SVA_FLOW_MAX_COPIES < 342) {
        TEST_IGNORE();  // this profile cannot hold needs up to 61
    }
    build_prime_needs(false);
    must_plan(SVA_ALGO_FLOW, &plan);
    TEST_ASSERT_EQUAL_INT(SVA_FLOW_INCOMPLETE_REWARD,
                          plan.stats.flow_incomplete);  // needs' lcm too large
    TEST_ASSERT_FALSE(plan.stats.optimal);
    TEST_ASSERT_TRUE(plan.stats.has_bound);
    TEST_ASSERT_TRUE(plan.stats.lower_bound >= 0);
    TEST_ASSERT_TRUE(plan.stats.lower_bound <= plan.cost);
    TEST_ASSERT_EQUAL_INT(1, plan.covered);  // only the need-1 target is within two UAVs
    TEST_ASSERT_EQUAL_INT(14, plan.cost);    // depot -> (3, 4) -> depot: 7 + 7 cells
    must_plan(SVA_ALGO_SVA, &other);
    TEST_ASSERT_FALSE(spec_better(other.covered, other.cost, plan.covered, plan.cost));

    // The control: the same mission with need 1 everywhere has exact rewards.
    build_prime_needs(true);
    must_plan(SVA_ALGO_FLOW, &plan);
    TEST_ASSERT_NOT_EQUAL_INT(SVA_FLOW_INCOMPLETE_REWARD, plan.stats.flow_incomplete);
}

void test_needs_past_the_copy_bound_fall_back(void)
{
    // need = SVA_MAX_UAVS on every target, one target more than the copies allow.
    const int32_t need = SVA_MAX_UAVS;
    const int32_t targets = ((int32_t)SVA_FLOW_MAX_COPIES / need) + 1;
    if (targets > SVA_MAX_TARGETS) {
        TEST_IGNORE();  // this profile's copy bound holds every mission
    }
    sva_mission_init(&mission);
    mission.uav_count = (uint16_t)SVA_MAX_UAVS;
    for (int32_t u = 0; u < SVA_MAX_UAVS; u++) {
        mission.uavs[u] = (sva_uav_t){u + 1, 0, 0, 1000, 0};
    }
    mission.target_count = (uint16_t)targets;
    for (int32_t t = 0; t < targets; t++) {
        mission.targets[t] = (sva_target_t){t + 1, 2, 3, (100 * t) + 10, (100 * t) + 20, need};
    }
    must_plan(SVA_ALGO_FLOW, &plan);
    TEST_ASSERT_EQUAL_INT(SVA_FLOW_OVER_COPIES,
                          plan.stats.flow_incomplete);  // needs summed above the bound
    TEST_ASSERT_FALSE(plan.stats.optimal);
    TEST_ASSERT_EQUAL_INT(0, plan.stats.lower_bound);
    TEST_ASSERT_EQUAL_INT(0, plan.stats.flow_graph_arcs);  // no graph was built
    must_plan(SVA_ALGO_SVA, &other);
    TEST_ASSERT_FALSE(spec_better(other.covered, other.cost, plan.covered, plan.cost));
    must_plan(SVA_ALGO_GA, &other);
    TEST_ASSERT_FALSE(spec_better(other.covered, other.cost, plan.covered, plan.cost));
    TEST_ASSERT_EQUAL_INT(targets, plan.covered);  // every UAV serves every target in turn
}

// Every test starts from a freshly initialised planner.
void setUp(void)
{
    TEST_ASSERT_EQUAL_INT(SVA_OK, sva_planner_init(&planner));
}
