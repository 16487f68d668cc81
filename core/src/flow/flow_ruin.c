// flow_ruin.c -- flow's ruin and recreate (DESIGN.md section 8).
//
// The incumbent loses a group of related visits, and the repair
// puts a plan back together (uncovered targets inserted in window order, every other
// round in reverse, ejection, local search when within reach, offer). For each group
// size in turn, each covered target s seeds a group: s and the covered targets
// nearest to it (cells between them plus the ticks between their window starts, in
// cells). With need 2 this is how a target short of its second UAV finds one: the
// group's visits leave room. Then swaps: one covered target out, one uncovered in.
// A large mission's rounds start from a current plan instead of the incumbent, which
// a round's plan replaces when within a falling threshold of it (threshold accepting).
// A plan with a need above 1 ends with such rounds (sva_flow_ruin_accepting).
#include "flow.h"

#define RUIN_ROUND_UNITS 8U   // work units per round, per target inserted x UAV
#define ACCEPT_SHARE     100  // the threshold starts at the incumbent's cost / ACCEPT_SHARE

static int64_t relatedness(const sva_mission_t* m, uint16_t a, uint16_t b)
{
    const sva_target_t* ta = &m->targets[a];
    const sva_target_t* tb = &m->targets[b];
    const int64_t ticks = (int64_t)ta->start_ticks - (int64_t)tb->start_ticks;
    return sva_distance(ta->x, ta->y, tb->x, tb->y) +
           (((ticks < 0) ? -ticks : ticks) / m->ticks_per_cell);
}

#if SVA_FLOW_GRANULAR
// Each target's SVA_FLOW_NEAR most related targets, nearest first (ties: lower index),
// the local search's granular neighbourhood during ruin and recreate.
static void find_near(sva_flow_work_t* w, const sva_mission_t* m)
{
    const uint16_t k_max = (m->target_count > (uint16_t)SVA_FLOW_NEAR)
                               ? (uint16_t)SVA_FLOW_NEAR
                               : (uint16_t)(m->target_count - 1U);
    w->near_count = k_max;
    for (uint16_t s = 0U; s < m->target_count; s++) {
        uint16_t n = 0U;
        for (uint16_t t = 0U; t < m->target_count; t++) {
            if (t == s) {
                continue;
            }
            const int64_t rel = relatedness(m, s, t);
            uint16_t at = n;
            while ((at > 0U) && (relatedness(m, s, w->near[s][at - 1U]) > rel)) {
                at--;
            }
            if (at >= k_max) {
                continue;
            }
            const uint16_t last = (n < k_max) ? n : (uint16_t)(k_max - 1U);
            for (uint16_t j = last; j > at; j--) {
                w->near[s][j] = w->near[s][j - 1U];
            }
            w->near[s][at] = t;
            n = (n < k_max) ? (uint16_t)(n + 1U) : n;
        }
    }
    for (uint16_t u = 0U; u < m->uav_count; u++) {
        w->uav_tried[u] = 0U;
    }
    w->try_epoch = 0U;
    w->work += (uint64_t)m->target_count * m->target_count;
}

// Threshold accepting (Dueck and Scheuer, 1990) for a large mission's rounds: a round's
// plan becomes the current one when its value is at most the current's plus a threshold
// that falls linearly from the incumbent's cost / ACCEPT_SHARE, when the rounds start,
// to 0 when their budget [from, to) is spent. Descent alone (each round from the
// incumbent) stalls on 100-target missions where fuel binds (docs/results.md). The
// incumbent, which the repair offered the plan to, keeps the best.
static void accept(sva_planner_priv_t* priv, const sva_mission_t* m, sva_plan_t* plan,
                   uint64_t from, uint64_t to, int64_t start_cost)
{
    const sva_flow_work_t* w = &priv->flow;
    int64_t threshold = 0;
    if ((to > from) && (to > w->work)) {
        const uint64_t span = to - from;
        const uint64_t left = to - w->work;
        const uint64_t share = (left < span) ? left : span;
        const uint64_t top = (uint64_t)start_cost / (uint64_t)ACCEPT_SHARE;
        const uint64_t part = (top * share) / span;
        threshold = (int64_t)part;
    }
    const int64_t value = sva_flow_plan_value(priv, m, plan);
    if (value <= (w->cur_value + threshold)) {
        sva_flow_keep_current(priv, m, plan, value);
    }
}
#endif

