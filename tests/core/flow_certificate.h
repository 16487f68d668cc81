// flow_certificate.h -- checks shared by the flow tests: a checked plan, and the
// certificate (stats.lower_bound and stats.optimal); a failure names the seed and round.
#ifndef SVA_FLOW_CERTIFICATE_H
#define SVA_FLOW_CERTIFICATE_H

#include <stdint.h>

#include "brute_force.h"
#include "sva/sva.h"

/// Plans with checked_plan (flow or a rival); fails the test when that does.
void must_plan_checked(sva_planner_t* planner, const sva_mission_t* mission,
                       sva_algorithm_t algorithm, sva_plan_t* out, uint64_t seed, int round);

/// The same plan twice: cost, coverage, certificate, work and every route (a plan must
/// not depend on what the planner planned before).
void check_same_plan(const sva_plan_t* again, const sva_plan_t* plan);

/// The bound is in [0, cost], and equals the cost when the plan claims optimality (which
/// claims its coverage too).
void check_certificate(const sva_plan_t* p, uint64_t seed, int round);

/// Against the brute-force optimum: a checked certificate, never better than the
/// optimum, "optimal" only when it is, "coverage_proven" only at the most coverage, and a
/// bound at most the optimum's cost when the plan covers no more targets than the optimum.
void check_against_optimum(const sva_plan_t* p, const brute_result_t* best, uint64_t seed,
                           int round);

#endif
