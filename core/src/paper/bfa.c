// bfa.c -- the exact optimum of SPEC section 1 by exhaustive search (paper section
// 4.2), for small missions: at most SVA_BFA_MAX_TARGETS targets, SVA_BFA_MAX_UAVS UAVs
// and SVA_BFA_MAX_NODES search nodes, else SVA_ERR_LIMIT naming the limit.
//
// Why targets in (start, end, id) order suffice: a UAV serves b after a only if
// a.end + travel <= b.start, so a.start < b.start; every route lists its targets in
// this order, and deciding targets in it (skip, or `need` UAVs that can append it)
// reaches every feasible plan exactly once. Depth-first with an explicit stack.
//
// Pruning keeps it exact: appending a target never lowers the cost (triangle
// inequality), so a branch that cannot cover more than the best plan, or covers as
// many at no lower cost, is cut. UAVs in identical state (position, free time, fuel)
// are interchangeable: only the lowest-ranked of them are chosen (symmetry breaking).
#include "paper.h"

enum { PHASE_FRESH = 0, PHASE_PICKED = 1, PHASE_SKIPPED = 2 };

static bool same_state(const sva_planner_priv_t* priv, uint16_t a, uint16_t b)
{
    return (priv->uav_x[a] == priv->uav_x[b]) && (priv->uav_y[a] == priv->uav_y[b]) &&
           (priv->uav_free_at[a] == priv->uav_free_at[b]) &&
           (priv->uav_fuel_left[a] == priv->uav_fuel_left[b]);
}

// Candidates for the target at depth d, cheapest insertion first (ties: lower id).
static void list_candidates(sva_planner_priv_t* priv, const sva_mission_t* mission,
                            const sva_plan_t* plan, uint16_t d, uint16_t t)
{
    sva_bfa_work_t* w = &priv->bfa;
    uint8_t n = 0U;
    for (uint16_t j = 0U; j < mission->uav_count; j++) {
        const uint16_t u = priv->uav_order[j];
        if (!sva_can_serve(priv, mission, plan, u, t)) {
            continue;
        }
        const int64_t cost = sva_insertion_cells(priv, mission, u, t);
        uint8_t i = n;
        while ((i > 0U) && (cost < w->cand_cost[d][i - 1U])) {
            w->cand[d][i] = w->cand[d][i - 1U];
            w->cand_cost[d][i] = w->cand_cost[d][i - 1U];
            i--;
        }
        w->cand[d][i] = u;
        w->cand_cost[d][i] = cost;
        n++;
    }
    w->cand_count[d] = n;
}

// Combinations of `need` candidate positions in lexicographic order.
static bool next_combination(uint8_t* pick, uint8_t need, uint8_t count, bool first)
{
    if (first) {
        for (uint8_t i = 0U; i < need; i++) {
            pick[i] = i;
        }
        return need <= count;
    }
    int32_t i = (int32_t)need - 1;
    while ((i >= 0) && (pick[i] == (uint8_t)((count - need) + (uint8_t)i))) {
        i--;
    }
    if (i < 0) {
        return false;
    }
    pick[i]++;
    for (uint8_t j = (uint8_t)(i + 1); j < need; j++) {
        pick[j] = (uint8_t)(pick[j - 1U] + 1U);
    }
    return true;
}

// Symmetry: a pick is canonical iff every candidate it skips is in a different state
// from each later candidate it takes.
static bool canonical(const sva_planner_priv_t* priv, uint16_t d, uint8_t need)
{
    const sva_bfa_work_t* w = &priv->bfa;
    uint8_t next = 0U;
    for (uint8_t c = 0U; c < w->cand_count[d]; c++) {
        if ((next < need) && (w->pick[d][next] == c)) {
            next++;
            continue;
        }
        for (uint8_t later = next; later < need; later++) {
            if (same_state(priv, w->cand[d][c], w->cand[d][w->pick[d][later]])) {
                return false;
            }
        }
    }
    return true;
}

static int64_t take(sva_planner_priv_t* priv, const sva_mission_t* mission, sva_plan_t* plan,
                    uint16_t d, uint16_t t)
{
    sva_bfa_work_t* w = &priv->bfa;
    int64_t added = 0;
    for (int32_t i = 0; i < mission->targets[t].need; i++) {
        const uint16_t u = w->cand[d][w->pick[d][i]];
        w->saved_x[d][i] = priv->uav_x[u];
        w->saved_y[d][i] = priv->uav_y[u];
        w->saved_free_at[d][i] = priv->uav_free_at[u];
        w->saved_fuel_left[d][i] = priv->uav_fuel_left[u];
        added += w->cand_cost[d][w->pick[d][i]];
        sva_commit(priv, mission, plan, u, t);
    }
    return added;
}

static void give_back(sva_planner_priv_t* priv, const sva_mission_t* mission, sva_plan_t* plan,
                      uint16_t d, uint16_t t)
{
    sva_bfa_work_t* w = &priv->bfa;
    for (int32_t i = 0; i < mission->targets[t].need; i++) {
        const uint16_t u = w->cand[d][w->pick[d][i]];
        priv->uav_x[u] = w->saved_x[d][i];
        priv->uav_y[u] = w->saved_y[d][i];
        priv->uav_free_at[u] = w->saved_free_at[d][i];
        priv->uav_fuel_left[u] = w->saved_fuel_left[d][i];
        plan->routes[u].target_count--;
        priv->target_served[t]--;
    }
}

