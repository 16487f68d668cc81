// Mission items of one planned route (sva_mavlink.h, docs/mavlink.md). No heap: the
// caller's array, the caller's geodesy.
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "common/mavlink.h"
#include "sva/sva_mavlink.h"

float sva_mavlink_speed(const sva_frame_t* frame, int32_t ticks_per_cell)
{
    double cell_m = (double)frame->cell_cm / 100.0;
    double tick_s = (double)frame->tick_ms / 1000.0;
    double alt_m = (double)frame->alt_cm / 100.0;
    double speed = cell_m / ((double)ticks_per_cell * tick_s);
    speed *= 1.0 + alt_m / SVA_MAVLINK_MIN_RADIUS_M;
    float f = (float)speed;
    if ((double)f < speed) {
        f = nextafterf(f, INFINITY);
    }
    return f;
}

static int64_t manhattan(int32_t ax, int32_t ay, int32_t bx, int32_t by)
{
    int64_t dx = (int64_t)ax - (int64_t)bx;
    int64_t dy = (int64_t)ay - (int64_t)by;
    return (dx < 0 ? -dx : dx) + (dy < 0 ? -dy : dy);
}

static int32_t to_e7(double deg)
{
    return (int32_t)lround(deg * 1e7);
}

static bool put(sva_mavlink_item_t* items, size_t capacity, size_t* n, uint16_t command,
                uint8_t frame, float p1, float p2, float p3, float p4, int32_t x, int32_t y,
                float z)
{
    if (*n >= capacity) {
        return false;
    }
    sva_mavlink_item_t* it = &items[*n];
    it->command = command;
    it->frame = frame;
    it->param1 = p1;
    it->param2 = p2;
    it->param3 = p3;
    it->param4 = p4;
    it->x = x;
    it->y = y;
    it->z = z;
    (*n)++;
    return true;
}

static size_t items_needed(size_t targets)
{
    return 3 + 2 * targets;
}

/// The builder's own bound (SVA_MAVLINK_MAX_ITEMS keeps one more for ArduPilot's home).
#define ROUTE_ITEMS_MAX (3 + 2 * SVA_MAVLINK_MAX_ROUTE_TARGETS)

