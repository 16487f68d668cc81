/// sva_live.h -- live missions (docs/SPEC.md section 12): a mission under way, its events
/// and its replans, over the planner of sva.h.
///
/// A live mission holds a clock, the plan in force, target states, and events (UAVs lost
/// or back, fuel, position, targets added, cancelled or changed; sva_live_apply).
/// sva_live_replan plans what is left and keeps the better of that and the plan in force
/// (visits under way are never broken). Everything lives in the caller's sva_live_t
/// (`static sva_live_t live;`); nothing is allocated. Reentrant as sva.h says.

#ifndef SVA_LIVE_H
#define SVA_LIVE_H

#include "sva.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef enum {
    SVA_TARGET_WAITING = 0,  ///< its window has not started (or starts now)
    SVA_TARGET_UNDER_WAY,    ///< window started with its UAVs present; they stay to the end
    SVA_TARGET_DONE,         ///< window ended with its UAVs present: covered
    SVA_TARGET_EXPIRED,      ///< not under way and fewer than `need` UAVs can reach its start
    SVA_TARGET_CANCELLED,    ///< cancelled by an event
    SVA_TARGET_LOST,         ///< under way when one of its UAVs was lost: not covered
    SVA_TARGET_STATE_COUNT_  ///< number of states (not a state)
} sva_target_state_t;

/// The SPEC name of a target state ("waiting", "under_way", "done", "expired",
/// "cancelled", "lost"), or "" when out of range. Never NULL.
const char* sva_target_state_name(sva_target_state_t state);

/// What an event does (SPEC section 12.3).
typedef enum {
    SVA_EVENT_CLOCK = 0,         ///< time passes: now becomes at_ticks
    SVA_EVENT_UAV_LOST,          ///< uav_id leaves service
    SVA_EVENT_UAV_BACK,          ///< uav_id returns to service at (x, y) with fuel
    SVA_EVENT_FUEL,              ///< uav_id's remaining fuel reads `fuel`
    SVA_EVENT_TARGET_ADDED,      ///< `target` joins the mission (a new id)
    SVA_EVENT_TARGET_CANCELLED,  ///< target.id is cancelled
    SVA_EVENT_TARGET_CHANGED,    ///< target.id gets target's position, window and need
    SVA_EVENT_POSITION,          ///< uav_id was seen at (x, y) with fuel: its route goes on
    SVA_EVENT_COUNT_             ///< number of event types (not a type)
} sva_event_type_t;

/// The SPEC name of an event type ("clock", ..., "position"), or "" when out of range.
const char* sva_event_type_name(sva_event_type_t type);

/// Looks an event type up by its SPEC name. SVA_OK, or SVA_ERR_ARGUMENT when unknown.
SVA_NODISCARD sva_status_t sva_event_type_from_name(const char* name, sva_event_type_t* out);

/// One event. Fields an event type does not use are ignored.
typedef struct {
    sva_event_type_t type;
    int32_t at_ticks;     ///< when it happened: >= the live mission's now
    int32_t uav_id;       ///< uav_lost, uav_back, fuel, position
    int32_t x;            ///< uav_back, position
    int32_t y;            ///< uav_back, position
    int32_t fuel;         ///< uav_back, fuel, position: [0, SVA_MAX_FUEL]
    sva_target_t target;  ///< target_added, target_changed; target_cancelled reads target.id
} sva_event_t;

/// What sva_live_replan() chose (valid until the next call on the same sva_live_t).
typedef struct {
    /// The residual mission the planner saw: the UAVs in service where the flight model
    /// puts them at `now` (a UAV under way waits at its target until the window ends),
    /// and the targets still waiting. A standalone mission: sva_plan() accepts it.
    const sva_mission_t* residual;
    /// The new plan in force, over `residual` (indices into residual->targets).
    const sva_plan_t* plan;
    /// The plan in force before the replan, over `residual`: its visits of the residual
    /// targets, as planned (whether or not they still fit). A changed visit is a
    /// (UAV, target) pair in one of `previous` and `plan` but not in the other.
    const sva_plan_t* previous;
    int32_t now_ticks;
    uint32_t revision;   ///< events applied so far (the clock's included)
    uint16_t under_way;  ///< targets under way with their UAVs (covered, not replanned)
    uint16_t covered;    ///< under_way + plan->covered
    uint32_t dropped;    ///< pairs of `previous` that `plan` drops
    uint32_t added;      ///< pairs of `plan` that `previous` lacks
    int64_t objective;   ///< plan->cost + change_penalty * (dropped + added)
    /// The plan in force, less what no longer fits, won (ties go to it); false: the
    /// planner's plan of the residual mission won.
    bool kept;
} sva_live_result_t;

