// flow_dive.c -- the dive on flow's route master: its LP solution turned into a plan
// (DESIGN.md section 8).
//
// The dive turns the cost master into a plan: fix the route of largest value (its
// whole part, at least one UAV), lower the right-hand sides by it, generate columns
// again (flow_lp.c), and so on. A fixed fraction leaves a deficit (its column negated,
// cost M) in the basis, and a target partly served gets cost M on w_t: the basis stays
// feasible and the primal simplex goes on; both leave for good. The fixed routes go
// through the repair and the local search (flow_repair.c) like every other plan.
#include "flow_master.h"

#if SVA_FLOW_LP_ROWS >= 2

// True if a penalty column or the artificial is basic and positive: the master
// cannot complete the fixed routes, or cannot reach its coverage at all.
static bool penalised(const sva_flow_lp_t* lp)
{
    for (uint16_t i = 0U; i < lp->rows; i++) {
        if ((lp->x[i] > 0) && (penalty(lp, lp->basic[i]) || (lp->basic[i] == artificial(lp)))) {
            return true;
        }
    }
    return false;
}

// The basic route with the largest value, or NO_COLUMN if none is positive.
static uint16_t largest_route(const sva_flow_lp_t* lp)
{
    uint16_t best = NO_COLUMN;
    for (uint16_t i = 0U; i < lp->rows; i++) {
        if ((lp->basic[i] >= first_route(lp)) && !penalty(lp, lp->basic[i]) && (lp->x[i] > 0) &&
            ((best == NO_COLUMN) || (lp->x[i] > lp->x[best]))) {
            best = i;
        }
    }
    return best;
}

// The row of the UAV state route column col is flown from.
static uint16_t state_row(const sva_flow_lp_t* lp, uint16_t col)
{
    uint16_t g = lp->targets;
    while ((g < slack_cover(lp)) && !has_row(lp, col, g)) {
        g++;
    }
    return g;  // (every route column has one state row)
}

// Fixes route column col k times: its state flies it with k more UAVs, its targets
// need k fewer, and a target now partly served must be served in whole (w_t costs M).
static void fix_route(sva_flow_lp_t* lp, uint16_t col, int64_t k)
{
    for (int64_t i = 0; (i < k) && (lp->fixed_count < (uint16_t)SVA_MAX_UAVS); i++) {
        lp->fixed[lp->fixed_count] = col;
        lp->fixed_count++;
    }
    lp->rhs[state_row(lp, col)] -= k;
    for (uint16_t t = 0U; t < lp->targets; t++) {
        if (has_row(lp, col, t)) {
            lp->rhs[t] -= k;
            lp->forced[t] = 1U;
        }
    }
}

// The fixed routes as a plan in *plan: each flown by a free UAV of its state, its
// targets in time order.
static void write_fixed(sva_planner_priv_t* priv, const sva_mission_t* m, sva_plan_t* plan)
{
    const sva_flow_lp_t* lp = &priv->flow.lp;
    sva_flow_clear_routes(priv, m, plan);
    for (uint16_t f = 0U; f < lp->fixed_count; f++) {
        const uint16_t col = lp->fixed[f];
        const uint16_t v = sva_flow_idle_uav(m, plan, lp->group_row, state_row(lp, col));
        if (v == m->uav_count) {
            continue;  // (cannot be: a state's row caps its routes at its UAVs)
        }
        sva_route_t* r = &plan->routes[v];
        for (uint16_t i = 0U;
             (i < m->target_count) && (r->target_count < (uint16_t)SVA_MAX_ROUTE_TARGETS); i++) {
            const uint16_t t = priv->target_order[i];
            if (has_row(lp, col, t)) {
                r->targets[r->target_count] = t;
                r->target_count++;
                priv->target_served[t]++;
            }
        }
    }
}

// Position i's route was fixed beyond its value (x_i < 0): its deficit, the column
// -A_col at cost M, replaces it in the basis. B' = B diag(.., -1, ..): row i of adj
// and x_i change sign, D stays. False if the master is full.
static bool swap_in_deficit(sva_flow_lp_t* lp, uint16_t i)
{
    const uint16_t col = (uint16_t)(lp->basic[i] - first_route(lp));
    if (lp->cols >= (uint16_t)SVA_FLOW_LP_COLS) {
        return false;
    }
    const uint16_t q = lp->cols;
    for (uint32_t k = 0U; k < SVA_FLOW_LP_WORDS; k++) {
        col_bits(lp, q)[k] = col_bits(lp, col)[k];
    }
    lp->col_cost[q] = lp->col_cost[col];
    lp->col_deficit[q] = 1U;
    lp->cols++;
    lp->in_basis[lp->basic[i]] = 0U;
    lp->basic[i] = (uint16_t)(first_route(lp) + q);
    lp->in_basis[lp->basic[i]] = 1U;
    int64_t* row = adj_row(lp, i);
    for (uint16_t k = 0U; k < lp->rows; k++) {
        row[k] = -row[k];
    }
    lp->x[i] = -lp->x[i];
    return true;
}

// The next route to fix: the basic route of largest value, and how many UAVs (its
// whole part, at least one, within its state's and its targets' rows); NO_COLUMN if
// none is left or a penalty column is positive.
static uint16_t route_to_fix(const sva_flow_lp_t* lp, int64_t* k)
{
    const uint16_t i = largest_route(lp);
    if ((i == NO_COLUMN) || penalised(lp)) {
        return NO_COLUMN;
    }
    const uint16_t col = (uint16_t)(lp->basic[i] - first_route(lp));
    const int64_t state_left = lp->rhs[state_row(lp, col)];
    int64_t n = lp->x[i] / lp->det;
    n = (n < 1) ? 1 : n;
    n = (n > state_left) ? state_left : n;
    for (uint16_t t = 0U; t < lp->targets; t++) {
        n = (has_row(lp, col, t) && (lp->rhs[t] < n)) ? lp->rhs[t] : n;
    }
    *k = n;
    return (n < 1) ? NO_COLUMN : i;  // (n >= 1: a positive route fits its rows)
}

bool sva_flow_lp_dive(sva_planner_priv_t* priv, const sva_mission_t* m, sva_plan_t* plan,
                      uint64_t budget)
{
    sva_flow_work_t* w = &priv->flow;
    sva_flow_lp_t* lp = &w->lp;
    // Every round fixes at least one UAV's route: at most one round per UAV.
    bool going = true;
    int64_t mu = 0;
    while (going && sva_flow_lp_prices(w, m, plan, 0, SVA_FLOW_LP_RESUME, budget, &mu)) {
        int64_t k = 0;
        const uint16_t i = route_to_fix(lp, &k);
        going = i != NO_COLUMN;
        if (going) {
            fix_route(lp, (uint16_t)(lp->basic[i] - first_route(lp)), k);
            lp->x[i] -= k * lp->det;  // B^-1 (b - k A_col) = x - k e_i: the column is basic at i
            going = (lp->x[i] >= 0) || swap_in_deficit(lp, i);  // false: the master is full
        }
    }
    if (lp->fixed_count == 0U) {
        return false;
    }
    write_fixed(priv, m, plan);
    return true;
}

#endif  // SVA_FLOW_LP_ROWS >= 2
