// flow_graph.c -- flow's time-feasibility graph (DESIGN.md section 8).
//
// A target with need n becomes n copies of need 1, so every node carries at most one
// unit and a flow decomposes into routes in exactly one way. The pooled graph (its root
// alone: flow.c's pooled_first) keeps one copy per target whose own arc carries up to
// n units: the same relaxation value, with about a quarter of the
// arcs at need 2 (copies of a target are interchangeable, and a path through the DAG
// visits a target once). Node ids:
//   0 .. U-1          the UAVs (mission order); a stranded UAV has no arcs
//   U .. U+C-1        copy c's in-node  (U + c)
//   U+C .. U+2C-1     copy c's out-node (U + C + c); in -> out is the copy's own arc
//   U+2C              the depot z, where every UAV's unit ends
//   U+2C+1            the super sink (the depot and forced copies drain into it)
// Copies follow the targets' (start, end, id) order. A UAV serves b after a only if
// a.end + travel <= b.start, so a.start < b.start: copy ids are a topological order.
// Explicit arcs (CSR by tail, arc costs = Manhattan distance):
//   u -> c_in    u can be at the target by its start, with fuel for some route on;
//   u -> z       flying home serving nothing;
//   c_out -> d_in  the windows chain in time, and some UAV could fly a route
//                through t -> t' on its fuel (fuel_labels: a necessary condition);
//   c_out -> z.
#include "flow.h"

#define FLOW_INT64_LIMIT (INT64_MAX / 4)

// Rewards: a covered target earns W, each copy W / need. W exceeds any flow cost
// (every node sends at most one unit, so a flow costs at most (U + C) * the widest
// leg), so covering one more target always wins (SPEC section 1 order). W is a
// multiple of every need when that fits int64 (exact ties); otherwise coverage stays
// exact and only ties in cost may be broken by at most need - 1 (reward_exact false).
static void set_rewards(sva_flow_work_t* w, const sva_mission_t* m, int64_t widest_leg)
{
    int32_t need_max = 1;
    for (uint16_t t = 0U; t < m->target_count; t++) {
        need_max = (m->targets[t].need > need_max) ? m->targets[t].need : need_max;
    }
    w->need_max = need_max;
    // Units cross arcs: at most one per UAV and one per slot (need summed) on their way.
    int64_t slots = 0;
    for (uint16_t t = 0U; t < m->target_count; t++) {
        slots += m->targets[t].need;
    }
    const int64_t max_cost = ((int64_t)w->uavs + slots) * widest_leg;
    // Even, so that a plan's value keeps its cost's parity (flow.c, no_better).
    int64_t base = max_cost + 1 + ((int64_t)m->target_count * (int64_t)need_max);
    base += base % 2;
    const int64_t room = FLOW_INT64_LIMIT / (base * ((int64_t)m->target_count + 1));
    int64_t lcm = 1;
    bool exact = true;
    for (uint16_t t = 0U; (t < m->target_count) && exact; t++) {
        const int64_t need = m->targets[t].need;
        const int64_t step = need / sva_gcd64(lcm, need);
        // step >= 1 as validation keeps need >= 1; the guard keeps the division safe
        // on its own.
        if ((step < 1) || (lcm > (room / step))) {
            exact = false;
        } else {
            lcm *= step;
        }
    }
    w->max_cost = max_cost;
    w->reward_exact = exact;
    w->reward_whole = base * (exact ? lcm : 1);
    for (uint16_t c = 0U; c < w->copies; c++) {
        w->copy_reward[c] = w->reward_whole / m->targets[w->copy_target[c]].need;
    }
}

static int32_t node_distance(const sva_flow_work_t* w, uint16_t a, uint16_t b)
{
    return sva_distance(w->node_x[a], w->node_y[a], w->node_x[b], w->node_y[b]);
}

