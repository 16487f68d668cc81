// validate.c -- SPEC section 4: untrusted missions are checked field by field; the
// first violation (instance fields, then UAVs, then targets, in list order) wins.
#include "model.h"

bool sva_in_range(sva_diag_t* diag, sva_field_t field, int32_t index, int64_t value, int64_t lo,
                  int64_t hi, const char* hi_name)
{
    if (value < lo) {
        sva_diag_set(diag, field, SVA_RULE_MIN, index, value, lo, NULL);
        return false;
    }
    if (value > hi) {
        sva_diag_set(diag, field, SVA_RULE_MAX, index, value, hi, hi_name);
        return false;
    }
    return true;
}

static bool coord_ok(sva_diag_t* diag, sva_field_t field, int32_t index, int32_t value)
{
    return sva_in_range(diag, field, index, value, SVA_COORD_MIN, SVA_COORD_MAX, NULL);
}

static bool instance_ok(const sva_mission_t* m, sva_diag_t* diag)
{
    return coord_ok(diag, SVA_FIELD_DEPOT_X, -1, m->depot_x) &&
           coord_ok(diag, SVA_FIELD_DEPOT_Y, -1, m->depot_y) &&
           sva_in_range(diag, SVA_FIELD_TICKS_PER_CELL, -1, m->ticks_per_cell, 1,
                        SVA_MAX_TICKS_PER_CELL, "SVA_MAX_TICKS_PER_CELL") &&
           sva_in_range(diag, SVA_FIELD_HOVER_FUEL, -1, m->hover_fuel, 0, SVA_MAX_HOVER_FUEL,
                        "SVA_MAX_HOVER_FUEL") &&
           sva_in_range(diag, SVA_FIELD_OVERLAP_PERCENT, -1, m->overlap_percent, 0, 100, NULL) &&
           sva_in_range(diag, SVA_FIELD_CHANGE_PENALTY, -1, m->change_penalty, 0,
                        SVA_MAX_CHANGE_PENALTY, "SVA_MAX_CHANGE_PENALTY") &&
           sva_in_range(diag, SVA_FIELD_TAKEOFF_TICKS, -1, m->takeoff_ticks, 0, SVA_MAX_TICK,
                        "SVA_MAX_TICK");
}

static bool uav_ok(const sva_mission_t* m, int32_t i, sva_diag_t* diag)
{
    const sva_uav_t* u = &m->uavs[i];
    if (!sva_in_range(diag, SVA_FIELD_UAV_ID, i, u->id, 1, SVA_MAX_ID, NULL) ||
        !coord_ok(diag, SVA_FIELD_UAV_X, i, u->x) || !coord_ok(diag, SVA_FIELD_UAV_Y, i, u->y) ||
        !sva_in_range(diag, SVA_FIELD_UAV_FUEL, i, u->fuel, 0, SVA_MAX_FUEL, "SVA_MAX_FUEL") ||
        !sva_in_range(diag, SVA_FIELD_UAV_READY_AT, i, u->ready_at_ticks, 0, SVA_MAX_TICK,
                      "SVA_MAX_TICK")) {
        return false;
    }
    for (int32_t j = 0; j < i; j++) {
        if (m->uavs[j].id == u->id) {
            sva_diag_set(diag, SVA_FIELD_UAV_ID, SVA_RULE_DUPLICATE, i, u->id, j, NULL);
            return false;
        }
    }
    return true;
}

static bool target_ok(const sva_mission_t* m, int32_t i, sva_diag_t* diag)
{
    const sva_target_t* t = &m->targets[i];
    if (!sva_in_range(diag, SVA_FIELD_TARGET_ID, i, t->id, 1, SVA_MAX_ID, NULL) ||
        !coord_ok(diag, SVA_FIELD_TARGET_X, i, t->x) ||
        !coord_ok(diag, SVA_FIELD_TARGET_Y, i, t->y) ||
        !sva_in_range(diag, SVA_FIELD_TARGET_START, i, t->start_ticks, 0, SVA_MAX_TICK - 1,
                      "SVA_MAX_TICK - 1") ||
        !sva_in_range(diag, SVA_FIELD_TARGET_END, i, t->end_ticks, 1, SVA_MAX_TICK,
                      "SVA_MAX_TICK") ||
        !sva_in_range(diag, SVA_FIELD_TARGET_NEED, i, t->need, 1, SVA_MAX_UAVS, "SVA_MAX_UAVS")) {
        return false;
    }
    if (t->end_ticks <= t->start_ticks) {
        sva_diag_set(diag, SVA_FIELD_TARGET_END, SVA_RULE_AFTER, i, t->end_ticks, t->start_ticks,
                     NULL);
        return false;
    }
    for (int32_t j = 0; j < i; j++) {
        if (m->targets[j].id == t->id) {
            sva_diag_set(diag, SVA_FIELD_TARGET_ID, SVA_RULE_DUPLICATE, i, t->id, j, NULL);
            return false;
        }
    }
    return true;
}

sva_status_t sva_mission_validate(const sva_mission_t* self, sva_diag_t* diag)
{
    SVA_ASSERT(self != NULL);
    if (self == NULL) {
        return SVA_ERR_ARGUMENT;
    }
    sva_diag_set(diag, SVA_FIELD_NONE, SVA_RULE_NONE, -1, 0, 0, NULL);
    if (!instance_ok(self, diag)) {
        return SVA_ERR_INVALID;
    }
    if (self->uav_count > SVA_MAX_UAVS) {
        sva_diag_set(diag, SVA_FIELD_UAVS, SVA_RULE_COUNT, -1, self->uav_count, SVA_MAX_UAVS,
                     "SVA_MAX_UAVS");
        return SVA_ERR_INVALID;
    }
    if (self->target_count > SVA_MAX_TARGETS) {
        sva_diag_set(diag, SVA_FIELD_TARGETS, SVA_RULE_COUNT, -1, self->target_count,
                     SVA_MAX_TARGETS, "SVA_MAX_TARGETS");
        return SVA_ERR_INVALID;
    }
    for (int32_t i = 0; i < (int32_t)self->uav_count; i++) {
        if (!uav_ok(self, i, diag)) {
            return SVA_ERR_INVALID;
        }
    }
    for (int32_t i = 0; i < (int32_t)self->target_count; i++) {
        if (!target_ok(self, i, diag)) {
            return SVA_ERR_INVALID;
        }
    }
    return SVA_OK;
}
