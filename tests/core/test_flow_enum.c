// Tests of flow's proof from the route master's prices (flow_enum.c; DESIGN.md section
// 8, "Route enumeration"), on tiny need-1 missions that brute force solves, some covered
// in full and some not (then at the optimum's coverage, which no plan exceeds):
// - its arithmetic holds for any prices, so given prices (zero, and drawn at random)
//   and an incumbent cost 2 or 4 above the optimum, it must return a proof and leave an
//   incumbent of the optimum's cost and coverage, which the independent SPEC checker
//   accepts;
// - given the optimum's own cost, it must prove it and offer no plan;
// - for coverage (cells free), at the optimum's coverage it must prove that no plan
//   covers more (with zero prices every route is listed, so it must), one below it never,
//   and with zero prices there it must offer a checked plan of the optimum's coverage.
// flow's own claims with the enumeration on (a budget that leaves the master room) are
// held to brute force by test_flow.c's test_bounds_take_the_plans_parity and to ref's
// optima by tests/tools/test_optima.py (fixtures/optima).
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

// The mission's graph built, the prices w->lagrange.price set (0, or drawn in
// [lo, hi]), no incumbent and no work yet.
static sva_flow_work_t* set_up(test_rng_t* rng, bool random_prices, int64_t lo, int64_t hi)
{
    sva_flow_work_t* w = &planner.priv.flow;
    sva_state_reset(&planner.priv, &mission, &plan);
    TEST_ASSERT_EQUAL_INT(SVA_FLOW_COMPLETE,
                          sva_flow_build(&planner.priv, &mission, &plan, false, &plan.stats));
    for (uint16_t t = 0U; t < mission.target_count; t++) {
        w->lagrange.price[t] = random_prices ? (int64_t)test_rng_range(rng, lo, hi) : 0;
    }
    w->has_inc = false;
    w->work = 0U;
    return w;
}

// Whether the enumeration offered a plan; if so, it is written to `plan`.
static bool take_offer(const sva_flow_work_t* w)
{
    if (w->has_inc) {
        sva_flow_write_incumbent(&planner.priv, &mission, &plan);
        sva_plan_finish(&planner.priv, &mission, &plan);
    }
    return w->has_inc;
}

// An offered plan must cover as many targets as the optimum (at its cost too, when
// `with_cost`) and pass the independent SPEC checker.
static void check_offer(uint64_t seed, int round, int k, const brute_result_t* best, bool with_cost)
{
    char msg[256];
    if ((plan.covered != (uint16_t)best->covered) || (with_cost && (plan.cost != best->cost))) {
        SVA_TEST_FAIL("seed %llu round %d try %d: cost %lld covering %u, the optimum %lld "
                      "covering %d",
                      (unsigned long long)seed, round, k, (long long)plan.cost,
                      (unsigned)plan.covered, best->cost, best->covered);
    }
    if (spec_check_plan(&mission, &plan, msg, sizeof msg) != 0) {
        SVA_TEST_FAIL("seed %llu round %d try %d: %s", (unsigned long long)seed, round, k, msg);
    }
}

// Runs the proof on the mission with these prices and an incumbent of this cost and
// coverage (none offered before); true when it proves, with the incumbent it leaves in
// plan (when any).
static bool prove(test_rng_t* rng, bool random_prices, int64_t cost, int64_t covered, bool* offered)
{
    sva_flow_work_t* w =
        set_up(rng, random_prices, -20 * SVA_FLOW_PRICE_SCALE, 40 * SVA_FLOW_PRICE_SCALE);
    sva_flow_enum_prices(w, &mission, true);
    const bool proved =
        sva_flow_enum_prove(&planner.priv, &mission, &plan, cost, covered, UINT64_MAX / 4U);
    *offered = take_offer(w);
    return proved;
}

// Runs the coverage question on the mission with these prices (the coverage master's
// scale: a target worth SVA_FLOW_PRICE_SCALE) and an incumbent covering `covered`;
// true when it proves no plan covers more, with the plan it offers (when any) in plan.
static bool prove_coverage(test_rng_t* rng, bool random_prices, int64_t covered, bool* offered)
{
    sva_flow_work_t* w = set_up(rng, random_prices, 0, 2 * SVA_FLOW_PRICE_SCALE);
    bool more = false;
    const bool proved =
        sva_flow_enum_cover(&planner.priv, &mission, &plan, covered, UINT64_MAX / 4U, &more);
    *offered = take_offer(w);
    TEST_ASSERT_TRUE(more == *offered);
    return proved;
}
#endif

