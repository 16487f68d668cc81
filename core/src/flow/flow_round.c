// flow_round.c -- flow's rounding: the routes of a relaxation's flow read off the graph
// into a plan under construction, for the repair (flow_repair.c) to complete
// (DESIGN.md section 8).
#include "flow.h"

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
