// The large profile (core/profiles/sva_profile_large.h), built by tests/core/CMakeLists.txt:
// - flow's arc bound holds the complete graph of a need-1 mission at the profile's
//   bounds (compile time);
// - the three caller-owned structs stay within the budgets CMake passes
//   (SVA_TEST_*_BUDGET, bytes on the host; docs/embedded.md states them);
// - flow plans missions of 1,000 targets x 100 UAVs with need 1 (the generator's fuel
//   and a tight fuel) with its relaxation: the graph within the arc bound, a lower
//   bound at or below the cost, a plan the independent SPEC checker accepts and that
//   covers no fewer targets than sva's.
#include <stdint.h>
#include <stdio.h>
#include "sva_unity.h"

#include "checked_plan.h"
#include "mission_gen.h"
#include "sva/sva.h"

#if !defined(SVA_TEST_PLANNER_BUDGET) || !defined(SVA_TEST_PLAN_BUDGET) || \
    !defined(SVA_TEST_MISSION_BUDGET)
#    error "tests/core/CMakeLists.txt passes the large profile's memory budgets"
#endif

// UAV -> copy, copy -> later copy, UAV -> depot and copy -> depot, one copy per target.
#define COMPLETE_NEED1_ARCS                  \
    ((1L * SVA_MAX_UAVS * SVA_MAX_TARGETS) + \
     ((1L * SVA_MAX_TARGETS * (SVA_MAX_TARGETS - 1L)) / 2L) + SVA_MAX_UAVS + SVA_MAX_TARGETS)
#if SVA_FLOW_MAX_ARCS < COMPLETE_NEED1_ARCS
#    error "the large profile's SVA_FLOW_MAX_ARCS must hold a complete need-1 graph"
#endif
#if (SVA_MAX_UAVS < 100) || (SVA_MAX_TARGETS < 1000)
#    error "the large profile is for 100 UAVs over 1,000 targets"
#endif

static sva_planner_t planner;
static sva_mission_t mission;
static sva_plan_t plan;
static sva_plan_t baseline;

void test_structs_within_budget(void)
{
    const sva_limits_t l = sva_limits();
    printf("# large profile sizes: planner %lu B (budget %lu), plan %lu B (budget %lu), "
           "mission %lu B (budget %lu), live %lu B\n",
           (unsigned long)l.planner_bytes, (unsigned long)SVA_TEST_PLANNER_BUDGET,
           (unsigned long)l.plan_bytes, (unsigned long)SVA_TEST_PLAN_BUDGET,
           (unsigned long)l.mission_bytes, (unsigned long)SVA_TEST_MISSION_BUDGET,
           (unsigned long)l.live_bytes);
    TEST_ASSERT_EQUAL_INT(sizeof(sva_planner_t), l.planner_bytes);
    TEST_ASSERT_TRUE(sizeof(sva_planner_t) <= (size_t)SVA_TEST_PLANNER_BUDGET);
    TEST_ASSERT_TRUE(sizeof(sva_plan_t) <= (size_t)SVA_TEST_PLAN_BUDGET);
    TEST_ASSERT_TRUE(sizeof(sva_mission_t) <= (size_t)SVA_TEST_MISSION_BUDGET);
}

// 1,000 targets x 100 UAVs, need 1, on a 20 x 20 grid, windows of 20 to 40 ticks over
// 30,000 ticks (as `sva-tools gen --targets 1000 --uavs 100 --need 1`), at `fuel`.
static void plan_1000x100(uint64_t seed_default, int fuel)
{
    const uint64_t seed = test_seed(seed_default);
    test_rng_t rng;
    test_rng_seed(&rng, seed);
    const test_gen_params_t p = {1000, 100, 20, 20, 40, 30000, 1, fuel, fuel, 0, 1, 0, 40};
    test_gen_mission(&rng, &p, &mission);
    char why[320] = "";
    if (checked_plan(&planner, &mission, SVA_ALGO_SVA, &baseline, why, sizeof(why)) != 0) {
        SVA_TEST_FAIL("seed %llu: %s", (unsigned long long)seed, why);
    }
    if (checked_plan(&planner, &mission, SVA_ALGO_FLOW, &plan, why, sizeof(why)) != 0) {
        SVA_TEST_FAIL("seed %llu: %s", (unsigned long long)seed, why);
    }
    const sva_stats_t* s = &plan.stats;
    printf("# 1000x100 fuel %d: covered %d (sva %d), cost %lld, lower bound %lld, graph %lu arcs, "
           "work %llu, flow_incomplete %d\n",
           fuel, (int)plan.covered, (int)baseline.covered, (long long)plan.cost,
           (long long)s->lower_bound, (unsigned long)s->flow_graph_arcs,
           (unsigned long long)s->flow_work, (int)s->flow_incomplete);
    TEST_ASSERT_TRUE(s->flow_graph_arcs > 0U);
    TEST_ASSERT_TRUE(s->flow_graph_arcs <= (uint32_t)SVA_FLOW_MAX_ARCS);
    TEST_ASSERT_NOT_EQUAL_INT(SVA_FLOW_OVER_ARCS, s->flow_incomplete);
    TEST_ASSERT_NOT_EQUAL_INT(SVA_FLOW_OVER_COPIES, s->flow_incomplete);
    TEST_ASSERT_TRUE(plan.covered >= baseline.covered);
    TEST_ASSERT_TRUE(s->has_bound);
    TEST_ASSERT_TRUE(s->lower_bound > 0);
    TEST_ASSERT_TRUE(s->lower_bound <= plan.cost);
}

void test_flow_plans_1000x100_with_its_bound(void)
{
    plan_1000x100(0x1A46E1ULL, 150);
}

void test_flow_plans_1000x100_tight_fuel_with_its_bound(void)
{
    plan_1000x100(0x1A46E2ULL, 80);
}

void setUp(void)
{
    TEST_ASSERT_EQUAL_INT(SVA_OK, sva_planner_init(&planner));
}
