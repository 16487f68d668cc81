// The integer tableau simplex against hand-solved problems and against an enumeration
// written here (independent of the core): the tableau's optimum delivers the most
// units, then costs least; hga's enumeration agrees on problems it can cover in full.
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>
#include "sva_unity.h"

#include "mission_gen.h"
#include "paper/paper.h"

static sva_planner_t planner;
#define NO SVA_TP_NO_ARC

static void load(sva_tp_t* tp, int m, int n, const int32_t* supply, const int32_t* demand,
                 const int32_t* cost)
{
    memset(tp, 0, sizeof(*tp));
    tp->source_count = (uint16_t)m;
    tp->sink_count = (uint16_t)n;
    for (int s = 0; s < m; s++) {
        tp->supply[s] = supply[s];
    }
    for (int k = 0; k < n; k++) {
        tp->demand[k] = demand[k];
    }
    for (int i = 0; i < m * n; i++) {
        tp->cost[i] = cost[i];
    }
}

// Flow respects supply, demand and arcs.
static void assert_flow_feasible(const sva_tp_t* tp)
{
    const int m = tp->source_count, n = tp->sink_count;
    for (int s = 0; s < m; s++) {
        int32_t out = 0;
        for (int k = 0; k < n; k++) {
            TEST_ASSERT_TRUE(tp->flow[s * n + k] >= 0);
            if (tp->cost[s * n + k] == NO) {
                TEST_ASSERT_EQUAL_INT(0, tp->flow[s * n + k]);
            }
            out += tp->flow[s * n + k];
        }
        TEST_ASSERT_TRUE(out <= tp->supply[s]);
    }
    for (int k = 0; k < n; k++) {
        int32_t in = 0;
        for (int s = 0; s < m; s++) {
            in += tp->flow[s * n + k];
        }
        TEST_ASSERT_TRUE(in <= tp->demand[k]);
    }
}

void test_hand_solved_problem(void)
{
    sva_tp_t* tp = &planner.priv.tp;
    sva_stats_t stats = {0};
    int32_t unmet[4];
    // Sources: 2 UAVs at A, 1 at B. Sinks: need 1 and need 2.
    // A->k0 4, A->k1 6, B->k0 1, B->k1 9. Best: B->k0 (1), A->k1 x2 (12) = 13.
    const int32_t supply[] = {2, 1}, demand[] = {1, 2}, cost[] = {4, 6, 1, 9};
    load(tp, 2, 2, supply, demand, cost);
    TEST_ASSERT_EQUAL_INT(SVA_OK, sva_tableau_solve(&planner.priv.tableau, tp, unmet, &stats));
    TEST_ASSERT_EQUAL_INT(13, sva_tp_flow_cost(tp));
    TEST_ASSERT_EQUAL_INT(2, tp->flow[1]);
    TEST_ASSERT_EQUAL_INT(1, tp->flow[2]);
    TEST_ASSERT_EQUAL_INT(0, unmet[0] + unmet[1]);
    TEST_ASSERT_TRUE(stats.pivots > 0);
}

void test_surplus_stays_and_missing_arcs_are_unmet(void)
{
    sva_tp_t* tp = &planner.priv.tp;
    sva_stats_t stats = {0};
    int32_t unmet[4];
    // 3 units at the only source, one sink of need 1 reachable, one unreachable.
    const int32_t supply[] = {3}, demand[] = {1, 2}, cost[] = {5, NO};
    load(tp, 1, 2, supply, demand, cost);
    TEST_ASSERT_EQUAL_INT(SVA_OK, sva_tableau_solve(&planner.priv.tableau, tp, unmet, &stats));
    TEST_ASSERT_EQUAL_INT(1, tp->flow[0]);
    TEST_ASSERT_EQUAL_INT(0, tp->flow[1]);
    TEST_ASSERT_EQUAL_INT(0, unmet[0]);
    TEST_ASSERT_EQUAL_INT(2, unmet[1]);
}

static long long lcm_of_demands(const sva_tp_t* tp)
{
    long long l = 1;
    for (int k = 0; k < tp->sink_count; k++) {
        long long a = l, b = tp->demand[k];
        while (b) {
            const long long r = a % b;
            a = b;
            b = r;
        }
        l = l / a * tp->demand[k];
    }
    return l;
}

