// sva_mavlink_bridge's plans (bridge.h): FLEET, MISSION, PLAN and REPLAN from LCM
// (docs/lcm.md); every plan (complete or partial) that answers the fleet and mission it
// holds becomes mission items per UAV with a vehicle, uploaded; an accepted replan
// uploads only to the vehicles whose remaining route changed. One line per vehicle and
// plan on stdout; errors name the vehicle. A dispatched plan holds the reports' frame.
#include <inttypes.h>
#include <stdio.h>
#include <string.h>

#include "bridge.h"
#include "sva/sva_lcm.h"
#include "sva_lcm_fleet_state_t.h"
#include "sva_lcm_mission_t.h"
#include "sva_lcm_plan_t.h"
#include "sva_lcm_replan_t.h"

/// Messages waiting per subscription.
#define QUEUE_CAPACITY 64

static sva_lcm_fleet_state_t fleet;
static sva_lcm_mission_t mission;
static bool have_fleet;
static bool have_mission;
static sva_lcm_plan_t pending_plan;  // a plan whose inputs have not arrived yet
static bool have_pending;
static sva_lcm_replan_t replan;
static bool ardupilot;    // --ardupilot: a home item 0 first
static float cruise_m_s;  // --cruise-speed: the speed commanded (0: the plan's)
static sva_mavlink_target_t route_targets[SVA_MAVLINK_MAX_ROUTE_TARGETS];
static sva_mavlink_item_t built[SVA_MAVLINK_MAX_ITEMS];

static vehicle_slot_t* slot_of(int32_t uav_id)
{
    for (size_t i = 0; i < bridge_slot_count; i++) {
        if (bridge_slots[i].link.spec.uav_id == uav_id) {
            return &bridge_slots[i];
        }
    }
    return NULL;
}

static const sva_lcm_target_t* find_target(const sva_lcm_mission_t* m, int32_t id)
{
    for (int i = 0; i < m->target_count && i < SVA_LCM_MISSION_T_MAX_TARGETS; i++) {
        if (m->targets[i].id == id) {
            return &m->targets[i];
        }
    }
    return NULL;
}

static void say_vehicle(const vehicle_slot_t* s, int64_t plan_id, const char* text)
{
    char prefix[32];
    snprintf(prefix, sizeof prefix, "plan %" PRId64 ":", plan_id);
    bridge_say(s, prefix, text);
}

// Uploads items[0..count) for plan_id; targets[0..target_count) are its targets in
// visit order (none for a return home), kept for the changed-route rule.
static void start_upload(vehicle_slot_t* s, const sva_mavlink_item_t* items, size_t count,
                         const sva_mavlink_target_t* targets, size_t target_count, int64_t plan_id)
{
    memcpy(s->link.items, items, count * sizeof items[0]);
    s->link.item_count = count;
    if (ardupilot) {
        (void)sva_mavlink_prepend_home(s->link.items, SVA_MAVLINK_MAX_ITEMS, &s->link.item_count);
    }
    memcpy(s->flown, items, count * sizeof items[0]);
    s->flown_count = count;
    for (size_t k = 0; k < target_count; k++) {
        s->flown_target_ids[k] = targets[k].id;
        s->flown_target_starts[k] = targets[k].start;
    }
    s->flown_target_count = target_count;
    bridge_vehicles_upload(s, plan_id);
}

// The changed-route rule of a replan at now_ticks for a vehicle flying s->flown whose
// new route is items[0..count) over targets[0..target_count): unchanged when the new
// waypoints, holds and return are the last ones of what it has, its targets the last
// ones of the targets it has, and every target left out before them has a window that
// started by now_ticks (served or under way). A target left out whose window is still to
// come was not served: it is gone (cancelled), and the vehicle must not fly to it.
static bool same_remaining_route(const vehicle_slot_t* s, const sva_mavlink_item_t* items,
                                 size_t count, const sva_mavlink_target_t* targets,
                                 size_t target_count, int32_t now_ticks)
{
    if (!sva_mavlink_same_remaining(s->flown, s->flown_count, items, count)) {
        return false;
    }
    if (target_count > s->flown_target_count) {
        return false;
    }
    const size_t left_out = s->flown_target_count - target_count;
    for (size_t k = 0; k < target_count; k++) {
        if (s->flown_target_ids[left_out + k] != targets[k].id) {
            return false;
        }
    }
    for (size_t k = 0; k < left_out; k++) {
        if (s->flown_target_starts[k] > now_ticks) {
            return false;
        }
    }
    return true;
}

