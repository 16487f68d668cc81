// sva_lcm.c -- the LCM adapter: checks, converts and answers (contract in sva_lcm.h).
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

static const char* const reject_names[SVA_LCM_REJECT_COUNT_] = {
    "truncated", "trailing", "fingerprint", "count",   "value",
    "invalid",   "planner",  "too_large",   "version",
};

const char* sva_lcm_reject_name(sva_lcm_reject_t reason)
{
    if ((unsigned)reason >= (unsigned)SVA_LCM_REJECT_COUNT_) {
        return "";
    }
    return reject_names[reason];
}

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
    memcpy(out + p, suffix, s + 1U);
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

// ---------------------------------------------------------------------------------
// Rejection bookkeeping: counted always, logged once per reason.

static void logf_line(sva_lcm_node_t* self, const char* line)
{
    if (self->log != NULL) {
        self->log(self->log_user, line);
    }
}

sva_lcm_verdict_t sva_lcm_reject(sva_lcm_node_t* self, sva_lcm_reject_t reason, const char* what)
{
    self->last_reject = reason;
    self->counters.rejected[reason] += 1U;
    const uint32_t bit = (uint32_t)1U << (uint32_t)reason;
    if ((self->priv.logged & bit) == 0U) {
        self->priv.logged |= bit;
        char line[360];
        (void)snprintf(line, sizeof line,
                       "rejected (%s; further ones only counted in %.63s): %.239s",
                       sva_lcm_reject_name(reason), self->channel_status, what);
        logf_line(self, line);
    }
    return SVA_LCM_REJECTED;
}

static sva_lcm_verdict_t reject_diag(sva_lcm_node_t* self, sva_lcm_reject_t reason,
                                     const char* channel)
{
    char msg[160];
    char what[240];
    (void)sva_diag_format(&self->last_diag, msg, sizeof msg);
    (void)snprintf(what, sizeof what, "%.63s: %.159s", channel, msg);
    return sva_lcm_reject(self, reason, what);
}

// Range check of one field: fills *d and returns false when value is outside [lo, hi].
static bool in_range(sva_diag_t* d, sva_field_t field, int32_t index, int64_t value, int64_t lo,
                     int64_t hi, const char* hi_name)
{
    if (value < lo) {
        sva_diag_set(d, field, SVA_RULE_MIN, index, value, lo, NULL);
        return false;
    }
    if (value > hi) {
        sva_diag_set(d, field, SVA_RULE_MAX, index, value, hi, hi_name);
        return false;
    }
    return true;
}

// Size and fingerprint, before the generated decoder sees the bytes. Returns
// SVA_LCM_ACCEPTED when the bytes may be decoded.
sva_lcm_verdict_t sva_lcm_check_frame(sva_lcm_node_t* self, const char* channel, const void* data,
                                      size_t size, size_t want, int64_t fingerprint)
{
    char what[160];
    if ((data == NULL) || (size < want)) {
        (void)snprintf(what, sizeof what, "%s: %zu bytes, the type needs exactly %zu", channel,
                       size, want);
        return sva_lcm_reject(self, SVA_LCM_REJECT_TRUNCATED, what);
    }
    if (size > want) {
        (void)snprintf(what, sizeof what, "%s: %zu bytes, the type needs exactly %zu", channel,
                       size, want);
        return sva_lcm_reject(self, SVA_LCM_REJECT_TRAILING, what);
    }
    const uint8_t* b = (const uint8_t*)data;
    uint64_t got = 0;
    for (size_t i = 0; i < 8U; ++i) {
        got = (got << 8U) | (uint64_t)b[i];
    }
    if (got != (uint64_t)fingerprint) {
        (void)snprintf(what, sizeof what, "%s: fingerprint 0x%016llx, expected 0x%016llx", channel,
                       (unsigned long long)got, (unsigned long long)(uint64_t)fingerprint);
        return sva_lcm_reject(self, SVA_LCM_REJECT_FINGERPRINT, what);
    }
    return SVA_LCM_ACCEPTED;
}

// A decoded message's version field against the type's VERSION: a refusal names both.
bool sva_lcm_version_ok(sva_lcm_node_t* self, const char* channel, const char* type, int version,
                        int want, sva_lcm_verdict_t* verdict)
{
    if (version == want) {
        return true;
    }
    char what[160];
    (void)snprintf(what, sizeof what, "%.63s: %s.version is %d, this node speaks version %d",
                   channel, type, version, want);
    *verdict = sva_lcm_reject(self, SVA_LCM_REJECT_VERSION, what);
    return false;
}

// ---------------------------------------------------------------------------------
// Durable inputs (sva_lcm_input_fn) and the plan id sequence a journal restores.

bool sva_lcm_input_durable(sva_lcm_node_t* self, sva_lcm_input_t kind, bool restarts,
                           const void* data, size_t size)
{
    if (self->input_hook == NULL) {
        return true;
    }
    if (self->input_hook(self->input_hook_user, kind, restarts, data, size) == 0) {
        self->counters.inputs_hooked += 1U;
        return true;
    }
    self->halted = true;
    logf_line(self, "the input hook failed: halted, no answer is published from now on");
    return false;
}

