// Model-based random tests with a printed, replayable seed (SVA_TEST_SEED=...):
// - every plan of every algorithm passes the independent SPEC checker;
// - on tiny missions bfa equals an independent brute force, and no algorithm beats bfa;
// - every transportation problem sva solves is optimal for the sinks it kept
//   (checked by an enumeration written here), and its dropped sinks carry no flow;
// - planning twice gives the same plan.
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>
#include "sva_unity.h"

#include "brute_force.h"
#include "mission_gen.h"
#include "checked_plan.h"
#include "spec_checker.h"
#include "sva/sva.h"

static sva_planner_t planner;
static sva_mission_t mission;
static sva_plan_t plan;
static sva_plan_t again;

static void plan_ok(sva_algorithm_t algorithm, uint64_t seed, int round)
{
    char why[320] = "";
    if (checked_plan(&planner, &mission, algorithm, &plan, why, sizeof(why)) != 0) {
        SVA_TEST_FAIL("seed %llu round %d %s", (unsigned long long)seed, round, why);
    }
}

void test_tiny_missions_bfa_is_optimal_and_never_beaten(void)
{
    const uint64_t seed = test_seed(0x5A1EULL);
    test_rng_t rng;
    test_rng_seed(&rng, seed);
    int bfa_better_than_sva = 0;
    const int rounds = 600;
    for (int round = 0; round < rounds; round++) {
        const test_gen_params_t p = {
            test_rng_range(&rng, 1, SVA_BFA_MAX_TARGETS < 6 ? SVA_BFA_MAX_TARGETS : 6),
            test_rng_range(&rng, 1, SVA_BFA_MAX_UAVS < 4 ? SVA_BFA_MAX_UAVS : 4),
            test_rng_range(&rng, 4, 20),
            2,
            15,
            40,
            2,
            test_rng_range(&rng, 5, 40),
            80,
            test_rng_range(&rng, 0, 3),
            test_rng_range(&rng, 1, 2),
            test_rng_range(&rng, 0, 1),
            0};
        test_gen_mission(&rng, &p, &mission);
        const brute_result_t best = brute_force_optimum(&mission);
        plan_ok(SVA_ALGO_BFA, seed, round);
        if (plan.covered != best.covered || plan.cost != best.cost) {
            SVA_TEST_FAIL("seed %llu round %d: bfa (%d, %lld) vs brute force (%d, %lld)",
                          (unsigned long long)seed, round, plan.covered, (long long)plan.cost,
                          best.covered, best.cost);
        }
        for (int a = 0; a < (int)SVA_ALGO_COUNT_; a++) {
            plan_ok((sva_algorithm_t)a, seed, round);
            if (spec_better(plan.covered, plan.cost, best.covered, best.cost)) {
                SVA_TEST_FAIL("seed %llu round %d: %s beats the optimum", (unsigned long long)seed,
                              round, sva_algorithm_name((sva_algorithm_t)a));
            }
            if (a == SVA_ALGO_SVA &&
                spec_better(best.covered, best.cost, plan.covered, plan.cost)) {
                bfa_better_than_sva++;
            }
        }
    }
    printf("# %d tiny missions: bfa strictly better than sva on %d\n", rounds, bfa_better_than_sva);
    TEST_ASSERT_TRUE(bfa_better_than_sva > 0);  // the generator does reach the heuristics' gaps
}

// Minimum cost of the kept sinks by enumeration (small problems only): -1 if infeasible.
static long long kept_optimum(const sva_tp_view_t* tp, int cell, int32_t* left, int32_t* got)
{
    const int m = tp->source_count, n = tp->sink_count;
    if (cell == m * n) {
        for (int k = 0; k < n; k++) {
            if (!tp->sink_dropped[k] && got[k] != tp->demand[k]) {
                return -1;
            }
        }
        return 0;
    }
    const int s = cell / n, k = cell % n;
    long long best = -1;
    int32_t most = tp->sink_dropped[k] || tp->cost[cell] == SVA_TP_NO_ARC ? 0 : left[s];
    most = most < tp->demand[k] - got[k] ? most : tp->demand[k] - got[k];
    for (int32_t x = 0; x <= most; x++) {
        left[s] -= x;
        got[k] += x;
        const long long rest = kept_optimum(tp, cell + 1, left, got);
        if (rest >= 0) {
            const long long c = rest + (x ? (long long)x * tp->cost[cell] : 0);
            best = (best < 0 || c < best) ? c : best;
        }
        left[s] += x;
        got[k] -= x;
    }
    return best;
}