// Demand left unmet, each unit weighted L / need: a whole target weighs L.
static long long weighted_unmet(const sva_tp_t* tp, const int32_t* got)
{
    const long long l = lcm_of_demands(tp);
    long long w = 0;
    for (int k = 0; k < tp->sink_count; k++) {
        w += (l / tp->demand[k]) * (tp->demand[k] - got[k]);
    }
    return w;
}

// Enumeration of every integer flow: best = least weighted unmet demand, then least
// cost. `u` is only carried along for the report.
static void enumerate(const sva_tp_t* tp, int cell, int32_t* left, int32_t* got, long long u,
                      long long c, long long* best_u, long long* best_c)
{
    const int m = tp->source_count, n = tp->sink_count;
    if (cell == m * n) {
        const long long w = weighted_unmet(tp, got);
        (void)u;
        if (*best_u < 0 || w < *best_u || (w == *best_u && c < *best_c)) {
            *best_u = w;
            *best_c = c;
        }
        return;
    }
    const int s = cell / n, k = cell % n;
    int32_t most = left[s] < (tp->demand[k] - got[k]) ? left[s] : (tp->demand[k] - got[k]);
    if (tp->cost[cell] == NO) {
        most = 0;
    }
    for (int32_t x = 0; x <= most; x++) {
        left[s] -= x;
        got[k] += x;
        enumerate(tp, cell + 1, left, got, u + x, c + (long long)x * (x ? tp->cost[cell] : 0),
                  best_u, best_c);
        left[s] += x;
        got[k] -= x;
    }
}

void test_random_problems_match_enumeration(void)
{
    test_rng_t rng;
    test_rng_seed(&rng, test_seed(20261121));
    sva_tp_t* tp = &planner.priv.tp;
    int full = 0;
    for (int round = 0; round < 3000; round++) {
        const int m = test_rng_range(&rng, 1, 4), n = test_rng_range(&rng, 1, 4);
        int32_t supply[4], demand[4], cost[16], unmet[4], left[4], got[4] = {0};
        for (int s = 0; s < m; s++) {
            supply[s] = test_rng_range(&rng, 1, 3);
            left[s] = supply[s];
        }
        for (int k = 0; k < n; k++) {
            demand[k] = test_rng_range(&rng, 1, 3);
        }
        for (int i = 0; i < m * n; i++) {
            cost[i] = test_rng_range(&rng, 0, 5) == 0 ? (int32_t)NO : test_rng_range(&rng, 0, 40);
        }
        load(tp, m, n, supply, demand, cost);
        long long best_u = -1, best_c = 0;
        enumerate(tp, 0, left, got, 0, 0, &best_u, &best_c);
        sva_stats_t stats = {0};
        TEST_ASSERT_EQUAL_INT(SVA_OK, sva_tableau_solve(&planner.priv.tableau, tp, unmet, &stats));
        assert_flow_feasible(tp);
        int32_t got_tab[4] = {0};
        for (int k = 0; k < n; k++) {
            got_tab[k] = demand[k] - unmet[k];
        }
        if (weighted_unmet(tp, got_tab) != best_u || sva_tp_flow_cost(tp) != best_c) {
            SVA_TEST_FAIL(
                "round %d: tableau (%lld weighted unmet, %lld) vs enumeration (%lld, %lld)", round,
                weighted_unmet(tp, got_tab), (long long)sva_tp_flow_cost(tp), best_u, best_c);
        }
        if (best_u == 0) {  // coverable in full: hga's enumeration agrees
            full++;
            load(tp, m, n, supply, demand, cost);
            sva_hga_solve(&planner.priv.hga, tp, &stats);
            TEST_ASSERT_EQUAL_INT(n, sva_tp_covered(tp));
            TEST_ASSERT_EQUAL_INT(best_c, sva_tp_flow_cost(tp));
        }
    }
    printf("# 3000 random problems, %d coverable in full\n", full);
    TEST_ASSERT_TRUE(full > 100);
}