static void place_nodes(sva_flow_work_t* w, const sva_mission_t* m)
{
    const uint16_t u_count = w->uavs;
    const uint16_t c_count = w->copies;
    for (uint16_t u = 0U; u < u_count; u++) {
        w->node_x[u] = m->uavs[u].x;
        w->node_y[u] = m->uavs[u].y;
    }
    for (uint16_t c = 0U; c < c_count; c++) {
        const sva_target_t* t = &m->targets[w->copy_target[c]];
        w->node_x[u_count + c] = t->x;
        w->node_y[u_count + c] = t->y;
        w->node_x[u_count + c_count + c] = t->x;
        w->node_y[u_count + c_count + c] = t->y;
    }
    for (uint16_t k = 0U; k < 2U; k++) {
        w->node_x[u_count + (2U * c_count) + k] = m->depot_x;
        w->node_y[u_count + (2U * c_count) + k] = m->depot_y;
    }
}

static int64_t widest_leg(const sva_flow_work_t* w)
{
    const uint32_t n = (uint32_t)w->uavs + (2U * (uint32_t)w->copies) + 1U;
    int32_t x_lo = w->node_x[0];
    int32_t x_hi = x_lo;
    int32_t y_lo = w->node_y[0];
    int32_t y_hi = y_lo;
    for (uint32_t v = 1U; v < n; v++) {
        x_lo = (w->node_x[v] < x_lo) ? w->node_x[v] : x_lo;
        x_hi = (w->node_x[v] > x_hi) ? w->node_x[v] : x_hi;
        y_lo = (w->node_y[v] < y_lo) ? w->node_y[v] : y_lo;
        y_hi = (w->node_y[v] > y_hi) ? w->node_y[v] : y_hi;
    }
    return ((int64_t)x_hi - x_lo) + ((int64_t)y_hi - y_lo);
}

// Appends arc tail -> head when there is room; always counts it.
static void add_arc(sva_flow_work_t* w, uint16_t tail, uint16_t head)
{
    if (w->arcs < (uint32_t)SVA_FLOW_MAX_ARCS) {
        w->arc_tail[w->arcs] = tail;
        w->arc_head[w->arcs] = head;
    }
    w->arcs++;
}

static bool uav_in_time(const sva_mission_t* m, uint16_t u, uint16_t t)
{
    const sva_uav_t* uav = &m->uavs[u];
    const sva_target_t* tg = &m->targets[t];
    const int64_t leg = sva_distance(uav->x, uav->y, tg->x, tg->y);
    return (uav->ready_at_ticks + (leg * m->ticks_per_cell)) <= tg->start_ticks;
}

bool sva_flow_targets_chain(const sva_mission_t* m, uint16_t a, uint16_t b)
{
    const sva_target_t* ta = &m->targets[a];
    const sva_target_t* tb = &m->targets[b];
    const int64_t leg = sva_distance(ta->x, ta->y, tb->x, tb->y);
    return (ta->end_ticks + (leg * m->ticks_per_cell)) <= tb->start_ticks;
}

static int64_t target_distance(const sva_mission_t* m, uint16_t a, uint16_t b)
{
    return sva_distance(m->targets[a].x, m->targets[a].y, m->targets[b].x, m->targets[b].y);
}