sva_status_t sva_lcm_node_set_plan_id(sva_lcm_node_t* self, int64_t plan_id)
{
    if ((self == NULL) || (plan_id < 0)) {
        return SVA_ERR_ARGUMENT;
    }
    self->priv.plan_id = plan_id;
    return SVA_OK;
}

// ---------------------------------------------------------------------------------
// Planning and publishing.

static int64_t now_us(clockid_t clock)
{
    struct timespec ts;
    if (clock_gettime(clock, &ts) != 0) {
        return 0;
    }
    return ((int64_t)ts.tv_sec * 1000000) + ((int64_t)ts.tv_nsec / 1000);
}

static void plan_diag(sva_lcm_plan_t* p, const sva_diag_t* d)
{
    p->diag_field = (int8_t)d->field;
    p->diag_rule = (int8_t)d->rule;
    p->diag_index = d->index;
    p->diag_value = d->value;
    p->diag_limit = d->limit;
}

// Fills *p from a core plan over mission m; false when the routes need more than
// MAX_ROUTE_ITEMS items (then the caller clears the routes).
static bool fill_plan(sva_lcm_plan_t* p, const sva_plan_t* plan, const sva_mission_t* m)
{
    p->status = (plan->status == SVA_PLAN_COMPLETE) ? SVA_LCM_PLAN_T_STATUS_COMPLETE
                                                    : SVA_LCM_PLAN_T_STATUS_PARTIAL;
    p->covered = (int16_t)plan->covered;
    p->cost = plan->cost;
    p->uncovered_count = (int16_t)plan->uncovered_count;
    for (uint16_t i = 0; i < plan->uncovered_count; ++i) {
        p->uncovered[i] = m->targets[plan->uncovered[i]].id;
    }
    size_t items = 0;
    for (uint16_t r = 0; r < plan->route_count; ++r) {
        items += plan->routes[r].target_count;
    }
    if (items > (size_t)SVA_LCM_PLAN_T_MAX_ROUTE_ITEMS) {
        return false;
    }
    p->route_count = (int16_t)plan->route_count;
    size_t k = 0;
    for (uint16_t r = 0; r < plan->route_count; ++r) {
        const sva_route_t* src = &plan->routes[r];
        sva_lcm_route_t* dst = &p->routes[r];
        dst->uav_id = src->uav_id;
        dst->target_count = (int16_t)src->target_count;
        dst->stranded = src->stranded ? (int8_t)1 : (int8_t)0;
        dst->distance_cells = src->distance_cells;
        dst->fuel_used = src->fuel_used;
        for (uint16_t j = 0; j < src->target_count; ++j) {
            p->route_targets[k++] = m->targets[src->targets[j]].id;
        }
    }
    p->item_count = (int16_t)k;
    // flow's certificate: only with the routes it certifies (a TOO_LARGE plan has none,
    // and keeps the zeros replan's memset left).
    if (plan->stats.has_bound) {
        p->has_bound = 1;
        p->lower_bound = plan->stats.lower_bound;
        p->optimal = plan->stats.optimal ? (int8_t)1 : (int8_t)0;
        p->flow_incomplete = (int8_t)plan->stats.flow_incomplete;
    }
    return true;
}

static void publish_plan(sva_lcm_node_t* self)
{
    sva_lcm_plan_t* p = &self->priv.plan_tx;
    p->utime = now_us(CLOCK_REALTIME);
    const int n = sva_lcm_plan_t_encode(self->priv.plan_buf, 0, (int)sizeof self->priv.plan_buf, p);
    if ((n != SVA_LCM_PLAN_BYTES) || (self->publish(self->publish_user, self->channel_plan,
                                                    self->priv.plan_buf, (unsigned int)n) != 0)) {
        self->counters.publish_errors += 1U;
        return;
    }
    self->counters.plans_published += 1U;
}

