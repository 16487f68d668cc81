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
    if (p->covered <= best->covered && p->stats.lower_bound > best->cost) {
        SVA_TEST_FAIL("seed %llu round %d: bound %lld above the optimum %lld (covering %d <= %d)",
                      (unsigned long long)seed, round, (long long)p->stats.lower_bound, best->cost,
                      p->covered, best->covered);
    }
}
