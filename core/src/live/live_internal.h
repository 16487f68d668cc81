// live_internal.h -- private interfaces of the live-mission module (core/src/live/).
// The module runs on top of the public planner API: it builds a residual mission,
// calls sva_plan(), and keeps the plan in force. docs/SPEC.md section 12 is its contract.
#ifndef SVA_LIVE_INTERNAL_H
#define SVA_LIVE_INTERNAL_H

#include "../model/model.h"
#include "sva/sva_live.h"

/// Where the flight model (SPEC section 12.2) puts a UAV at a tick.
typedef struct {
    int32_t x;  ///< the cell it stands on, or the next cell of the step in progress
    int32_t y;
    int32_t from_x;  ///< where the leg in progress started (the cell itself when standing)
    int32_t from_y;
    int64_t fuel_now;   ///< fuel at the tick (cells completed, windows started)
    int64_t fuel;       ///< fuel once at (x, y)
    int64_t ready;      ///< from this tick it can take new work (>= the tick)
    int32_t busy_with;  ///< mission index of the target under way, or -1
    uint16_t next;      ///< route position of the first visit whose window is still ahead
} sva_live_pos_t;

/// No arrival: the UAV does not get there (lost, or the target is not on its route).
#define SVA_LIVE_NEVER INT64_MAX

// live_track.c: the flight model.
/// UAV u's position at tick `at` (>= its route's from_ticks or not). When `probe` is a
/// route position, *arrival gets the tick the UAV reaches it (SVA_LIVE_NEVER if never).
void sva_live_walk(const sva_live_t* self, uint16_t u, int64_t at, sva_live_pos_t* out,
                   int32_t probe, int64_t* arrival);
/// Makes UAV u's route start at tick `at` (SPEC section 12.2): the visits behind it are
/// dropped, a visit under way becomes busy_with, a step in progress is finished first.
void sva_live_rebase(sva_live_t* self, uint16_t u, int64_t at);
/// Takes target i off UAV u's route (wherever it stands).
void sva_live_route_remove(sva_live_uav_t* uav, uint16_t target);
/// The state target i has at tick `at` (>= now) if nothing but time happens;
/// `reach` also tells waiting from expired for windows still ahead (O(U * R)).
sva_target_state_t sva_live_state_at(const sva_live_t* self, uint16_t i, int64_t at, bool reach);
/// Moves every target's state to tick `at` and makes it now.
void sva_live_advance(sva_live_t* self, int64_t at);

// live_event.c: the checks events, targets and plans in force must pass.
/// SPEC section 1 bounds of one target (id excepted) as target `index`; false with diag.
bool sva_live_target_ok(const sva_target_t* target, int32_t index, int64_t now, sva_diag_t* diag);
/// The mission index of the UAV or target with `id`, or -1.
int32_t sva_live_find_uav(const sva_live_t* self, int32_t id);
int32_t sva_live_find_target(const sva_live_t* self, int32_t id);

// live_carry.c: the plan in force carried over to the residual mission.
/// Prunes the routes of *plan over `mission` until every visit fits (time, fuel, whole
/// needs) and fills its figures, as sva_plan() would (SPEC section 12.4). `served` is
/// scratch for SVA_MAX_TARGETS counts.
void sva_live_carry(const sva_mission_t* mission, sva_plan_t* plan, sva_algorithm_t algorithm,
                    uint16_t* served);

#endif  // SVA_LIVE_INTERNAL_H