// The incumbent without s and the size - 1 covered targets most related to it.
static void ruin(sva_planner_priv_t* priv, const sva_mission_t* m, sva_plan_t* plan, uint16_t s,
                 uint8_t size)
{
    sva_flow_work_t* w = &priv->flow;
    for (uint16_t u = 0U; u < m->uav_count; u++) {
        w->route_cells[u] = sva_route_cells(m, u, &plan->routes[u]);
#if SVA_FLOW_GRANULAR
        w->route_changed[u] = 0U;
#endif
    }
    sva_flow_remove_target(priv, m, plan, s);
    for (uint8_t k = 1U; k < size; k++) {
        int32_t pick = -1;
        int64_t pick_rel = 0;
        for (uint16_t t = 0U; t < m->target_count; t++) {
            const int64_t rel = relatedness(m, s, t);
            if ((priv->target_served[t] > 0U) && ((pick < 0) || (rel < pick_rel))) {
                pick = (int32_t)t;
                pick_rel = rel;
            }
        }
        if (pick >= 0) {
            sva_flow_remove_target(priv, m, plan, (uint16_t)pick);
        }
    }
}

// One round on the plan in *plan: s and the size - 1 covered targets most related to it
// out, then the repair (insertions in reverse window order when `backwards`; its local
// search only from the changed routes when `granular`), charged `units` of work.
static void ruin_round(sva_planner_priv_t* priv, const sva_mission_t* m, sva_plan_t* plan,
                       uint16_t s, uint8_t size, bool backwards, bool granular, uint64_t units)
{
    sva_flow_work_t* w = &priv->flow;
    ruin(priv, m, plan, s, size);
    w->insert_backwards = backwards;
#if SVA_FLOW_GRANULAR
    w->local_changed_only = granular;
#else
    (void)granular;
#endif
    sva_flow_repair(priv, m, plan, true);
#if SVA_FLOW_GRANULAR
    w->local_changed_only = false;
#endif
    w->insert_backwards = false;
    w->work += units;
    plan->stats.flow_ruin_rounds++;
}

#if SVA_FLOW_GRANULAR
// A round from the current plan in *plan (ruin_round), then the threshold's test over
// the rounds' span [from, to) for a plan that started at start_cost; leaves the current
// plan in *plan.
static void accepting_round(sva_planner_priv_t* priv, const sva_mission_t* m, sva_plan_t* plan,
                            uint16_t s, uint8_t size, bool backwards, bool granular, uint64_t units,
                            uint64_t from, uint64_t to, int64_t start_cost)
{
    ruin_round(priv, m, plan, s, size, backwards, granular, units);
    accept(priv, m, plan, from, to, start_cost);
    sva_flow_write_current(priv, m, plan);
}

void sva_flow_ruin_accepting(sva_planner_priv_t* priv, const sva_mission_t* m, sva_plan_t* plan,
                             uint64_t end, int64_t proven_bound)
{
    // Group sizes, pass by pass; each pass starts its seeds three targets further on.
    static const uint8_t sizes[] = {4U, 7U, 2U, 9U, 5U, 12U, 3U, 6U};
    sva_flow_work_t* w = &priv->flow;
    int64_t cost = 0;
    int64_t covered = 0;
    sva_flow_incumbent(priv, m, plan, &cost, &covered);
    if (proven_bound >= cost) {
        return;  // proven optimal
    }
    const uint64_t units = (uint64_t)m->target_count * m->uav_count * RUIN_ROUND_UNITS;
    const uint64_t from = w->work;
    sva_flow_keep_current(priv, m, plan, sva_flow_plan_value(priv, m, plan));
    uint32_t pass = 0U;
    // A pass without a covered target to seed a round ends them: a plan covering
    // nothing gets none.
    bool seeded = true;
    while (seeded && (w->work < end)) {
        const uint8_t size = sizes[pass % (uint32_t)(sizeof(sizes) / sizeof(sizes[0]))];
        const uint32_t first = pass * 3U;
        seeded = false;
        for (uint16_t k = 0U; (k < m->target_count) && (w->work < end); k++) {
            const uint16_t s = (uint16_t)((first + k) % m->target_count);
            if ((int32_t)priv->target_served[s] == m->targets[s].need) {
                accepting_round(priv, m, plan, s, size, ((k + pass) % 2U) == 1U, false, units, from,
                                end, cost);
                seeded = true;
            }
        }
        pass++;
    }
    sva_flow_write_incumbent(priv, m, plan);
}
#endif

