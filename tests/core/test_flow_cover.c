// flow's coverage search (core/src/flow/flow_cover.c), judged by brute force on small
// missions (UAVs scattered with ready times, as in a replan; needs 1 to 3; fuel often
// binding):
// - asked for one target more than the most brute force covers, it never finds a plan,
//   and with room to finish it proves that none exists;
// - asked for one target more than the most less one, it finds a plan covering the
//   most, whose routes pass the SPEC checker;
// - within a small budget it may give up (open), but never answers wrongly;
// - past its bounds (more targets than SVA_FLOW_COVER_TARGETS) it gives up at once;
// - flow with it: every plan checked, every "optimal" claim true, and the most
//   coverage on every mission where the search ran.
// Seeds are printed and replayable (SVA_TEST_SEED=...).
#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include "sva_unity.h"

#include "brute_force.h"
#include "flow_certificate.h"
#include "mission_gen.h"
#include "spec_checker.h"
#include "flow/flow.h"

static sva_planner_t planner;
static sva_mission_t mission;
static sva_plan_t plan;

#define ROUNDS 300

// Up to 6 targets and 4 UAVs (brute force's reach), needs up to 3, scattered UAVs.
static void next_mission(test_rng_t* rng)
{
    const test_gen_params_t p = {test_rng_range(rng, 3, 6),
                                 test_rng_range(rng, 2, 4),
                                 20,
                                 4,
                                 15,
                                 60,
                                 test_rng_range(rng, 1, 3),
                                 test_rng_range(rng, 25, 60),
                                 70,
                                 test_rng_range(rng, 0, 2),
                                 1,
                                 1,
                                 10};
    test_gen_mission(rng, &p, &mission);
}

// The search's answer for one target more than `covered`, from a reset state.
static sva_flow_cover_result_t cover(int64_t covered, uint64_t budget, uint16_t* nodes)
{
    sva_state_reset(&planner.priv, &mission, &plan);
    planner.priv.flow.work = 0U;
    return sva_flow_cover(&planner.priv, &mission, &plan, covered, budget, nodes);
}

void test_search_is_exact_against_brute_force(void)
{
    const uint64_t seed = test_seed(0xC0FE4ULL);
    test_rng_t rng;
    test_rng_seed(&rng, seed);
    int found = 0;
    int proven = 0;
    for (int round = 0; round < ROUNDS; round++) {
        next_mission(&rng);
        const brute_result_t best = brute_force_optimum(&mission);
        uint16_t nodes = 0U;
        // One more than the most: no plan, and proven with room to finish.
        const sva_flow_cover_result_t none = cover(best.covered, UINT64_MAX / 2U, &nodes);
        if (none != SVA_FLOW_COVER_PROVEN) {
            SVA_TEST_FAIL("seed %llu round %d: %d targets the most, the search answered %d",
                          (unsigned long long)seed, round, best.covered, (int)none);
        }
        proven++;
        if (best.covered == 0) {
            continue;
        }
        // The most less one: a plan covering the most, within the SPEC's rules.
        const sva_flow_cover_result_t more = cover(best.covered - 1, UINT64_MAX / 2U, &nodes);
        TEST_ASSERT_EQUAL_INT(SVA_FLOW_COVER_FOUND, more);
        sva_plan_finish(&planner.priv, &mission, &plan);
        char msg[256];
        if (spec_check_plan(&mission, &plan, msg, sizeof msg) != 0) {
            SVA_TEST_FAIL("seed %llu round %d: the search's plan breaks the SPEC: %s",
                          (unsigned long long)seed, round, msg);
        }
        if (plan.covered != best.covered) {
            SVA_TEST_FAIL("seed %llu round %d: the search's plan covers %d, the most is %d",
                          (unsigned long long)seed, round, (int)plan.covered, best.covered);
        }
        found++;
    }
    printf("# %d missions: %d proven the most, %d plans covering the most found\n", ROUNDS, proven,
           found);
    TEST_ASSERT_TRUE(found > ROUNDS / 2);
}

void test_small_budget_is_never_wrong(void)
{
    const uint64_t seed = test_seed(0xB0D6E7ULL);
    test_rng_t rng;
    test_rng_seed(&rng, seed);
    int open = 0;
    for (int round = 0; round < ROUNDS; round++) {
        next_mission(&rng);
        const brute_result_t best = brute_force_optimum(&mission);
        for (int64_t asked = 0; asked <= (int64_t)best.covered; asked++) {
            uint16_t nodes = 0U;
            const sva_flow_cover_result_t r = cover(asked, 40U, &nodes);
            if (r == SVA_FLOW_COVER_OPEN) {
                open++;
            }
            // FOUND only below the most, PROVEN only at it.
            if (((r == SVA_FLOW_COVER_FOUND) && (asked >= best.covered)) ||
                ((r == SVA_FLOW_COVER_PROVEN) && (asked < best.covered))) {
                SVA_TEST_FAIL(
                    "seed %llu round %d: asked for more than %lld (the most %d): answer %d",
                    (unsigned long long)seed, round, (long long)asked, best.covered, (int)r);
            }
        }
    }
    printf("# %d missions at a budget of 40 units: %d answers open\n", ROUNDS, open);
    TEST_ASSERT_TRUE(open > 0);
}

void test_past_its_bounds_it_gives_up(void)
{
    test_rng_t rng;
    test_rng_seed(&rng, 7U);
    const test_gen_params_t p = {
        SVA_FLOW_COVER_TARGETS + 1, 2, 20, 4, 15, 200, 1, 60, 90, 0, 1, 0, 0};
    if (SVA_FLOW_COVER_TARGETS + 1 > SVA_MAX_TARGETS) {
        TEST_IGNORE();  // the profile cannot hold such a mission
    }
    test_gen_mission(&rng, &p, &mission);
    uint16_t nodes = 0U;
    TEST_ASSERT_EQUAL_INT(SVA_FLOW_COVER_OPEN, cover(0, UINT64_MAX / 2U, &nodes));
    TEST_ASSERT_EQUAL_INT(0U, nodes);
    TEST_ASSERT_EQUAL_INT(0U, planner.priv.flow.work);
}

void test_flow_covers_the_most_where_the_search_ran(void)
{
    const uint64_t seed = test_seed(0xF10C0ULL);
    test_rng_t rng;
    test_rng_seed(&rng, seed);
    planner.flow_max_work = 20000U;
    int ran = 0;
    for (int round = 0; round < ROUNDS; round++) {
        next_mission(&rng);
        const brute_result_t best = brute_force_optimum(&mission);
        must_plan_checked(&planner, &mission, SVA_ALGO_FLOW, &plan, seed, round);
        check_against_optimum(&plan, &best, seed, round);
        if (plan.stats.flow_cover_nodes > 0U) {
            ran++;
            if ((int)plan.covered != best.covered) {
                SVA_TEST_FAIL("seed %llu round %d: the search ran, flow covers %d, the most is %d",
                              (unsigned long long)seed, round, (int)plan.covered, best.covered);
            }
        }
    }
    TEST_ASSERT_EQUAL_INT(SVA_OK, sva_planner_init(&planner));
    printf("# %d missions: the coverage search ran in flow on %d\n", ROUNDS, ran);
    TEST_ASSERT_TRUE(ran > 0);
}

// The planner starts in its initial state for every test.
void setUp(void)
{
    TEST_ASSERT_EQUAL_INT(SVA_OK, sva_planner_init(&planner));
}
