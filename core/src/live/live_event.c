// live_event.c -- a live mission's start and its events (SPEC sections 5.1 and 5.3):
// every check first, then the change, so a rejected event changes nothing.
#include "live_internal.h"

#include <string.h>

int32_t sva_live_find_uav(const sva_live_t* self, int32_t id)
{
    for (uint16_t u = 0U; u < self->mission.uav_count; u++) {
        if (self->mission.uavs[u].id == id) {
            return (int32_t)u;
        }
    }
    return -1;
}

int32_t sva_live_find_target(const sva_live_t* self, int32_t id)
{
    for (uint16_t i = 0U; i < self->mission.target_count; i++) {
        if (self->mission.targets[i].id == id) {
            return (int32_t)i;
        }
    }
    return -1;
}

bool sva_live_target_ok(const sva_target_t* t, int32_t index, int64_t now, sva_diag_t* diag)
{
    if (!sva_in_range(diag, SVA_FIELD_TARGET_ID, index, t->id, 1, SVA_MAX_ID, NULL) ||
        !sva_in_range(diag, SVA_FIELD_TARGET_X, index, t->x, SVA_COORD_MIN, SVA_COORD_MAX, NULL) ||
        !sva_in_range(diag, SVA_FIELD_TARGET_Y, index, t->y, SVA_COORD_MIN, SVA_COORD_MAX, NULL) ||
        !sva_in_range(diag, SVA_FIELD_TARGET_START, index, t->start_ticks, 0, SVA_MAX_TICK - 1,
                      "SVA_MAX_TICK")) {
        return false;
    }
    if (t->start_ticks < now) {
        sva_diag_set(diag, SVA_FIELD_TARGET_START, SVA_RULE_PAST, index, t->start_ticks, now, NULL);
        return false;
    }
    if (t->end_ticks <= t->start_ticks) {
        sva_diag_set(diag, SVA_FIELD_TARGET_END, SVA_RULE_AFTER, index, t->end_ticks,
                     t->start_ticks, NULL);
        return false;
    }
    return sva_in_range(diag, SVA_FIELD_TARGET_END, index, t->end_ticks, 1, SVA_MAX_TICK,
                        "SVA_MAX_TICK") &&
           sva_in_range(diag, SVA_FIELD_TARGET_NEED, index, t->need, 1, SVA_MAX_UAVS,
                        "SVA_MAX_UAVS");
}

// The plan in force given at the start: one route per UAV in mission order, known
// targets, none twice in a route.
static bool plan_ok(const sva_mission_t* m, const sva_plan_t* plan, sva_diag_t* diag)
{
    if (plan->route_count != m->uav_count) {
        sva_diag_set(diag, SVA_FIELD_ROUTES, SVA_RULE_ROUTE, -1, plan->route_count, m->uav_count,
                     NULL);
        return false;
    }
    for (uint16_t u = 0U; u < m->uav_count; u++) {
        const sva_route_t* r = &plan->routes[u];
        if (r->uav_id != m->uavs[u].id) {
            sva_diag_set(diag, SVA_FIELD_ROUTE_UAV, SVA_RULE_ROUTE, (int32_t)u, r->uav_id,
                         m->uavs[u].id, NULL);
            return false;
        }
        if ((uint32_t)r->target_count > (uint32_t)SVA_MAX_ROUTE_TARGETS) {
            sva_diag_set(diag, SVA_FIELD_ROUTE_TARGETS, SVA_RULE_COUNT, (int32_t)u, r->target_count,
                         SVA_MAX_ROUTE_TARGETS, "SVA_MAX_ROUTE_TARGETS");
            return false;
        }
        for (uint16_t k = 0U; k < r->target_count; k++) {
            if (r->targets[k] >= m->target_count) {
                sva_diag_set(diag, SVA_FIELD_ROUTE_TARGETS, SVA_RULE_MAX, (int32_t)u, r->targets[k],
                             (int64_t)m->target_count - 1, NULL);
                return false;
            }
            for (uint16_t j = 0U; j < k; j++) {
                if (r->targets[j] == r->targets[k]) {
                    sva_diag_set(diag, SVA_FIELD_ROUTE_TARGETS, SVA_RULE_DUPLICATE, (int32_t)u,
                                 m->targets[r->targets[k]].id, j, NULL);
                    return false;
                }
            }
        }
    }
    return true;
}