// Below an incumbent 2 or 4 above the optimum it must prove and leave an incumbent of
// the optimum's cost; at the optimum itself it must prove and offer nothing. Each with
// zero and with random prices.
void test_enumeration_finds_or_proves_the_optimum(void)
{
#if SVA_FLOW_ENUM_ROUTES > 0
    const uint64_t seed = test_seed(0xE1A0ULL);
    test_rng_t rng;
    test_rng_seed(&rng, seed);
    const int rounds = 400;
    int tried = 0;
    int partial = 0;
    int fuel_binds = 0;
    for (int round = 0; round < rounds; round++) {
        draw_mission(&rng, round);
        const brute_result_t best = brute_force_optimum(&mission);
        tried++;
        partial += (best.covered < (int)mission.target_count) ? 1 : 0;
        for (int k = 0; k < 6; k++) {
            const int64_t above = (k < 2) ? 0 : ((k < 4) ? 2 : 4);
            bool offered = false;
            const bool proved =
                prove(&rng, (k % 2) == 1, best.cost + above, best.covered, &offered);
            if (!proved || (offered != (above > 0))) {
                SVA_TEST_FAIL("seed %llu round %d try %d: incumbent %lld, the optimum %lld: "
                              "proved %d, offered %d",
                              (unsigned long long)seed, round, k, best.cost + above, best.cost,
                              proved ? 1 : 0, offered ? 1 : 0);
            }
            if (offered) {
                check_offer(seed, round, k, &best, true);
            }
        }
        // Fuel binds when the optimum with unbounded fuel covers more or costs less.
        free_fuel = mission;
        for (uint16_t u = 0U; u < free_fuel.uav_count; u++) {
            free_fuel.uavs[u].fuel = SVA_MAX_FUEL;
        }
        const brute_result_t unbound = brute_force_optimum(&free_fuel);
        fuel_binds += ((unbound.covered > best.covered) || (unbound.cost < best.cost)) ? 1 : 0;
    }
    printf("# %d missions, %d not covered in full, fuel binding on %d\n", tried, partial,
           fuel_binds);
    TEST_ASSERT_TRUE(partial >= rounds / 10);
    TEST_ASSERT_TRUE((tried - partial) >= rounds / 4);
    TEST_ASSERT_TRUE(fuel_binds > 0);
#else
    TEST_IGNORE_MESSAGE("the profile keeps no routes (SVA_FLOW_ENUM_ROUTES 0)");
#endif
}

// Coverage: at the optimum's coverage it must prove that no plan covers more and offer
// nothing; one target below it, it must not, and with zero prices (every route listed)
// it must offer a checked plan of the optimum's coverage. Random prices may make it
// claim nothing, never a wrong claim; a plan it offers is checked.
void test_enumeration_proves_the_coverage_or_covers_more(void)
{
#if SVA_FLOW_ENUM_ROUTES > 0
    const uint64_t seed = test_seed(0xE1A1ULL);
    test_rng_t rng;
    test_rng_seed(&rng, seed);
    const int rounds = 300;
    int proofs = 0;
    int found = 0;
    for (int round = 0; round < rounds; round++) {
        draw_mission(&rng, round);
        const brute_result_t best = brute_force_optimum(&mission);
        for (int k = 0; k < 4; k++) {
            const bool random_prices = (k % 2) == 1;
            const int64_t covered = best.covered - ((k < 2) ? 0 : 1);
            if ((covered < 0) || (covered >= (int64_t)mission.target_count)) {
                continue;  // nothing to ask: every target covered, or none below
            }
            bool offered = false;
            const bool proved = prove_coverage(&rng, random_prices, covered, &offered);
            const bool at_optimum = covered == best.covered;
            // With zero prices every route is listed, so the answer is exact.
            const bool wrong = at_optimum ? (!proved && !random_prices) : proved;
            if (wrong) {
                SVA_TEST_FAIL("seed %llu round %d try %d: coverage %lld, the optimum's %d: "
                              "proved %d",
                              (unsigned long long)seed, round, k, (long long)covered, best.covered,
                              proved ? 1 : 0);
            }
            if (at_optimum && offered) {
                SVA_TEST_FAIL("seed %llu round %d try %d: a plan offered at the optimum's "
                              "coverage %d",
                              (unsigned long long)seed, round, k, best.covered);
            }
            if (!at_optimum && !random_prices && !offered) {
                SVA_TEST_FAIL("seed %llu round %d try %d: no plan covering %d offered",
                              (unsigned long long)seed, round, k, best.covered);
            }
            proofs += proved ? 1 : 0;
            if (offered) {
                found++;
                check_offer(seed, round, k, &best, false);
            }
        }
    }
    printf("# coverage proved %d times, a plan covering more offered %d times\n", proofs, found);
    TEST_ASSERT_TRUE(proofs >= rounds / 4);
    TEST_ASSERT_TRUE(found >= rounds / 4);
#else
    TEST_IGNORE_MESSAGE("the profile keeps no routes (SVA_FLOW_ENUM_ROUTES 0)");
#endif
}
