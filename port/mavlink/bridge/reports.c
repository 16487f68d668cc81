// sva_mavlink_bridge's reports (bridge.h): while a plan is held, one report_t per heard
// vehicle every report period on <prefix>REPORT, in the frame of the mission held. The
// bridge translates telemetry (sva_mavlink_report_make); what a report means for the
// mission is the node's rule. Changes of a vehicle's report status and health are
// printed, not every report.
#include <inttypes.h>
#include <stdio.h>
#include <string.h>

#include "bridge.h"
#include "sva_lcm_report_t.h"

/// report_t's encoded size (8-byte fingerprint and the fields), with room to spare.
#define REPORT_BYTES 64

static char channel[BRIDGE_CHANNEL_SIZE];
static int64_t period_ms;
static sva_mavlink_report_config_t config;

static bool holding;
static sva_frame_t frame;
static sva_frame_geodesy_t* geodesy;
static int64_t held_fleet_revision;
static int64_t held_mission_revision;
static int64_t next_ms;

void bridge_reports_configure(const bridge_options_t* o)
{
    snprintf(channel, sizeof channel, "%sREPORT", o->prefix);
    period_ms = o->report_ms;
    config.heartbeat_timeout_ms = (int32_t)o->heartbeat_timeout_ms;
    config.fuel_capacity_cells = (int32_t)o->fuel_capacity_cells;
}

void bridge_reports_release(void)
{
    holding = false;
    if (geodesy != NULL) {
        sva_frame_geodesy_close(geodesy);
        geodesy = NULL;
    }
}

// Field by field: sva_frame_t has padding before t0_ms, which memcmp would compare too.
static bool same_frame(const sva_frame_t* a, const sva_frame_t* b)
{
    return (a->lat_e7 == b->lat_e7) && (a->lon_e7 == b->lon_e7) && (a->alt_cm == b->alt_cm) &&
           (a->cell_cm == b->cell_cm) && (a->tick_ms == b->tick_ms) && (a->t0_ms == b->t0_ms);
}

void bridge_reports_hold(const sva_frame_t* f, int64_t fleet_revision, int64_t mission_revision,
                         int64_t now_ms)
{
    held_fleet_revision = fleet_revision;
    held_mission_revision = mission_revision;
    const bool same = holding && same_frame(&frame, f);
    if (!same) {
        bridge_reports_release();
        char err[SVA_FRAME_ERROR_SIZE];
        geodesy = sva_frame_geodesy_open(f, err, sizeof err);
        if (geodesy == NULL) {
            fprintf(stderr, "sva_mavlink_bridge: error: reports: %s\n", err);
            return;
        }
        frame = *f;
        next_ms = now_ms + period_ms;
    }
    holding = true;
}

void bridge_reports_on_fleet(int64_t revision)
{
    if (holding && revision != held_fleet_revision) {
        bridge_reports_release();
    }
}

void bridge_reports_on_mission(int64_t revision)
{
    if (holding && revision != held_mission_revision) {
        bridge_reports_release();
    }
}

static void publish(lcm_t* lcm, const sva_mavlink_report_t* r)
{
    sva_lcm_report_t msg;
    memset(&msg, 0, sizeof msg);
    msg.version = SVA_LCM_REPORT_T_VERSION;
    msg.uav_id = r->uav_id;
    msg.at_ticks = r->at_ticks;
    msg.health = (int8_t)(r->health == SVA_MAVLINK_HEALTH_LOST ? SVA_LCM_REPORT_T_HEALTH_LOST
                                                               : SVA_LCM_REPORT_T_HEALTH_OK);
    msg.x = r->x;
    msg.y = r->y;
    msg.fuel = r->fuel;
    msg.mission_seq = (int16_t)r->mission_seq;  // [-1, 32767] (sva_mavlink_report_t)
    msg.reached_seq = (int16_t)r->reached_seq;
    uint8_t buf[REPORT_BYTES];
    int n = sva_lcm_report_t_encode(buf, 0, (int)sizeof buf, &msg);
    if (n <= 0 || lcm_publish(lcm, channel, buf, (unsigned)n) != 0) {
        fprintf(stderr, "sva_mavlink_bridge: error: %s: cannot publish the report of uav %d\n",
                channel, (int)r->uav_id);
    }
}

