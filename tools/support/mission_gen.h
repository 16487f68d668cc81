// mission_gen.h -- seeded random missions for model-based tests and the benchmark
// (xorshift64*, so a seed replays the same missions on every platform).
#ifndef SVA_MISSION_GEN_H
#define SVA_MISSION_GEN_H

#include <stdint.h>

#include "sva/sva.h"

typedef struct {
    uint64_t state;
} test_rng_t;

void test_rng_seed(test_rng_t* rng, uint64_t seed);
/// Uniform in [lo, hi].
int32_t test_rng_range(test_rng_t* rng, int32_t lo, int32_t hi);

typedef struct {
    int targets;
    int uavs;
    int grid;  ///< coordinates in [0, grid]
    int window_min;
    int window_max;
    int horizon;  ///< window starts in [0, horizon]
    int need_max;
    int fuel_min;
    int fuel_max;
    int hover_fuel;
    int ticks_per_cell;
    int scattered;  ///< 1: UAVs start anywhere with ready_at > 0 (replanning)
    int start_min;  ///< earliest window start (0 when left out)
} test_gen_params_t;

/// Fills *m with a valid random mission.
void test_gen_mission(test_rng_t* rng, const test_gen_params_t* params, sva_mission_t* m);

/// Seed for a model-based test: $SVA_TEST_SEED if set, else `fallback`. Printed so a
/// failure can be replayed.
uint64_t test_seed(uint64_t fallback);

#endif
