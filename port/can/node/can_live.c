// can_live.c -- the CAN node's live mission (contract in can_live.h, docs/can.md).
#include "can_live.h"

#include <string.h>

static void logf_line(const sva_can_live_t* self, const char* what, long a, long b)
{
    if (self->log != NULL) {
        fprintf(self->log, "sva_can_node: %s", what);
        if (a >= 0) {
            fprintf(self->log, " %ld", a);
        }
        if (b >= 0) {
            fprintf(self->log, " at tick %ld", b);
        }
        fputc('\n', self->log);
    }
}

static int32_t uav_index(const sva_can_live_t* self, int32_t id)
{
    uint16_t u;
    for (u = 0; u < self->live.mission.uav_count; ++u) {
        if (self->live.mission.uavs[u].id == id) {
            return (int32_t)u;
        }
    }
    return -1;
}

uint16_t sva_can_live_in_service(const sva_can_live_t* self)
{
    uint16_t u;
    uint16_t n = 0;
    for (u = 0; u < self->live.mission.uav_count; ++u) {
        n = (uint16_t)(n + (self->live.priv.uavs[u].lost ? 0U : 1U));
    }
    return n;
}

// Applies one event; logs it, its refusal, and every target whose state it changed.
static int apply(sva_can_live_t* self, const sva_event_t* e, uint32_t now_ms)
{
    uint8_t before[SVA_MAX_TARGETS];
    sva_diag_t diag;
    const uint16_t targets = self->live.mission.target_count;
    memcpy(before, self->live.target_state, sizeof before);
    if (sva_live_apply(&self->live, e, &diag) != SVA_OK) {
        char msg[200];
        (void)sva_diag_format(&diag, msg, sizeof msg);
        if (self->log != NULL) {
            fprintf(self->log, "sva_can_node: %s event refused: %s\n", sva_event_type_name(e->type),
                    msg);
        }
        ++self->stats.events_refused;
        return -1;
    }
    ++self->stats.events_applied;
    ++self->pending;
    self->last_event_ms = now_ms;
    if (self->log != NULL) {
        fprintf(self->log, "sva_can_node: event %s", sva_event_type_name(e->type));
        if (e->type != SVA_EVENT_CLOCK) {
            fprintf(self->log, " uav %ld", (long)e->uav_id);
        }
        if ((e->type == SVA_EVENT_POSITION) || (e->type == SVA_EVENT_UAV_BACK)) {
            fprintf(self->log, " at (%ld, %ld)", (long)e->x, (long)e->y);
        }
        if (e->type != SVA_EVENT_CLOCK && e->type != SVA_EVENT_UAV_LOST) {
            fprintf(self->log, " fuel %ld", (long)e->fuel);
        }
        fprintf(self->log, " at tick %ld\n", (long)e->at_ticks);
        for (uint16_t i = 0; i < targets; ++i) {
            if (before[i] != self->live.target_state[i]) {
                fprintf(self->log, "sva_can_node: target %ld %s at tick %ld\n",
                        (long)self->live.mission.targets[i].id,
                        sva_target_state_name((sva_target_state_t)self->live.target_state[i]),
                        (long)self->live.now_ticks);
            }
        }
    }
    return 1;
}

int sva_can_live_start(sva_can_live_t* self, const sva_mission_t* mission,
                       sva_algorithm_t algorithm, char* err, size_t err_size)
{
    sva_diag_t diag;
    sva_status_t st;
    uint16_t u;
    memset(self->fuel_heard, 0xFF, sizeof self->fuel_heard);
    memset(&self->stats, 0, sizeof self->stats);
    self->algorithm = algorithm;
    self->pending = 0U;
    if (self->track_tolerance_cells < 0) {
        self->track_tolerance_cells = 0;
    }
    if (sva_planner_init(&self->planner) != SVA_OK) {
        (void)snprintf(err, err_size, "planner init failed");
        return -1;
    }
    sva_diag_clear(&diag);
    st = sva_plan(&self->planner, mission, algorithm, &self->plan, &diag);
    if (st == SVA_OK) {
        st = sva_live_init(&self->live, mission, &self->plan, &diag);
    }
    if (st != SVA_OK) {
        char msg[200];
        (void)sva_diag_format(&diag, msg, sizeof msg);
        (void)snprintf(err, err_size, "plan 1 failed (status %d): %s", (int)st, msg);
        return -1;
    }
    if (sva_can_plan_from_core(&self->wire, mission, &self->plan, 1U) != SVA_CAN_OK) {
        (void)snprintf(err, err_size, "plan 1 does not fit the wire (more than %d items?)",
                       SVA_CAN_MAX_ITEMS);
        return -1;
    }
    for (u = 0; u < mission->uav_count; ++u) {
        self->fuel_heard[u] = mission->uavs[u].fuel;
    }
    self->plan_id = 1U;
    self->covered = (uint8_t)((self->plan.covered > 255U) ? 255U : self->plan.covered);
    self->sent = self->wire;
    return 0;
}