// Prints what changed since the last report of the vehicle: why it has none, or its
// health (and why it is withheld).
static void say_changes(vehicle_slot_t* s, sva_mavlink_report_status_t status,
                        const sva_mavlink_report_t* r)
{
    char text[200];
    if (status != s->said_status) {
        if (status == SVA_MAVLINK_REPORT_OK) {
            snprintf(text, sizeof text, "reporting on %s", channel);
        } else {
            snprintf(text, sizeof text, "not reported: %s", sva_mavlink_report_status_text(status));
        }
        bridge_say(s, "", text);
        s->said_status = status;
    }
    if (status == SVA_MAVLINK_REPORT_OK &&
        (r->health != s->said_health || s->withheld != s->said_withheld)) {
        if (s->withheld == BRIDGE_HELD_REFUSED) {
            snprintf(text, sizeof text,
                     "LOST: an upload failed for good; withheld until it is silent for more than "
                     "%d ms, its link drops or it reboots, and is heard again",
                     (int)config.heartbeat_timeout_ms);
        } else if (s->withheld == BRIDGE_HELD_GONE) {
            snprintf(text, sizeof text,
                     "LOST: its link dropped, it rebooted or went silent after a failed upload: "
                     "no mission of ours is assumed; withheld until heard again");
        } else if (r->health == SVA_MAVLINK_HEALTH_LOST) {
            snprintf(text, sizeof text, "LOST: no HEARTBEAT for more than %d ms",
                     (int)config.heartbeat_timeout_ms);
        } else {
            snprintf(text, sizeof text, "OK: heard again");
        }
        bridge_say(s, "", text);
        s->said_health = r->health;
        s->said_withheld = s->withheld;
    }
}

// The withheld rule (bridge_withheld_t) at now_ms, before the vehicle's report: REFUSED
// turns GONE once the vehicle is silent past the heartbeat timeout (its drops and
// reboots are taken by vehicles.c); GONE is released once a LOST report of it went out
// (or none of it ever did: nothing to take back) and it is heard again: a report of its
// own, a fresh HEARTBEAT, and a SYSTEM_TIME heard since it went GONE (a position of the
// link or boot before could still be held until then).
static void apply_withheld_rule(vehicle_slot_t* s, sva_mavlink_report_status_t status,
                                const sva_mavlink_report_t* r, int64_t now_ms)
{
    const sva_mavlink_telemetry_t* t = &s->link.telemetry;
    if (s->withheld == BRIDGE_HELD_REFUSED && t->heard &&
        now_ms - t->heartbeat_host_ms > config.heartbeat_timeout_ms) {
        s->withheld = BRIDGE_HELD_GONE;
        s->gone_host_ms = now_ms;
        s->lost_said = false;
    }
    if (s->withheld == BRIDGE_HELD_GONE && (s->lost_said || !s->has_last) &&
        status == SVA_MAVLINK_REPORT_OK && r->health == SVA_MAVLINK_HEALTH_OK &&
        s->link.link == SVA_MAVLINK_LINK_UP && t->has_time_boot &&
        t->time_host_ms >= s->gone_host_ms) {
        s->withheld = BRIDGE_HELD_NO;
    }
}

int64_t bridge_reports_service(lcm_t* lcm, int64_t now_ms)
{
    if (!holding || geodesy == NULL) {
        return -1;
    }
    if (now_ms < next_ms) {
        return next_ms - now_ms;
    }
    for (size_t k = 0; k < bridge_slot_count; k++) {
        vehicle_slot_t* s = &bridge_slots[k];
        sva_mavlink_report_t r;
        sva_mavlink_report_status_t status = sva_mavlink_report_make(
            &s->link.telemetry, s->link.spec.uav_id, &frame, geodesy, &config, now_ms, &r);
        apply_withheld_rule(s, status, &r, now_ms);
        if (s->withheld != BRIDGE_HELD_NO && status != SVA_MAVLINK_REPORT_OK && s->has_last) {
            r = s->last;  // nothing of its own yet (a new boot): where it was last reported
            status = SVA_MAVLINK_REPORT_OK;
        }
        if (s->withheld != BRIDGE_HELD_NO && status == SVA_MAVLINK_REPORT_OK) {
            r.health = SVA_MAVLINK_HEALTH_LOST;
        }
        say_changes(s, status, &r);
        if (status == SVA_MAVLINK_REPORT_OK) {
            publish(lcm, &r);
            s->last = r;
            s->has_last = true;
            s->lost_said = s->lost_said || r.health == SVA_MAVLINK_HEALTH_LOST;
        }
    }
    // The period is kept even when a round is late (the loop wakes at least every 50 ms).
    next_ms += period_ms;
    if (next_ms <= now_ms) {
        next_ms = now_ms + period_ms;
    }
    return next_ms - now_ms;
}