sva_mavlink_status_t sva_mavlink_build(const sva_frame_t* frame, sva_frame_geodesy_t* geodesy,
                                       const sva_mavlink_route_t* route, sva_mavlink_item_t* items,
                                       size_t capacity, size_t* count, char* err, size_t err_size)
{
    if ((frame == NULL) || (route == NULL) || (items == NULL) || (count == NULL)) {
        return SVA_MAVLINK_ERR_ARGUMENT;
    }
    *count = 0;
    if (route->target_count == 0) {
        return SVA_MAVLINK_OK;
    }
    if (route->target_count > SVA_MAVLINK_MAX_ROUTE_TARGETS ||
        items_needed(route->target_count) > capacity) {
        snprintf(err, err_size,
                 "uav %d: route: %zu targets need %zu mission items, more than the limit %zu",
                 (int)route->uav_id, route->target_count, items_needed(route->target_count),
                 capacity < (size_t)ROUTE_ITEMS_MAX ? capacity : (size_t)ROUTE_ITEMS_MAX);
        return SVA_MAVLINK_ERR_LIMIT;
    }
    if (route->ticks_per_cell < 1) {
        snprintf(err, err_size, "uav %d: ticks_per_cell: must be >= 1, got %d", (int)route->uav_id,
                 (int)route->ticks_per_cell);
        return SVA_MAVLINK_ERR_INVALID;
    }
    float speed = sva_mavlink_speed(frame, route->ticks_per_cell);
    if (route->cruise_m_s > 0.0F) {
        if (route->cruise_m_s < speed) {
            snprintf(err, err_size,
                     "uav %d: cruise speed %.3g m/s is below the plan's speed %.3g m/s "
                     "(cell_m / (ticks_per_cell * tick_s), raised for the altitude)",
                     (int)route->uav_id, (double)route->cruise_m_s, (double)speed);
            return SVA_MAVLINK_ERR_INVALID;
        }
        speed = route->cruise_m_s;
    }
    const float alt = (float)frame->alt_cm / 100.0F;
    const uint8_t global = MAV_FRAME_GLOBAL_RELATIVE_ALT_INT;
    sva_frame_geo_t geo;
    size_t n = 0;
    if (!sva_frame_cell_to_geo(geodesy, route->x, route->y, &geo)) {
        snprintf(err, err_size, "uav %d: start cell (%d, %d): PROJ cannot convert it",
                 (int)route->uav_id, (int)route->x, (int)route->y);
        return SVA_MAVLINK_ERR_GEODESY;
    }
    (void)put(items, capacity, &n, MAV_CMD_NAV_TAKEOFF, global, 0.0F, 0.0F, 0.0F, NAN,
              to_e7(geo.lat_deg), to_e7(geo.lon_deg), alt);
    (void)put(items, capacity, &n, MAV_CMD_DO_CHANGE_SPEED, MAV_FRAME_MISSION, 1.0F, speed, -1.0F,
              0.0F, 0, 0, 0.0F);

    int32_t at_x = route->x;
    int32_t at_y = route->y;
    int64_t departure = route->ready_at;
    for (size_t i = 0; i < route->target_count; i++) {
        const sva_mavlink_target_t* t = &route->targets[i];
        int64_t travel = manhattan(at_x, at_y, t->x, t->y) * (int64_t)route->ticks_per_cell;
        if (departure + travel > (int64_t)t->start) {
            snprintf(err, err_size,
                     "uav %d: targets[%zu] (id %d): leaving at tick %lld and flying %lld ticks "
                     "arrives after the window's start %d",
                     (int)route->uav_id, i, (int)t->id, (long long)departure, (long long)travel,
                     (int)t->start);
            return SVA_MAVLINK_ERR_INVALID;
        }
        int64_t end_ms = sva_frame_tick_utc_ms(frame, t->end);
        int64_t dep_ms = sva_frame_tick_utc_ms(frame, departure);
        if (end_ms < 0 || end_ms > SVA_FRAME_MAX_T0_MS) {
            snprintf(err, err_size,
                     "uav %d: targets[%zu] (id %d).end: tick %d is outside the frame's UTC "
                     "range (1970 to 9999)",
                     (int)route->uav_id, i, (int)t->id, (int)t->end);
            return SVA_MAVLINK_ERR_INVALID;
        }
        if (end_ms - dep_ms >= SVA_MAVLINK_MAX_HOLD_MS) {
            snprintf(err, err_size,
                     "uav %d: targets[%zu] (id %d): from the departure at tick %lld to the "
                     "window's end %d is %lld ms, must be < 86400000 (MAV_CMD_NAV_DELAY holds "
                     "until a UTC time of day)",
                     (int)route->uav_id, i, (int)t->id, (long long)departure, (int)t->end,
                     (long long)(end_ms - dep_ms));
            return SVA_MAVLINK_ERR_INVALID;
        }
        if (!sva_frame_cell_to_geo(geodesy, t->x, t->y, &geo)) {
            snprintf(err, err_size, "uav %d: targets[%zu] (id %d): PROJ cannot convert (%d, %d)",
                     (int)route->uav_id, i, (int)t->id, (int)t->x, (int)t->y);
            return SVA_MAVLINK_ERR_GEODESY;
        }
        (void)put(items, capacity, &n, MAV_CMD_NAV_WAYPOINT, global, 0.0F, 0.0F, 0.0F, NAN,
                  to_e7(geo.lat_deg), to_e7(geo.lon_deg), alt);
        // the window's end rounded up to a whole second: the hold never ends early
        int64_t end_s = (end_ms + 999) / 1000;
        int64_t tod = end_s % 86400;
        int64_t hour = tod / 3600;
        int64_t minute = (tod / 60) % 60;
        int64_t second = tod % 60;
        (void)put(items, capacity, &n, MAV_CMD_NAV_DELAY, MAV_FRAME_MISSION, -1.0F, (float)hour,
                  (float)minute, (float)second, 0, 0, 0.0F);
        at_x = t->x;
        at_y = t->y;
        departure = t->end;
    }
    (void)put(items, capacity, &n, MAV_CMD_NAV_RETURN_TO_LAUNCH, MAV_FRAME_MISSION, 0.0F, 0.0F,
              0.0F, 0.0F, 0, 0, 0.0F);
    *count = n;
    return SVA_MAVLINK_OK;
}

// Equal values, or both NaN (the yaw parameters are NaN on purpose).
static bool same_float(float a, float b)
{
    return (a <= b && a >= b) || (isnan(a) && isnan(b));
}

static bool same_item(const sva_mavlink_item_t* a, const sva_mavlink_item_t* b)
{
    return a->command == b->command && a->frame == b->frame && same_float(a->param1, b->param1) &&
           same_float(a->param2, b->param2) && same_float(a->param3, b->param3) &&
           same_float(a->param4, b->param4) && a->x == b->x && a->y == b->y &&
           same_float(a->z, b->z);
}

bool sva_mavlink_same_remaining(const sva_mavlink_item_t* a, size_t a_count,
                                const sva_mavlink_item_t* b, size_t b_count)
{
    if (b_count == 0) {
        return true;  // nothing new to fly: the vehicle keeps what it has
    }
    if (a_count < 3 || b_count < 3) {
        return false;
    }
    size_t a_body = a_count - 2;
    size_t b_body = b_count - 2;
    if (b_body > a_body) {
        return false;
    }
    if (!same_item(&a[1], &b[1])) {
        return false;  // another speed
    }
    for (size_t i = 0; i < b_body; i++) {
        if (!same_item(&a[a_count - b_body + i], &b[2 + i])) {
            return false;
        }
    }
    return true;
}

bool sva_mavlink_same_items(const sva_mavlink_item_t* a, size_t a_count,
                            const sva_mavlink_item_t* b, size_t b_count)
{
    if (a_count != b_count) {
        return false;
    }
    for (size_t i = 0; i < a_count; i++) {
        if (!same_item(&a[i], &b[i])) {
            return false;
        }
    }
    return true;
}

bool sva_mavlink_prepend_home(sva_mavlink_item_t* items, size_t capacity, size_t* count)
{
    if (*count == 0 || *count >= capacity) {
        return false;
    }
    memmove(&items[1], &items[0], *count * sizeof items[0]);
    items[0] = items[1];
    items[0].command = MAV_CMD_NAV_WAYPOINT;
    items[0].param4 = 0.0F;
    items[0].z = 0.0F;
    (*count)++;
    return true;
}
