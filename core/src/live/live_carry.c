// live_carry.c -- the plan in force carried over to a residual mission (SPEC section
// 12.4): its visits of the targets still waiting, less every visit that no longer fits.
// It is the candidate that keeps a replan from covering fewer targets than the plan in
// force still could.
#include "live_internal.h"

// Takes target t out of every route.
static void drop_target(sva_plan_t* plan, uint16_t t)
{
    for (uint16_t r = 0U; r < plan->route_count; r++) {
        sva_route_t* route = &plan->routes[r];
        uint16_t kept = 0U;
        for (uint16_t k = 0U; k < route->target_count; k++) {
            if (route->targets[k] != t) {
                route->targets[kept] = route->targets[k];
                kept++;
            }
        }
        route->target_count = kept;
    }
}

// The first target of route r that its UAV cannot serve (late, or the fuel runs out
// before it is home), or -1 when the whole route fits (SPEC section 1).
static int32_t first_misfit(const sva_mission_t* m, const sva_plan_t* plan, uint16_t r)
{
    const sva_uav_t* uav = &m->uavs[r];
    const sva_route_t* route = &plan->routes[r];
    int32_t x = uav->x;
    int32_t y = uav->y;
    int64_t free_at = uav->ready_at_ticks;
    int64_t fuel = uav->fuel;
    for (uint16_t k = 0U; k < route->target_count; k++) {
        const sva_target_t* t = &m->targets[route->targets[k]];
        const int64_t cells = sva_distance(x, y, t->x, t->y);
        const int64_t home = sva_distance(t->x, t->y, m->depot_x, m->depot_y);
        fuel -= cells + m->hover_fuel;
        if (((free_at + (cells * m->ticks_per_cell)) > t->start_ticks) || (fuel < home)) {
            return (int32_t)route->targets[k];
        }
        x = t->x;
        y = t->y;
        free_at = t->end_ticks;
    }
    return -1;
}

// Distances, fuel, cost, coverage and status of a plan whose routes are set.
static void plan_figures(const sva_mission_t* m, sva_plan_t* plan, uint16_t* served)
{
    for (uint16_t t = 0U; t < m->target_count; t++) {
        served[t] = 0U;
    }
    plan->cost = 0;
    plan->stranded_count = 0U;
    for (uint16_t r = 0U; r < m->uav_count; r++) {
        sva_route_t* route = &plan->routes[r];
        const sva_uav_t* uav = &m->uavs[r];
        route->uav_id = uav->id;
        route->stranded = (int64_t)uav->fuel < sva_distance(uav->x, uav->y, m->depot_x, m->depot_y);
        plan->stranded_count = (uint16_t)(plan->stranded_count + (route->stranded ? 1U : 0U));
        if (route->stranded) {
            route->target_count = 0U;
            route->distance_cells = 0;
            route->fuel_used = 0;
            continue;
        }
        for (uint16_t k = 0U; k < route->target_count; k++) {
            served[route->targets[k]]++;
        }
        const int64_t cells = sva_route_cells(m, r, route);
        route->distance_cells = cells;
        route->fuel_used = cells + ((int64_t)m->hover_fuel * (int64_t)route->target_count);
        plan->cost += cells;
    }
    plan->covered = 0U;
    plan->uncovered_count = 0U;
    for (uint16_t t = 0U; t < m->target_count; t++) {
        if ((int32_t)served[t] == m->targets[t].need) {
            plan->covered++;
        } else {
            plan->uncovered[plan->uncovered_count] = t;
            plan->uncovered_count++;
        }
    }
    plan->status = (plan->uncovered_count == 0U) ? SVA_PLAN_COMPLETE : SVA_PLAN_PARTIAL;
}

void sva_live_carry(const sva_mission_t* m, sva_plan_t* plan, sva_algorithm_t algorithm,
                    uint16_t* served)
{
    plan->algorithm = algorithm;
    plan->route_count = m->uav_count;
    bool changed = true;
    while (changed) {
        changed = false;
        // Whole needs only: a target with more or fewer UAVs than its need goes.
        for (uint16_t t = 0U; t < m->target_count; t++) {
            served[t] = 0U;
        }
        for (uint16_t r = 0U; r < plan->route_count; r++) {
            for (uint16_t k = 0U; k < plan->routes[r].target_count; k++) {
                served[plan->routes[r].targets[k]]++;
            }
        }
        for (uint16_t t = 0U; t < m->target_count; t++) {
            if ((served[t] != 0U) && ((int32_t)served[t] != m->targets[t].need)) {
                drop_target(plan, t);
                changed = true;
            }
        }
        for (uint16_t r = 0U; (r < plan->route_count) && !changed; r++) {
            const int32_t misfit = first_misfit(m, plan, r);
            if (misfit >= 0) {
                drop_target(plan, (uint16_t)misfit);
                changed = true;
            }
        }
    }
    plan_figures(m, plan, served);
}