static void replan(sva_lcm_node_t* self)
{
    sva_lcm_plan_t* p = &self->priv.plan_tx;
    // Every array is encoded in full: clear what the last plan left behind.
    memset(p, 0, sizeof(*p));
    self->priv.plan_id += 1;
    p->version = SVA_LCM_PLAN_T_VERSION;
    p->plan_id = self->priv.plan_id;
    p->fleet_revision = self->priv.fleet_revision;
    p->mission_revision = self->priv.mission_revision;
    p->algorithm = (int8_t)self->algorithm;

    sva_diag_t diag;
    sva_diag_clear(&diag);
    const int64_t t0 = now_us(CLOCK_MONOTONIC);
    const sva_status_t st = sva_plan(&self->priv.planner, &self->priv.mission, self->algorithm,
                                     &self->priv.plan, &diag);
    const int64_t dt = now_us(CLOCK_MONOTONIC) - t0;
    p->solve_us = (dt > (int64_t)INT32_MAX) ? INT32_MAX : (int32_t)dt;

    // The plan published starts the live mission (sva_live_init validates again; a
    // change_penalty or takeoff_ticks out of range fails here and leaves no live mission).
    self->priv.live_active = false;
    if (st == SVA_OK) {
        sva_diag_t live_diag;
        self->priv.mission.change_penalty = self->change_penalty;
        self->priv.mission.takeoff_ticks = self->takeoff_ticks;
        self->priv.live_active = (sva_live_init(&self->priv.live, &self->priv.mission,
                                                &self->priv.plan, &live_diag) == SVA_OK);
        if (!fill_plan(p, &self->priv.plan, &self->priv.mission)) {
            memset(p->routes, 0, sizeof p->routes);
            memset(p->route_targets, 0, sizeof p->route_targets);
            p->route_count = 0;
            p->item_count = 0;
            p->status = SVA_LCM_PLAN_T_STATUS_TOO_LARGE;
            char what[128];
            (void)snprintf(what, sizeof what,
                           "%s: plan needs more than MAX_ROUTE_ITEMS (%d) route items",
                           self->channel_plan, SVA_LCM_PLAN_T_MAX_ROUTE_ITEMS);
            (void)sva_lcm_reject(self, SVA_LCM_REJECT_TOO_LARGE, what);
        }
    } else {
        self->last_diag = diag;
        plan_diag(p, &diag);
        p->error_code = (int8_t)st;
        if (st == SVA_ERR_INVALID) {
            p->status = SVA_LCM_PLAN_T_STATUS_REJECTED;
            (void)reject_diag(self, SVA_LCM_REJECT_INVALID, "fleet+mission");
        } else {
            p->status = SVA_LCM_PLAN_T_STATUS_FAILED;
            (void)reject_diag(self, SVA_LCM_REJECT_PLANNER, "planner");
        }
    }
    publish_plan(self);
}

// ---------------------------------------------------------------------------------
// Inputs.

// The live mission's handlers (defined below, with the events).

static bool check_fleet(sva_lcm_node_t* self, sva_lcm_reject_t* reason, int32_t* bad_health)
{
    const sva_lcm_fleet_state_t* f = &self->priv.fleet_rx;
    sva_diag_t* d = &self->last_diag;
    if ((f->uav_count < 0) || (f->uav_count > SVA_LCM_FLEET_STATE_T_MAX_UAVS)) {
        sva_diag_set(d, SVA_FIELD_UAVS, SVA_RULE_COUNT, -1, f->uav_count, SVA_MAX_UAVS,
                     "SVA_MAX_UAVS");
        *reason = SVA_LCM_REJECT_COUNT;
        return false;
    }
    *reason = SVA_LCM_REJECT_VALUE;
    for (int32_t i = 0; i < (int32_t)f->uav_count; ++i) {
        const sva_lcm_uav_state_t* u = &f->uavs[i];
        if (!in_range(d, SVA_FIELD_UAV_ID, i, u->id, 1, SVA_MAX_ID, "SVA_MAX_ID") ||
            !in_range(d, SVA_FIELD_UAV_X, i, u->x, SVA_COORD_MIN, SVA_COORD_MAX, "SVA_COORD_MAX") ||
            !in_range(d, SVA_FIELD_UAV_Y, i, u->y, SVA_COORD_MIN, SVA_COORD_MAX, "SVA_COORD_MAX") ||
            !in_range(d, SVA_FIELD_UAV_FUEL, i, u->fuel, 0, SVA_MAX_FUEL, "SVA_MAX_FUEL") ||
            !in_range(d, SVA_FIELD_UAV_READY_AT, i, u->ready_at_ticks, 0, SVA_MAX_TICK,
                      "SVA_MAX_TICK")) {
            return false;
        }
        if ((u->health != SVA_LCM_UAV_STATE_T_HEALTH_OK) &&
            (u->health != SVA_LCM_UAV_STATE_T_HEALTH_UNAVAILABLE)) {
            // A wire-only field (no sva_field_t): described here, not by sva_diag_format.
            sva_diag_clear(d);
            *bad_health = i;
            return false;
        }
    }
    return true;
}

