// lcm_reports.c -- what vehicles say of themselves, into the live mission: vehicle
// reports (<prefix>REPORT) and fleet reports (fleet messages with fleet_reports set).
// The port translates; the core's sva_live_report decides (contract in sva_lcm.h).
#include <stdio.h>
#include <string.h>

#include "lcm_internal.h"

// Applies one report through the core's rule at the live mission's now. True when it
// became an event that the live mission took; *type is then that event's type.
static bool apply_report(sva_lcm_node_t* self, const sva_report_t* report, int8_t* type)
{
    sva_event_t ev;
    if (!sva_live_report(&self->priv.live, report, self->track_tolerance_cells, &ev)) {
        return false;
    }
    if (sva_live_apply(&self->priv.live, &ev, NULL) != SVA_OK) {
        return false;  // e.g. a cell or fuel out of bounds: the live mission is unchanged
    }
    self->counters.reports_applied += 1U;
    *type = (int8_t)ev.type;
    return true;
}

// Clears the replan being built and sets the header of a report's answer.
static void begin_answer(sva_lcm_node_t* self)
{
    sva_lcm_replan_t* r = &self->priv.replan_tx;
    memset(r, 0, sizeof(*r));
    sva_lcm_stamp_replan_versions(r);
    r->event_seq = -1;
    r->change_penalty = self->change_penalty;
}

static void answer(sva_lcm_node_t* self, int8_t type)
{
    sva_lcm_replan_t* r = &self->priv.replan_tx;
    r->event_type = type;
    r->now_ticks = self->priv.live.now_ticks;
    r->revision = (int64_t)self->priv.live.revision;
    sva_lcm_replan_live(self);
}

void sva_lcm_fleet_report(sva_lcm_node_t* self)
{
    const sva_lcm_fleet_state_t* f = &self->priv.fleet_rx;
    begin_answer(self);
    int8_t type = 0;
    uint32_t applied = 0U;
    for (int32_t i = 0; i < (int32_t)f->uav_count; ++i) {
        const sva_lcm_uav_state_t* w = &f->uavs[i];
        const sva_report_t report = {w->id, w->health == SVA_LCM_UAV_STATE_T_HEALTH_OK, w->x, w->y,
                                     w->fuel};
        applied += apply_report(self, &report, &type) ? 1U : 0U;
    }
    if (applied > 0U) {
        answer(self, type);
    }
}

// A field of a report outside [lo, hi]: refused as a value, naming the field and limit.
static bool report_field_ok(sva_lcm_node_t* self, const char* field, int64_t value, int64_t lo,
                            int64_t hi, sva_lcm_status_t* verdict)
{
    if ((value >= lo) && (value <= hi)) {
        return true;
    }
    char what[160];
    (void)snprintf(what, sizeof what, "%.63s: report_t.%s: must be in [%lld, %lld], got %lld",
                   self->channel_report, field, (long long)lo, (long long)hi, (long long)value);
    *verdict = sva_lcm_reject(self, SVA_LCM_REJECT_VALUE, what);
    return false;
}

sva_lcm_status_t sva_lcm_on_report(sva_lcm_node_t* self, const void* data, size_t size)
{
    if (self->halted) {
        return SVA_LCM_HALTED;
    }
    self->counters.report_rx += 1U;
    sva_lcm_status_t v = sva_lcm_check_frame(self, self->channel_report, data, size,
                                             SVA_LCM_REPORT_BYTES, __sva_lcm_report_t_get_hash());
    if (v != SVA_LCM_ACCEPTED) {
        return v;
    }
    sva_lcm_report_t* w = &self->priv.report_rx;
    if (sva_lcm_report_t_decode(data, 0, (int)size, w) != (int)size) {
        return sva_lcm_reject(self, SVA_LCM_REJECT_TRUNCATED, "report: decoder refused the bytes");
    }
    if (!sva_lcm_version_ok(self, self->channel_report, "report_t", w->version,
                            SVA_LCM_REPORT_T_VERSION, &v)) {
        return v;
    }
    if (!report_field_ok(self, "health", w->health, SVA_LCM_REPORT_T_HEALTH_OK,
                         SVA_LCM_REPORT_T_HEALTH_LOST, &v) ||
        !report_field_ok(self, "at_ticks", w->at_ticks, 0, SVA_MAX_TICK, &v) ||
        !report_field_ok(self, "x", w->x, SVA_COORD_MIN, SVA_COORD_MAX, &v) ||
        !report_field_ok(self, "y", w->y, SVA_COORD_MIN, SVA_COORD_MAX, &v) ||
        !report_field_ok(self, "fuel", w->fuel, SVA_REPORT_FUEL_UNKNOWN, SVA_MAX_FUEL, &v)) {
        return v;
    }
    if (!self->priv.live_active) {
        char what[160];
        (void)snprintf(what, sizeof what,
                       "%.63s: no live mission: a fleet and a mission must be planned first",
                       self->channel_report);
        return sva_lcm_reject(self, SVA_LCM_REJECT_VALUE, what);
    }
    sva_live_t* live = &self->priv.live;
    const uint32_t revision = live->revision;  // a report that changes nothing is not an input
    if (w->at_ticks > live->now_ticks) {
        sva_event_t clock;
        memset(&clock, 0, sizeof clock);
        clock.type = SVA_EVENT_CLOCK;
        clock.at_ticks = w->at_ticks;
        if (sva_live_apply(live, &clock, NULL) != SVA_OK) {
            return sva_lcm_reject(self, SVA_LCM_REJECT_INVALID, "report: the clock was refused");
        }
    }
    begin_answer(self);
    int8_t type = 0;
    const sva_report_t report = {w->uav_id, w->health == SVA_LCM_REPORT_T_HEALTH_OK, w->x, w->y,
                                 w->fuel};
    const bool applied = apply_report(self, &report, &type);
    if ((live->revision != revision) &&
        !sva_lcm_input_durable(self, SVA_LCM_INPUT_REPORT, false, data, size)) {
        return SVA_LCM_HALTED;
    }
    if (applied) {
        answer(self, type);
    }
    return SVA_LCM_ACCEPTED;
}