sva_status_t sva_live_init(sva_live_t* self, const sva_mission_t* mission, const sva_plan_t* plan,
                           sva_diag_t* diag)
{
    SVA_ASSERT((self != NULL) && (mission != NULL));
    if ((self == NULL) || (mission == NULL)) {
        return SVA_ERR_ARGUMENT;
    }
    if (diag != NULL) {
        sva_diag_clear(diag);
    }
    if (sva_mission_validate(mission, diag) != SVA_OK) {
        return SVA_ERR_INVALID;
    }
    if ((plan != NULL) && !plan_ok(mission, plan, diag)) {
        return SVA_ERR_INVALID;
    }
    (void)memset(self, 0, sizeof(*self));
    self->mission = *mission;
    for (uint16_t u = 0U; u < mission->uav_count; u++) {
        sva_live_uav_t* v = &self->priv.uavs[u];
        const sva_uav_t* s = &mission->uavs[u];
        v->x = s->x;
        v->y = s->y;
        v->fuel = s->fuel;
        v->from_ticks = s->ready_at_ticks;
        v->busy_with = -1;
        if (plan != NULL) {
            v->route_count = plan->routes[u].target_count;
            (void)memcpy(v->route, plan->routes[u].targets,
                         sizeof(v->route[0]) * (size_t)v->route_count);
        }
    }
    sva_live_advance(self, 0);
    return SVA_OK;
}