bool sva_flow_ruin_recreate(sva_planner_priv_t* priv, const sva_mission_t* m, sva_plan_t* plan,
                            uint64_t end, int64_t proven_bound)
{
    static const uint8_t ruin_sizes[] = {6U, 8U, 10U, 3U};  // group sizes, in turn
    sva_flow_work_t* w = &priv->flow;
    int64_t cost = 0;
    int64_t covered = 0;
    sva_flow_incumbent(priv, m, plan, &cost, &covered);
    if (proven_bound >= cost) {
        return true;  // proven optimal: nothing to find
    }
    // Not when the coverage is proven and the plan within 1/SVA_FLOW_CLOSE of the bound:
    // the search, with the rest of the budget, may prove it.
    const bool near = sva_flow_close(cost, proven_bound);
    const uint64_t rest = ((end > w->work) && !near) ? (end - w->work) : 0U;
    const uint64_t budget = w->work + (rest - (rest / 4U));
    // A round's insertions: every target's, or past SVA_FLOW_LARGE_FROM targets
    // the ruined ones' (a swap round: two) and a scan of the targets.
    const bool large = sva_flow_large(m);
    const uint64_t uav_units = (uint64_t)m->uav_count * RUIN_ROUND_UNITS;
    const uint64_t whole_units = (uint64_t)m->target_count * uav_units;
#if SVA_FLOW_GRANULAR
    const uint64_t from = w->work;
    if (large && (rest > 0U)) {
        find_near(w, m);
        sva_flow_keep_current(priv, m, plan, sva_flow_plan_value(priv, m, plan));
    }
#endif
    // *plan holds the incumbent (a large mission's rounds: the current plan) whenever a
    // round is chosen (sva_flow_incumbent above, then a write after each round).
    for (size_t i = 0U; i < (sizeof(ruin_sizes) / sizeof(ruin_sizes[0])); i++) {
        for (uint16_t s = 0U; (s < m->target_count) && (w->work < budget); s++) {
            if ((int32_t)priv->target_served[s] == m->targets[s].need) {
                const bool backwards = ((s + i) % 2U) == 1U;
#if SVA_FLOW_GRANULAR
                if (large) {
                    const uint64_t units = (uint64_t)m->target_count + (ruin_sizes[i] * uav_units);
                    accepting_round(priv, m, plan, s, ruin_sizes[i], backwards, true, units, from,
                                    budget, cost);
                    continue;
                }
#endif
                ruin_round(priv, m, plan, s, ruin_sizes[i], backwards, false, whole_units);
                sva_flow_write_incumbent(priv, m, plan);
            }
        }
    }
#if SVA_FLOW_GRANULAR
    sva_flow_write_incumbent(priv, m, plan);  // the swaps start from the incumbent
#endif
    // Swaps: a covered target c leaves, an uncovered target t goes in first (all its
    // need at once), and the repair puts the rest back. With need 2 a plan may cover
    // the right number of targets but the wrong ones; groups reinserted in window
    // order rarely change which.
    for (uint16_t c = 0U; (c < m->target_count) && (w->work < budget); c++) {
        for (uint16_t t = 0U; (t < m->target_count) && (w->work < budget); t++) {
            if (((int32_t)priv->target_served[c] == m->targets[c].need) &&
                (priv->target_served[t] == 0U)) {
                ruin(priv, m, plan, c, 1U);
                sva_flow_try_insert(priv, m, plan, t);
                if (priv->target_served[t] != 0U) {
                    sva_flow_repair(priv, m, plan, true);
                    plan->stats.flow_ruin_rounds++;
                }
                w->work += large ? ((uint64_t)m->target_count + (2U * uav_units)) : whole_units;
                sva_flow_write_incumbent(priv, m, plan);
            }
        }
    }
    return false;
}
