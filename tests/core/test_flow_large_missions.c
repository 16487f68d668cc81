// Tests of flow on large missions (more than SVA_FLOW_LARGE_FROM targets; DESIGN.md
// section 8): 100 targets x 20 UAVs where fuel binds.
// - every plan passes the SPEC checker and its bound holds;
// - the work budget grows with the targets: the work spent passes flow_max_work and
//   stays within flow_max_work x targets / SVA_FLOW_LARGE_FROM and one round more;
// - ruin and recreate runs, and flow covers as many targets as sva and ga and costs no
//   more than the better of them at equal coverage (their plans seed it);
// - the same mission gives the same plan after another was planned: the index of the
//   granular moves carries nothing over.
// Seeds are printed and replayable (SVA_TEST_SEED=...).
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>
#include "sva_unity.h"

#include "flow_certificate.h"
#include "mission_gen.h"
#include "sva/sva.h"

#define LARGE_TARGETS 100
#define LARGE_UAVS    20
#define MISSIONS      4
// What a run may spend past its budget: the step under way when it is reached (a
// ruin round and its local search, a flow solve).
#define OVERSHOOT_NUM 3U
#define OVERSHOOT_DEN 10U

static sva_planner_t planner;
static sva_mission_t mission;
static sva_mission_t second;
static sva_plan_t plan;
static sva_plan_t other;
static sva_plan_t again;

static test_gen_params_t params(int targets)
{
    const test_gen_params_t p = {targets, LARGE_UAVS, 40, 20, 40, 300, 1, 80, 80, 0, 1, 0, 0};
    return p;
}

static bool fits_the_profile(void)
{
    return (SVA_MAX_TARGETS >= LARGE_TARGETS) && (SVA_MAX_UAVS >= LARGE_UAVS) &&
           (SVA_FLOW_MAX_ARCS >= 8000L);
}

void test_large_missions_plan_checked_within_their_grown_budget(void)
{
    if (!fits_the_profile()) {
        TEST_IGNORE_MESSAGE("the profile holds no 100 x 20 mission with flow's graph");
    }
    const uint64_t seed = test_seed(0x1A26EULL);
    test_rng_t rng;
    test_rng_seed(&rng, seed);
    uint64_t past_base = 0U;
    for (int round = 0; round < MISSIONS; round++) {
        const test_gen_params_t p = params(LARGE_TARGETS);
        test_gen_mission(&rng, &p, &mission);
        TEST_ASSERT_EQUAL_INT(SVA_OK, sva_planner_init(&planner));
        must_plan_checked(&planner, &mission, SVA_ALGO_FLOW, &plan, seed, round);
        check_certificate(&plan, seed, round);
        const uint64_t base = planner.flow_max_work;
        const uint64_t grown = (base * LARGE_TARGETS) / (uint64_t)SVA_FLOW_LARGE_FROM;
        printf("# round %d: covered %d cost %lld bound %lld work %llu (budget %llu) ruin %u\n",
               round, plan.covered, (long long)plan.cost, (long long)plan.stats.lower_bound,
               (unsigned long long)plan.stats.flow_work, (unsigned long long)grown,
               (unsigned)plan.stats.flow_ruin_rounds);
        TEST_ASSERT_TRUE(plan.stats.flow_work <= grown + (grown * OVERSHOOT_NUM) / OVERSHOOT_DEN);
        past_base += (plan.stats.flow_work > base) ? 1U : 0U;
        TEST_ASSERT_TRUE(plan.stats.optimal || (plan.stats.flow_ruin_rounds > 0U));
        const sva_algorithm_t seeds[] = {SVA_ALGO_SVA, SVA_ALGO_GA};
        for (size_t i = 0U; i < (sizeof(seeds) / sizeof(seeds[0])); i++) {
            must_plan_checked(&planner, &mission, seeds[i], &other, seed, round);
            TEST_ASSERT_TRUE(plan.covered >= other.covered);
            TEST_ASSERT_TRUE((plan.covered > other.covered) || (plan.cost <= other.cost));
        }
    }
    // Fuel binds here: a 100-target mission is not solved within the small budget.
    TEST_ASSERT_TRUE(past_base > 0U);
}

void test_large_plans_do_not_depend_on_the_planners_history(void)
{
    if (!fits_the_profile()) {
        TEST_IGNORE_MESSAGE("the profile holds no 100 x 20 mission with flow's graph");
    }
    const uint64_t seed = test_seed(0x1A26FULL);
    test_rng_t rng;
    test_rng_seed(&rng, seed);
    const test_gen_params_t p = params(LARGE_TARGETS);
    test_gen_mission(&rng, &p, &mission);
    test_gen_mission(&rng, &p, &second);
    TEST_ASSERT_EQUAL_INT(SVA_OK, sva_planner_init(&planner));
    must_plan_checked(&planner, &mission, SVA_ALGO_FLOW, &plan, seed, 0);
    const sva_mission_t kept = mission;
    mission = second;
    must_plan_checked(&planner, &mission, SVA_ALGO_FLOW, &other, seed, 1);
    mission = kept;
    must_plan_checked(&planner, &mission, SVA_ALGO_FLOW, &again, seed, 2);
    check_same_plan(&again, &plan);
}

// Every test starts from a freshly initialised planner.
void setUp(void)
{
    TEST_ASSERT_EQUAL_INT(SVA_OK, sva_planner_init(&planner));
}