static bool check_mission(sva_lcm_node_t* self, sva_lcm_reject_t* reason)
{
    const sva_lcm_mission_t* m = &self->priv.mission_rx;
    sva_diag_t* d = &self->last_diag;
    if ((m->target_count < 0) || (m->target_count > SVA_LCM_MISSION_T_MAX_TARGETS)) {
        sva_diag_set(d, SVA_FIELD_TARGETS, SVA_RULE_COUNT, -1, m->target_count, SVA_MAX_TARGETS,
                     "SVA_MAX_TARGETS");
        *reason = SVA_LCM_REJECT_COUNT;
        return false;
    }
    *reason = SVA_LCM_REJECT_VALUE;
    if (!in_range(d, SVA_FIELD_DEPOT_X, -1, m->depot_x, SVA_COORD_MIN, SVA_COORD_MAX,
                  "SVA_COORD_MAX") ||
        !in_range(d, SVA_FIELD_DEPOT_Y, -1, m->depot_y, SVA_COORD_MIN, SVA_COORD_MAX,
                  "SVA_COORD_MAX") ||
        !in_range(d, SVA_FIELD_TICKS_PER_CELL, -1, m->ticks_per_cell, 1, SVA_MAX_TICKS_PER_CELL,
                  "SVA_MAX_TICKS_PER_CELL") ||
        !in_range(d, SVA_FIELD_HOVER_FUEL, -1, m->hover_fuel, 0, SVA_MAX_HOVER_FUEL,
                  "SVA_MAX_HOVER_FUEL") ||
        !in_range(d, SVA_FIELD_OVERLAP_PERCENT, -1, m->overlap_percent, 0, 100, NULL)) {
        return false;
    }
    for (int32_t i = 0; i < (int32_t)m->target_count; ++i) {
        const sva_lcm_target_t* t = &m->targets[i];
        if (!in_range(d, SVA_FIELD_TARGET_ID, i, t->id, 1, SVA_MAX_ID, "SVA_MAX_ID") ||
            !in_range(d, SVA_FIELD_TARGET_X, i, t->x, SVA_COORD_MIN, SVA_COORD_MAX,
                      "SVA_COORD_MAX") ||
            !in_range(d, SVA_FIELD_TARGET_Y, i, t->y, SVA_COORD_MIN, SVA_COORD_MAX,
                      "SVA_COORD_MAX") ||
            !in_range(d, SVA_FIELD_TARGET_START, i, t->start_ticks, 0, SVA_MAX_TICK - 1,
                      "SVA_MAX_TICK") ||
            !in_range(d, SVA_FIELD_TARGET_END, i, t->end_ticks, 1, SVA_MAX_TICK, "SVA_MAX_TICK") ||
            !in_range(d, SVA_FIELD_TARGET_NEED, i, t->need, 1, SVA_MAX_UAVS, "SVA_MAX_UAVS")) {
            return false;
        }
    }
    return true;
}

// A mission's frame: present 0 with every field 0, or present 1 with a frame that
// sva_frame_check accepts. False with one line in err naming the field, rule and limit.
static bool check_frame_fields(const sva_lcm_frame_t* w, char* err, size_t err_size)
{
    if (w->present == 0) {
        if ((w->lat_e7 != 0) || (w->lon_e7 != 0) || (w->alt_cm != 0) || (w->cell_cm != 0) ||
            (w->tick_ms != 0) || (w->t0_ms != 0)) {
            (void)snprintf(err, err_size, "frame: present is 0, every other field must be 0");
            return false;
        }
        return true;
    }
    if (w->present != 1) {
        (void)snprintf(err, err_size, "frame.present: must be 0 (no frame) or 1, got %d",
                       (int)w->present);
        return false;
    }
    sva_frame_t f;
    f.lat_e7 = w->lat_e7;
    f.lon_e7 = w->lon_e7;
    f.alt_cm = w->alt_cm;
    f.cell_cm = w->cell_cm;
    f.tick_ms = w->tick_ms;
    f.t0_ms = w->t0_ms;
    return sva_frame_check(&f, err, err_size);
}