// Every rule of SPEC section 12.3 against the live mission as it will be at event->at.
static bool event_ok(const sva_live_t* self, const sva_event_t* e, sva_diag_t* diag)
{
    if ((unsigned)e->type >= (unsigned)SVA_EVENT_COUNT_) {
        sva_diag_set(diag, SVA_FIELD_EVENT_TYPE, SVA_RULE_MAX, -1, (int64_t)e->type,
                     (int64_t)SVA_EVENT_COUNT_ - 1, NULL);
        return false;
    }
    if (e->at_ticks < self->now_ticks) {
        sva_diag_set(diag, SVA_FIELD_EVENT_AT, SVA_RULE_PAST, -1, e->at_ticks, self->now_ticks,
                     NULL);
        return false;
    }
    if (!sva_in_range(diag, SVA_FIELD_EVENT_AT, -1, e->at_ticks, 0, SVA_MAX_TICK, "SVA_MAX_TICK")) {
        return false;
    }
    const sva_mission_t* m = &self->mission;
    if ((e->type == SVA_EVENT_UAV_LOST) || (e->type == SVA_EVENT_UAV_BACK) ||
        (e->type == SVA_EVENT_FUEL) || (e->type == SVA_EVENT_POSITION)) {
        const int32_t u = sva_live_find_uav(self, e->uav_id);
        if (u < 0) {
            sva_diag_set(diag, SVA_FIELD_EVENT_UAV, SVA_RULE_UNKNOWN, -1, e->uav_id, 0, NULL);
            return false;
        }
        // The UAV must be lost for uav_back, in service for the others (value: 1 lost).
        if (self->priv.uavs[u].lost != (e->type == SVA_EVENT_UAV_BACK)) {
            sva_diag_set(diag, SVA_FIELD_EVENT_UAV, SVA_RULE_STATE, -1,
                         self->priv.uavs[u].lost ? 1 : 0, 0, NULL);
            return false;
        }
    }
    switch (e->type) {
    case SVA_EVENT_UAV_BACK:
    case SVA_EVENT_POSITION:
        return sva_in_range(diag, SVA_FIELD_EVENT_X, -1, e->x, SVA_COORD_MIN, SVA_COORD_MAX,
                            NULL) &&
               sva_in_range(diag, SVA_FIELD_EVENT_Y, -1, e->y, SVA_COORD_MIN, SVA_COORD_MAX,
                            NULL) &&
               sva_in_range(diag, SVA_FIELD_EVENT_FUEL, -1, e->fuel, 0, SVA_MAX_FUEL,
                            "SVA_MAX_FUEL");
    case SVA_EVENT_FUEL:
        return sva_in_range(diag, SVA_FIELD_EVENT_FUEL, -1, e->fuel, 0, SVA_MAX_FUEL,
                            "SVA_MAX_FUEL");
    case SVA_EVENT_TARGET_ADDED: {
        const int32_t same = sva_live_find_target(self, e->target.id);
        if (same >= 0) {
            sva_diag_set(diag, SVA_FIELD_EVENT_TARGET, SVA_RULE_DUPLICATE, -1, e->target.id, same,
                         NULL);
            return false;
        }
        if ((uint32_t)m->target_count >= (uint32_t)SVA_MAX_TARGETS) {
            sva_diag_set(diag, SVA_FIELD_TARGETS, SVA_RULE_COUNT, -1, (int64_t)m->target_count + 1,
                         SVA_MAX_TARGETS, "SVA_MAX_TARGETS");
            return false;
        }
        return sva_live_target_ok(&e->target, (int32_t)m->target_count, e->at_ticks, diag);
    }
    case SVA_EVENT_TARGET_CANCELLED:
    case SVA_EVENT_TARGET_CHANGED: {
        const int32_t i = sva_live_find_target(self, e->target.id);
        if (i < 0) {
            sva_diag_set(diag, SVA_FIELD_EVENT_TARGET, SVA_RULE_UNKNOWN, -1, e->target.id, 0, NULL);
            return false;
        }
        const sva_target_state_t state = sva_live_state_at(self, (uint16_t)i, e->at_ticks, false);
        if (e->type == SVA_EVENT_TARGET_CANCELLED) {
            if ((state == SVA_TARGET_DONE) || (state == SVA_TARGET_LOST) ||
                (state == SVA_TARGET_CANCELLED)) {
                sva_diag_set(diag, SVA_FIELD_EVENT_TARGET, SVA_RULE_STATE, -1, (int64_t)state, 0,
                             NULL);
                return false;
            }
            return true;
        }
        if (m->targets[i].start_ticks <= e->at_ticks) {
            sva_diag_set(diag, SVA_FIELD_EVENT_TARGET, SVA_RULE_STARTED, -1,
                         m->targets[i].start_ticks, e->at_ticks, NULL);
            return false;
        }
        if (state == SVA_TARGET_CANCELLED) {
            sva_diag_set(diag, SVA_FIELD_EVENT_TARGET, SVA_RULE_STATE, -1, (int64_t)state, 0, NULL);
            return false;
        }
        return sva_live_target_ok(&e->target, i, e->at_ticks, diag);
    }
    case SVA_EVENT_CLOCK:
    case SVA_EVENT_UAV_LOST:
    case SVA_EVENT_COUNT_:
    default:
        return true;
    }
}

// Target i ends early (lost or cancelled) at `at`: the UAVs under way there are free.
static void end_target(sva_live_t* self, uint16_t i, sva_target_state_t state, int64_t at)
{
    self->target_state[i] = (uint8_t)state;
    self->priv.target_ended[i] = (int32_t)at;
    for (uint16_t u = 0U; u < self->mission.uav_count; u++) {
        sva_live_uav_t* v = &self->priv.uavs[u];
        if (v->lost) {
            continue;
        }
        sva_live_rebase(self, u, at);
        if (v->busy_with == (int32_t)i) {
            v->busy_with = -1;
            v->from_ticks = at;
        }
        sva_live_route_remove(v, i);
    }
}

