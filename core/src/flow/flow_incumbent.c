// flow_incumbent.c -- flow's plans: whether a route fits its UAV, the value of a plan,
// and the best plan found so far (the incumbent), kept as linked copies of the graph
// (DESIGN.md section 8).
#include "flow.h"

bool sva_flow_fits(const sva_mission_t* m, uint16_t u, int64_t cells, uint32_t targets)
{
    return (targets <= (uint32_t)SVA_MAX_ROUTE_TARGETS) &&
           ((cells + ((int64_t)m->hover_fuel * (int64_t)targets)) <= m->uavs[u].fuel);
}

bool sva_flow_route_fits(const sva_mission_t* m, uint16_t u, const uint16_t* copies, uint16_t n,
                         const sva_flow_work_t* w)
{
    int32_t x = m->uavs[u].x;
    int32_t y = m->uavs[u].y;
    int64_t cells = 0;
    for (uint16_t k = 0U; k < n; k++) {
        const sva_target_t* t = &m->targets[w->copy_target[copies[k]]];
        cells += sva_distance(x, y, t->x, t->y);
        x = t->x;
        y = t->y;
    }
    cells += sva_distance(x, y, m->depot_x, m->depot_y);
    return sva_flow_fits(m, u, cells, n);
}

// ---------------------------------------------------------------------------------
// The incumbent.

int64_t sva_flow_plan_value(const sva_planner_priv_t* priv, const sva_mission_t* m,
                            const sva_plan_t* plan)
{
    const sva_flow_work_t* w = &priv->flow;
    int64_t value = 0;
    for (uint16_t u = 0U; u < m->uav_count; u++) {
        if (!plan->routes[u].stranded) {
            value += sva_route_cells(m, u, &plan->routes[u]);
        }
    }
    for (uint16_t t = 0U; t < m->target_count; t++) {
        if ((int32_t)priv->target_served[t] == m->targets[t].need) {
            value -= (int64_t)m->targets[t].need * w->copy_reward[w->target_first_copy[t]];
        }
    }
    return value;
}

uint16_t sva_flow_covered_now(const sva_planner_priv_t* priv, const sva_mission_t* m)
{
    uint16_t covered = 0U;
    for (uint16_t t = 0U; t < m->target_count; t++) {
        covered = (uint16_t)(covered +
                             (((int32_t)priv->target_served[t] == m->targets[t].need) ? 1U : 0U));
    }
    return covered;
}

// The routes of *plan as successor lists over copies (first[u], next[c]).
static void link_routes(sva_flow_work_t* w, const sva_mission_t* m, const sva_plan_t* plan,
                        uint16_t* first, uint16_t* next)
{
    for (uint16_t t = 0U; t < m->target_count; t++) {
        w->target_taken[t] = 0U;
    }
    for (uint16_t u = 0U; u < m->uav_count; u++) {
        const sva_route_t* r = &plan->routes[u];
        uint16_t* link = &first[u];
        for (uint16_t k = 0U; k < r->target_count; k++) {
            const uint16_t t = r->targets[k];
            const uint16_t c = (uint16_t)(w->target_first_copy[t] + w->target_taken[t]);
            w->target_taken[t]++;
            *link = c;
            link = &next[c];
        }
        *link = SVA_FLOW_ROUTE_END;
    }
}

bool sva_flow_offer_plan(sva_planner_priv_t* priv, const sva_mission_t* m, const sva_plan_t* plan)
{
    sva_flow_work_t* w = &priv->flow;
    sva_flow_offer_standing(priv, m, plan);
    const int64_t value = sva_flow_plan_value(priv, m, plan);
    if (w->has_inc && (value >= w->inc_value)) {
        return false;
    }
    link_routes(w, m, plan, w->inc_first, w->inc_next);
    w->inc_value = value;
    w->has_inc = true;
    return true;
}

// ---------------------------------------------------------------------------------
// The plan best against the standing plan (sva_replan()'s).