sva_lcm_verdict_t sva_lcm_on_fleet(sva_lcm_node_t* self, const void* data, size_t size)
{
    if (self->halted) {
        return SVA_LCM_HALTED;
    }
    self->counters.fleet_rx += 1U;
    sva_lcm_verdict_t v =
        sva_lcm_check_frame(self, self->channel_fleet, data, size, SVA_LCM_FLEET_BYTES,
                            __sva_lcm_fleet_state_t_get_hash());
    if (v != SVA_LCM_ACCEPTED) {
        return v;
    }
    if (sva_lcm_fleet_state_t_decode(data, 0, (int)size, &self->priv.fleet_rx) != (int)size) {
        return sva_lcm_reject(self, SVA_LCM_REJECT_TRUNCATED, "fleet: decoder refused the bytes");
    }
    if (!sva_lcm_version_ok(self, self->channel_fleet, "fleet_state_t", self->priv.fleet_rx.version,
                            SVA_LCM_FLEET_STATE_T_VERSION, &v)) {
        return v;
    }
    sva_lcm_reject_t reason = SVA_LCM_REJECT_VALUE;
    int32_t bad_health = -1;
    if (!check_fleet(self, &reason, &bad_health)) {
        if (bad_health >= 0) {
            char what[160];
            (void)snprintf(what, sizeof what,
                           "%s: uavs[%ld].health: must be 0 (ok) or 1 (unavailable), got %d",
                           self->channel_fleet, (long)bad_health,
                           (int)self->priv.fleet_rx.uavs[bad_health].health);
            return sva_lcm_reject(self, reason, what);
        }
        return reject_diag(self, reason, self->channel_fleet);
    }
    if (self->priv.have_fleet && (memcmp(self->priv.fleet_raw, data, size) == 0)) {
        self->counters.unchanged += 1U;
        return SVA_LCM_UNCHANGED;
    }
    memcpy(self->priv.fleet_raw, data, size);
    const sva_lcm_fleet_state_t* f = &self->priv.fleet_rx;
    sva_mission_t* m = &self->priv.mission;
    m->uav_count = (uint16_t)f->uav_count;
    // Slots past the count cleared: the state is a function of the current inputs
    // alone, so a journal compacted to them replays to the same bytes.
    memset(&m->uavs[f->uav_count], 0, sizeof m->uavs[0] * (size_t)(SVA_MAX_UAVS - f->uav_count));
    for (int i = 0; i < (int)f->uav_count; ++i) {
        const sva_lcm_uav_state_t* u = &f->uavs[i];
        m->uavs[i].id = u->id;
        m->uavs[i].x = u->x;
        m->uavs[i].y = u->y;
        m->uavs[i].fuel = u->fuel;
        // An unavailable UAV keeps its place in the plan (SPEC 3: one route per UAV, in
        // order) but can reach no window: every start is < SVA_MAX_TICK.
        m->uavs[i].ready_at_ticks = (u->health == SVA_LCM_UAV_STATE_T_HEALTH_OK)
                                        ? u->ready_at_ticks
                                        : (int32_t)SVA_MAX_TICK;
    }
    self->priv.fleet_revision = f->revision;
    self->priv.have_fleet = true;
    const bool report = self->fleet_reports && self->priv.live_active;
    if (!sva_lcm_input_durable(self, SVA_LCM_INPUT_FLEET, !report, data, size)) {
        return SVA_LCM_HALTED;
    }
    if (report) {
        sva_lcm_fleet_report(self);
    } else if (self->priv.have_mission) {
        replan(self);
    }
    return SVA_LCM_ACCEPTED;
}

sva_lcm_verdict_t sva_lcm_on_mission(sva_lcm_node_t* self, const void* data, size_t size)
{
    if (self->halted) {
        return SVA_LCM_HALTED;
    }
    self->counters.mission_rx += 1U;
    sva_lcm_verdict_t v =
        sva_lcm_check_frame(self, self->channel_mission, data, size, SVA_LCM_MISSION_BYTES,
                            __sva_lcm_mission_t_get_hash());
    if (v != SVA_LCM_ACCEPTED) {
        return v;
    }
    if (sva_lcm_mission_t_decode(data, 0, (int)size, &self->priv.mission_rx) != (int)size) {
        return sva_lcm_reject(self, SVA_LCM_REJECT_TRUNCATED, "mission: decoder refused the bytes");
    }
    if (!sva_lcm_version_ok(self, self->channel_mission, "mission_t", self->priv.mission_rx.version,
                            SVA_LCM_MISSION_T_VERSION, &v)) {
        return v;
    }
    sva_lcm_reject_t reason = SVA_LCM_REJECT_VALUE;
    if (!check_mission(self, &reason)) {
        return reject_diag(self, reason, self->channel_mission);
    }
    char frame_err[SVA_FRAME_ERROR_SIZE];
    if (!check_frame_fields(&self->priv.mission_rx.frame, frame_err, sizeof frame_err)) {
        char what[240];
        (void)snprintf(what, sizeof what, "%.63s: %.159s", self->channel_mission, frame_err);
        return sva_lcm_reject(self, SVA_LCM_REJECT_VALUE, what);
    }
    if (self->priv.have_mission && (memcmp(self->priv.mission_raw, data, size) == 0)) {
        self->counters.unchanged += 1U;
        return SVA_LCM_UNCHANGED;
    }
    memcpy(self->priv.mission_raw, data, size);
    const sva_lcm_mission_t* w = &self->priv.mission_rx;
    sva_mission_t* m = &self->priv.mission;
    m->depot_x = w->depot_x;
    m->depot_y = w->depot_y;
    m->ticks_per_cell = w->ticks_per_cell;
    m->hover_fuel = w->hover_fuel;
    m->overlap_percent = w->overlap_percent;
    m->target_count = (uint16_t)w->target_count;
    memset(&m->targets[w->target_count], 0,
           sizeof m->targets[0] * (size_t)(SVA_MAX_TARGETS - w->target_count));
    for (int i = 0; i < (int)w->target_count; ++i) {
        const sva_lcm_target_t* t = &w->targets[i];
        m->targets[i].id = t->id;
        m->targets[i].x = t->x;
        m->targets[i].y = t->y;
        m->targets[i].start_ticks = t->start_ticks;
        m->targets[i].end_ticks = t->end_ticks;
        m->targets[i].need = t->need;
    }
    self->priv.frame = w->frame;
    self->priv.mission_revision = w->revision;
    self->priv.have_mission = true;
    if (!sva_lcm_input_durable(self, SVA_LCM_INPUT_MISSION, true, data, size)) {
        return SVA_LCM_HALTED;
    }
    if (self->priv.have_fleet) {
        replan(self);
    }
    return SVA_LCM_ACCEPTED;
}

