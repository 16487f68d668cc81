// Tests of flow's proof from the route master's prices (flow_enum.c; DESIGN.md section
// 8, "Route enumeration"), on tiny need-1 missions that brute force covers in full:
// - its arithmetic holds for any prices, so given prices (zero, and drawn at random)
//   and an incumbent cost 2 or 4 above the optimum, it must return a proof and leave an
//   incumbent of the optimum's cost, which the independent SPEC checker accepts;
// - given the optimum's own cost, it must prove it and offer no plan;
// - planned by flow (a budget that leaves the master room, and the default), every
//   "optimal" claim and bound holds against brute force.
// Seeds are printed and replayable (SVA_TEST_SEED=...).
#include <stdint.h>
#include <stdio.h>
#include "sva_unity.h"

#include "brute_force.h"
#include "flow/flow.h"
#include "flow_certificate.h"
#include "mission_gen.h"
#include "spec_checker.h"
#include "sva/sva.h"

static sva_planner_t planner;
static sva_mission_t mission;
static sva_plan_t plan;
static sva_mission_t free_fuel;

#if SVA_FLOW_ENUM_ROUTES > 0
// A tiny need-1 mission with fuel that often binds; half with UAVs away from the depot.
static void draw_mission(test_rng_t* rng, int round)
{
    const test_gen_params_t p = {test_rng_range(rng, 4, 6),
                                 test_rng_range(rng, 3, 4),
                                 20,
                                 2,
                                 6,
                                 80,
                                 1,
                                 test_rng_range(rng, 40, 70),
                                 70,
                                 test_rng_range(rng, 0, 2),
                                 1,
                                 round % 2,
                                 0};
    test_gen_mission(rng, &p, &mission);
}

// Runs the proof on the mission with these prices and an incumbent of this cost (none
// offered before); true when it proves, with the incumbent it leaves in plan (when any).
static bool prove(test_rng_t* rng, bool random_prices, int64_t cost, bool* offered)
{
    sva_flow_work_t* w = &planner.priv.flow;
    sva_state_reset(&planner.priv, &mission, &plan);
    TEST_ASSERT_EQUAL_INT(SVA_FLOW_COMPLETE,
                          sva_flow_build(&planner.priv, &mission, &plan, false, &plan.stats));
    for (uint16_t t = 0U; t < mission.target_count; t++) {
        w->lagrange.price[t] = random_prices
                                   ? (int64_t)test_rng_range(rng, -20 * SVA_FLOW_PRICE_SCALE,
                                                             40 * SVA_FLOW_PRICE_SCALE)
                                   : 0;
    }
    sva_flow_enum_prices(w, &mission, true);
    w->has_inc = false;
    w->work = 0U;
    const bool proved = sva_flow_enum_prove(&planner.priv, &mission, &plan, cost, UINT64_MAX / 4U);
    *offered = w->has_inc;
    if (*offered) {
        sva_flow_write_incumbent(&planner.priv, &mission, &plan);
        sva_plan_finish(&planner.priv, &mission, &plan);
    }
    return proved;
}
#endif

