// lcm_node.c -- the LCM adapter's node: channels and subscriptions (contract in sva_lcm.h).
// The messages are handled a layer down: lcm_inputs.c (fleet, mission), lcm_live.c
// (events), lcm_reports.c (vehicle reports); lcm_status.c publishes the status.
#include "sva/sva_lcm.h"

#include "sva/sva_frame.h"

#include "lcm_internal.h"

#include <stdio.h>
#include <string.h>
#include <time.h>

// The .lcm files cannot include sva_config.h: their array sizes are literals, checked
// here so that a change on either side fails the build.
#define SVA_LCM_STATIC_ASSERT(cond, name) typedef char sva_lcm_static_assert_##name[(cond) ? 1 : -1]
SVA_LCM_STATIC_ASSERT(SVA_LCM_FLEET_STATE_T_MAX_UAVS == SVA_MAX_UAVS, fleet_max_uavs);
SVA_LCM_STATIC_ASSERT(SVA_LCM_MISSION_T_MAX_TARGETS == SVA_MAX_TARGETS, mission_max_targets);
SVA_LCM_STATIC_ASSERT(SVA_LCM_PLAN_T_MAX_UAVS == SVA_MAX_UAVS, plan_max_uavs);
SVA_LCM_STATIC_ASSERT(SVA_LCM_PLAN_T_MAX_TARGETS == SVA_MAX_TARGETS, plan_max_targets);
SVA_LCM_STATIC_ASSERT(SVA_LCM_PLAN_T_MAX_ROUTE_TARGETS == SVA_MAX_ROUTE_TARGETS,
                      plan_max_route_targets);
SVA_LCM_STATIC_ASSERT(SVA_LCM_PLAN_T_MAX_ROUTE_ITEMS >= SVA_MAX_ROUTE_TARGETS,
                      plan_route_items_hold_one_route);
SVA_LCM_STATIC_ASSERT(SVA_LCM_NODE_STATUS_T_NUM_REASONS == SVA_LCM_REJECT_COUNT_, reasons);
SVA_LCM_STATIC_ASSERT(SVA_LCM_NODE_STATUS_T_REJECT_TOO_LARGE == SVA_LCM_REJECT_TOO_LARGE,
                      reason_values);
SVA_LCM_STATIC_ASSERT(SVA_LCM_NODE_STATUS_T_REJECT_VERSION == SVA_LCM_REJECT_VERSION,
                      reason_version);
SVA_LCM_STATIC_ASSERT(SVA_LCM_REJECT_COUNT_ <= 32, reasons_fit_logged_mask);
// The plan must fit one udpm datagram (65499 bytes) with the longest channel name, so
// that it is never fragmented (fragments are allocated by the receiver).
SVA_LCM_STATIC_ASSERT(SVA_LCM_PLAN_BYTES + SVA_LCM_CHANNEL_SIZE <= 65499, plan_one_datagram);
SVA_LCM_STATIC_ASSERT(SVA_LCM_REPLAN_BYTES + SVA_LCM_CHANNEL_SIZE <= 65499, replan_one_datagram);
// event_t's TYPE_* are sva_event_type_t's numbers.
SVA_LCM_STATIC_ASSERT(SVA_LCM_EVENT_T_TYPE_POSITION == (int)SVA_EVENT_POSITION &&
                          SVA_EVENT_COUNT_ == 8,
                      event_type_numbers);
SVA_LCM_STATIC_ASSERT(SVA_LCM_REPLAN_T_MAX_CHANGES <= 32767, changes_fit_int16);
// Counts travel as int16_t.
SVA_LCM_STATIC_ASSERT(SVA_LCM_PLAN_T_MAX_ROUTE_ITEMS <= 32767, items_fit_int16);
// plan_t.lcm names the algorithm numbers in its comment on `algorithm`.
SVA_LCM_STATIC_ASSERT(SVA_ALGO_FLOW == 4 && SVA_ALGO_COUNT_ == 5, algorithm_numbers);

static int publish_lcm(void* user, const char* channel, const void* data, unsigned int size)
{
    return lcm_publish((lcm_t*)user, channel, data, size);
}

static bool make_channel(char* out, const char* prefix, const char* suffix)
{
    const size_t p = strlen(prefix);
    const size_t s = strlen(suffix);
    if ((p + s + 1U) > SVA_LCM_CHANNEL_SIZE) {
        return false;
    }
    memcpy(out, prefix, p);
    memcpy(out + p, suffix, s);
    out[p + s] = '\0';
    return true;
}

sva_status_t sva_lcm_node_init(sva_lcm_node_t* self, lcm_t* lcm, const char* prefix,
                               sva_algorithm_t algorithm)
{
    if ((self == NULL) || (prefix == NULL) || (strlen(prefix) > SVA_LCM_PREFIX_MAX) ||
        ((unsigned)algorithm >= (unsigned)SVA_ALGO_COUNT_)) {
        return SVA_ERR_ARGUMENT;
    }
    memset(self, 0, sizeof(*self));
    self->lcm = lcm;
    self->algorithm = algorithm;
    self->publish = publish_lcm;
    self->publish_user = lcm;
    if (!make_channel(self->channel_fleet, prefix, "FLEET") ||
        !make_channel(self->channel_mission, prefix, "MISSION") ||
        !make_channel(self->channel_plan, prefix, "PLAN") ||
        !make_channel(self->channel_status, prefix, "STATUS") ||
        !make_channel(self->channel_event, prefix, "EVENT") ||
        !make_channel(self->channel_replan, prefix, "REPLAN") ||
        !make_channel(self->channel_report, prefix, "REPORT")) {
        return SVA_ERR_ARGUMENT;
    }
    sva_diag_clear(&self->last_diag);
    sva_mission_init(&self->priv.mission);
    self->priv.fleet_revision = -1;
    self->priv.mission_revision = -1;
    self->track_tolerance_cells = SVA_LCM_TRACK_TOLERANCE_DEFAULT;
    return sva_planner_init(&self->priv.planner);
}

