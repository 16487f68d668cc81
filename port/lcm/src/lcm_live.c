// lcm_live.c -- the live mission: events in, replans out.
#include <stdio.h>
#include <string.h>
#include <time.h>

#include "lcm_internal.h"

static void publish_replan(sva_lcm_node_t* self)
{
    sva_lcm_replan_t* r = &self->priv.replan_tx;
    r->plan.utime = sva_lcm_now_us(CLOCK_REALTIME);
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
static sva_lcm_status_t refuse_event(sva_lcm_node_t* self, sva_lcm_reject_t reason,
                                     const sva_diag_t* diag, const char* text)
{
    sva_lcm_replan_t* r = &self->priv.replan_tx;
    r->accepted = 0;
    if (diag != NULL) {
        r->diag_field = (int8_t)diag->field;
        r->diag_rule = (int8_t)diag->rule;
        r->diag_value = diag->value;
        r->diag_limit = diag->limit;
        sva_lcm_plan_diag(&r->plan, diag);
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
    const sva_lcm_status_t v = sva_lcm_reject(self, reason, text);
    publish_replan(self);
    return v;
}

// Lists the (UAV id, target id) pairs of `from` that `to` lacks (sva_plan_changes), the
// first MAX_CHANGES of them, into uav[] and target[]; returns how many were listed.
static int16_t list_changes(const sva_plan_t* from, const sva_plan_t* to, const sva_mission_t* m,
                            int32_t* uav, int32_t* target)
{
    sva_visit_t visits[SVA_LCM_REPLAN_T_MAX_CHANGES];
    const uint32_t n = sva_plan_changes(from, to, visits, SVA_LCM_REPLAN_T_MAX_CHANGES);
    int16_t listed = 0;
    for (uint32_t i = 0; (i < n) && (i < (uint32_t)SVA_LCM_REPLAN_T_MAX_CHANGES); ++i) {
        uav[i] = from->routes[visits[i].route].uav_id;
        target[i] = m->targets[visits[i].target].id;
        listed += 1;
    }
    return listed;
}

// Every message a replan carries names its version, also when it is empty.
void sva_lcm_stamp_replan_versions(sva_lcm_replan_t* r)
{
    r->version = SVA_LCM_REPLAN_T_VERSION;
    r->residual_fleet.version = SVA_LCM_FLEET_STATE_T_VERSION;
    r->residual_mission.version = SVA_LCM_MISSION_T_VERSION;
    r->plan.version = SVA_LCM_PLAN_T_VERSION;
}

sva_lcm_status_t sva_lcm_on_event(sva_lcm_node_t* self, const void* data, size_t size)
{
    if (self->halted) {
        return SVA_LCM_HALTED;
    }
    self->counters.event_rx += 1U;
    const sva_lcm_status_t v = sva_lcm_check_frame(
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
    if (!sva_in_range(&diag, SVA_FIELD_EVENT_TYPE, -1, e->type, 0, (int64_t)SVA_EVENT_COUNT_ - 1,
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
    r->accepted = 1;
    self->priv.plan_id += 1;
    sva_lcm_plan_t* p = &r->plan;
    p->version = SVA_LCM_PLAN_T_VERSION;
    p->plan_id = self->priv.plan_id;
    p->fleet_revision = self->priv.fleet_revision;
    p->mission_revision = self->priv.mission_revision;
    p->algorithm = (int8_t)self->algorithm;
    sva_live_result_t* res = &self->priv.live_result;
    const int64_t t0 = sva_lcm_now_us(CLOCK_MONOTONIC);
    const sva_status_t st = sva_live_replan(live, &self->priv.planner, self->algorithm, res, &diag);
    const int64_t dt = sva_lcm_now_us(CLOCK_MONOTONIC) - t0;
    p->solve_us = (dt > (int64_t)INT32_MAX) ? INT32_MAX : (int32_t)dt;
    r->now_ticks = live->now_ticks;
    r->revision = (int64_t)live->revision;
    if (st != SVA_OK) {
        // The event stands; the plan in force stays as it was (sva_live_replan).
        self->last_diag = diag;
        sva_lcm_plan_diag(p, &diag);
        p->error_code = (int8_t)st;
        p->status = SVA_LCM_PLAN_T_STATUS_FAILED;
        char msg[128];
        char text[SVA_LCM_REPLAN_T_DIAG_TEXT_SIZE];
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
    sva_lcm_fill_residual(r, res->residual, r->revision, &self->priv.frame);
    if (!sva_lcm_fill_plan(p, res->plan, res->residual)) {
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