// Hands one input to the hook; a failure halts the live mission.
static int keep(sva_can_live_t* self, sva_can_live_input_kind_t kind, const sva_can_msg_t* msg,
                uint32_t now_ms, int outcome)
{
    sva_can_live_input_t in;
    if (self->input_hook == NULL) {
        return outcome;
    }
    in.kind = kind;
    in.msg = msg;
    in.now_ms = now_ms;
    in.outcome = outcome;
    if (self->input_hook(self->input_hook_user, &in) != 0) {
        self->halted = true;
        return SVA_CAN_LIVE_HALTED;
    }
    return outcome;
}

static int on_msg(sva_can_live_t* self, const sva_can_msg_t* msg, uint32_t now_ms);

int sva_can_live_on_msg(sva_can_live_t* self, const sva_can_msg_t* msg, uint32_t now_ms)
{
    int32_t heard[SVA_MAX_UAVS];
    int r;
    if (self->halted) {
        return SVA_CAN_LIVE_HALTED;
    }
    memcpy(heard, self->fuel_heard, sizeof heard);
    r = on_msg(self, msg, now_ms);
    if ((r == 1) || (memcmp(heard, self->fuel_heard, sizeof heard) != 0)) {
        return keep(self, SVA_CAN_LIVE_INPUT_MSG, msg, now_ms, r);
    }
    return r;
}

static int on_msg(sva_can_live_t* self, const sva_can_msg_t* msg, uint32_t now_ms)
{
    sva_event_t e;
    int32_t u;
    int32_t x = 0;
    int32_t y = 0;
    int32_t fuel = 0;
    int32_t ready = 0;
    bool in_service;
    memset(&e, 0, sizeof e);
    e.at_ticks = self->live.now_ticks;
    if (msg->kind == SVA_CAN_MSG_MISSION_CLOCK) {
        // 24 bits: always an int32_t tick; one before now is refused by the core.
        if ((int32_t)msg->u.clock.tick == self->live.now_ticks) {
            return 0;
        }
        e.type = SVA_EVENT_CLOCK;
        e.at_ticks = (int32_t)msg->u.clock.tick;
        return apply(self, &e, now_ms);
    }
    if ((msg->kind != SVA_CAN_MSG_VEHICLE_STATUS) && (msg->kind != SVA_CAN_MSG_VEHICLE_FUEL)) {
        return 0;
    }
    e.uav_id =
        (msg->kind == SVA_CAN_MSG_VEHICLE_STATUS) ? msg->u.vehicle.uav_id : msg->u.fuel.uav_id;
    u = uav_index(self, e.uav_id);
    if (u < 0) {
        logf_line(self, "frame ignored: not a UAV of the live mission: uav", e.uav_id, -1);
        ++self->stats.events_refused;
        return -1;
    }
    in_service =
        sva_live_uav_at(&self->live, (uint16_t)u, self->live.now_ticks, &x, &y, &fuel, &ready);
    // Every frame is a report and the core's rule decides (sva_live_report).
    sva_report_t report;
    report.uav_id = e.uav_id;
    if (msg->kind == SVA_CAN_MSG_VEHICLE_FUEL) {
        // Above the core's bound: clamped to it (SVA_MAX_FUEL).
        self->fuel_heard[u] = (msg->u.fuel.fuel > (uint32_t)SVA_MAX_FUEL)
                                  ? (int32_t)SVA_MAX_FUEL
                                  : (int32_t)msg->u.fuel.fuel;
        if (!in_service) {
            return 0;  // kept for its uav_back
        }
        // A fuel frame says nothing of the cell: the model's, so only the fuel rule can act.
        report.in_service = true;
        report.x = x;
        report.y = y;
        report.fuel = self->fuel_heard[u];
        if (!sva_live_report(&self->live, &report, self->track_tolerance_cells, &e)) {
            return 0;
        }
        return apply(self, &e, now_ms);
    }
    // A status frame: lost, back with the last fuel heard, off its track with the
    // model's fuel, or nothing.
    report.x = msg->u.vehicle.x;
    report.y = msg->u.vehicle.y;
    report.fuel = in_service ? SVA_REPORT_FUEL_UNKNOWN : self->fuel_heard[u];
    switch (msg->u.vehicle.state) {
    case SVA_CAN_VEHICLE_UNAVAILABLE:
        report.in_service = false;
        break;
    case SVA_CAN_VEHICLE_AVAILABLE:
    case SVA_CAN_VEHICLE_BUSY:
        report.in_service = true;
        break;
    default:
        return 0;  // UNKNOWN: nothing to go by
    }
    if (!sva_live_report(&self->live, &report, self->track_tolerance_cells, &e)) {
        return 0;
    }
    return apply(self, &e, now_ms);
}

