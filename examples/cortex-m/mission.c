// mission.c -- the bundled mission fixtures/missions/hand_5_3.json as a constant
// sva_mission_t: 3 UAVs at the depot, 5 targets, hover fuel 2. `const` puts it in
// flash; sva_plan() only reads its mission. (The golden sva plan covers all five
// targets at cost 124: fixtures/golden/sva/hand_5_3.json.)
#include "sva/sva.h"

const sva_mission_t fw_mission = {
    .depot_x = 0,
    .depot_y = 0,
    .ticks_per_cell = 1,
    .hover_fuel = 2,
    .overlap_percent = 70,
    .uav_count = 3,
    .target_count = 5,
    .uavs =
        {
            {.id = 1, .x = 0, .y = 0, .fuel = 100, .ready_at_ticks = 0},
            {.id = 2, .x = 0, .y = 0, .fuel = 100, .ready_at_ticks = 0},
            {.id = 3, .x = 0, .y = 0, .fuel = 100, .ready_at_ticks = 0},
        },
    .targets =
        {
            {.id = 1, .x = 3, .y = 4, .start_ticks = 10, .end_ticks = 30, .need = 2},
            {.id = 2, .x = 10, .y = 2, .start_ticks = 12, .end_ticks = 28, .need = 1},
            {.id = 3, .x = 15, .y = 9, .start_ticks = 40, .end_ticks = 55, .need = 1},
            {.id = 4, .x = 6, .y = 13, .start_ticks = 42, .end_ticks = 58, .need = 1},
            {.id = 5, .x = 18, .y = 18, .start_ticks = 70, .end_ticks = 90, .need = 1},
        },
};
