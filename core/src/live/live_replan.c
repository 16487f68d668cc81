// live_replan.c -- a live mission's replan (SPEC section 12.4): the residual mission,
// two candidates (the plan in force carried over, and the planner's plan of it with the
// carried plan standing: sva_replan()), the better by coverage, then cost +
// change_penalty * changed visits, made the plan in force.
#include "live_internal.h"

#include <string.h>

// The residual mission at now: the UAVs in service where the flight model puts them
// (busy ones at their target until its end), the targets still waiting.
static void build_residual(sva_live_t* self)
{
    const sva_mission_t* m = &self->mission;
    sva_mission_t* r = &self->residual;
    sva_mission_init(r);
    r->depot_x = m->depot_x;
    r->depot_y = m->depot_y;
    r->ticks_per_cell = m->ticks_per_cell;
    r->hover_fuel = m->hover_fuel;
    r->overlap_percent = m->overlap_percent;
    r->change_penalty = m->change_penalty;
    r->takeoff_ticks = m->takeoff_ticks;
    for (uint16_t u = 0U; u < m->uav_count; u++) {
        if (self->priv.uavs[u].lost) {
            continue;
        }
        sva_live_pos_t pos;
        sva_live_walk(self, u, self->now_ticks, &pos, -1, NULL);
        sva_uav_t* uav = &r->uavs[r->uav_count];
        uav->id = m->uavs[u].id;
        uav->x = pos.x;
        uav->y = pos.y;
        // Fuel readings may say less than the model flew: an empty tank is 0.
        uav->fuel = (int32_t)((pos.fuel < 0) ? 0 : pos.fuel);
        uav->ready_at_ticks = (int32_t)((pos.ready > SVA_MAX_TICK) ? SVA_MAX_TICK : pos.ready);
        self->priv.uav_of[r->uav_count] = u;
        self->priv.busy_with[r->uav_count] = pos.busy_with;
        r->uav_count++;
    }
    for (uint16_t i = 0U; i < m->target_count; i++) {
        self->priv.residual_of[i] = -1;
        if ((self->target_state[i] == (uint8_t)SVA_TARGET_WAITING) &&
            (m->targets[i].start_ticks >= self->now_ticks)) {
            self->priv.residual_of[i] = (int32_t)r->target_count;
            self->priv.target_of[r->target_count] = i;
            r->targets[r->target_count] = m->targets[i];
            r->target_count++;
        }
    }
}

// The plan in force's visits of residual targets, per residual UAV, as planned.
static void build_previous(sva_live_t* self)
{
    const sva_mission_t* r = &self->residual;
    sva_plan_t* prev = &self->previous;
    (void)memset(prev, 0, sizeof(*prev));
    prev->route_count = r->uav_count;
    for (uint16_t k = 0U; k < r->uav_count; k++) {
        const sva_live_uav_t* v = &self->priv.uavs[self->priv.uav_of[k]];
        sva_route_t* route = &prev->routes[k];
        route->uav_id = r->uavs[k].id;
        for (uint16_t j = 0U; j < v->route_count; j++) {
            const int32_t t = self->priv.residual_of[v->route[j]];
            if (t >= 0) {
                route->targets[route->target_count] = (uint16_t)t;
                route->target_count++;
            }
        }
    }
}

static int64_t objective(const sva_live_t* self, const sva_plan_t* plan)
{
    const uint32_t changes = sva_plan_changes(&self->previous, plan, NULL, 0U) +
                             sva_plan_changes(plan, &self->previous, NULL, 0U);
    return plan->cost + ((int64_t)self->mission.change_penalty * (int64_t)changes);
}

// The chosen plan becomes the plan in force: each UAV's route starts where the residual
// mission put it.
static void commit(sva_live_t* self, const sva_plan_t* plan)
{
    const sva_mission_t* r = &self->residual;
    for (uint16_t k = 0U; k < r->uav_count; k++) {
        sva_live_uav_t* v = &self->priv.uavs[self->priv.uav_of[k]];
        const sva_route_t* route = &plan->routes[k];
        sva_live_pos_t pos;
        sva_live_walk(self, self->priv.uav_of[k], self->now_ticks, &pos, -1, NULL);
        v->x = pos.x;
        v->y = pos.y;
        v->fuel = pos.fuel;
        v->from_ticks = pos.ready;
        v->busy_with = pos.busy_with;
        v->route_count = route->target_count;
        for (uint16_t j = 0U; j < route->target_count; j++) {
            v->route[j] = self->priv.target_of[route->targets[j]];
        }
    }
}

sva_status_t sva_live_replan(sva_live_t* self, sva_planner_t* planner, sva_algorithm_t algorithm,
                             sva_live_result_t* result, sva_diag_t* diag)
{
    SVA_ASSERT((self != NULL) && (planner != NULL) && (result != NULL));
    if ((self == NULL) || (planner == NULL) || (result == NULL)) {
        return SVA_ERR_ARGUMENT;
    }
    build_residual(self);
    build_previous(self);
    self->candidate = self->previous;
    sva_live_carry(&self->residual, &self->candidate, algorithm, self->priv.served);
    // The carried plan stands while the planner plans: flow weighs its changes against it.
    const sva_status_t status =
        sva_replan(planner, &self->residual, algorithm, &self->candidate, &self->plan, diag);
    if (status != SVA_OK) {
        return status;
    }
    self->candidate.stats = self->plan.stats;
    const sva_plan_t* fresh = &self->plan;
    const sva_plan_t* kept = &self->candidate;
    const bool keep =
        (kept->covered > fresh->covered) ||
        ((kept->covered == fresh->covered) && (objective(self, kept) <= objective(self, fresh)));
    if (keep) {
        self->plan = self->candidate;
    }
    commit(self, &self->plan);
    (void)memset(result, 0, sizeof(*result));
    result->residual = &self->residual;
    result->plan = &self->plan;
    result->previous = &self->previous;
    result->now_ticks = self->now_ticks;
    result->revision = self->revision;
    for (uint16_t i = 0U; i < self->mission.target_count; i++) {
        if (self->target_state[i] == (uint8_t)SVA_TARGET_UNDER_WAY) {
            result->under_way++;
        }
    }
    result->covered = (uint16_t)(result->under_way + self->plan.covered);
    result->dropped = sva_plan_changes(&self->previous, &self->plan, NULL, 0U);
    result->added = sva_plan_changes(&self->plan, &self->previous, NULL, 0U);
    result->objective = objective(self, &self->plan);
    result->kept = keep;
    return SVA_OK;
}