// ---------------------------------------------------------------------------------
// The live mission: events in, replans out.

static void publish_replan(sva_lcm_node_t* self)
{
    sva_lcm_replan_t* r = &self->priv.replan_tx;
    r->plan.utime = now_us(CLOCK_REALTIME);
    const int n =
        sva_lcm_replan_t_encode(self->priv.replan_buf, 0, (int)sizeof self->priv.replan_buf, r);
    if ((n != SVA_LCM_REPLAN_BYTES) ||
        (self->publish(self->publish_user, self->channel_replan, self->priv.replan_buf,
                       (unsigned int)n) != 0)) {
        self->counters.publish_errors += 1U;
        return;
    }
    self->counters.replans_published += 1U;
}

// Answers the event in replan_tx (its header already set) as refused: `text` names the
// field, the rule and the limit; diag (may be NULL) gives the fields. Counts and logs the
// refusal as `reason`, publishes, and leaves the live mission as it was.
static sva_lcm_verdict_t refuse_event(sva_lcm_node_t* self, sva_lcm_reject_t reason,
                                      const sva_diag_t* diag, const char* text)
{
    sva_lcm_replan_t* r = &self->priv.replan_tx;
    r->accepted = 0;
    if (diag != NULL) {
        r->diag_field = (int8_t)diag->field;
        r->diag_rule = (int8_t)diag->rule;
        r->diag_value = diag->value;
        r->diag_limit = diag->limit;
        plan_diag(&r->plan, diag);
    }
    for (size_t i = 0; (i + 1U < (size_t)SVA_LCM_REPLAN_T_DIAG_TEXT_SIZE) && (text[i] != '\0');
         ++i) {
        r->diag_text[i] = (int8_t)text[i];
    }
    r->plan.status = SVA_LCM_PLAN_T_STATUS_REJECTED;
    r->plan.version = SVA_LCM_PLAN_T_VERSION;
    r->plan.algorithm = (int8_t)self->algorithm;
    r->plan.fleet_revision = self->priv.fleet_revision;
    r->plan.mission_revision = self->priv.mission_revision;
    const sva_lcm_verdict_t v = sva_lcm_reject(self, reason, text);
    publish_replan(self);
    return v;
}

// The residual mission as wire messages (stamped with the live revision).
static void fill_residual(sva_lcm_replan_t* r, const sva_mission_t* m, int64_t revision,
                          const sva_lcm_frame_t* frame)
{
    sva_lcm_fleet_state_t* f = &r->residual_fleet;
    f->version = SVA_LCM_FLEET_STATE_T_VERSION;
    f->revision = revision;
    f->uav_count = (int16_t)m->uav_count;
    for (uint16_t u = 0; u < m->uav_count; ++u) {
        sva_lcm_uav_state_t* w = &f->uavs[u];
        w->id = m->uavs[u].id;
        w->x = m->uavs[u].x;
        w->y = m->uavs[u].y;
        w->fuel = m->uavs[u].fuel;
        w->ready_at_ticks = m->uavs[u].ready_at_ticks;
        w->health = SVA_LCM_UAV_STATE_T_HEALTH_OK;
    }
    sva_lcm_mission_t* w = &r->residual_mission;
    w->version = SVA_LCM_MISSION_T_VERSION;
    w->revision = revision;
    w->depot_x = m->depot_x;
    w->depot_y = m->depot_y;
    w->ticks_per_cell = m->ticks_per_cell;
    w->hover_fuel = m->hover_fuel;
    w->overlap_percent = m->overlap_percent;
    w->target_count = (int16_t)m->target_count;
    for (uint16_t i = 0; i < m->target_count; ++i) {
        sva_lcm_target_t* t = &w->targets[i];
        t->id = m->targets[i].id;
        t->x = m->targets[i].x;
        t->y = m->targets[i].y;
        t->start_ticks = m->targets[i].start_ticks;
        t->end_ticks = m->targets[i].end_ticks;
        t->need = m->targets[i].need;
    }
    w->frame = *frame;
}

// Lists the (UAV id, target id) pairs of `from` that `to` lacks (sva_plan_changes), the
// first MAX_CHANGES of them, into uav[] and target[]; returns how many were listed.
static int16_t list_changes(const sva_plan_t* from, const sva_plan_t* to, const sva_mission_t* m,
                            int32_t* uav, int32_t* target)
{
    sva_visit_t visits[SVA_LCM_REPLAN_T_MAX_CHANGES];
    const uint32_t n = sva_plan_changes(from, to, visits, SVA_LCM_REPLAN_T_MAX_CHANGES);
    const uint32_t listed = (n < SVA_LCM_REPLAN_T_MAX_CHANGES) ? n : SVA_LCM_REPLAN_T_MAX_CHANGES;
    for (uint32_t i = 0; i < listed; ++i) {
        uav[i] = from->routes[visits[i].route].uav_id;
        target[i] = m->targets[visits[i].target].id;
    }
    return (int16_t)listed;
}