static bool in_list(const int32_t* uavs, int listed, int32_t uav_id)
{
    for (int i = 0; i < listed; i++) {
        if (uavs[i] == uav_id) {
            return true;
        }
    }
    return false;
}

// Builds and uploads the routes of plan p over fleet f and mission m (frame from m, or
// from frame_m when m has none). replan: the replan_t answered (changed-route rule), or
// NULL for a fresh plan (upload what differs from the vehicle's last mission).
static void dispatch(const sva_lcm_plan_t* p, const sva_lcm_fleet_state_t* f,
                     const sva_lcm_mission_t* m, const sva_lcm_mission_t* frame_m,
                     const sva_lcm_replan_t* rp)
{
    char err[SVA_MAVLINK_ERROR_SIZE];
    const sva_lcm_frame_t* lf = m->frame.present ? &m->frame : &frame_m->frame;
    if (!lf->present) {
        bridge_reports_release();
        for (size_t i = 0; i < bridge_slot_count; i++) {
            say_vehicle(&bridge_slots[i], p->plan_id,
                        "error: frame: the mission has none (mission_t.frame.present 0): cells "
                        "and ticks cannot be placed on the Earth; nothing uploaded");
        }
        return;
    }
    sva_frame_t frame = {lf->lat_e7, lf->lon_e7, lf->alt_cm, lf->cell_cm, lf->tick_ms, lf->t0_ms};
    if (sva_frame_check(&frame, err, sizeof err) != SVA_OK) {
        bridge_reports_release();
        for (size_t i = 0; i < bridge_slot_count; i++) {
            char text[SVA_MAVLINK_ERROR_SIZE + 32];
            snprintf(text, sizeof text, "error: %s; nothing uploaded", err);
            say_vehicle(&bridge_slots[i], p->plan_id, text);
        }
        return;
    }
    sva_frame_geodesy_t* geo = sva_frame_geodesy_open(&frame, err, sizeof err);
    if (geo == NULL) {
        bridge_reports_release();
        fprintf(stderr, "sva_mavlink_bridge: error: %s\n", err);
        return;
    }
    bridge_reports_hold(&frame, p->fleet_revision, p->mission_revision, sva_mavlink_now_ms());
    int offset = 0;
    for (int r = 0; r < p->route_count && r < SVA_LCM_PLAN_T_MAX_UAVS; r++) {
        const sva_lcm_route_t* route = &p->routes[r];
        int first = offset;
        offset += route->target_count;
        vehicle_slot_t* s = slot_of(route->uav_id);
        if (s == NULL) {
            continue;
        }
        const sva_lcm_uav_state_t* u = NULL;
        for (int k = 0; k < f->uav_count && k < SVA_LCM_FLEET_STATE_T_MAX_UAVS; k++) {
            if (f->uavs[k].id == route->uav_id) {
                u = &f->uavs[k];
            }
        }
        if (u == NULL || route->target_count < 0 || offset > p->item_count ||
            offset > SVA_LCM_PLAN_T_MAX_ROUTE_ITEMS) {
            say_vehicle(s, p->plan_id, "error: plan: the route does not match the fleet");
            continue;
        }
        size_t n = 0;
        bool ok = true;
        for (int k = first; k < offset && ok; k++) {
            const sva_lcm_target_t* t = find_target(m, p->route_targets[k]);
            if (t == NULL) {
                snprintf(err, sizeof err, "error: plan: target %d is not in the mission",
                         (int)p->route_targets[k]);
                say_vehicle(s, p->plan_id, err);
                ok = false;
            } else if (n == SVA_MAVLINK_MAX_ROUTE_TARGETS) {
                n++;  // the builder names the limit
            } else {
                route_targets[n].id = t->id;
                route_targets[n].x = t->x;
                route_targets[n].y = t->y;
                route_targets[n].start = t->start_ticks;
                route_targets[n].end = t->end_ticks;
                n++;
            }
        }
        if (!ok) {
            continue;
        }
        sva_mavlink_route_t rt = {route->uav_id,     u->x,          u->y, u->ready_at_ticks,
                                  m->ticks_per_cell, route_targets, n,    cruise_m_s};
        size_t count = 0;
        if (sva_mavlink_build(&frame, geo, &rt, built, SVA_MAVLINK_MAX_ITEMS, &count, err,
                              sizeof err) != SVA_MAVLINK_OK) {
            char text[SVA_MAVLINK_ERROR_SIZE + 32];
            snprintf(text, sizeof text, "error: %s; nothing uploaded", err);
            say_vehicle(s, p->plan_id, text);
            continue;
        }
        bool changed;
        if (rp != NULL) {
            changed = in_list(rp->dropped_uav, rp->dropped_listed, route->uav_id) ||
                      in_list(rp->added_uav, rp->added_listed, route->uav_id) ||
                      !same_remaining_route(s, built, count, route_targets, n, rp->now_ticks);
        } else {
            changed = !sva_mavlink_same_items(s->flown, s->flown_count, built, count);
        }
        if (s->withheld != BRIDGE_HELD_NO) {
            // reported LOST: the node replans its work when it takes the report; its next
            // mission comes from the plan after it is back
            say_vehicle(s, p->plan_id, "withheld (reported LOST), not uploaded");
            continue;
        }
        if (!changed) {
            say_vehicle(s, p->plan_id, "route unchanged, not uploaded");
            continue;
        }
        if (count == 0) {
            if (s->flown_count == 0) {
                say_vehicle(s, p->plan_id, "no targets, nothing to upload");
                continue;
            }
            // its targets were taken away: the new mission is to come home
            built[0].command = MAV_CMD_NAV_RETURN_TO_LAUNCH;
            built[0].frame = MAV_FRAME_MISSION;
            built[0].param1 = built[0].param2 = built[0].param3 = built[0].param4 = 0.0F;
            built[0].x = built[0].y = 0;
            built[0].z = 0.0F;
            count = 1;
        }
        start_upload(s, built, count, route_targets, n, p->plan_id);
    }
    sva_frame_geodesy_close(geo);
}

