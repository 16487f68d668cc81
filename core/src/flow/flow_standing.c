// flow_standing.c -- the standing plan (sva_planner_t.standing): a live mission's plan
// in force carried over (docs/SPEC.md section 12.4). It is checked and repaired as the
// first seed of a replan (flow.c gives it flow_replan_work); when the mission has a
// change_penalty flow counts changed visits against it, and the plan best against it
// (flow_incumbent.c keeps it) is the one returned.
// Compiled out with SVA_FLOW_STANDING 0 (flow then ignores the standing plan).
#include "flow.h"

#if SVA_FLOW_STANDING

// Whether the standing plan is one of mission m (*plan fresh from sva_state_reset): a
// route per UAV, none for a stranded one, every visit in time (fuel is the repair's)
// and no target served beyond its need.
static bool fits(sva_planner_priv_t* priv, const sva_mission_t* m, const sva_plan_t* plan,
                 const sva_plan_t* standing)
{
    if (standing->route_count != m->uav_count) {
        return false;
    }
    sva_flow_work_t* w = &priv->flow;
    for (uint16_t t = 0U; t < m->target_count; t++) {
        w->target_taken[t] = 0U;
    }
    for (uint16_t u = 0U; u < m->uav_count; u++) {
        const sva_route_t* r = &standing->routes[u];
        if ((r->target_count > (uint16_t)SVA_MAX_ROUTE_TARGETS) ||
            (plan->routes[u].stranded && (r->target_count > 0U))) {
            return false;
        }
        for (uint16_t k = 0U; k < r->target_count; k++) {
            const uint16_t t = r->targets[k];
            if (t >= m->target_count) {
                return false;
            }
            int32_t x = 0;
            int32_t y = 0;
            int64_t free_at = 0;
            sva_flow_leg_ends(m, u, r, k, &x, &y, &free_at);
            w->target_taken[t]++;
            if (!sva_flow_arrives_in_time(m, free_at, x, y, &m->targets[t]) ||
                ((int32_t)w->target_taken[t] > m->targets[t].need)) {
                return false;
            }
        }
    }
    return true;
}

bool sva_flow_standing_begin(sva_planner_priv_t* priv, const sva_mission_t* m,
                             const sva_plan_t* plan, const sva_plan_t* standing)
{
    sva_flow_work_t* w = &priv->flow;
    w->has_pen = false;
    w->standing = NULL;
    if ((standing == NULL) || !fits(priv, m, plan, standing)) {
        return false;
    }
    w->standing = (m->change_penalty > 0) ? standing : NULL;
    return true;
}

void sva_flow_seed_standing(sva_planner_priv_t* priv, const sva_mission_t* m, sva_plan_t* plan,
                            const sva_plan_t* standing)
{
    if (standing == NULL) {
        return;
    }
    const sva_stats_t kept = plan->stats;
    sva_state_reset(priv, m, plan);
    for (uint16_t u = 0U; u < m->uav_count; u++) {
        const sva_route_t* s = &standing->routes[u];
        sva_route_t* r = &plan->routes[u];
        r->target_count = s->target_count;
        for (uint16_t k = 0U; k < s->target_count; k++) {
            r->targets[k] = s->targets[k];
            priv->target_served[s->targets[k]]++;
        }
    }
    sva_flow_repair(priv, m, plan, true);
    sva_state_reset(priv, m, plan);
    plan->stats = kept;
}

void sva_flow_standing_finish(sva_planner_priv_t* priv, const sva_mission_t* m, sva_plan_t* plan)
{
    const uint16_t incumbent_covered = sva_flow_covered_now(priv, m);
    if (!sva_flow_write_standing_pick(priv, m, plan)) {
        return;
    }
    // The coverage proven is the incumbent's: the pick keeps the claim if it covers as many.
    plan->stats.coverage_proven =
        plan->stats.coverage_proven && (priv->flow.pen_covered == incumbent_covered);
    // Optimal only if it costs what the proven incumbent does (then it covers as many
    // targets: optimal needs exact rewards). lower_bound stays a bound on the cost.
    sva_stats_t* stats = &plan->stats;
    const int64_t value = sva_flow_plan_value(priv, m, plan);
    stats->optimal = stats->optimal && (value == priv->flow.inc_value);
    int64_t cost = 0;
    for (uint16_t u = 0U; u < m->uav_count; u++) {
        cost += plan->routes[u].stranded ? 0 : sva_route_cells(m, u, &plan->routes[u]);
    }
    stats->lower_bound = (stats->lower_bound > cost) ? cost : stats->lower_bound;
}

#else

bool sva_flow_standing_begin(sva_planner_priv_t* priv, const sva_mission_t* m,
                             const sva_plan_t* plan, const sva_plan_t* standing)
{
    (void)m;
    (void)plan;
    (void)standing;
    priv->flow.standing = NULL;
    priv->flow.has_pen = false;
    return false;
}

void sva_flow_seed_standing(sva_planner_priv_t* priv, const sva_mission_t* m, sva_plan_t* plan,
                            const sva_plan_t* standing)
{
    (void)priv;
    (void)m;
    (void)plan;
    (void)standing;
}

void sva_flow_standing_finish(sva_planner_priv_t* priv, const sva_mission_t* m, sva_plan_t* plan)
{
    (void)priv;
    (void)m;
    (void)plan;
}

#endif  // SVA_FLOW_STANDING
