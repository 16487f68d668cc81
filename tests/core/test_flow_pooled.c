// flow's pooled graph (core/src/flow/flow_graph.c): one node per target carrying its need,
// which gives flow its bound when the graph of copies is past SVA_FLOW_MAX_ARCS. Built
// against a core whose arc bound is SVA_FLOW_MAX_ARCS 48, so that small missions with
// need 2 go past it and brute force can judge the bound:
// - where both graphs fit, the pooled relaxation's value equals the copies' (the same
//   min-cost flow: copies of a target are interchangeable);
// - past the arc bound: a bound from the pooled graph that never exceeds the optimum,
//   "optimal" only when it is, every plan checked and never behind sva's or ga's (the
//   pooled flow's routes are the first plan, then those seeds unless it is proven);
//   with need 1 everywhere the pooled graph is the copies' and there is no bound (0);
// - under the arc bound, with a need above 1: when the pooled flow's routes are a plan,
//   flow takes them as the optimum with no search (search_nodes 0), and brute force
//   agrees.
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
static sva_plan_t other;

// Small missions with needs 1 and 2, fuel often binding; `spread` widens the horizon
// and shrinks the grid, so more windows chain (more arcs).
static void next_mission(test_rng_t* rng, int targets_min, int targets_max, bool spread)
{
    const test_gen_params_t p = {test_rng_range(rng, targets_min, targets_max),
                                 test_rng_range(rng, 2, 3),
                                 spread ? 10 : 20,
                                 4,
                                 15,
                                 spread ? 120 : 60,
                                 2,
                                 test_rng_range(rng, 30, spread ? 90 : 60),
                                 spread ? 120 : 70,
                                 2,
                                 1,
                                 test_rng_range(rng, 0, 1),
                                 0};
    test_gen_mission(rng, &p, &mission);
}

void test_pooled_relaxation_equals_the_copies(void)
{
    const uint64_t seed = test_seed(0x9001EDULL);
    test_rng_t rng;
    test_rng_seed(&rng, seed);
    sva_planner_priv_t* priv = &planner.priv;
    int compared = 0;
    for (int round = 0; round < 400; round++) {
        next_mission(&rng, 3, 4, false);
        sva_state_reset(priv, &mission, &plan);
        if (sva_flow_build(priv, &mission, &plan, false, &plan.stats) != 0U) {
            continue;  // the copies do not fit this core
        }
        const uint32_t copy_arcs = plan.stats.flow_graph_arcs;
        TEST_ASSERT_TRUE(sva_flow_solve(&priv->flow, &plan.stats));
        const int64_t copies_value = priv->flow.value;
        TEST_ASSERT_EQUAL_INT(0, sva_flow_build(priv, &mission, &plan, true, &plan.stats));
        TEST_ASSERT_TRUE(plan.stats.flow_graph_arcs <= copy_arcs);
        TEST_ASSERT_TRUE(sva_flow_solve(&priv->flow, &plan.stats));
        if (priv->flow.value != copies_value) {
            SVA_TEST_FAIL("seed %llu round %d: pooled value %lld, copies %lld",
                          (unsigned long long)seed, round, (long long)priv->flow.value,
                          (long long)copies_value);
        }
        compared++;
    }
    printf("# pooled and copies' relaxations compared on %d of 400 missions\n", compared);
    TEST_ASSERT_TRUE(compared >= 100);
}

