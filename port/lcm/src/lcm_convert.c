// lcm_convert.c -- core plans and missions into wire messages (plan_t, replan_t's
// residual fleet and mission).
#include "lcm_internal.h"

void sva_lcm_plan_diag(sva_lcm_plan_t* p, const sva_diag_t* d)
{
    p->diag_field = (int8_t)d->field;
    p->diag_rule = (int8_t)d->rule;
    p->diag_index = d->index;
    p->diag_value = d->value;
    p->diag_limit = d->limit;
}

// Fills *p from a core plan over mission m; false when the routes need more than
// MAX_ROUTE_ITEMS items (then the caller clears the routes).
bool sva_lcm_fill_plan(sva_lcm_plan_t* p, const sva_plan_t* plan, const sva_mission_t* m)
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

// The residual mission as wire messages (stamped with the live revision).
void sva_lcm_fill_residual(sva_lcm_replan_t* r, const sva_mission_t* m, int64_t revision,
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