// Every message a replan carries names its version, also when it is empty.
void sva_lcm_stamp_replan_versions(sva_lcm_replan_t* r)
{
    r->version = SVA_LCM_REPLAN_T_VERSION;
    r->residual_fleet.version = SVA_LCM_FLEET_STATE_T_VERSION;
    r->residual_mission.version = SVA_LCM_MISSION_T_VERSION;
    r->plan.version = SVA_LCM_PLAN_T_VERSION;
}

sva_lcm_verdict_t sva_lcm_on_event(sva_lcm_node_t* self, const void* data, size_t size)
{
    if (self->halted) {
        return SVA_LCM_HALTED;
    }
    self->counters.event_rx += 1U;
    const sva_lcm_verdict_t v = sva_lcm_check_frame(
        self, self->channel_event, data, size, SVA_LCM_EVENT_BYTES, __sva_lcm_event_t_get_hash());
    if (v != SVA_LCM_ACCEPTED) {
        return v;
    }
    sva_lcm_event_t* e = &self->priv.event_rx;
    if (sva_lcm_event_t_decode(data, 0, (int)size, e) != (int)size) {
        return sva_lcm_reject(self, SVA_LCM_REJECT_TRUNCATED, "event: decoder refused the bytes");
    }
    sva_lcm_replan_t* r = &self->priv.replan_tx;
    // Every array is encoded in full: clear what the last answer left behind.
    memset(r, 0, sizeof(*r));
    sva_lcm_stamp_replan_versions(r);
    r->event_seq = e->seq;
    r->event_type = e->type;
    r->change_penalty = self->change_penalty;
    if (self->priv.live_active) {
        r->now_ticks = self->priv.live.now_ticks;
        r->revision = (int64_t)self->priv.live.revision;
    }
    char text[SVA_LCM_REPLAN_T_DIAG_TEXT_SIZE];
    if (e->version != SVA_LCM_EVENT_T_VERSION) {
        (void)snprintf(text, sizeof text,
                       "%.63s: event_t.version is %d, this node speaks version %d",
                       self->channel_event, (int)e->version, (int)SVA_LCM_EVENT_T_VERSION);
        return refuse_event(self, SVA_LCM_REJECT_VERSION, NULL, text);
    }
    if (!self->priv.live_active) {
        (void)snprintf(text, sizeof text,
                       "%.63s: no live mission: a fleet and a mission must be planned first",
                       self->channel_event);
        return refuse_event(self, SVA_LCM_REJECT_VALUE, NULL, text);
    }
    sva_diag_t diag;
    sva_diag_clear(&diag);
    char msg[128];
    if (!in_range(&diag, SVA_FIELD_EVENT_TYPE, -1, e->type, 0, (int64_t)SVA_EVENT_COUNT_ - 1,
                  NULL)) {
        (void)sva_diag_format(&diag, msg, sizeof msg);
        (void)snprintf(text, sizeof text, "%.31s: %.126s", self->channel_event, msg);
        return refuse_event(self, SVA_LCM_REJECT_VALUE, &diag, text);
    }
    sva_event_t ev;
    memset(&ev, 0, sizeof ev);
    ev.type = (sva_event_type_t)e->type;
    ev.at_ticks = e->at_ticks;
    ev.uav_id = e->uav_id;
    ev.x = e->x;
    ev.y = e->y;
    ev.fuel = e->fuel;
    ev.target.id = e->target.id;
    ev.target.x = e->target.x;
    ev.target.y = e->target.y;
    ev.target.start_ticks = e->target.start_ticks;
    ev.target.end_ticks = e->target.end_ticks;
    ev.target.need = e->target.need;
    sva_live_t* live = &self->priv.live;
    if (sva_live_apply(live, &ev, &diag) != SVA_OK) {
        self->last_diag = diag;
        (void)sva_diag_format(&diag, msg, sizeof msg);
        (void)snprintf(text, sizeof text, "%.31s: %.126s", self->channel_event, msg);
        return refuse_event(self, SVA_LCM_REJECT_INVALID, &diag, text);
    }
    if (!sva_lcm_input_durable(self, SVA_LCM_INPUT_EVENT, false, data, size)) {
        return SVA_LCM_HALTED;
    }
    sva_lcm_replan_live(self);
    return SVA_LCM_ACCEPTED;
}