// The plan in force over the whole live mission: for each UAV in service (residual
// order), the visit it is under way with, then its route in force. False when a route
// would exceed SVA_MAX_ROUTE_TARGETS (a visit under way and a full route).
static bool plan_in_force(sva_can_live_t* self)
{
    const sva_live_result_t* r = &self->result;
    sva_plan_t* p = &self->plan;
    uint16_t k;
    memset(p, 0, sizeof *p);
    p->status = r->plan->status;
    p->algorithm = r->plan->algorithm;
    p->covered = r->covered;
    p->route_count = r->residual->uav_count;
    for (k = 0; k < r->residual->uav_count; ++k) {
        const sva_route_t* planned = &r->plan->routes[k];
        sva_route_t* route = &p->routes[k];
        const int32_t busy = self->live.priv.busy_with[k];
        uint16_t j;
        uint16_t n = 0;
        route->uav_id = r->residual->uavs[k].id;
        if (busy >= 0) {
            route->targets[n++] = (uint16_t)busy;
        }
        if ((uint32_t)n + planned->target_count > (uint32_t)SVA_MAX_ROUTE_TARGETS) {
            return false;
        }
        for (j = 0; j < planned->target_count; ++j) {
            route->targets[n++] = self->live.priv.target_of[planned->targets[j]];
        }
        route->target_count = n;
    }
    return true;
}

static bool same_plan(const sva_can_plan_t* a, const sva_can_plan_t* b)
{
    uint16_t i;
    if ((a->algorithm != b->algorithm) || (a->plan_status != b->plan_status) ||
        (a->route_count != b->route_count) || (a->item_count != b->item_count)) {
        return false;
    }
    for (i = 0; i < a->item_count; ++i) {
        const sva_can_item_t* x = &a->items[i];
        const sva_can_item_t* y = &b->items[i];
        if ((x->uav_id != y->uav_id) || (x->target_id != y->target_id) || (x->x != y->x) ||
            (x->y != y->y) || (x->arrive_by_ticks != y->arrive_by_ticks) ||
            (x->hold_until_ticks != y->hold_until_ticks)) {
            return false;
        }
    }
    return true;
}

static int poll_settled(sva_can_live_t* self);

int sva_can_live_poll(sva_can_live_t* self, uint32_t now_ms, uint32_t settle_ms)
{
    if (self->halted) {
        return SVA_CAN_LIVE_HALTED;
    }
    if ((self->pending == 0U) || ((uint32_t)(now_ms - self->last_event_ms) < settle_ms)) {
        return 0;
    }
    return keep(self, SVA_CAN_LIVE_INPUT_REPLAN, NULL, now_ms, poll_settled(self));
}

// Replans the pending events (sva_can_live_poll past the settle time).
static int poll_settled(sva_can_live_t* self)
{
    sva_diag_t diag;
    sva_status_t st;
    uint16_t next_id;
    self->pending = 0U;
    st = sva_live_replan(&self->live, &self->planner, self->algorithm, &self->result, &diag);
    if (st != SVA_OK) {
        char msg[200];
        (void)sva_diag_format(&diag, msg, sizeof msg);
        if (self->log != NULL) {
            fprintf(self->log, "sva_can_node: replan at tick %ld failed (status %d): %s\n",
                    (long)self->live.now_ticks, (int)st, msg);
        }
        return -1;
    }
    ++self->stats.replans;
    self->covered = (uint8_t)((self->result.covered > 255U) ? 255U : self->result.covered);
    next_id = (uint16_t)((self->plan_id == 65535U) ? 1U : (self->plan_id + 1U));
    if (!plan_in_force(self) || (sva_can_plan_from_core(&self->wire, &self->live.mission,
                                                        &self->plan, next_id) != SVA_CAN_OK)) {
        logf_line(self, "replan does not fit the wire: plan in force kept on the bus", -1,
                  self->live.now_ticks);
        return -1;
    }
    if (self->log != NULL) {
        fprintf(self->log,
                "sva_can_node: replan at tick %ld (revision %lu): %s, covered %u, %u under way, "
                "%lu changed visits\n",
                (long)self->live.now_ticks, (unsigned long)self->live.revision,
                self->result.kept ? "plan in force kept" : "new plan",
                (unsigned)self->result.covered, (unsigned)self->result.under_way,
                (unsigned long)self->result.dropped + (unsigned long)self->result.added);
    }
    if (same_plan(&self->wire, &self->sent)) {
        ++self->stats.unchanged;
        logf_line(self, "plan unchanged: nothing sent", -1, -1);
        return 0;
    }
    self->plan_id = next_id;
    self->sent = self->wire;
    return 1;
}