static void save_best(sva_planner_priv_t* priv, const sva_mission_t* mission,
                      const sva_plan_t* plan)
{
    for (uint16_t u = 0U; u < mission->uav_count; u++) {
        priv->bfa.best_len[u] = (uint8_t)plan->routes[u].target_count;
        for (uint16_t k = 0U; k < plan->routes[u].target_count; k++) {
            priv->bfa.best_route[u][k] = plan->routes[u].targets[k];
        }
    }
}

static sva_status_t check_size(const sva_mission_t* mission, sva_diag_t* diag)
{
    if (mission->target_count > SVA_BFA_MAX_TARGETS) {
        sva_diag_set(diag, SVA_FIELD_TARGETS, SVA_RULE_ALGO_LIMIT, -1, mission->target_count,
                     SVA_BFA_MAX_TARGETS, "SVA_BFA_MAX_TARGETS");
        return SVA_ERR_LIMIT;
    }
    if (mission->uav_count > SVA_BFA_MAX_UAVS) {
        sva_diag_set(diag, SVA_FIELD_UAVS, SVA_RULE_ALGO_LIMIT, -1, mission->uav_count,
                     SVA_BFA_MAX_UAVS, "SVA_BFA_MAX_UAVS");
        return SVA_ERR_LIMIT;
    }
    return SVA_OK;
}

sva_status_t sva_run_bfa(sva_planner_priv_t* priv, const sva_mission_t* mission, sva_plan_t* plan,
                         sva_diag_t* diag)
{
    sva_status_t st = check_size(mission, diag);
    if (st != SVA_OK) {
        return st;
    }
    sva_bfa_work_t* w = &priv->bfa;
    const int32_t n = (int32_t)mission->target_count;
    int64_t cost = 0;  // every planned UAV flying home from where it is
    for (uint16_t u = 0U; u < mission->uav_count; u++) {
        if (!plan->routes[u].stranded) {
            cost += sva_distance(mission->uavs[u].x, mission->uavs[u].y, mission->depot_x,
                                 mission->depot_y);
        }
    }
    int32_t best_covered = -1;
    int64_t best_cost = 0;
    int32_t covered = 0;
    uint64_t nodes = 0U;
    int32_t depth = 0;
    w->phase[0] = PHASE_FRESH;
    while (depth >= 0) {
        if (depth == n) {
            if ((covered > best_covered) || ((covered == best_covered) && (cost < best_cost))) {
                best_covered = covered;
                best_cost = cost;
                save_best(priv, mission, plan);
            }
            depth--;
            continue;
        }
        const uint16_t d = (uint16_t)depth;
        const uint16_t t = priv->target_order[d];
        // need <= SVA_MAX_UAVS may exceed the fleet (<= SVA_BFA_MAX_UAVS): never coverable.
        const bool coverable = mission->targets[t].need <= (int32_t)mission->uav_count;
        const uint8_t need = coverable ? (uint8_t)mission->targets[t].need : 0U;
        bool picked = false;
        if (w->phase[d] == PHASE_FRESH) {
            list_candidates(priv, mission, plan, d, t);
            picked = coverable && (need <= w->cand_count[d]) &&
                     next_combination(w->pick[d], need, w->cand_count[d], true);
        } else if (w->phase[d] == PHASE_PICKED) {
            give_back(priv, mission, plan, d, t);
            cost = w->cost_before[d];
            covered--;
            picked = next_combination(w->pick[d], need, w->cand_count[d], false);
        } else {
            depth--;
            continue;
        }
        while (picked && !canonical(priv, d, need)) {
            picked = next_combination(w->pick[d], need, w->cand_count[d], false);
        }
        if (picked) {
            w->cost_before[d] = cost;
            cost += take(priv, mission, plan, d, t);
            covered++;
            w->phase[d] = PHASE_PICKED;
        } else {
            w->phase[d] = PHASE_SKIPPED;
        }
        nodes++;
        if (nodes > (uint64_t)SVA_BFA_MAX_NODES) {
            plan->stats.search_nodes = nodes;
            sva_diag_set(diag, SVA_FIELD_NONE, SVA_RULE_ALGO_LIMIT, -1, (int64_t)nodes,
                         SVA_BFA_MAX_NODES, "SVA_BFA_MAX_NODES");
            return SVA_ERR_LIMIT;
        }
        const int32_t reachable = covered + (n - depth - 1);
        if ((reachable < best_covered) || ((reachable == best_covered) && (cost >= best_cost))) {
            continue;
        }
        depth++;
        if (depth < n) {
            w->phase[depth] = PHASE_FRESH;
        }
    }
    // Replay the best plan through the shared state so plan.c finishes it as usual.
    sva_state_reset(priv, mission, plan);
    for (uint16_t u = 0U; u < mission->uav_count; u++) {
        for (uint16_t k = 0U; k < w->best_len[u]; k++) {
            sva_commit(priv, mission, plan, u, w->best_route[u][k]);
        }
    }
    plan->stats.search_nodes = nodes;
    return SVA_OK;
}