// Replans the live mission after applied events and publishes the replan (header set).
void sva_lcm_replan_live(sva_lcm_node_t* self)
{
    sva_lcm_replan_t* r = &self->priv.replan_tx;
    sva_live_t* live = &self->priv.live;
    sva_diag_t diag;
    sva_diag_clear(&diag);
    char msg[128];
    char text[SVA_LCM_REPLAN_T_DIAG_TEXT_SIZE];
    r->accepted = 1;
    self->priv.plan_id += 1;
    sva_lcm_plan_t* p = &r->plan;
    p->version = SVA_LCM_PLAN_T_VERSION;
    p->plan_id = self->priv.plan_id;
    p->fleet_revision = self->priv.fleet_revision;
    p->mission_revision = self->priv.mission_revision;
    p->algorithm = (int8_t)self->algorithm;
    sva_live_result_t* res = &self->priv.live_result;
    const int64_t t0 = now_us(CLOCK_MONOTONIC);
    const sva_status_t st = sva_live_replan(live, &self->priv.planner, self->algorithm, res, &diag);
    const int64_t dt = now_us(CLOCK_MONOTONIC) - t0;
    p->solve_us = (dt > (int64_t)INT32_MAX) ? INT32_MAX : (int32_t)dt;
    r->now_ticks = live->now_ticks;
    r->revision = (int64_t)live->revision;
    if (st != SVA_OK) {
        // The event stands; the plan in force stays as it was (sva_live_replan).
        self->last_diag = diag;
        plan_diag(p, &diag);
        p->error_code = (int8_t)st;
        p->status = SVA_LCM_PLAN_T_STATUS_FAILED;
        (void)sva_diag_format(&diag, msg, sizeof msg);
        (void)snprintf(text, sizeof text, "%.31s: %.126s", self->channel_replan, msg);
        for (size_t i = 0; (i + 1U < sizeof text) && (text[i] != '\0'); ++i) {
            r->diag_text[i] = (int8_t)text[i];
        }
        (void)sva_lcm_reject(self, SVA_LCM_REJECT_PLANNER, text);
        publish_replan(self);
        return;
    }
    r->kept = res->kept ? (int8_t)1 : (int8_t)0;
    r->under_way = (int16_t)res->under_way;
    r->covered = (int16_t)res->covered;
    r->objective = res->objective;
    r->dropped = (int32_t)res->dropped;
    r->added = (int32_t)res->added;
    r->dropped_listed =
        list_changes(res->previous, res->plan, res->residual, r->dropped_uav, r->dropped_target);
    r->added_listed =
        list_changes(res->plan, res->previous, res->residual, r->added_uav, r->added_target);
    fill_residual(r, res->residual, r->revision, &self->priv.frame);
    if (!fill_plan(p, res->plan, res->residual)) {
        memset(p->routes, 0, sizeof p->routes);
        memset(p->route_targets, 0, sizeof p->route_targets);
        p->route_count = 0;
        p->item_count = 0;
        p->status = SVA_LCM_PLAN_T_STATUS_TOO_LARGE;
        (void)sva_lcm_reject(self, SVA_LCM_REJECT_TOO_LARGE,
                             "replan: plan needs more than MAX_ROUTE_ITEMS");
    }
    publish_replan(self);
}

sva_status_t sva_lcm_publish_status(sva_lcm_node_t* self, int64_t utime)
{
    sva_lcm_node_status_t* s = &self->priv.status_tx;
    memset(s, 0, sizeof(*s));
    self->counters.status_seq += 1U;
    s->version = SVA_LCM_NODE_STATUS_T_VERSION;
    s->utime = utime;
    s->seq = (int64_t)self->counters.status_seq;
    s->state = (self->priv.have_fleet && self->priv.have_mission)
                   ? SVA_LCM_NODE_STATUS_T_STATE_READY
                   : SVA_LCM_NODE_STATUS_T_STATE_WAITING;
    s->algorithm = (int8_t)self->algorithm;
    s->fleet_revision = self->priv.have_fleet ? self->priv.fleet_revision : -1;
    s->mission_revision = self->priv.have_mission ? self->priv.mission_revision : -1;
    s->last_plan_id = (self->priv.plan_id > 0) ? self->priv.plan_id : -1;
    s->fleet_rx = (int64_t)self->counters.fleet_rx;
    s->mission_rx = (int64_t)self->counters.mission_rx;
    s->plans_published = (int64_t)self->counters.plans_published;
    s->unchanged = (int64_t)self->counters.unchanged;
    for (int r = 0; r < (int)SVA_LCM_REJECT_COUNT_; ++r) {
        s->rejected[r] = (self->counters.rejected[r] > (uint32_t)INT32_MAX)
                             ? INT32_MAX
                             : (int32_t)self->counters.rejected[r];
    }
    const int n = sva_lcm_node_status_t_encode(self->priv.status_buf, 0,
                                               (int)sizeof self->priv.status_buf, s);
    if ((n != SVA_LCM_STATUS_BYTES) ||
        (self->publish(self->publish_user, self->channel_status, self->priv.status_buf,
                       (unsigned int)n) != 0)) {
        self->counters.publish_errors += 1U;
        return SVA_ERR_ARGUMENT;
    }
    return SVA_OK;
}
