// brute_force.h -- the SPEC section 1 optimum by plain enumeration, for tiny missions
// (at most 6 targets and 4 UAVs): every target gets no UAV or any `need`-subset of
// UAVs; each UAV's targets are then ordered by start and checked. No pruning, no
// shared code with bfa: an independent reference.
#ifndef SVA_BRUTE_FORCE_H
#define SVA_BRUTE_FORCE_H

#include "sva/sva.h"

typedef struct {
    int covered;
    long long cost;
} brute_result_t;

brute_result_t brute_force_optimum(const sva_mission_t* mission);

#endif