// A message (or a message inside one, `what`) of its type's version: true; else one
// line naming both versions on stderr and false (the adapter's check, sva_lcm.h).
static bool version_ok(const char* kind, const char* what, int got, int want)
{
    char err[200];
    if (sva_lcm_version_check(kind, what, got, want, "bridge", err, sizeof err) ==
        SVA_LCM_ACCEPTED) {
        return true;
    }
    fprintf(stderr, "sva_mavlink_bridge: %s; ignored\n", err);
    return false;
}

static bool plan_usable(const sva_lcm_plan_t* p)
{
    return p->status == SVA_LCM_PLAN_T_STATUS_COMPLETE ||
           p->status == SVA_LCM_PLAN_T_STATUS_PARTIAL;
}

static void try_pending(void)
{
    if (have_pending && have_fleet && have_mission &&
        pending_plan.fleet_revision == fleet.revision &&
        pending_plan.mission_revision == mission.revision) {
        have_pending = false;
        dispatch(&pending_plan, &fleet, &mission, &mission, NULL);
    }
}

static void on_fleet(const lcm_recv_buf_t* rbuf, const char* channel, void* user)
{
    (void)channel;
    (void)user;
    if (sva_lcm_fleet_state_t_decode(rbuf->data, 0, (int)rbuf->data_size, &fleet) !=
        (int)rbuf->data_size) {
        fprintf(stderr, "sva_mavlink_bridge: FLEET: not a fleet_state_t of this build; ignored\n");
        have_fleet = false;
        return;
    }
    if (!version_ok("FLEET", "fleet_state_t", fleet.version, SVA_LCM_FLEET_STATE_T_VERSION)) {
        have_fleet = false;
        return;
    }
    have_fleet = true;
    bridge_reports_on_fleet(fleet.revision);
    try_pending();
}

static void on_mission(const lcm_recv_buf_t* rbuf, const char* channel, void* user)
{
    (void)channel;
    (void)user;
    if (sva_lcm_mission_t_decode(rbuf->data, 0, (int)rbuf->data_size, &mission) !=
        (int)rbuf->data_size) {
        fprintf(stderr, "sva_mavlink_bridge: MISSION: not a mission_t of this build; ignored\n");
        have_mission = false;
        return;
    }
    if (!version_ok("MISSION", "mission_t", mission.version, SVA_LCM_MISSION_T_VERSION)) {
        have_mission = false;
        return;
    }
    have_mission = true;
    bridge_reports_on_mission(mission.revision);
    try_pending();
}

