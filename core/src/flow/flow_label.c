// flow_label.c -- a UAV's best route under target prices: the resource-constrained
// shortest path that both the Lagrangian (flow_lagrange.c) and the route master's
// pricing (flow_lp.c) run (DESIGN.md section 8).
//
// The DAG of targets is the first copies of flow_graph.c's graph, fuel the resource:
// labels (reduced cost, fuel used), Pareto-best, at most SVA_FLOW_LABELS per target
// (more with cells free: labels_for); past that two merge into one that dominates
// both, which can only weaken a bound.
// A merged label's path may break fuel, so a heuristic that flies the paths can ask
// for real ones instead (lg->real_paths): of the two, the cheaper label is kept as it
// is, which keeps every path flyable but is no bound.
#include "flow.h"

#define COVER_LABELS 64U  // labels per target with cells free, at most (uint8_t counts)

// Copy d is the first copy of its target (the DAG of targets uses only those).
static bool first_copy(const sva_flow_work_t* w, uint16_t d)
{
    return w->target_first_copy[w->copy_target[d]] == d;
}

// Whether a full label set keeps real paths (only a large mission's heuristic asks).
static inline bool keeps_real_paths(const sva_flow_lagrange_t* lg)
{
#if SVA_FLOW_LARGE
    return lg->real_paths;
#else
    (void)lg;
    return false;
#endif
}

// Whether a label of target t's Pareto set dominates (cost, fuel); tested inline, so
// that only labels that go in pay for the call to add_label.
static inline bool dominated(const sva_flow_lagrange_t* lg, uint16_t t, int64_t cost, int32_t fuel)
{
    const uint32_t base = (uint32_t)t * sva_flow_label_stride(lg);
    const uint32_t end = base + lg->label_count[t];
    for (uint32_t j = base; j < end; j++) {
        if ((lg->label_fuel[j] <= fuel) && (lg->label_cost[j] <= cost)) {
            return true;
        }
    }
    return false;
}

// Adds label (cost, fuel, pred) to target t's Pareto set, which none dominates.
static void add_label(sva_flow_lagrange_t* lg, uint16_t t, int64_t cost, int32_t fuel,
                      uint32_t pred)
{
    const uint32_t base = (uint32_t)t * sva_flow_label_stride(lg);
    uint32_t n = lg->label_count[t];
    int64_t new_cost = cost;
    int32_t new_fuel = fuel;
    uint32_t new_pred = pred;
    if (n == sva_flow_label_stride(lg)) {
        // Full: merge into the label nearest in fuel (min of both: dominates both),
        // which leaves the set to be re-added; for real paths, keep the cheaper.
        uint32_t near = base;
        for (uint32_t j = base + 1U; j < (base + n); j++) {
            const int64_t dj = (int64_t)lg->label_fuel[j] - fuel;
            const int64_t dn = (int64_t)lg->label_fuel[near] - fuel;
            near = (((dj < 0) ? -dj : dj) < ((dn < 0) ? -dn : dn)) ? j : near;
        }
        if (lg->label_cost[near] <= cost) {
            if (keeps_real_paths(lg)) {
                return;
            }
            new_cost = lg->label_cost[near];
            new_pred = lg->label_pred[near];
        }
        if (!keeps_real_paths(lg) && (lg->label_fuel[near] < fuel)) {
            new_fuel = lg->label_fuel[near];
        }
        lg->label_cost[near] = lg->label_cost[base + n - 1U];
        lg->label_fuel[near] = lg->label_fuel[base + n - 1U];
        lg->label_pred[near] = lg->label_pred[base + n - 1U];
        n--;
    }
    uint32_t kept = base;
    for (uint32_t j = base; j < (base + n); j++) {
        if ((new_fuel > lg->label_fuel[j]) || (new_cost > lg->label_cost[j])) {
            lg->label_cost[kept] = lg->label_cost[j];
            lg->label_fuel[kept] = lg->label_fuel[j];
            lg->label_pred[kept] = lg->label_pred[j];
            kept++;
        }
    }
    lg->label_cost[kept] = new_cost;
    lg->label_fuel[kept] = new_fuel;
    lg->label_pred[kept] = new_pred;
    lg->label_count[t] = (uint8_t)((kept - base) + 1U);
}

void sva_flow_label_path(sva_flow_lagrange_t* lg, uint32_t l)
{
    lg->path_len = 0U;
    for (uint32_t k = l; k != SVA_FLOW_NO_LABEL; k = lg->label_pred[k]) {
        lg->path[lg->path_len] = (uint16_t)(k / sva_flow_label_stride(lg));
        lg->path_len++;
    }
    for (uint16_t i = 0U; i < (lg->path_len / 2U); i++) {
        const uint16_t k = lg->path[i];
        lg->path[i] = lg->path[lg->path_len - 1U - i];
        lg->path[lg->path_len - 1U - i] = k;
    }
}