void test_enumeration_finds_the_optimum_below_an_incumbent(void)
{
#if SVA_FLOW_ENUM_ROUTES > 0
    const uint64_t seed = test_seed(0xE1A0ULL);
    test_rng_t rng;
    test_rng_seed(&rng, seed);
    const int rounds = 400;
    int tried = 0;
    int fuel_binds = 0;
    char msg[256];
    for (int round = 0; round < rounds; round++) {
        draw_mission(&rng, round);
        const brute_result_t best = brute_force_optimum(&mission);
        if (best.covered != (int)mission.target_count) {
            continue;  // the proof is for plans covering every target
        }
        tried++;
        for (int k = 0; k < 4; k++) {
            bool offered = false;
            const int64_t above = (k < 2) ? 2 : 4;
            if (!prove(&rng, (k % 2) == 1, best.cost + above, &offered)) {
                SVA_TEST_FAIL("seed %llu round %d try %d: no proof below an incumbent of %lld",
                              (unsigned long long)seed, round, k, best.cost + above);
            }
            if (!offered || (plan.cost != best.cost) ||
                (plan.covered != (uint16_t)mission.target_count)) {
                SVA_TEST_FAIL("seed %llu round %d try %d: offered %d, cost %lld covering %u, the "
                              "optimum %lld covering %d",
                              (unsigned long long)seed, round, k, offered ? 1 : 0,
                              (long long)plan.cost, (unsigned)plan.covered, best.cost,
                              best.covered);
            }
            if (spec_check_plan(&mission, &plan, msg, sizeof msg) != 0) {
                SVA_TEST_FAIL("seed %llu round %d try %d: %s", (unsigned long long)seed, round, k,
                              msg);
            }
        }
        // Fuel binds when the optimum with unbounded fuel costs less.
        free_fuel = mission;
        for (uint16_t u = 0U; u < free_fuel.uav_count; u++) {
            free_fuel.uavs[u].fuel = SVA_MAX_FUEL;
        }
        fuel_binds += (brute_force_optimum(&free_fuel).cost < best.cost) ? 1 : 0;
    }
    printf("# %d missions covered in full, fuel binding on %d\n", tried, fuel_binds);
    TEST_ASSERT_TRUE(tried >= rounds / 4);
    TEST_ASSERT_TRUE(fuel_binds > 0);
#else
    TEST_IGNORE_MESSAGE("the profile keeps no routes (SVA_FLOW_ENUM_ROUTES 0)");
#endif
}

void test_enumeration_proves_the_optimum_and_offers_nothing(void)
{
#if SVA_FLOW_ENUM_ROUTES > 0
    const uint64_t seed = test_seed(0xE1A1ULL);
    test_rng_t rng;
    test_rng_seed(&rng, seed);
    const int rounds = 300;
    int tried = 0;
    for (int round = 0; round < rounds; round++) {
        draw_mission(&rng, round);
        const brute_result_t best = brute_force_optimum(&mission);
        if (best.covered != (int)mission.target_count) {
            continue;
        }
        tried++;
        for (int k = 0; k < 2; k++) {
            bool offered = true;
            if (!prove(&rng, k == 1, best.cost, &offered) || offered) {
                SVA_TEST_FAIL("seed %llu round %d try %d: at the optimum %lld: offered %d",
                              (unsigned long long)seed, round, k, best.cost, offered ? 1 : 0);
            }
        }
    }
    printf("# %d missions covered in full\n", tried);
    TEST_ASSERT_TRUE(tried >= rounds / 4);
#else
    TEST_IGNORE_MESSAGE("the profile keeps no routes (SVA_FLOW_ENUM_ROUTES 0)");
#endif
}

// flow itself, at a budget that leaves the master room and at the default: against
// brute force, every bound at most the optimum and every "optimal" claim true.
void test_flow_claims_hold_with_the_enumeration(void)
{
    const uint64_t seed = test_seed(0xE1A2ULL);
    test_rng_t rng;
    test_rng_seed(&rng, seed);
    const int rounds = 300;
    int proven = 0;
    for (int round = 0; round < rounds; round++) {
        const test_gen_params_t p = {test_rng_range(&rng, 4, 6),
                                     test_rng_range(&rng, 2, 4),
                                     20,
                                     4,
                                     15,
                                     60,
                                     1,
                                     test_rng_range(&rng, 30, 60),
                                     70,
                                     2,
                                     1,
                                     round % 2,
                                     0};
        test_gen_mission(&rng, &p, &mission);
        const brute_result_t best = brute_force_optimum(&mission);
        for (int budget = 0; budget < 2; budget++) {
            if (budget == 0) {
                planner.flow_max_work = 6000U;
            } else {
                TEST_ASSERT_EQUAL_INT(SVA_OK, sva_planner_init(&planner));
            }
            must_plan_checked(&planner, &mission, SVA_ALGO_FLOW, &plan, seed, round);
            check_against_optimum(&plan, &best, seed, round);
            proven += plan.stats.optimal ? 1 : 0;
        }
    }
    printf("# %d plans, %d proven optimal\n", 2 * rounds, proven);
    TEST_ASSERT_TRUE(proven > rounds);
}