void test_pooled_bounds_and_plans_against_brute_force(void)
{
    const uint64_t seed = test_seed(0x9002EDULL);
    test_rng_t rng;
    test_rng_seed(&rng, seed);
    int past = 0;
    int full = 0;     // of those, covering every target
    int bounded = 0;  // of those, with a bound above 0
    int proven = 0;   // of those, proven optimal
    int taken = 0;    // under the bound: the pooled root taken as the plan
    for (int round = 0; round < 400; round++) {
        next_mission(&rng, 5, 6, true);
        const brute_result_t best = brute_force_optimum(&mission);
        must_plan_checked(&planner, &mission, SVA_ALGO_FLOW, &plan, seed, round);
        check_against_optimum(&plan, &best, seed, round);
        if ((plan.stats.flow_graph_arcs <= (uint32_t)SVA_FLOW_MAX_ARCS) &&
            (plan.stats.search_nodes == 0U)) {
            TEST_ASSERT_TRUE(plan.stats.optimal);  // and check_against_optimum held it to that
            taken++;
        }
        if (plan.stats.flow_graph_arcs > (uint32_t)SVA_FLOW_MAX_ARCS) {
            TEST_ASSERT_EQUAL_INT(plan.stats.optimal ? SVA_FLOW_COMPLETE : SVA_FLOW_OVER_ARCS,
                                  plan.stats.flow_incomplete);
            // The pooled routes come first; ga and sva seed it unless they are proven.
            for (int a = 0; a < 2; a++) {
                const sva_algorithm_t rival = (a == 0) ? SVA_ALGO_SVA : SVA_ALGO_GA;
                must_plan_checked(&planner, &mission, rival, &other, seed, round);
                if (spec_better(other.covered, other.cost, plan.covered, plan.cost)) {
                    SVA_TEST_FAIL("seed %llu round %d: flow (%d, %lld) behind %s (%d, %lld)",
                                  (unsigned long long)seed, round, plan.covered,
                                  (long long)plan.cost, (a == 0) ? "sva" : "ga", other.covered,
                                  (long long)other.cost);
                }
            }
            past++;
            // Fewer targets than the fuel-free relaxation covers get the bound 0 (it
            // earns more rewards); every target covered gets the relaxation's cost, above
            // 0 when some UAV leaves the depot. The pooled graph always fits here (6
            // targets and 3 UAVs: at most 18 + 15 + 6 + 3 arcs).
            if (plan.covered == mission.target_count) {
                full++;
                bounded += (plan.stats.lower_bound > 0) ? 1 : 0;
                proven += plan.stats.optimal ? 1 : 0;
            }
        }
    }
    printf("# 400 missions: %d past the arc bound, %d of them covering every target, %d with a "
           "bound, %d "
           "proven optimal; under it, the pooled root taken on %d\n",
           past, full, bounded, proven, taken);
    TEST_ASSERT_TRUE(taken > 0);
    TEST_ASSERT_TRUE(past >= 100);
    TEST_ASSERT_TRUE(full >= 15);
    TEST_ASSERT_EQUAL_INT(full, bounded);
    TEST_ASSERT_TRUE(proven > 0);
}

void test_need_one_past_the_arc_bound_has_no_bound(void)
{
    // 12 chained windows, 2 UAVs, need 1: 2 * 12 + 66 + 12 + 2 = 104 arcs.
    sva_mission_init(&mission);
    mission.uav_count = 2;
    for (int32_t u = 0; u < 2; u++) {
        mission.uavs[u] = (sva_uav_t){u + 1, 0, 0, 1000, 0};
    }
    mission.target_count = 12;
    for (int32_t t = 0; t < 12; t++) {
        mission.targets[t] = (sva_target_t){t + 1, t % 3, t % 4, 100 + (20 * t), 105 + (20 * t), 1};
    }
    must_plan_checked(&planner, &mission, SVA_ALGO_FLOW, &plan, 0U, 0);
    TEST_ASSERT_TRUE(plan.stats.flow_graph_arcs > (uint32_t)SVA_FLOW_MAX_ARCS);
    TEST_ASSERT_EQUAL_INT(SVA_FLOW_OVER_ARCS, plan.stats.flow_incomplete);
    TEST_ASSERT_EQUAL_INT(0, plan.stats.lower_bound);
    TEST_ASSERT_FALSE(plan.stats.optimal);
    // With need 2 the pooled graph holds the same 104 arcs: still past, still no bound.
    for (int32_t t = 0; t < 12; t++) {
        mission.targets[t].need = 2;
    }
    must_plan_checked(&planner, &mission, SVA_ALGO_FLOW, &plan, 0U, 1);
    TEST_ASSERT_EQUAL_INT(SVA_FLOW_OVER_ARCS, plan.stats.flow_incomplete);
    TEST_ASSERT_EQUAL_INT(0, plan.stats.lower_bound);
}

// Every test starts from a freshly initialised planner.
void setUp(void)
{
    TEST_ASSERT_EQUAL_INT(SVA_OK, sva_planner_init(&planner));
}
