// live_report.c -- the one rule that turns what a vehicle says of itself into a live
// event (contract in sva.h, sva_live_report). Every path that hears vehicles uses it:
// the LCM node's fleet and vehicle reports, and through them the MAVLink telemetry.
#include "live_internal.h"

// How far v lies outside [min(a, b), max(a, b)] (0 inside).
static int64_t outside(int64_t v, int64_t a, int64_t b)
{
    int64_t lo = a;
    int64_t hi = b;
    if (b < a) {
        lo = b;
        hi = a;
    }
    int64_t out = 0;
    if (v < lo) {
        out = lo - v;
    } else if (v > hi) {
        out = v - hi;
    } else {
        // inside
    }
    return out;
}

// Rule 3 (sva.h): off the track the flight model flies, from the leg's origin to its end.
static bool off_track(const sva_live_t* self, uint16_t u, const sva_live_pos_t* pos,
                      const sva_report_t* report, int64_t tolerance)
{
    const sva_mission_t* m = &self->mission;
    const sva_live_uav_t* v = &self->priv.uavs[u];
    int32_t ex = m->depot_x;
    int32_t ey = m->depot_y;
    if (pos->busy_with >= 0) {
        ex = m->targets[pos->busy_with].x;
        ey = m->targets[pos->busy_with].y;
    } else if (pos->next < v->route_count) {
        ex = m->targets[v->route[pos->next]].x;
        ey = m->targets[v->route[pos->next]].y;
    } else {
        // no work left: home to the depot
    }
    if ((outside(report->x, pos->from_x, ex) > tolerance) ||
        (outside(report->y, pos->from_y, ey) > tolerance)) {
        return true;
    }
    const int64_t behind = (int64_t)sva_distance(report->x, report->y, ex, ey) -
                           (int64_t)sva_distance(pos->x, pos->y, ex, ey);
    return behind > tolerance;
}

bool sva_live_report(const sva_live_t* self, const sva_report_t* report,
                     int32_t track_tolerance_cells, sva_event_t* event)
{
    if ((self == NULL) || (report == NULL) || (event == NULL)) {
        return false;
    }
    const int32_t u = sva_live_find_uav(self, report->uav_id);
    if (u < 0) {
        return false;
    }
    const bool known_fuel = report->fuel != SVA_REPORT_FUEL_UNKNOWN;
    sva_event_t e;
    e.at_ticks = self->now_ticks;
    e.uav_id = report->uav_id;
    e.x = report->x;
    e.y = report->y;
    e.fuel = report->fuel;
    e.target.id = 0;
    e.target.x = 0;
    e.target.y = 0;
    e.target.start_ticks = 0;
    e.target.end_ticks = 0;
    e.target.need = 0;
    if (self->priv.uavs[u].lost) {
        if (!report->in_service) {
            return false;
        }
        e.type = SVA_EVENT_UAV_BACK;
        if (!known_fuel) {
            e.fuel = self->mission.uavs[u].fuel;
        }
        *event = e;
        return true;
    }
    if (!report->in_service) {
        e.type = SVA_EVENT_UAV_LOST;
        *event = e;
        return true;
    }
    sva_live_pos_t pos;
    sva_live_walk(self, (uint16_t)u, self->now_ticks, &pos, -1, NULL);
    const int64_t fuel_now = (pos.fuel < 0) ? 0 : pos.fuel;
    int64_t tolerance = track_tolerance_cells;
    if (tolerance < 0) {
        tolerance = 0;
    }
    if (off_track(self, (uint16_t)u, &pos, report, tolerance)) {
        e.type = SVA_EVENT_POSITION;
        if (!known_fuel) {
            e.fuel = (int32_t)fuel_now;
        }
        *event = e;
        return true;
    }
    if (!known_fuel) {
        return false;
    }
    sva_live_pos_t end;
    sva_live_walk(self, (uint16_t)u, (int64_t)SVA_MAX_TICK, &end, -1, NULL);
    const int64_t fuel_end = (end.fuel < 0) ? 0 : end.fuel;
    if ((int64_t)report->fuel >= (fuel_now - fuel_end)) {
        return false;
    }
    e.type = SVA_EVENT_FUEL;
    *event = e;
    return true;
}
