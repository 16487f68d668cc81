// live_track.c -- the flight model of a live mission (SPEC section 12.2): where each
// UAV is at a tick, the visits it has made, and every target's state as time passes.
#include "live_internal.h"

// The cell s steps from a towards b, x first, then y.
static void step_point(int32_t ax, int32_t ay, int32_t bx, int32_t by, int64_t s, int32_t* x,
                       int32_t* y)
{
    const int64_t x0 = ax;
    const int64_t y0 = ay;
    int64_t east = 1;
    int64_t north = 1;
    if ((int64_t)bx < x0) {
        east = -1;
    }
    if ((int64_t)by < y0) {
        north = -1;
    }
    const int64_t dx = ((int64_t)bx - x0) * east;
    if (s <= dx) {
        *x = (int32_t)(x0 + (s * east));
        *y = ay;
    } else {
        *x = bx;
        *y = (int32_t)(y0 + ((s - dx) * north));
    }
}

// On a leg from (x, y) left at `t` towards (bx, by): the UAV at `at` (< arrival). A
// cell's fuel is charged when its step starts, so a step in progress is paid for.
static void on_leg(int32_t x, int32_t y, int32_t bx, int32_t by, int64_t t, int64_t tpc,
                   int64_t fuel, int64_t at, sva_live_pos_t* out)
{
    const int64_t done = (at - t) / tpc;
    const int64_t steps = done + ((((at - t) % tpc) != 0) ? 1 : 0);
    step_point(x, y, bx, by, steps, &out->x, &out->y);
    out->from_x = x;
    out->from_y = y;
    out->fuel = fuel - steps;
    out->ready = t + (steps * tpc);
}

void sva_live_walk(const sva_live_t* self, uint16_t u, int64_t at_ticks, sva_live_pos_t* out,
                   int32_t probe, int64_t* arrival)
{
    int64_t at = at_ticks;  // -1 once the position is known
    out->x = self->priv.uavs[u].x;
    out->y = self->priv.uavs[u].y;
    out->from_x = out->x;
    out->from_y = out->y;
    out->fuel = self->priv.uavs[u].fuel;
    out->ready = self->priv.uavs[u].from_ticks;

    const sva_mission_t* m = &self->mission;
    const sva_live_uav_t* v = &self->priv.uavs[u];
    const int64_t tpc = m->ticks_per_cell;
    int32_t x = v->x;
    int32_t y = v->y;
    int64_t fuel = v->fuel;
    int64_t t = v->from_ticks;
    if (arrival != NULL) {
        *arrival = SVA_LIVE_NEVER;
    }
    out->busy_with = -1;
    out->next = 0U;
    if (at < t) {
        // Still finishing what the route starts with: a visit under way or a step.
        out->x = x;
        out->y = y;
        out->fuel = fuel;
        out->ready = t;
        out->busy_with = v->busy_with;
        at = -1;  // the position is known; the loop only looks for the probe
    }
    for (uint16_t k = 0U; k < v->route_count; k++) {
        const sva_target_t* tg = &m->targets[v->route[k]];
        const int64_t cells = sva_distance(x, y, tg->x, tg->y);
        const int64_t arrive = t + (cells * tpc);
        if ((int32_t)k == probe) {
            *arrival = arrive;
            if (at < 0) {
                return;
            }
        }
        if ((at >= 0) && (at < arrive)) {
            on_leg(x, y, tg->x, tg->y, t, tpc, fuel, at, out);
            out->next = k;
            at = -1;
        }
        x = tg->x;
        y = tg->y;
        fuel -= cells;
        if ((at >= 0) && (at < tg->start_ticks)) {
            out->x = x;
            out->y = y;
            out->from_x = x;
            out->from_y = y;
            out->fuel = fuel;
            out->ready = at;
            out->next = k;
            at = -1;
        }
        if (arrive <= tg->start_ticks) {
            // Present at the start: hovers (its fuel charged then) until the end.
            fuel -= m->hover_fuel;
            if ((at >= 0) && (at < tg->end_ticks)) {
                out->x = x;
                out->y = y;
                out->from_x = x;
                out->from_y = y;
                out->fuel = fuel;
                out->ready = tg->end_ticks;
                out->busy_with = (int32_t)v->route[k];
                out->next = (uint16_t)(k + 1U);
                at = -1;
            }
            t = tg->end_ticks;
        } else {
            t = arrive;  // too late to serve: it does not stop
        }
        if ((at < 0) && ((probe < 0) || ((int32_t)k >= probe))) {
            return;
        }
    }
    if (at < 0) {
        return;
    }
    // No work left: home to the depot.
    const int64_t cells = sva_distance(x, y, m->depot_x, m->depot_y);
    const int64_t arrive = t + (cells * tpc);
    out->next = v->route_count;
    if (at < arrive) {
        on_leg(x, y, m->depot_x, m->depot_y, t, tpc, fuel, at, out);
        return;
    }
    out->x = m->depot_x;
    out->y = m->depot_y;
    out->from_x = m->depot_x;
    out->from_y = m->depot_y;
    out->fuel = fuel - cells;
    // At home with nothing left: on the ground after the tick it got there (or was free
    // to leave), so it leaves again only after its take-off (SPEC section 12.2).
    out->ready = (at > arrive) ? (at + m->takeoff_ticks) : at;
}

