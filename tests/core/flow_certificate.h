// flow_certificate.h -- checks of a flow plan's certificate (stats.lower_bound and
// stats.optimal), shared by the flow tests; a failure names the seed and round.
#ifndef SVA_FLOW_CERTIFICATE_H
#define SVA_FLOW_CERTIFICATE_H

#include <stdint.h>

#include "brute_force.h"
#include "sva/sva.h"

/// The bound is in [0, cost], and equals the cost when the plan claims optimality.
void check_certificate(const sva_plan_t* p, uint64_t seed, int round);

/// Against the brute-force optimum: a checked certificate, never better than the
/// optimum, "optimal" only when it is, and a bound at most the optimum's cost when the
/// plan covers no more targets than the optimum.
void check_against_optimum(const sva_plan_t* p, const brute_result_t* best, uint64_t seed, int round);

#endif