/// A live mission. Initialise with sva_live_init(); then read only.
typedef struct {
    sva_mission_t mission;  ///< UAVs as they started; targets as they stand now
    int32_t now_ticks;
    uint32_t revision;                      ///< events applied
    uint8_t target_state[SVA_MAX_TARGETS];  ///< sva_target_state_t of each target
    /// The last replan, where sva_live_result_t points: the residual mission, the plan
    /// chosen and the plan in force before it (candidate: the replan's scratch).
    sva_mission_t residual;
    sva_plan_t plan;
    sva_plan_t previous;
    sva_plan_t candidate;
    sva_live_priv_t priv;  ///< read-only to users (sva_private.h)
} sva_live_t;

/// Starts a live mission at now = 0 from a mission (its change_penalty included) and,
/// when plan is not NULL, the plan in force over it (only its routes are read).
/// Returns SVA_OK; SVA_ERR_ARGUMENT for a NULL self or mission; SVA_ERR_INVALID when the
/// mission breaks a rule or a route names an unknown target, a target twice or a UAV
/// out of mission order (diag says which). Fails iff it returns non-zero, and then
/// *self is unspecified.
/// Allocates nothing; O(U * R + T^2 + U^2) with R = SVA_MAX_ROUTE_TARGETS.
SVA_NODISCARD sva_status_t sva_live_init(sva_live_t* self, const sva_mission_t* mission,
                                         const sva_plan_t* plan, sva_diag_t* diag);

/// Applies one event: the clock moves to event->at_ticks (visits start, end or expire on
/// the way), then the event acts (SPEC section 12.3). Returns SVA_OK, or SVA_ERR_INVALID
/// with diag naming the field and rule of SPEC 12.3's "rejected when" column.
/// All-or-nothing: a rejected event leaves *self byte for byte as it was.
/// Allocates nothing; O(U * R + T).
SVA_NODISCARD sva_status_t sva_live_apply(sva_live_t* self, const sva_event_t* event,
                                          sva_diag_t* diag);

/// Plans the residual mission with `algorithm` and keeps the better of that plan and the
/// plan in force (SPEC section 12.4), planned with sva_replan() with the carried plan
/// standing. Returns SVA_OK with *result filled; otherwise
/// sva_plan()'s status and diag, and the plan in force stays as it was.
/// Allocates nothing; sva_plan()'s complexity plus O(U * R * T).
SVA_NODISCARD sva_status_t sva_live_replan(sva_live_t* self, sva_planner_t* planner,
                                           sva_algorithm_t algorithm, sva_live_result_t* result,
                                           sva_diag_t* diag);

/// Where a UAV is at `at_ticks` (>= now) by the flight model of SPEC section 12.2, with
/// its fuel and the tick from which it can take new work (later than at_ticks while
/// it finishes a cell step or a visit under way). False for an unknown index or a UAV
/// out of service. Allocates nothing; O(R).
bool sva_live_uav_at(const sva_live_t* self, uint16_t uav, int32_t at_ticks, int32_t* x, int32_t* y,
                     int32_t* fuel, int32_t* ready_ticks);

/// A vehicle's report of itself (MAVLink telemetry, an LCM fleet report, a CAN frame).
typedef struct {
    int32_t uav_id;
    bool in_service;  ///< heard and healthy; false: silent past its timeout, or failed
    int32_t x;        ///< the cell it is on
    int32_t y;
    int32_t fuel;  ///< remaining fuel, or SVA_REPORT_FUEL_UNKNOWN
} sva_report_t;
#define SVA_REPORT_FUEL_UNKNOWN (-1)
/// The one rule that turns a report into a live event at now, for every node and bridge
/// (SPEC section 12.3, "Vehicle reports"): the first of uav_lost, uav_back, position (off
/// its track by more than track_tolerance_cells) and fuel that applies. True with *event
/// filled (not applied: sva_live_apply checks it); false when the report agrees, the UAV
/// is unknown or an argument is NULL. Changes nothing; allocates nothing; O(R).
bool sva_live_report(const sva_live_t* self, const sva_report_t* report,
                     int32_t track_tolerance_cells, sva_event_t* event);

#ifdef __cplusplus
}
#endif

#endif  // SVA_LIVE_H