#if SVA_FLOW_LP_ROWS >= 2
// Labels per target for a route with cells weighted by alpha: with cells at no cost (alpha 0:
// the coverage questions, flow_lagrange.c and flow_lp.c), a UAV's Pareto set of
// (reduced cost, fuel) is long and merged labels weaken the coverage bound, so as many
// as the label store holds for the mission's targets, at most COVER_LABELS; otherwise
// SVA_FLOW_LABELS.
static uint16_t labels_for(const sva_mission_t* m, int64_t alpha)
{
    const uint32_t room = ((uint32_t)SVA_MAX_TARGETS * (uint32_t)SVA_FLOW_LABELS) / m->target_count;
    const uint32_t wide = (room < COVER_LABELS) ? room : COVER_LABELS;
    return (uint16_t)((alpha == 0) ? wide : (uint32_t)SVA_FLOW_LABELS);
}
#endif

// UAV u's best route under lg->path_price (targets with lg->closed skipped):
// min over routes of alpha * cells - sum of prices, flying home at once included.
// The route goes to lg->path. Label extensions count as work.
int64_t sva_flow_best_route(sva_flow_work_t* w, const sva_mission_t* m, uint16_t u, int64_t alpha)
{
    sva_flow_lagrange_t* lg = &w->lagrange;
    const sva_uav_t* uav = &m->uavs[u];
    const int64_t hover = m->hover_fuel;
    const uint16_t out_base = (uint16_t)(w->uavs + w->copies);
#if SVA_FLOW_LP_ROWS >= 2
    lg->labels = labels_for(m, alpha);
#endif
    for (uint16_t t = 0U; t < m->target_count; t++) {
        lg->label_count[t] = 0U;
    }
    for (uint32_t e = w->out_start[u]; e < w->out_start[u + 1U]; e++) {
        const uint16_t h = w->arc_head[e];
        if ((h >= w->uavs) && (h < out_base) && first_copy(w, (uint16_t)(h - w->uavs))) {
            const uint16_t t = w->copy_target[h - w->uavs];
            if (lg->closed[t] == 0U) {
                const int64_t leg = sva_distance(uav->x, uav->y, m->targets[t].x, m->targets[t].y);
                const int64_t cost = (alpha * leg) - lg->path_price[t];
                if (!dominated(lg, t, cost, (int32_t)(leg + hover))) {
                    add_label(lg, t, cost, (int32_t)(leg + hover), SVA_FLOW_NO_LABEL);
                }
                w->work++;
            }
        }
    }
    int64_t best = alpha * sva_distance(uav->x, uav->y, m->depot_x, m->depot_y);
    uint32_t best_label = SVA_FLOW_NO_LABEL;
    for (uint16_t c = 0U; c < w->copies; c++) {
        const uint16_t t = w->copy_target[c];
        if (!first_copy(w, c) || (lg->label_count[t] == 0U)) {
            continue;
        }
        const sva_target_t* tg = &m->targets[t];
        const uint32_t base = (uint32_t)t * sva_flow_label_stride(lg);
        const uint16_t tail = (uint16_t)(out_base + c);
        // Labels of t are final here: every arc into t comes from an earlier copy.
        const uint32_t end = base + lg->label_count[t];
        {
            const int32_t home = sva_distance(tg->x, tg->y, m->depot_x, m->depot_y);
            for (uint32_t l = base; l < end; l++) {
                if ((((int64_t)lg->label_fuel[l] + home) <= uav->fuel) &&
                    ((lg->label_cost[l] + (alpha * home)) < best)) {
                    best = lg->label_cost[l] + (alpha * home);
                    best_label = l;
                }
            }
        }
        // Arc by arc, then label by label: the arcs lead to different targets, so
        // each target b still receives t's labels in index order. flow_graph.c adds
        // the arcs in copy order, the depot's last: the arcs into b's copies are
        // adjacent, its first copy's first, and that one stands for all need of them
        // (the Lagrangian phase runs on the graph of copies, never the pooled one).
        uint32_t e = w->out_start[tail];
        while (e < w->out_start[tail + 1U]) {
            const uint16_t h = w->arc_head[e];
            if (h >= out_base) {
                break;  // the depot
            }
            SVA_ASSERT(first_copy(w, (uint16_t)(h - w->uavs)) &&
                       (w->copy_units[h - w->uavs] == 1U));
            const uint16_t b = w->copy_target[h - w->uavs];
            e += (uint32_t)m->targets[b].need;
            w->work += lg->label_count[t];
            if (lg->closed[b] == 0U) {
                const int32_t leg = sva_distance(tg->x, tg->y, m->targets[b].x, m->targets[b].y);
                const int64_t fuel_cap = uav->fuel - leg - w->target_tail[b];
                const int64_t leg_price = (alpha * leg) - lg->path_price[b];
                for (uint32_t l = base; l < end; l++) {
                    const int64_t cost = lg->label_cost[l] + leg_price;
                    const int32_t fuel = (int32_t)((int64_t)lg->label_fuel[l] + leg + hover);
                    if (((int64_t)lg->label_fuel[l] <= fuel_cap) && !dominated(lg, b, cost, fuel)) {
                        add_label(lg, b, cost, fuel, l);
                    }
                }
            }
        }
    }
    sva_flow_label_path(lg, best_label);
    return best;
}
