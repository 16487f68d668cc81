// Vehicle reports (sva_mavlink.h): telemetry in mission terms -- cell, tick, health,
// fuel. A translation only: what a report means for the mission is the node's rule.
#include <math.h>
#include <stdint.h>

#include "sva/sva_mavlink.h"

#define CM_PER_M    100.0
#define PERCENT_MAX 100

const char* sva_mavlink_report_status_text(sva_mavlink_report_status_t status)
{
    switch (status) {
    case SVA_MAVLINK_REPORT_OK:
        return "reported";
    case SVA_MAVLINK_REPORT_NEVER_HEARD:
        return "no HEARTBEAT heard yet";
    case SVA_MAVLINK_REPORT_NO_POSITION:
        return "no GLOBAL_POSITION_INT heard yet";
    case SVA_MAVLINK_REPORT_NO_GPS_TIME:
        return "no SYSTEM_TIME with a GPS time (time_unix_usec) heard yet";
    case SVA_MAVLINK_REPORT_NO_PLACE:
        return "the position cannot be placed in the mission frame";
    case SVA_MAVLINK_REPORT_CELL_RANGE:
        return "the position's cell is outside [-32768, 32767]";
    case SVA_MAVLINK_REPORT_TICK_RANGE:
        return "the GPS time is more than 2147483647 ticks after t0";
    default:
        return "an unknown report status";
    }
}

bool sva_mavlink_cell_of(double metres, int32_t cell_cm, int32_t* cell)
{
    if (cell_cm <= 0 || !isfinite(metres)) {
        return false;
    }
    const double cells = metres * CM_PER_M / (double)cell_cm;
    // Half away from zero (docs/flight-stack.md): 12.5 -> 13, -12.5 -> -13.
    const double rounded = cells >= 0.0 ? floor(cells + 0.5) : -floor(-cells + 0.5);
    if (!(rounded >= (double)SVA_MAVLINK_MIN_CELL && rounded <= (double)SVA_MAVLINK_MAX_CELL)) {
        return false;
    }
    *cell = (int32_t)rounded;
    return true;
}

sva_mavlink_report_status_t sva_mavlink_report_make(const sva_mavlink_telemetry_t* telemetry,
                                                    int32_t uav_id, const sva_frame_t* frame,
                                                    sva_frame_geodesy_t* geodesy,
                                                    const sva_mavlink_report_config_t* config,
                                                    int64_t now_host_ms, sva_mavlink_report_t* out)
{
    const sva_mavlink_telemetry_t* t = telemetry;
    if (!t->heard) {
        return SVA_MAVLINK_REPORT_NEVER_HEARD;
    }
    if (!t->has_position) {
        return SVA_MAVLINK_REPORT_NO_POSITION;
    }
    int64_t gps_ms = 0;
    if (!sva_mavlink_telemetry_gps_ms(t, &gps_ms)) {
        return SVA_MAVLINK_REPORT_NO_GPS_TIME;
    }
    double east_m = 0.0;
    double north_m = 0.0;
    if (!sva_frame_geo_to_enu(geodesy, (double)t->lat_e7 / 1e7, (double)t->lon_e7 / 1e7, &east_m,
                              &north_m)) {
        return SVA_MAVLINK_REPORT_NO_PLACE;
    }
    int32_t x = 0;
    int32_t y = 0;
    if (!sva_mavlink_cell_of(east_m, frame->cell_cm, &x) ||
        !sva_mavlink_cell_of(north_m, frame->cell_cm, &y)) {
        return SVA_MAVLINK_REPORT_CELL_RANGE;
    }
    // Before t0 is tick 0; gps_ms - t0_ms >= 0 below, so the division is floor.
    const int64_t since_t0_ms = gps_ms > frame->t0_ms ? gps_ms - frame->t0_ms : 0;
    const int64_t ticks = since_t0_ms / frame->tick_ms;
    if (ticks > INT32_MAX) {
        return SVA_MAVLINK_REPORT_TICK_RANGE;
    }
    out->uav_id = uav_id;
    out->at_ticks = (int32_t)ticks;
    out->health = now_host_ms - t->heartbeat_host_ms > config->heartbeat_timeout_ms
                      ? SVA_MAVLINK_HEALTH_LOST
                      : SVA_MAVLINK_HEALTH_OK;
    out->x = x;
    out->y = y;
    out->fuel =
        (config->fuel_capacity_cells > 0 && t->battery_percent >= 0)
            ? (int32_t)((int64_t)config->fuel_capacity_cells * t->battery_percent / PERCENT_MAX)
            : SVA_MAVLINK_UNKNOWN;
    out->mission_seq = t->mission_seq;
    out->reached_seq = t->reached_seq;
    return SVA_MAVLINK_REPORT_OK;
}