// Fuel labels over the time DAG of targets (necessary conditions, exact when the
// UAVs' fuel is equal):
//   lead[t] = least (fuel flown + hover, up to and including t) - that UAV's fuel,
//             over every UAV and time-feasible way of reaching t;
//   tail[t] = least fuel from t (its hover included) back to the depot.
// A route through arc a -> b needs lead[a] + |a b| + tail[b] <= 0; through u -> t,
// |u t| + tail[t] <= fuel(u). Rejected arcs lie on no fuel-feasible route.
static void fuel_labels(sva_planner_priv_t* priv, const sva_mission_t* m, const sva_plan_t* plan)
{
    sva_flow_work_t* w = &priv->flow;
    int64_t* lead = w->target_lead;
    int64_t* tail = w->target_tail;
    const uint16_t n = m->target_count;
    for (uint16_t i = 0U; i < n; i++) {
        const uint16_t t = priv->target_order[i];
        const sva_target_t* tg = &m->targets[t];
        lead[t] = INT64_MAX / 4;
        for (uint16_t u = 0U; u < m->uav_count; u++) {
            const sva_uav_t* uav = &m->uavs[u];
            const int64_t v =
                (int64_t)sva_distance(uav->x, uav->y, tg->x, tg->y) + m->hover_fuel - uav->fuel;
            if (!plan->routes[u].stranded && uav_in_time(m, u, t) && (v < lead[t])) {
                lead[t] = v;
            }
        }
        for (uint16_t j = 0U; j < i; j++) {
            const uint16_t a = priv->target_order[j];
            const int64_t v = lead[a] + target_distance(m, a, t) + m->hover_fuel;
            if ((lead[a] < (INT64_MAX / 4)) && sva_flow_targets_chain(m, a, t) && (v < lead[t])) {
                lead[t] = v;
            }
        }
    }
    for (uint16_t i = n; i > 0U; i--) {
        const uint16_t t = priv->target_order[i - 1U];
        const sva_target_t* tg = &m->targets[t];
        tail[t] = (int64_t)m->hover_fuel + sva_distance(tg->x, tg->y, m->depot_x, m->depot_y);
        for (uint16_t j = i; j < n; j++) {
            const uint16_t b = priv->target_order[j];
            const int64_t v = (int64_t)m->hover_fuel + target_distance(m, t, b) + tail[b];
            if (sva_flow_targets_chain(m, t, b) && (v < tail[t])) {
                tail[t] = v;
            }
        }
    }
}

static bool uav_reaches(const sva_mission_t* m, const sva_flow_work_t* w, uint16_t u, uint16_t c)
{
    const uint16_t t = w->copy_target[c];
    const sva_uav_t* uav = &m->uavs[u];
    const sva_target_t* tg = &m->targets[t];
    return uav_in_time(m, u, t) &&
           (((int64_t)sva_distance(uav->x, uav->y, tg->x, tg->y) + w->target_tail[t]) <= uav->fuel);
}

static bool copies_chain(const sva_mission_t* m, const sva_flow_work_t* w, uint16_t c, uint16_t d)
{
    const uint16_t a = w->copy_target[c];
    const uint16_t b = w->copy_target[d];
    return sva_flow_targets_chain(m, a, b) &&
           ((w->target_lead[a] + target_distance(m, a, b) + w->target_tail[b]) <= 0);
}

static void index_heads(sva_flow_work_t* w, uint32_t nodes)
{
    for (uint32_t v = 0U; v <= nodes; v++) {
        w->in_start[v] = 0U;
    }
    for (uint32_t e = 0U; e < w->arcs; e++) {
        w->in_start[w->arc_head[e] + 1U]++;
    }
    for (uint32_t v = 0U; v < nodes; v++) {
        w->in_start[v + 1U] += w->in_start[v];
    }
    // Fill in arc order with in_start[h] as the cursor, then shift the starts back.
    for (uint32_t e = 0U; e < w->arcs; e++) {
        const uint16_t h = w->arc_head[e];
        w->in_arc[w->in_start[h]] = (sva_flow_arc_t)e;
        w->in_start[h]++;
    }
    for (uint32_t v = nodes; v > 0U; v--) {
        w->in_start[v] = w->in_start[v - 1U];
    }
    w->in_start[0] = 0U;
}

// UAVs in the same state (position, ready time, fuel) share a group: the first of them.
// The shortest paths start as a bound's (only the heuristic's flights ask for real paths).
static void group_uavs(sva_flow_lagrange_t* lg, const sva_mission_t* m)
{
    lg->labels = (uint16_t)SVA_FLOW_LABELS;
#if SVA_FLOW_LARGE
    lg->real_paths = false;
#endif
    for (uint16_t u = 0U; u < m->uav_count; u++) {
        const sva_uav_t* a = &m->uavs[u];
        lg->group[u] = u;
        for (uint16_t v = 0U; v < u; v++) {
            const sva_uav_t* b = &m->uavs[v];
            if ((a->x == b->x) && (a->y == b->y) && (a->ready_at_ticks == b->ready_at_ticks) &&
                (a->fuel == b->fuel)) {
                lg->group[u] = v;
                break;
            }
        }
    }
}

