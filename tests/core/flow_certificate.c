// flow_certificate.c -- checks shared by the flow tests (flow_certificate.h).
#include <stddef.h>
#include <stdint.h>
#include "sva_unity.h"

#include "checked_plan.h"
#include "flow_certificate.h"
#include "spec_checker.h"

void must_plan_checked(sva_planner_t* planner, const sva_mission_t* mission,
                       sva_algorithm_t algorithm, sva_plan_t* out, uint64_t seed, int round)
{
    char why[320] = "";
    if (checked_plan(planner, mission, algorithm, out, why, sizeof(why)) != 0) {
        SVA_TEST_FAIL("seed %llu round %d %s", (unsigned long long)seed, round, why);
    }
}

void check_certificate(const sva_plan_t* p, uint64_t seed, int round)
{
    if (!p->stats.has_bound || p->stats.lower_bound < 0 || p->stats.lower_bound > p->cost) {
        SVA_TEST_FAIL("seed %llu round %d: bound %lld outside [0, cost %lld]",
                      (unsigned long long)seed, round, (long long)p->stats.lower_bound,
                      (long long)p->cost);
    }
    if (p->stats.optimal && p->stats.lower_bound != p->cost) {
        SVA_TEST_FAIL("seed %llu round %d: optimal but bound %lld != cost %lld",
                      (unsigned long long)seed, round, (long long)p->stats.lower_bound,
                      (long long)p->cost);
    }
    if (p->stats.optimal && !p->stats.coverage_proven) {
        SVA_TEST_FAIL("seed %llu round %d: optimal but its coverage not proven",
                      (unsigned long long)seed, round);
    }
}

void check_against_optimum(const sva_plan_t* p, const brute_result_t* best, uint64_t seed,
                           int round)
{
    check_certificate(p, seed, round);
    if (spec_better(p->covered, p->cost, best->covered, best->cost)) {
        SVA_TEST_FAIL("seed %llu round %d: flow (%d, %lld) beats the optimum (%d, %lld)",
                      (unsigned long long)seed, round, p->covered, (long long)p->cost,
                      best->covered, best->cost);
    }
    if (p->stats.optimal && (p->covered != best->covered || p->cost != best->cost)) {
        SVA_TEST_FAIL("seed %llu round %d: flow claims optimal (%d, %lld), optimum (%d, %lld)",
                      (unsigned long long)seed, round, p->covered, (long long)p->cost,
                      best->covered, best->cost);
    }
    if (p->stats.coverage_proven && (p->covered != best->covered)) {
        SVA_TEST_FAIL("seed %llu round %d: flow claims no plan covers more than %d, the most is %d",
                      (unsigned long long)seed, round, p->covered, best->covered);
    }
    if (p->covered <= best->covered && p->stats.lower_bound > best->cost) {
        SVA_TEST_FAIL("seed %llu round %d: bound %lld above the optimum %lld (covering %d <= %d)",
                      (unsigned long long)seed, round, (long long)p->stats.lower_bound, best->cost,
                      p->covered, best->covered);
    }
}

void check_same_plan(const sva_plan_t* again, const sva_plan_t* plan)
{
    TEST_ASSERT_EQUAL_INT(again->cost, plan->cost);
    TEST_ASSERT_EQUAL_INT(again->covered, plan->covered);
    TEST_ASSERT_EQUAL_INT(again->stats.lower_bound, plan->stats.lower_bound);
    TEST_ASSERT_EQUAL_INT(again->stats.optimal, plan->stats.optimal);
    TEST_ASSERT_EQUAL_INT(again->stats.coverage_proven, plan->stats.coverage_proven);
    TEST_ASSERT_EQUAL_INT(again->stats.flow_work, plan->stats.flow_work);
    TEST_ASSERT_EQUAL_INT(again->stats.flow_ruin_rounds, plan->stats.flow_ruin_rounds);
    TEST_ASSERT_EQUAL_INT(again->route_count, plan->route_count);
    for (uint16_t u = 0U; u < plan->route_count; u++) {
        TEST_ASSERT_EQUAL_INT(again->routes[u].target_count, plan->routes[u].target_count);
        SVA_TEST_ASSERT_EQUAL_BYTES(again->routes[u].targets, plan->routes[u].targets,
                                    sizeof(uint16_t) * plan->routes[u].target_count);
    }
}
