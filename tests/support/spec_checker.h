// spec_checker.h -- an independent SPEC section 1 checker for plans, written for the
// tests from the SPEC text alone: it recomputes every figure from the mission and the
// routes and shares no code with the planner.
#ifndef SVA_SPEC_CHECKER_H
#define SVA_SPEC_CHECKER_H

#include <stddef.h>

#include "sva/sva.h"

/// Returns the number of violations; the first is described in msg (may be NULL).
int spec_check_plan(const sva_mission_t* mission, const sva_plan_t* plan, char* msg, size_t size);

/// Lexicographic objective (SPEC section 1): is plan a strictly better than plan b?
int spec_better(int covered_a, long long cost_a, int covered_b, long long cost_b);

#endif
