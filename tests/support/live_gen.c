// Random events for the live-mission tests (live_gen.h).
#include "live_gen.h"

#include <string.h>

const test_gen_params_t test_live_params = {.targets = 8,
                                            .uavs = 4,
                                            .grid = 10,
                                            .window_min = 4,
                                            .window_max = 12,
                                            .horizon = 60,
                                            .need_max = 2,
                                            .fuel_min = 30,
                                            .fuel_max = 80,
                                            .hover_fuel = 1,
                                            .ticks_per_cell = 1,
                                            .scattered = 0,
                                            .start_min = 12};

sva_event_t test_event_at(sva_event_type_t type, int32_t at)
{
    sva_event_t e;
    (void)memset(&e, 0, sizeof(e));
    e.type = type;
    e.at_ticks = at;
    return e;
}

sva_event_t test_live_random_event(test_rng_t* rng, const sva_live_t* live, int32_t at, int k,
                                   sva_event_type_t max_type)
{
    sva_event_t e = test_event_at((sva_event_type_t)test_rng_range(rng, 0, (int32_t)max_type), at);
    e.uav_id = live->mission.uavs[test_rng_range(rng, 0, live->mission.uav_count - 1)].id;
    e.x = test_rng_range(rng, 0, 10);
    e.y = test_rng_range(rng, 0, 10);
    e.fuel = test_rng_range(rng, 0, 60);
    const int32_t start = at + test_rng_range(rng, 1, 20);
    e.target = (sva_target_t){100 + k, e.x, e.y, start, start + 8, 1};
    if ((e.type == SVA_EVENT_TARGET_CANCELLED) || (e.type == SVA_EVENT_TARGET_CHANGED)) {
        e.target.id =
            live->mission.targets[test_rng_range(rng, 0, live->mission.target_count - 1)].id;
    }
    return e;
}
