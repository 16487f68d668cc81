// plan.c -- the planning state every algorithm shares: where each UAV is, when it is
// free, how much fuel it has left, its route so far; and the finished plan.
#include "model.h"

#include <string.h>

void sva_state_reset(sva_planner_priv_t* priv, const sva_mission_t* mission, sva_plan_t* plan)
{
    sva_sort_targets(priv, mission);
    sva_sort_uavs(priv, mission);
    (void)memset(priv->target_served, 0, sizeof(priv->target_served));
    plan->route_count = mission->uav_count;
    plan->stranded_count = 0U;
    for (uint16_t u = 0U; u < mission->uav_count; u++) {
        const sva_uav_t* uav = &mission->uavs[u];
        sva_route_t* route = &plan->routes[u];
        priv->uav_x[u] = uav->x;
        priv->uav_y[u] = uav->y;
        priv->uav_free_at[u] = uav->ready_at_ticks;
        priv->uav_fuel_left[u] = uav->fuel;
        route->uav_id = uav->id;
        route->target_count = 0U;
        route->distance_cells = 0;
        route->fuel_used = 0;
        // SPEC section 1: fuel that cannot even bring it home -> reported, not planned.
        route->stranded =
            (int64_t)uav->fuel < sva_distance(uav->x, uav->y, mission->depot_x, mission->depot_y);
        if (route->stranded) {
            plan->stranded_count++;
        }
    }
}

// SPEC section 1 serving rule plus SPEC section 2 readiness: free in time to arrive by
// the window start, and fuel to hover there and still get home.
bool sva_can_serve(const sva_planner_priv_t* priv, const sva_mission_t* mission,
                   const sva_plan_t* plan, uint16_t uav, uint16_t target)
{
    const sva_target_t* t = &mission->targets[target];
    const sva_route_t* route = &plan->routes[uav];
    if (route->stranded || (route->target_count >= SVA_MAX_ROUTE_TARGETS)) {
        return false;
    }
    const int64_t leg = sva_distance(priv->uav_x[uav], priv->uav_y[uav], t->x, t->y);
    const int64_t home = sva_distance(t->x, t->y, mission->depot_x, mission->depot_y);
    const int64_t arrival = priv->uav_free_at[uav] + (leg * mission->ticks_per_cell);
    return (arrival <= t->start_ticks) &&
           ((leg + mission->hover_fuel + home) <= priv->uav_fuel_left[uav]);
}

int64_t sva_insertion_cells(const sva_planner_priv_t* priv, const sva_mission_t* mission,
                            uint16_t uav, uint16_t target)
{
    const sva_target_t* t = &mission->targets[target];
    const int32_t x = priv->uav_x[uav];
    const int32_t y = priv->uav_y[uav];
    return (int64_t)sva_distance(x, y, t->x, t->y) +
           sva_distance(t->x, t->y, mission->depot_x, mission->depot_y) -
           sva_distance(x, y, mission->depot_x, mission->depot_y);
}

void sva_commit(sva_planner_priv_t* priv, const sva_mission_t* mission, sva_plan_t* plan,
                uint16_t uav, uint16_t target)
{
    const sva_target_t* t = &mission->targets[target];
    sva_route_t* route = &plan->routes[uav];
    SVA_ASSERT(route->target_count < SVA_MAX_ROUTE_TARGETS);
    const int64_t leg = sva_distance(priv->uav_x[uav], priv->uav_y[uav], t->x, t->y);
    priv->uav_fuel_left[uav] -= leg + mission->hover_fuel;
    priv->uav_x[uav] = t->x;
    priv->uav_y[uav] = t->y;
    priv->uav_free_at[uav] = t->end_ticks;
    route->targets[route->target_count] = target;
    route->target_count++;
    priv->target_served[target]++;
}

int64_t sva_path_cells(const sva_mission_t* mission, uint16_t uav, const uint16_t* targets,
                       uint16_t count)
{
    int32_t x = mission->uavs[uav].x;
    int32_t y = mission->uavs[uav].y;
    int64_t cells = 0;
    for (uint16_t k = 0U; k < count; k++) {
        const sva_target_t* t = &mission->targets[targets[k]];
        cells += sva_distance(x, y, t->x, t->y);
        x = t->x;
        y = t->y;
    }
    return cells + sva_distance(x, y, mission->depot_x, mission->depot_y);
}

int64_t sva_route_cells(const sva_mission_t* mission, uint16_t uav, const sva_route_t* route)
{
    return sva_path_cells(mission, uav, route->targets, route->target_count);
}

// Routes get their legs summed from the mission's start positions (not the state),
// so the figures are recomputed from the route itself.
void sva_plan_finish(sva_planner_priv_t* priv, const sva_mission_t* mission, sva_plan_t* plan)
{
    plan->cost = 0;
    for (uint16_t u = 0U; u < mission->uav_count; u++) {
        sva_route_t* route = &plan->routes[u];
        if (route->stranded) {
            continue;
        }
        const int64_t cells = sva_route_cells(mission, u, route);
        route->distance_cells = cells;
        route->fuel_used = cells + ((int64_t)mission->hover_fuel * (int64_t)route->target_count);
        plan->cost += cells;
    }
    plan->covered = 0U;
    plan->uncovered_count = 0U;
    for (uint16_t t = 0U; t < mission->target_count; t++) {
        // Algorithms commit whole targets only: served is 0 or need.
        SVA_ASSERT((priv->target_served[t] == 0U) ||
                   ((int32_t)priv->target_served[t] == mission->targets[t].need));
        if ((int32_t)priv->target_served[t] == mission->targets[t].need) {
            plan->covered++;
        } else {
            plan->uncovered[plan->uncovered_count] = t;
            plan->uncovered_count++;
        }
    }
    plan->status = (plan->uncovered_count == 0U) ? SVA_PLAN_COMPLETE : SVA_PLAN_PARTIAL;
}

// Whether the route (NULL: none) visits the target.
static bool route_has(const sva_route_t* route, uint16_t target)
{
    if (route == NULL) {
        return false;
    }
    for (uint16_t k = 0U; k < route->target_count; k++) {
        if (route->targets[k] == target) {
            return true;
        }
    }
    return false;
}

uint32_t sva_plan_changes(const sva_plan_t* from, const sva_plan_t* to, sva_visit_t* out,
                          uint32_t cap)
{
    SVA_ASSERT((from != NULL) && (to != NULL) && ((out != NULL) || (cap == 0U)));
    if ((from == NULL) || (to == NULL)) {
        return 0U;
    }
    uint32_t count = 0U;
    for (uint16_t r = 0U; r < from->route_count; r++) {
        const sva_route_t* a = &from->routes[r];
        const sva_route_t* b = (r < to->route_count) ? &to->routes[r] : NULL;
        for (uint16_t k = 0U; k < a->target_count; k++) {
            if (route_has(b, a->targets[k])) {
                continue;
            }
            if ((out != NULL) && (count < cap)) {
                out[count].route = r;
                out[count].target = a->targets[k];
            }
            count++;
        }
    }
    return count;
}
