// flow_repair.c -- flow's rounding heuristic: a relaxation, or any routes, turned into
// a plan and offered to the incumbent (DESIGN.md section 8).
//
// Rounding: read each UAV's route off the flow; then the repair (also used by the
// Lagrangian heuristic, flow_lagrange.c, the dive, flow_dive.c, and ruin and
// recreate, flow_ruin.c): drop every target served by fewer than `need` UAVs; while a
// route breaks its fuel (or SVA_MAX_ROUTE_TARGETS), drop from every route the target
// whose removal shortens that route most; then insert
// each uncovered target, in (start, end, id) order, at the cheapest time- and
// fuel-feasible place of its `need` cheapest UAVs, or leave it out (flow_insert.c);
// then the local search (flow_local.c). Removing a target keeps a route feasible in
// time (triangle inequality), so every result is a plan.
// The plan under construction lives in the caller's sva_plan_t (its routes and
// priv->target_served), exactly as the other algorithms build theirs.
#include "flow.h"

void sva_flow_repair(sva_planner_priv_t* priv, const sva_mission_t* m, sva_plan_t* plan, bool polish)
{
    sva_flow_work_t* w = &priv->flow;
    for (uint16_t u = 0U; u < m->uav_count; u++) {
        w->route_cells[u] = sva_route_cells(m, u, &plan->routes[u]);
    }
    for (uint16_t t = 0U; t < m->target_count; t++) {
        if ((priv->target_served[t] > 0U) && ((int32_t)priv->target_served[t] < m->targets[t].need)) {
            sva_flow_remove_target(priv, m, plan, t);
        }
    }
    for (uint16_t u = 0U; u < m->uav_count; u++) {
        sva_route_t* r = &plan->routes[u];
        while ((r->target_count > 0U) && !sva_flow_fits(m, u, w->route_cells[u], r->target_count)) {
            sva_flow_remove_target(priv, m, plan, r->targets[sva_flow_costliest_stop(m, u, r)]);
        }
    }
    for (uint16_t i = 0U; i < m->target_count; i++) {
        const uint16_t t = priv->target_order[w->insert_backwards ? ((m->target_count - 1U) - i) : i];
        if (priv->target_served[t] == 0U) {
            sva_flow_try_insert(priv, m, plan, t);
        }
    }
    for (uint16_t i = 0U; i < m->target_count; i++) {
        const uint16_t t = priv->target_order[i];
        if ((priv->target_served[t] == 0U) && (m->targets[t].need == 1)) {
            (void)sva_flow_eject_for(priv, m, plan, t);
        }
    }
    // Local search only for plans within reach of the best: better already, or (when
    // `polish`) at most 1/16 of their length worse.
    int64_t margin = 0;
    for (uint16_t u = 0U; polish && (u < m->uav_count); u++) {
        margin += w->route_cells[u] / 16;
    }
    if (w->has_inc && (sva_flow_plan_value(priv, m, plan) >= (w->inc_value + margin))) {
        (void)sva_flow_offer_plan(priv, m, plan);
        return;
    }
    sva_flow_local_search(priv, m, plan);
    for (uint16_t i = 0U; i < m->target_count; i++) {
        const uint16_t t = priv->target_order[i];
        if (priv->target_served[t] == 0U) {
            sva_flow_try_insert(priv, m, plan, t);
        }
    }
    (void)sva_flow_offer_plan(priv, m, plan);
}

// The current relaxation's routes into *plan, over targets, with priv->target_served.
static void relaxation_routes(sva_planner_priv_t* priv, const sva_mission_t* m, sva_plan_t* plan)
{
    sva_flow_work_t* w = &priv->flow;
    for (uint16_t t = 0U; t < m->target_count; t++) {
        priv->target_served[t] = 0U;
    }
    for (uint16_t u = 0U; u < m->uav_count; u++) {
        sva_route_t* r = &plan->routes[u];
        r->target_count = 0U;
        if (r->stranded) {
            continue;
        }
        // A route longer than SVA_MAX_ROUTE_TARGETS loses its tail here; those
        // targets then count as short of their need and are dropped by the repair.
        r->target_count = sva_flow_route(w, u, r->targets, SVA_MAX_ROUTE_TARGETS);
        for (uint16_t k = 0U; k < r->target_count; k++) {
            r->targets[k] = w->copy_target[r->targets[k]];
            priv->target_served[r->targets[k]]++;
        }
    }
}

void sva_flow_round(sva_planner_priv_t* priv, const sva_mission_t* m, sva_plan_t* plan, bool polish)
{
    relaxation_routes(priv, m, plan);
    sva_flow_repair(priv, m, plan, polish);
}

void sva_flow_take_relaxation(sva_planner_priv_t* priv, const sva_mission_t* m, sva_plan_t* plan)
{
    relaxation_routes(priv, m, plan);
    (void)sva_flow_offer_plan(priv, m, plan);
}

bool sva_flow_pooled_routes(sva_planner_priv_t* priv, const sva_mission_t* m, sva_plan_t* plan)
{
    sva_flow_work_t* w = &priv->flow;
    const uint16_t depot = (uint16_t)(w->uavs + (2U * w->copies));
    bool whole = true;  // no route cut at SVA_MAX_ROUTE_TARGETS
    for (uint16_t t = 0U; t < m->target_count; t++) {
        priv->target_served[t] = 0U;
    }
    for (uint16_t u = 0U; u < m->uav_count; u++) {
        sva_route_t* r = &plan->routes[u];
        r->target_count = 0U;
        // Each unit takes the first arc out of its node that still carries flow, and
        // takes that unit off it: flow conservation leaves one for every unit to come.
        uint16_t v = u;
        while ((v != depot) && !r->stranded) {
            uint16_t next = depot;
            for (uint32_t e = w->out_start[v]; e < w->out_start[v + 1U]; e++) {
                if (w->arc_flow[e] != 0U) {
                    w->arc_flow[e]--;
                    next = w->arc_head[e];
                    break;
                }
            }
            if (next != depot) {
                const uint16_t c = (uint16_t)(next - w->uavs);
                // Past SVA_MAX_ROUTE_TARGETS the route loses its tail, as in
                // relaxation_routes.
                if (r->target_count < (uint16_t)SVA_MAX_ROUTE_TARGETS) {
                    r->targets[r->target_count] = w->copy_target[c];
                    r->target_count++;
                    priv->target_served[w->copy_target[c]]++;
                } else {
                    whole = false;
                }
                next = (uint16_t)(w->uavs + w->copies + c);
            }
            v = next;
        }
        whole = whole && sva_flow_fits(m, u, sva_route_cells(m, u, r), r->target_count);
    }
    for (uint16_t t = 0U; t < m->target_count; t++) {
        const int32_t served = (int32_t)priv->target_served[t];
        whole = whole && ((served == 0) || (served == m->targets[t].need));
    }
    return whole;
}
