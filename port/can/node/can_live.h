// can_live.h -- the CAN node's live mission (docs/can.md, "The live mission"): it keeps
// an sva_live_t from the plan it sends, turns the flight stack's frames into core
// events (SVA_MISSION_CLOCK: clock; SVA_VEHICLE_STATUS: uav_lost, uav_back, position;
// SVA_VEHICLE_FUEL: fuel), replans once the bus has been quiet for the settle time
// after the last event, and hands out a new wire plan only when it differs from the
// last one sent. Transport-free, so the host tests drive it over the loopback bus.
#ifndef SVA_CAN_LIVE_H
#define SVA_CAN_LIVE_H

#include <stdbool.h>
#include <stdint.h>
#include <stdio.h>

#include "sva/sva_live.h"
#include "sva/sva_can.h"

/// Default cells (Manhattan) a reported position may be from the flight model's.
#define SVA_CAN_LIVE_TRACK_TOLERANCE 2

/// Counters the node logs at exit.
typedef struct {
    uint32_t events_applied;  ///< core events the live mission took
    uint32_t events_refused;  ///< core events it refused, and frames naming unknown UAVs
    uint32_t replans;         ///< sva_live_replan() calls that succeeded
    uint32_t unchanged;       ///< replans whose wire plan equals the one sent before
} sva_can_live_stats_t;

/// Returned by sva_can_live_on_msg() and sva_can_live_poll() once the input hook failed:
/// the input was taken but could not be kept; the node must stop without answering.
#define SVA_CAN_LIVE_HALTED (-2)

/// What changed the live mission, handed to the input hook (the node's journal,
/// can_journal.h) in the order it happened.
typedef enum {
    SVA_CAN_LIVE_INPUT_MSG = 0,     ///< a flight-stack frame that changed the live mission
    SVA_CAN_LIVE_INPUT_REPLAN = 1,  ///< a replan attempt (sva_can_live_poll past the settle time)
} sva_can_live_input_kind_t;

typedef struct {
    sva_can_live_input_kind_t kind;
    const sva_can_msg_t* msg;  ///< _MSG: the decoded frame
    uint32_t now_ms;           ///< the time the node passed with it
    int outcome;               ///< _MSG: on_msg's result; _REPLAN: poll's (1, 0, -1)
} sva_can_live_input_t;

/// Called once for each input that changes the live mission, after it was applied and
/// before the node answers it (sends a plan). Returns 0, or non-zero when the input
/// could not be kept (then the live mission halts: SVA_CAN_LIVE_HALTED).
typedef int (*sva_can_live_input_fn)(void* user, const sva_can_live_input_t* input);

/// The node's live mission. Static storage (large): `static sva_can_live_t live;`.
typedef struct {
    sva_live_t live;
    sva_planner_t planner;
    sva_live_result_t result;
    sva_plan_t plan;      ///< the plan in force over live.mission (visits under way first)
    sva_can_plan_t wire;  ///< the plan to send (valid after start, or poll returning 1)
    sva_can_plan_t sent;  ///< the last plan handed out
    sva_algorithm_t algorithm;
    int32_t track_tolerance_cells;
    int32_t fuel_heard[SVA_MAX_UAVS];  ///< last SVA_VEHICLE_FUEL reading, -1 for none
    uint32_t pending;                  ///< events applied since the last replan
    uint32_t last_event_ms;
    uint16_t plan_id;  ///< id of the last wire plan made
    uint8_t covered;   ///< targets the plan in force covers (saturates at 255)
    FILE* log;         ///< one line per event, state change and plan; NULL: silent
    sva_can_live_stats_t stats;
    sva_can_live_input_fn input_hook;  ///< NULL: none (set by the journal)
    void* input_hook_user;
    bool halted;  ///< the input hook failed: every later call returns SVA_CAN_LIVE_HALTED
} sva_can_live_t;

/// Plans `mission` (at tick 0) with `algorithm`, starts the live mission with that plan
/// in force and makes it self->wire (plan id 1). Returns 0, or -1 with a one-line
/// message in err. log and track_tolerance_cells may be set before or after.
int sva_can_live_start(sva_can_live_t* self, const sva_mission_t* mission,
                       sva_algorithm_t algorithm, char* err, size_t err_size);

/// One decoded frame from the flight stack (other kinds are ignored). Returns 1 when it
/// became a core event the live mission applied, 0 when it changed nothing, -1 when
/// the event was refused (or names a UAV not in the mission); the log says why.
/// A frame that applied an event, or changed the fuel last heard of a UAV, goes to the
/// input hook (SVA_CAN_LIVE_HALTED when it fails, or once halted).
int sva_can_live_on_msg(sva_can_live_t* self, const sva_can_msg_t* msg, uint32_t now_ms);

/// Replans when events are pending and none came for settle_ms. Returns 1 when the new
/// plan in force differs from the last plan handed out: it is in self->wire with the
/// next plan id (and becomes self->sent); 0 otherwise; -1 when the replan failed (the
/// plan in force stays, the log says why). Every replan attempt goes to the input hook
/// before this returns (SVA_CAN_LIVE_HALTED when it fails, or once halted).
int sva_can_live_poll(sva_can_live_t* self, uint32_t now_ms, uint32_t settle_ms);

/// UAVs of the live mission in service.
uint16_t sva_can_live_in_service(const sva_can_live_t* self);

#endif