typedef struct {
    int problems;
    int checked;
    int failures;
} observed_t;

static void check_problem(void* user, const sva_tp_view_t* tp)
{
    observed_t* seen = user;
    seen->problems++;
    const int m = tp->source_count, n = tp->sink_count;
    for (int k = 0; k < n; k++) {
        int32_t in = 0;
        for (int s = 0; s < m; s++) {
            in += tp->flow[s * n + k];
        }
        if (in != (tp->sink_dropped[k] ? 0 : tp->demand[k])) {
            seen->failures++;  // a kept sink short, or a dropped one served
        }
    }
    if (m * n > 12) {
        return;
    }
    int32_t left[SVA_MAX_TP_SOURCES], got[SVA_MAX_TP_SINKS];
    for (int s = 0; s < m; s++) {
        left[s] = tp->supply[s];
    }
    memset(got, 0, sizeof(got));
    seen->checked++;
    if (kept_optimum(tp, 0, left, got) != tp->cost_total) {
        seen->failures++;
    }
}

void test_paper_sizes_feasible_and_problems_optimal(void)
{
    const uint64_t seed = test_seed(0xC0FFEEULL);
    test_rng_t rng;
    test_rng_seed(&rng, seed);
    observed_t seen = {0, 0, 0};
    planner.on_transport = check_problem;
    planner.on_transport_user = &seen;
    const int sizes[][2] = {{3, 3}, {5, 3}, {7, 5}, {10, 5}, {25, 5}, {40, 8}};
    int planned = 0;
    for (size_t size = 0; size < sizeof(sizes) / sizeof(sizes[0]); size++) {
        if (sizes[size][0] > SVA_MAX_TARGETS || sizes[size][1] > SVA_MAX_UAVS) {
            continue;
        }
        for (int round = 0; round < 150; round++) {
            const test_gen_params_t p = {sizes[size][0],
                                         sizes[size][1],
                                         20,
                                         10,
                                         20,
                                         4 * sizes[size][0],
                                         test_rng_range(&rng, 1, 2),
                                         test_rng_range(&rng, 20, 60),
                                         200,
                                         2,
                                         1,
                                         test_rng_range(&rng, 0, 1),
                                         0};
            test_gen_mission(&rng, &p, &mission);
            for (int a = 0; a < (int)SVA_ALGO_COUNT_; a++) {
                if (a == SVA_ALGO_BFA &&
                    (mission.target_count > 10 || mission.target_count > SVA_BFA_MAX_TARGETS ||
                     mission.uav_count > SVA_BFA_MAX_UAVS)) {
                    continue;
                }
                plan_ok((sva_algorithm_t)a, seed, round);
                planned++;
                // Determinism: the same mission plans to the same plan.
                sva_diag_t diag;
                TEST_ASSERT_EQUAL_INT(
                    SVA_OK, sva_plan(&planner, &mission, (sva_algorithm_t)a, &again, &diag));
                TEST_ASSERT_EQUAL_INT(plan.cost, again.cost);
                TEST_ASSERT_EQUAL_INT(plan.covered, again.covered);
                for (int u = 0; u < mission.uav_count; u++) {
                    TEST_ASSERT_EQUAL_INT(plan.routes[u].target_count,
                                          again.routes[u].target_count);
                    SVA_TEST_ASSERT_EQUAL_BYTES(plan.routes[u].targets, again.routes[u].targets,
                                                plan.routes[u].target_count * sizeof(uint16_t));
                }
            }
        }
    }
    planner.on_transport = NULL;
    printf("# %d plans checked; %d transportation problems, %d enumerated\n", planned,
           seen.problems, seen.checked);
    TEST_ASSERT_EQUAL_INT(0, seen.failures);
    TEST_ASSERT_TRUE(seen.checked > 100);
}

// Every test starts from a freshly initialised planner.
void setUp(void)
{
    TEST_ASSERT_EQUAL_INT(SVA_OK, sva_planner_init(&planner));
}