static void on_plan(const lcm_recv_buf_t* rbuf, const char* channel, void* user)
{
    (void)channel;
    (void)user;
    if (sva_lcm_plan_t_decode(rbuf->data, 0, (int)rbuf->data_size, &pending_plan) !=
        (int)rbuf->data_size) {
        fprintf(stderr, "sva_mavlink_bridge: PLAN: not a plan_t of this build; ignored\n");
        have_pending = false;
        return;
    }
    if (!version_ok("PLAN", "plan_t", pending_plan.version, SVA_LCM_PLAN_T_VERSION)) {
        have_pending = false;
        return;
    }
    if (!plan_usable(&pending_plan)) {
        printf("plan %" PRId64 ": status %d (not complete or partial): nothing uploaded\n",
               pending_plan.plan_id, (int)pending_plan.status);
        fflush(stdout);
        return;
    }
    have_pending = true;
    try_pending();
}

static void on_replan(const lcm_recv_buf_t* rbuf, const char* channel, void* user)
{
    (void)channel;
    (void)user;
    if (sva_lcm_replan_t_decode(rbuf->data, 0, (int)rbuf->data_size, &replan) !=
        (int)rbuf->data_size) {
        fprintf(stderr, "sva_mavlink_bridge: REPLAN: not a replan_t of this build; ignored\n");
        return;
    }
    if (!version_ok("REPLAN", "replan_t", replan.version, SVA_LCM_REPLAN_T_VERSION) ||
        !version_ok("REPLAN", "replan_t.residual_fleet", replan.residual_fleet.version,
                    SVA_LCM_FLEET_STATE_T_VERSION) ||
        !version_ok("REPLAN", "replan_t.residual_mission", replan.residual_mission.version,
                    SVA_LCM_MISSION_T_VERSION) ||
        !version_ok("REPLAN", "replan_t.plan", replan.plan.version, SVA_LCM_PLAN_T_VERSION)) {
        return;
    }
    if (!replan.accepted || !plan_usable(&replan.plan)) {
        printf("plan %" PRId64 ": replan of event %" PRId64 " %s: nothing uploaded\n",
               replan.plan.plan_id, replan.event_seq,
               replan.accepted ? "has no usable plan" : "was refused");
        fflush(stdout);
        return;
    }
    if (!have_mission) {
        fprintf(stderr, "sva_mavlink_bridge: REPLAN: no mission held yet; ignored\n");
        return;
    }
    dispatch(&replan.plan, &replan.residual_fleet, &replan.residual_mission, &mission, &replan);
}

bool bridge_plans_subscribe(lcm_t* lcm, const bridge_options_t* o)
{
    ardupilot = o->ardupilot;
    cruise_m_s = o->cruise_m_s;
    static const char* const names[] = {"FLEET", "MISSION", "PLAN", "REPLAN"};
    const lcm_msg_handler_t handlers[] = {on_fleet, on_mission, on_plan, on_replan};
    for (size_t k = 0; k < sizeof names / sizeof names[0]; k++) {
        char channel[BRIDGE_CHANNEL_SIZE * 2 + BRIDGE_SUFFIX_ROOM];
        // lcm_subscribe takes a regular expression: escape the prefix
        size_t n = 0;
        for (const char* c = o->prefix; *c != '\0'; c++) {
            if (strchr(".^$*+?()[]{}|\\", *c) != NULL) {
                channel[n++] = '\\';
            }
            channel[n++] = *c;
        }
        snprintf(channel + n, sizeof channel - n, "%s", names[k]);
        lcm_subscription_t* sub = lcm_subscribe(lcm, channel, handlers[k], NULL);
        if (sub == NULL || lcm_subscription_set_queue_capacity(sub, QUEUE_CAPACITY) != 0) {
            fprintf(stderr, "sva_mavlink_bridge: error: cannot subscribe to %s%s\n", o->prefix,
                    names[k]);
            return false;
        }
    }
    return true;
}