sva_status_t sva_lcm_channel_escape(const char* name, char* out, size_t size)
{
    if ((name == NULL) || (out == NULL)) {
        return SVA_ERR_ARGUMENT;
    }
    size_t n = 0;
    for (const char* c = name; *c != '\0'; ++c) {
        const bool plain = ((*c >= 'a') && (*c <= 'z')) || ((*c >= 'A') && (*c <= 'Z')) ||
                           ((*c >= '0') && (*c <= '9')) || (*c == '_');
        const size_t need = plain ? 1U : 2U;
        if ((n + need + 1U) > size) {
            if (size > 0U) {
                out[0] = '\0';
            }
            return SVA_ERR_ARGUMENT;
        }
        if (!plain) {
            out[n++] = '\\';
        }
        out[n++] = *c;
    }
    if (size == 0U) {
        return SVA_ERR_ARGUMENT;
    }
    out[n] = '\0';
    return SVA_OK;
}

static void on_fleet_raw(const lcm_recv_buf_t* rbuf, const char* channel, void* user)
{
    (void)channel;
    (void)sva_lcm_on_fleet((sva_lcm_node_t*)user, rbuf->data, rbuf->data_size);
}

static void on_mission_raw(const lcm_recv_buf_t* rbuf, const char* channel, void* user)
{
    (void)channel;
    (void)sva_lcm_on_mission((sva_lcm_node_t*)user, rbuf->data, rbuf->data_size);
}

static void on_event_raw(const lcm_recv_buf_t* rbuf, const char* channel, void* user)
{
    (void)channel;
    (void)sva_lcm_on_event((sva_lcm_node_t*)user, rbuf->data, rbuf->data_size);
}

static void on_report_raw(const lcm_recv_buf_t* rbuf, const char* channel, void* user)
{
    (void)channel;
    (void)sva_lcm_on_report((sva_lcm_node_t*)user, rbuf->data, rbuf->data_size);
}

sva_status_t sva_lcm_node_subscribe(sva_lcm_node_t* self)
{
    if ((self == NULL) || (self->lcm == NULL)) {
        return SVA_ERR_ARGUMENT;
    }
    // An escaped name can double in length.
    char regex[2 * SVA_LCM_CHANNEL_SIZE];
    if (sva_lcm_channel_escape(self->channel_fleet, regex, sizeof regex) != SVA_OK) {
        return SVA_ERR_ARGUMENT;
    }
    self->priv.sub_fleet = lcm_subscribe(self->lcm, regex, on_fleet_raw, self);
    if (sva_lcm_channel_escape(self->channel_mission, regex, sizeof regex) != SVA_OK) {
        sva_lcm_node_unsubscribe(self);
        return SVA_ERR_ARGUMENT;
    }
    self->priv.sub_mission = lcm_subscribe(self->lcm, regex, on_mission_raw, self);
    if (sva_lcm_channel_escape(self->channel_event, regex, sizeof regex) != SVA_OK) {
        sva_lcm_node_unsubscribe(self);
        return SVA_ERR_ARGUMENT;
    }
    self->priv.sub_event = lcm_subscribe(self->lcm, regex, on_event_raw, self);
    if (sva_lcm_channel_escape(self->channel_report, regex, sizeof regex) != SVA_OK) {
        sva_lcm_node_unsubscribe(self);
        return SVA_ERR_ARGUMENT;
    }
    self->priv.sub_report = lcm_subscribe(self->lcm, regex, on_report_raw, self);
    if ((self->priv.sub_fleet == NULL) || (self->priv.sub_mission == NULL) ||
        (self->priv.sub_event == NULL) || (self->priv.sub_report == NULL) ||
        (lcm_subscription_set_queue_capacity(self->priv.sub_report, SVA_LCM_QUEUE_CAPACITY) != 0) ||
        (lcm_subscription_set_queue_capacity(self->priv.sub_fleet, SVA_LCM_QUEUE_CAPACITY) != 0) ||
        (lcm_subscription_set_queue_capacity(self->priv.sub_mission, SVA_LCM_QUEUE_CAPACITY) !=
         0) ||
        (lcm_subscription_set_queue_capacity(self->priv.sub_event, SVA_LCM_QUEUE_CAPACITY) != 0)) {
        sva_lcm_node_unsubscribe(self);
        return SVA_ERR_ARGUMENT;
    }
    return SVA_OK;
}

void sva_lcm_node_unsubscribe(sva_lcm_node_t* self)
{
    if ((self == NULL) || (self->lcm == NULL)) {
        return;
    }
    if (self->priv.sub_fleet != NULL) {
        (void)lcm_unsubscribe(self->lcm, self->priv.sub_fleet);
        self->priv.sub_fleet = NULL;
    }
    if (self->priv.sub_mission != NULL) {
        (void)lcm_unsubscribe(self->lcm, self->priv.sub_mission);
        self->priv.sub_mission = NULL;
    }
    if (self->priv.sub_event != NULL) {
        (void)lcm_unsubscribe(self->lcm, self->priv.sub_event);
        self->priv.sub_event = NULL;
    }
    if (self->priv.sub_report != NULL) {
        (void)lcm_unsubscribe(self->lcm, self->priv.sub_report);
        self->priv.sub_report = NULL;
    }
}
