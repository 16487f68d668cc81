// lcm_inputs.c -- fleet and mission messages in: checked, converted to the core's
// mission, kept (input hook) and planned, or taken as fleet reports (lcm_reports.c).
#include <stdio.h>
#include <string.h>

#include "sva/sva_frame.h"

#include "lcm_internal.h"

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
        if (!sva_in_range(d, SVA_FIELD_UAV_ID, i, u->id, 1, SVA_MAX_ID, "SVA_MAX_ID") ||
            !sva_in_range(d, SVA_FIELD_UAV_X, i, u->x, SVA_COORD_MIN, SVA_COORD_MAX,
                          "SVA_COORD_MAX") ||
            !sva_in_range(d, SVA_FIELD_UAV_Y, i, u->y, SVA_COORD_MIN, SVA_COORD_MAX,
                          "SVA_COORD_MAX") ||
            !sva_in_range(d, SVA_FIELD_UAV_FUEL, i, u->fuel, 0, SVA_MAX_FUEL, "SVA_MAX_FUEL") ||
            !sva_in_range(d, SVA_FIELD_UAV_READY_AT, i, u->ready_at_ticks, 0, SVA_MAX_TICK,
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
    if (!sva_in_range(d, SVA_FIELD_DEPOT_X, -1, m->depot_x, SVA_COORD_MIN, SVA_COORD_MAX,
                      "SVA_COORD_MAX") ||
        !sva_in_range(d, SVA_FIELD_DEPOT_Y, -1, m->depot_y, SVA_COORD_MIN, SVA_COORD_MAX,
                      "SVA_COORD_MAX") ||
        !sva_in_range(d, SVA_FIELD_TICKS_PER_CELL, -1, m->ticks_per_cell, 1, SVA_MAX_TICKS_PER_CELL,
                      "SVA_MAX_TICKS_PER_CELL") ||
        !sva_in_range(d, SVA_FIELD_HOVER_FUEL, -1, m->hover_fuel, 0, SVA_MAX_HOVER_FUEL,
                      "SVA_MAX_HOVER_FUEL") ||
        !sva_in_range(d, SVA_FIELD_OVERLAP_PERCENT, -1, m->overlap_percent, 0, 100, NULL)) {
        return false;
    }
    for (int32_t i = 0; i < (int32_t)m->target_count; ++i) {
        const sva_lcm_target_t* t = &m->targets[i];
        if (!sva_in_range(d, SVA_FIELD_TARGET_ID, i, t->id, 1, SVA_MAX_ID, "SVA_MAX_ID") ||
            !sva_in_range(d, SVA_FIELD_TARGET_X, i, t->x, SVA_COORD_MIN, SVA_COORD_MAX,
                          "SVA_COORD_MAX") ||
            !sva_in_range(d, SVA_FIELD_TARGET_Y, i, t->y, SVA_COORD_MIN, SVA_COORD_MAX,
                          "SVA_COORD_MAX") ||
            !sva_in_range(d, SVA_FIELD_TARGET_START, i, t->start_ticks, 0, SVA_MAX_TICK - 1,
                          "SVA_MAX_TICK") ||
            !sva_in_range(d, SVA_FIELD_TARGET_END, i, t->end_ticks, 1, SVA_MAX_TICK,
                          "SVA_MAX_TICK") ||
            !sva_in_range(d, SVA_FIELD_TARGET_NEED, i, t->need, 1, SVA_MAX_UAVS, "SVA_MAX_UAVS")) {
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
    return sva_frame_check(&f, err, err_size) == SVA_OK;
}

sva_lcm_status_t sva_lcm_on_fleet(sva_lcm_node_t* self, const void* data, size_t size)
{
    if (self->halted) {
        return SVA_LCM_HALTED;
    }
    self->counters.fleet_rx += 1U;
    sva_lcm_status_t v =
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
        return sva_lcm_reject_diag(self, reason, self->channel_fleet);
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
        sva_lcm_replan(self);
    }
    return SVA_LCM_ACCEPTED;
}

sva_lcm_status_t sva_lcm_on_mission(sva_lcm_node_t* self, const void* data, size_t size)
{
    if (self->halted) {
        return SVA_LCM_HALTED;
    }
    self->counters.mission_rx += 1U;
    sva_lcm_status_t v = sva_lcm_check_frame(self, self->channel_mission, data, size,
                                             SVA_LCM_MISSION_BYTES, __sva_lcm_mission_t_get_hash());
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
        return sva_lcm_reject_diag(self, reason, self->channel_mission);
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
        sva_lcm_replan(self);
    }
    return SVA_LCM_ACCEPTED;
}