sva_status_t sva_live_apply(sva_live_t* self, const sva_event_t* event, sva_diag_t* diag)
{
    SVA_ASSERT((self != NULL) && (event != NULL));
    if ((self == NULL) || (event == NULL)) {
        return SVA_ERR_ARGUMENT;
    }
    if (!event_ok(self, event, diag)) {
        return SVA_ERR_INVALID;
    }
    const int64_t at = event->at_ticks;
    // event_ok found the UAV of a UAV event; 0 stands in for the others (unused).
    const int32_t found = sva_live_find_uav(self, event->uav_id);
    const uint16_t u = (uint16_t)((found < 0) ? 0 : found);
    sva_live_uav_t* v = &self->priv.uavs[u];
    sva_live_advance(self, at);
    switch (event->type) {
    case SVA_EVENT_UAV_LOST: {
        sva_live_pos_t pos;
        sva_live_walk(self, u, at, &pos, -1, NULL);
        v->lost = true;
        if ((pos.busy_with >= 0) &&
            (self->target_state[(uint16_t)pos.busy_with] == (uint8_t)SVA_TARGET_UNDER_WAY)) {
            end_target(self, (uint16_t)pos.busy_with, SVA_TARGET_LOST, at);
        }
        break;
    }
    case SVA_EVENT_UAV_BACK:
        v->lost = false;
        v->x = event->x;
        v->y = event->y;
        v->fuel = event->fuel;
        v->from_ticks = at + self->mission.takeoff_ticks;  // on the ground: takes off first
        v->busy_with = -1;
        v->route_count = 0U;
        break;
    case SVA_EVENT_FUEL: {
        sva_live_rebase(self, u, at);
        sva_live_pos_t pos;
        sva_live_walk(self, u, at, &pos, -1, NULL);
        v->fuel += (int64_t)event->fuel - pos.fuel;
        break;
    }
    case SVA_EVENT_POSITION: {
        sva_live_rebase(self, u, at);
        sva_live_pos_t pos;
        sva_live_walk(self, u, at, &pos, -1, NULL);
        const int32_t busy = pos.busy_with;
        if ((busy >= 0) && (self->target_state[(uint16_t)busy] == (uint8_t)SVA_TARGET_UNDER_WAY)) {
            const sva_target_t* tg = &self->mission.targets[(uint16_t)busy];
            if ((tg->x == event->x) && (tg->y == event->y)) {
                v->fuel = event->fuel;  // on station: the visit goes on
                break;
            }
            // Off station during its visit: the visit is broken, as by a loss there.
            end_target(self, (uint16_t)busy, SVA_TARGET_LOST, at);
        }
        v->x = event->x;
        v->y = event->y;
        v->fuel = event->fuel;
        v->from_ticks = at;
        v->busy_with = -1;
        break;
    }
    case SVA_EVENT_TARGET_ADDED:
        self->mission.targets[self->mission.target_count] = event->target;
        self->target_state[self->mission.target_count] = (uint8_t)SVA_TARGET_WAITING;
        self->mission.target_count++;
        break;
    case SVA_EVENT_TARGET_CANCELLED:
        end_target(self, (uint16_t)sva_live_find_target(self, event->target.id),
                   SVA_TARGET_CANCELLED, at);
        break;
    case SVA_EVENT_TARGET_CHANGED: {
        const uint16_t i = (uint16_t)sva_live_find_target(self, event->target.id);
        // Fix the tracks flown so far before the target moves under them.
        for (uint16_t w = 0U; w < self->mission.uav_count; w++) {
            if (!self->priv.uavs[w].lost) {
                sva_live_rebase(self, w, at);
            }
        }
        self->mission.targets[i] = event->target;
        self->target_state[i] = (uint8_t)SVA_TARGET_WAITING;
        break;
    }
    case SVA_EVENT_CLOCK:
    case SVA_EVENT_COUNT_:
    default:
        break;
    }
    self->revision++;
    sva_live_advance(self, at);  // expired or not, with the event in
    return SVA_OK;
}

bool sva_live_uav_at(const sva_live_t* self, uint16_t uav, int32_t at_ticks, int32_t* x, int32_t* y,
                     int32_t* fuel, int32_t* ready_ticks)
{
    SVA_ASSERT((self != NULL) && (x != NULL) && (y != NULL) && (fuel != NULL) &&
               (ready_ticks != NULL));
    if ((self == NULL) || (uav >= self->mission.uav_count) || self->priv.uavs[uav].lost ||
        (at_ticks < self->now_ticks)) {
        return false;
    }
    sva_live_pos_t pos;
    sva_live_walk(self, uav, at_ticks, &pos, -1, NULL);
    *x = pos.x;
    *y = pos.y;
    *fuel = (int32_t)((pos.fuel < 0) ? 0 : pos.fuel);
    *ready_ticks = (int32_t)((pos.ready > SVA_MAX_TICK) ? SVA_MAX_TICK : pos.ready);
    return true;
}