void sva_live_route_remove(sva_live_uav_t* uav, uint16_t target)
{
    uint16_t kept = 0U;
    for (uint16_t k = 0U; k < uav->route_count; k++) {
        if (uav->route[k] != target) {
            uav->route[kept] = uav->route[k];
            kept++;
        }
    }
    uav->route_count = kept;
}

void sva_live_rebase(sva_live_t* self, uint16_t u, int64_t at)
{
    sva_live_uav_t* v = &self->priv.uavs[u];
    if (at < v->from_ticks) {
        return;  // the route has not started yet: nothing is behind it
    }
    sva_live_pos_t pos;
    sva_live_walk(self, u, at, &pos, -1, NULL);
    v->x = pos.x;
    v->y = pos.y;
    v->fuel = pos.fuel;
    v->from_ticks = pos.ready;
    v->busy_with = pos.busy_with;
    const uint16_t next = pos.next;
    for (uint16_t k = next; k < v->route_count; k++) {
        v->route[k - next] = v->route[k];
    }
    v->route_count = (uint16_t)(v->route_count - next);
}

// UAVs present for target i's whole window so far: in service, and either busy with it
// or on their way with an arrival by its start.
static int32_t present(const sva_live_t* self, uint16_t i)
{
    const sva_target_t* tg = &self->mission.targets[i];
    int32_t count = 0;
    for (uint16_t u = 0U; u < self->mission.uav_count; u++) {
        const sva_live_uav_t* v = &self->priv.uavs[u];
        if (v->lost) {
            continue;
        }
        if (v->busy_with == (int32_t)i) {
            count++;
            continue;
        }
        for (uint16_t k = 0U; k < v->route_count; k++) {
            if (v->route[k] == i) {
                int64_t arrival = SVA_LIVE_NEVER;
                sva_live_pos_t pos;
                sva_live_walk(self, u, -1, &pos, (int32_t)k, &arrival);
                count += (arrival <= tg->start_ticks) ? 1 : 0;
                break;
            }
        }
    }
    return count;
}

// UAVs in service that could still be at target i by its start, fuel home included.
static int32_t reachable(const sva_live_t* self, uint16_t i, int64_t at)
{
    const sva_mission_t* m = &self->mission;
    const sva_target_t* tg = &m->targets[i];
    const int64_t home = sva_distance(tg->x, tg->y, m->depot_x, m->depot_y);
    int32_t count = 0;
    for (uint16_t u = 0U; u < m->uav_count; u++) {
        if (self->priv.uavs[u].lost) {
            continue;
        }
        sva_live_pos_t pos;
        sva_live_walk(self, u, at, &pos, -1, NULL);
        const int64_t cells = sva_distance(pos.x, pos.y, tg->x, tg->y);
        const bool in_time = (pos.ready + (cells * m->ticks_per_cell)) <= tg->start_ticks;
        count += (in_time && ((cells + m->hover_fuel + home) <= pos.fuel)) ? 1 : 0;
    }
    return count;
}

sva_target_state_t sva_live_state_at(const sva_live_t* self, uint16_t i, int64_t at, bool reach)
{
    const sva_target_t* tg = &self->mission.targets[i];
    const sva_target_state_t state = (sva_target_state_t)self->target_state[i];
    switch (state) {
    case SVA_TARGET_UNDER_WAY:
        return (tg->end_ticks <= at) ? SVA_TARGET_DONE : SVA_TARGET_UNDER_WAY;
    case SVA_TARGET_WAITING:
    case SVA_TARGET_EXPIRED:
        if (tg->start_ticks <= at) {
            if ((state == SVA_TARGET_WAITING) && (present(self, i) >= tg->need)) {
                return (tg->end_ticks <= at) ? SVA_TARGET_DONE : SVA_TARGET_UNDER_WAY;
            }
            // SPEC 12.1: starting now, it may still be covered by UAVs already there.
            return (tg->start_ticks < at) ? SVA_TARGET_EXPIRED : state;
        }
        if (!reach) {
            return state;
        }
        return (reachable(self, i, at) >= tg->need) ? SVA_TARGET_WAITING : SVA_TARGET_EXPIRED;
    case SVA_TARGET_DONE:
    case SVA_TARGET_CANCELLED:
    case SVA_TARGET_LOST:
    case SVA_TARGET_STATE_COUNT_:
    default:
        return state;
    }
}

void sva_live_advance(sva_live_t* self, int64_t at)
{
    SVA_ASSERT(at >= self->now_ticks);
    for (uint16_t i = 0U; i < self->mission.target_count; i++) {
        self->target_state[i] = (uint8_t)sva_live_state_at(self, i, at, true);
    }
    // A UAV whose visit ended is no longer busy with it (the walk moves it on anyway).
    self->now_ticks = (int32_t)at;
}