#if SVA_FLOW_STANDING
void sva_flow_offer_standing(sva_planner_priv_t* priv, const sva_mission_t* m,
                             const sva_plan_t* plan)
{
    sva_flow_work_t* w = &priv->flow;
    const sva_plan_t* standing = w->standing;
    if (standing == NULL) {
        return;
    }
    const uint16_t covered = sva_flow_covered_now(priv, m);
    if (w->has_pen && (covered < w->pen_covered)) {
        return;
    }
    int64_t cost = 0;
    for (uint16_t u = 0U; u < m->uav_count; u++) {
        const sva_route_t* r = &plan->routes[u];
        if (!r->stranded) {
            cost += sva_route_cells(m, u, r);
        }
        w->work += 1U + ((uint64_t)r->target_count * standing->routes[u].target_count);
    }
    const int64_t changes = (int64_t)sva_plan_changes(plan, standing, NULL, 0U) +
                            (int64_t)sva_plan_changes(standing, plan, NULL, 0U);
    const int64_t value = cost + ((int64_t)m->change_penalty * changes);
    if (w->has_pen && (covered == w->pen_covered) && (value >= w->pen_value)) {
        return;
    }
    link_routes(w, m, plan, w->pen_first, w->pen_next);
    w->pen_value = value;
    w->pen_covered = covered;
    w->has_pen = true;
}
#else
void sva_flow_offer_standing(sva_planner_priv_t* priv, const sva_mission_t* m,
                             const sva_plan_t* plan)
{
    (void)priv;
    (void)m;
    (void)plan;
}
#endif  // SVA_FLOW_STANDING

// Whether the incumbent's route from copy a comes before the one from copy b: their
// targets compared in window order (copy ids follow it: flow_graph.c), a route before
// its own extensions, an empty route (SVA_FLOW_ROUTE_END) last.
static bool route_before(const sva_flow_work_t* w, uint16_t a, uint16_t b)
{
    if ((a == SVA_FLOW_ROUTE_END) || (b == SVA_FLOW_ROUTE_END)) {
        return (a != SVA_FLOW_ROUTE_END) && (b == SVA_FLOW_ROUTE_END);
    }
    uint16_t ca = a;
    uint16_t cb = b;
    while ((ca != SVA_FLOW_ROUTE_END) && (cb != SVA_FLOW_ROUTE_END) &&
           (w->copy_target[ca] == w->copy_target[cb])) {
        ca = w->inc_next[ca];
        cb = w->inc_next[cb];
    }
    if ((ca == SVA_FLOW_ROUTE_END) || (cb == SVA_FLOW_ROUTE_END)) {
        return (ca == SVA_FLOW_ROUTE_END) && (cb != SVA_FLOW_ROUTE_END);  // a proper prefix first
    }
    return ca < cb;
}

void sva_flow_canonical_incumbent(sva_planner_priv_t* priv, const sva_mission_t* m)
{
    sva_flow_work_t* w = &priv->flow;
    for (uint16_t i = 0U; i < m->uav_count; i++) {
        const uint16_t a = priv->uav_order[i];
        for (uint16_t j = (uint16_t)(i + 1U); j < m->uav_count; j++) {
            const uint16_t b = priv->uav_order[j];
            if ((w->lagrange.group[a] == w->lagrange.group[b]) &&
                route_before(w, w->inc_first[b], w->inc_first[a])) {
                const uint16_t first = w->inc_first[a];
                w->inc_first[a] = w->inc_first[b];
                w->inc_first[b] = first;
            }
        }
    }
}

// The routes of successor lists first/next into *plan and priv->target_served.
static void write_routes(sva_planner_priv_t* priv, const sva_mission_t* m, sva_plan_t* plan,
                         const uint16_t* first, const uint16_t* next)
{
    const sva_flow_work_t* w = &priv->flow;
    for (uint16_t t = 0U; t < m->target_count; t++) {
        priv->target_served[t] = 0U;
    }
    for (uint16_t u = 0U; u < m->uav_count; u++) {
        sva_route_t* r = &plan->routes[u];
        r->target_count = 0U;
        for (uint16_t c = first[u]; c != SVA_FLOW_ROUTE_END; c = next[c]) {
            const uint16_t t = w->copy_target[c];
            SVA_ASSERT(r->target_count < SVA_MAX_ROUTE_TARGETS);
            r->targets[r->target_count] = t;
            r->target_count++;
            priv->target_served[t]++;
        }
    }
}

void sva_flow_write_incumbent(sva_planner_priv_t* priv, const sva_mission_t* m, sva_plan_t* plan)
{
    write_routes(priv, m, plan, priv->flow.inc_first, priv->flow.inc_next);
}