sva_flow_incomplete_t sva_flow_build(sva_planner_priv_t* priv, const sva_mission_t* m,
                                     const sva_plan_t* plan, bool pooled, sva_stats_t* stats)
{
    sva_flow_work_t* w = &priv->flow;
    int64_t copies = 0;
    for (uint16_t t = 0U; t < m->target_count; t++) {
        copies += pooled ? 1 : m->targets[t].need;
    }
    if (copies > SVA_FLOW_MAX_COPIES) {
        return SVA_FLOW_OVER_COPIES;
    }
    w->uavs = m->uav_count;
    w->copies = (uint16_t)copies;
    uint16_t c = 0U;
    for (uint16_t i = 0U; i < m->target_count; i++) {
        const uint16_t t = priv->target_order[i];
        const int32_t need = m->targets[t].need;
        w->target_first_copy[t] = c;
        for (int32_t k = 0; k < (pooled ? 1 : need); k++) {
            w->copy_target[c] = t;
            w->copy_units[c] = (uint8_t)(pooled ? need : 1);  // pooled: need <= UINT8_MAX
            w->copy_cover[c] = 0U;
            w->copy_forced[c] = 0U;
            w->copy_banned[c] = 0U;
            c++;
        }
    }
    place_nodes(w, m);
    group_uavs(&w->lagrange, m);
    set_rewards(w, m, widest_leg(w));

    fuel_labels(priv, m, plan);
    const uint16_t u_count = w->uavs;
    const uint16_t c_count = w->copies;
    const uint16_t depot = (uint16_t)(u_count + (2U * c_count));
    const uint32_t nodes = (uint32_t)depot + 2U;
    w->arcs = 0U;
    // Every plan's cost modulo 2 (sva_flow_cost_floor): each UAV that is not stranded
    // flies a route (an empty one too) whose length is its distance home modulo 2, and
    // |dx| + |dy| has the parity of x + y + the depot's x + y.
    uint32_t parity = 0U;
    for (uint16_t u = 0U; u < u_count; u++) {
        w->out_start[u] = w->arcs;
        if (plan->routes[u].stranded) {
            continue;
        }
        parity ^= (uint32_t)m->uavs[u].x ^ (uint32_t)m->uavs[u].y ^ (uint32_t)m->depot_x ^
                  (uint32_t)m->depot_y;
        for (uint16_t d = 0U; d < c_count; d++) {
            if (uav_reaches(m, w, u, d)) {
                add_arc(w, u, (uint16_t)(u_count + d));
            }
        }
        add_arc(w, u, depot);
    }
    for (uint16_t d = 0U; d < c_count; d++) {
        w->out_start[u_count + d] = w->arcs;  // in-nodes: only the copy's own arc
    }
    for (uint16_t a = 0U; a < c_count; a++) {
        w->out_start[u_count + c_count + a] = w->arcs;
        for (uint16_t d = (uint16_t)(a + 1U); d < c_count; d++) {
            if (copies_chain(m, w, a, d)) {
                add_arc(w, (uint16_t)(u_count + c_count + a), (uint16_t)(u_count + d));
            }
        }
        add_arc(w, (uint16_t)(u_count + c_count + a), depot);
    }
    w->cost_parity = (uint8_t)(parity & 1U);
    w->out_start[depot] = w->arcs;
    w->out_start[depot + 1U] = w->arcs;
    w->out_start[nodes] = w->arcs;
    stats->flow_graph_arcs = w->arcs;
    if (w->arcs > (uint32_t)SVA_FLOW_MAX_ARCS) {
        return SVA_FLOW_OVER_ARCS;
    }
    for (uint32_t e = 0U; e < w->arcs; e++) {
        w->arc_flow[e] = 0U;
        w->arc_ban[e] = 0U;
    }
    index_heads(w, nodes);
    return SVA_FLOW_COMPLETE;
}

int32_t sva_flow_arc_cost(const sva_flow_work_t* w, uint32_t arc)
{
    return node_distance(w, w->arc_tail[arc], w->arc_head[arc]);
}
