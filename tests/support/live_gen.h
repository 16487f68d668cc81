// Random events for the live-mission tests (tests/core/test_live*.c): one generator, so
// the model-based tests draw their events the same way.
#ifndef SVA_TEST_LIVE_GEN_H
#define SVA_TEST_LIVE_GEN_H

#include <stdint.h>

#include "mission_gen.h"
#include "sva/sva_live.h"

/// Small random live missions (8 targets, 4 UAVs, need up to 2, fuel 30 to 80) whose
/// windows start from tick 12, so events come before the visits.
extern const test_gen_params_t test_live_params;

/// An event of `type` at tick `at`, every other field zero.
sva_event_t test_event_at(sva_event_type_t type, int32_t at);

/// A random event at tick `at` over the live mission `live`, of a type in [0, max_type]:
/// a UAV of the mission, a position in [0, 10] x [0, 10], fuel in [0, 60], and a target:
/// a new one (id 100 + k, need 1, an 8-tick window starting 1 to 20 ticks after `at`)
/// or, for a cancellation or a change, the id of one of the mission's targets. The live
/// mission may still reject it (a lost UAV, a target under way, ...).
sva_event_t test_live_random_event(test_rng_t* rng, const sva_live_t* live, int32_t at, int k,
                                   sva_event_type_t max_type);

#endif