#if SVA_FLOW_GRANULAR
void sva_flow_keep_current(sva_planner_priv_t* priv, const sva_mission_t* m, const sva_plan_t* plan,
                           int64_t value)
{
    sva_flow_work_t* w = &priv->flow;
    link_routes(w, m, plan, w->cur_first, w->cur_next);
    w->cur_value = value;
}

void sva_flow_write_current(sva_planner_priv_t* priv, const sva_mission_t* m, sva_plan_t* plan)
{
    write_routes(priv, m, plan, priv->flow.cur_first, priv->flow.cur_next);
}
#endif

#if SVA_FLOW_STANDING
bool sva_flow_write_standing_pick(sva_planner_priv_t* priv, const sva_mission_t* m,
                                  sva_plan_t* plan)
{
    if ((priv->flow.standing == NULL) || !priv->flow.has_pen) {
        return false;
    }
    write_routes(priv, m, plan, priv->flow.pen_first, priv->flow.pen_next);
    return true;
}
#endif  // SVA_FLOW_STANDING

void sva_flow_incumbent(sva_planner_priv_t* priv, const sva_mission_t* m, sva_plan_t* plan,
                        int64_t* cost, int64_t* covered)
{
    sva_flow_write_incumbent(priv, m, plan);
    *cost = 0;
    for (uint16_t u = 0U; u < m->uav_count; u++) {
        if (!plan->routes[u].stranded) {
            *cost += sva_route_cells(m, u, &plan->routes[u]);
        }
    }
    *covered = (int64_t)sva_flow_covered_now(priv, m);
}

#if SVA_FLOW_LP_ROWS >= 2
void sva_flow_clear_routes(sva_planner_priv_t* priv, const sva_mission_t* m, sva_plan_t* plan)
{
    for (uint16_t t = 0U; t < m->target_count; t++) {
        priv->target_served[t] = 0U;
    }
    for (uint16_t u = 0U; u < m->uav_count; u++) {
        plan->routes[u].target_count = 0U;
    }
}

uint16_t sva_flow_idle_uav(const sva_mission_t* m, const sva_plan_t* plan, const uint16_t* state,
                           uint16_t want)
{
    uint16_t v = 0U;
    while ((v < m->uav_count) && (plan->routes[v].stranded || (state[v] != want) ||
                                  (plan->routes[v].target_count > 0U))) {
        v++;
    }
    return v;
}
#endif

int64_t sva_flow_cost_floor(const sva_flow_work_t* w, int64_t bound)
{
    // The low bit of the two's complement, which is the parity for negatives too.
    const uint64_t off = ((uint64_t)bound ^ (uint64_t)w->cost_parity) & 1U;
    return bound + (int64_t)off;
}

bool sva_flow_cost_bound(const sva_planner_priv_t* priv, const sva_mission_t* m, int64_t open,
                         int64_t lagrange_bound, bool coverage_known, int64_t* cost, int64_t* bound)
{
    const sva_flow_work_t* w = &priv->flow;
    // Any plan p: cost(p) - reward(p) >= min(best, open). A plan covering c targets
    // earns c * W (exact rewards) or at least c * (W - need + 1), and costs at most
    // w->max_cost < W.
    int64_t covered = 0;
    int64_t reward = 0;
    for (uint16_t t = 0U; t < m->target_count; t++) {
        if ((int32_t)priv->target_served[t] == m->targets[t].need) {
            covered++;
            reward += (int64_t)m->targets[t].need * w->copy_reward[w->target_first_copy[t]];
        }
    }
    *cost = w->inc_value + reward;
    const int64_t least_whole =
        w->reward_exact ? w->reward_whole : (w->reward_whole - w->need_max + 1);
    const int64_t floor_value = (w->inc_value < open) ? w->inc_value : open;
    *bound = floor_value + (covered * least_whole);
    *bound = (*bound < lagrange_bound) ? lagrange_bound : *bound;
    *bound = (*bound > 0) ? sva_flow_cost_floor(w, *bound) : 0;  // 0: no bound (SPEC)
    // No open node holds a plan covering one target more: such a plan's value is at
    // most max_cost - (covered + 1) * least_whole.
    return coverage_known || (floor_value > (w->max_cost - ((covered + 1) * least_whole)));
}
