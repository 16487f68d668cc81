// flow_lp.c -- the route master of flow's Lagrangian phase, solved by column
// generation, to give the Lagrangian its prices (DESIGN.md section 8).
//
// Master, over the routes generated so far (x_r) and at the incumbent's coverage c
// (the cost master):
//   min  sum_r cells_r x_r + M a
//   row t (target t):   sum_{r serves t} x_r + w_t = need_t      (w_t: t's unserved part)
//   row n+g (state g):  sum_{r flown from g} x_r + s_g = UAVs in state g
//   row n+G (coverage): sum_t (L / need_t) w_t + s - a = L (n - c)
// all variables >= 0, L the lcm of the needs: the coverage row says that at least c
// targets are served in whole, a (cost M) lets the first basis be all slacks. Its
// duals are the Lagrangian's multipliers: pi_t for row t and mu = -L * dual(coverage).
// The cover master asks for c + 1 targets with the cells' cost 0 and a's 1: if even its
// optimum needs a > 0, no plan covers c + 1, and its duals, scaled to mu = S, are
// prices that make flow_lagrange.c's coverage phase prove it.
// A new column is the best route of each UAV state under those duals: the labels of
// flow_label.c run with the cells weighted by det(B) and the prices det(B) * pi,
// in integers.
//
// The master's simplex (revised, fraction-free) is flow_simplex.c; the dive that turns
// the cost master into a plan is flow_dive.c.
//
// Nothing here is trusted for a claim: the prices are only proposed, and the bound is
// the Lagrangian's value at them (flow_lagrange.c), valid for any prices.
#include "flow_master.h"

#if SVA_FLOW_LP_ROWS >= 2

#    define COST_MAX        (INT64_C(1) << 24)  // cells of a route, and M
#    define LCM_MAX         INT64_C(64)
#    define ENTER_PER_STATE 8U   // columns one pricing round may add per UAV state
#    define PICKS_PER_STATE 32U  // labels one pricing round may read back per UAV state

// Adds UAV u's route over path[0..len-1] as a column; false if the master is full.
static bool add_column(sva_flow_lp_t* lp, const sva_mission_t* m, uint16_t u, const uint16_t* path,
                       uint16_t len)
{
    if ((lp->cols >= (uint16_t)SVA_FLOW_LP_COLS) || (len == 0U)) {
        return false;
    }
    uint32_t* bits = col_bits(lp, lp->cols);
    for (uint32_t k = 0U; k < SVA_FLOW_LP_WORDS; k++) {
        bits[k] = 0U;
    }
    for (uint16_t i = 0U; i < len; i++) {
        bits[(uint32_t)path[i] / 32U] |= (uint32_t)1U << ((uint32_t)path[i] % 32U);
    }
    const uint16_t g = lp->group_row[u];
    bits[(uint32_t)g / 32U] |= (uint32_t)1U << ((uint32_t)g % 32U);
    lp->col_cost[lp->cols] = (int32_t)sva_path_cells(m, u, path, len);
    lp->col_deficit[lp->cols] = 0U;
    lp->in_basis[first_route(lp) + lp->cols] = 0U;
    lp->cols++;
    return true;
}

// Rows, groups and the all-slack basis (D = 1) at coverage c; false if the master
// does not fit its bounds. cover: routes cost nothing and a costs 1.
static bool start(sva_flow_work_t* w, const sva_mission_t* m, const sva_plan_t* plan,
                  int64_t covered, bool cover)
{
    sva_flow_lp_t* lp = &w->lp;
    const sva_flow_lagrange_t* lg = &w->lagrange;
    int64_t lcm = 1;
    for (uint16_t t = 0U; t < m->target_count; t++) {
        const int64_t need = m->targets[t].need;
        if (need < 1) {
            return false;  // (validated: cannot be)
        }
        lcm = (lcm / sva_gcd64(lcm, need)) * need;
        if (lcm > LCM_MAX) {
            return false;
        }
    }
    uint16_t groups = 0U;
    for (uint16_t u = 0U; u < m->uav_count; u++) {
        if (!plan->routes[u].stranded && (lg->group[u] == u)) {
            groups++;
        }
    }
    const uint32_t rows = (uint32_t)m->target_count + groups + 1U;
    if ((m->target_count == 0U) || (rows > (uint32_t)SVA_FLOW_LP_ROWS) ||
        (w->max_cost >= COST_MAX)) {
        return false;
    }
    lp->targets = m->target_count;
    lp->groups = groups;
    lp->rows = (uint16_t)rows;
    lp->lcm = lcm;
    lp->big_m = cover ? 1 : (w->max_cost + 1);
    lp->cells_weight = cover ? INT64_C(0) : INT64_C(1);
    lp->cols = 0U;
    lp->det = 1;
    lp->fixed_count = 0U;
    uint16_t g = 0U;
    for (uint16_t u = 0U; u < m->uav_count; u++) {
        lp->group_row[u] = 0U;
        if (!plan->routes[u].stranded && (lg->group[u] == u)) {
            lp->group_row[u] = (uint16_t)(m->target_count + g);
            lp->rhs[m->target_count + g] = 0;
            g++;
        }
    }
    for (uint16_t u = 0U; u < m->uav_count; u++) {
        if (!plan->routes[u].stranded) {
            lp->group_row[u] = lp->group_row[lg->group[u]];
            lp->rhs[lp->group_row[u]]++;
        }
    }
    const uint16_t row_c = slack_cover(lp);
    lp->rhs[row_c] = lcm * ((int64_t)m->target_count - covered);
    // Basis: w_t for row t, s_g for row n+g, a for the coverage row. Its inverse is
    // the identity but for the coverage row: a = sum_t (L / need_t) b_t - b_cover.
    for (uint16_t i = 0U; i < lp->rows; i++) {
        int64_t* row = adj_row(lp, i);
        for (uint16_t k = 0U; k < lp->rows; k++) {
            row[k] = (i == k) ? INT64_C(1) : INT64_C(0);
        }
        lp->basic[i] = i;
        lp->in_basis[i] = 1U;
    }
    lp->basic[row_c] = artificial(lp);
    lp->in_basis[row_c] = 0U;
    lp->in_basis[artificial(lp)] = 1U;
    int64_t* row = adj_row(lp, row_c);
    row[row_c] = -1;
    for (uint16_t t = 0U; t < m->target_count; t++) {
        row[t] = lcm / m->targets[t].need;
        lp->rhs[t] = m->targets[t].need;
        lp->forced[t] = 0U;
    }
    for (uint16_t i = 0U; i < lp->rows; i++) {
        int64_t sum = 0;
        for (uint16_t k = 0U; k < lp->rows; k++) {
            sum += adj_row(lp, i)[k] * lp->rhs[k];
        }
        lp->x[i] = sum;
    }
    return true;
}

// Reduced cost (scaled by D) of the label l's route flown home, or 0 if it cannot fly
// home within fuel.
static int64_t label_rc(const sva_flow_work_t* w, const sva_mission_t* m, uint16_t u, uint32_t l)
{
    const sva_flow_lagrange_t* lg = &w->lagrange;
    const sva_target_t* t = &m->targets[l / sva_flow_label_stride(lg)];
    const int64_t home = sva_distance(t->x, t->y, m->depot_x, m->depot_y);
    if (((int64_t)lg->label_fuel[l] + home) > m->uavs[u].fuel) {
        return 0;
    }
    return (lg->label_cost[l] + (w->lp.det * w->lp.cells_weight * home)) -
           w->lp.dual[w->lp.group_row[u]];
}

// Pricing: for each UAV state, the labels of its best routes under the duals, most
// negative first; up to ENTER_PER_STATE enter. A merged label's path may break fuel
// (flow_lagrange.c): such a path is no route, so it is passed over (at most
// PICKS_PER_STATE labels read). True if a route entered.
static bool price_routes(sva_flow_work_t* w, const sva_mission_t* m, const sva_plan_t* plan)
{
    sva_flow_lp_t* lp = &w->lp;
    sva_flow_lagrange_t* lg = &w->lagrange;
    for (uint16_t t = 0U; t < m->target_count; t++) {
        lg->path_price[t] = lp->dual[t];
        lg->closed[t] = (lp->rhs[t] == 0) ? 1U : 0U;  // served in whole by the dive
    }
    bool added = false;
    for (uint16_t u = 0U; u < m->uav_count; u++) {
        if (plan->routes[u].stranded || (lg->group[u] != u) || (lp->rhs[lp->group_row[u]] == 0)) {
            continue;
        }
        (void)sva_flow_best_route(w, m, u, lp->det * lp->cells_weight);
        int64_t above = -INT64_MAX;  // the last read label's reduced cost
        uint32_t last = SVA_FLOW_NO_LABEL;
        uint16_t entered = 0U;
        uint16_t k = 0U;
        while ((k < (uint16_t)PICKS_PER_STATE) && (entered < (uint16_t)ENTER_PER_STATE)) {
            k++;
            // The next label in (reduced cost, index) order.
            uint32_t pick = SVA_FLOW_NO_LABEL;
            int64_t pick_rc = 0;
            for (uint16_t t = 0U; t < m->target_count; t++) {
                const uint32_t base = (uint32_t)t * sva_flow_label_stride(lg);
                for (uint32_t l = base; l < (base + lg->label_count[t]); l++) {
                    const int64_t rc = label_rc(w, m, u, l);
                    const bool after = (rc > above) || ((rc == above) && (l > last));
                    if (after && (rc < pick_rc)) {
                        pick = l;
                        pick_rc = rc;
                    }
                }
            }
            if (pick == SVA_FLOW_NO_LABEL) {
                break;
            }
            above = pick_rc;
            last = pick;
            sva_flow_label_path(lg, pick);
            // Merged labels may stand for no real route: only routes that price out enter.
            const int64_t cells = sva_path_cells(m, u, lg->path, lg->path_len);
            int64_t rc = (lp->det * lp->cells_weight * cells) - lp->dual[lp->group_row[u]];
            for (uint16_t i = 0U; i < lg->path_len; i++) {
                rc -= lp->dual[lg->path[i]];
            }
            if ((rc < 0) && sva_flow_fits(m, u, cells, lg->path_len)) {
                added = add_column(lp, m, u, lg->path, lg->path_len) || added;
                entered++;
            }
        }
        w->work += (uint64_t)k * (uint64_t)m->target_count * (uint64_t)sva_flow_label_stride(lg);
    }
    return added;
}

bool sva_flow_lp_prices(sva_flow_work_t* w, const sva_mission_t* m, const sva_plan_t* plan,
                        int64_t covered, sva_flow_lp_mode_t mode, uint64_t budget, int64_t* mu)
{
    sva_flow_lp_t* lp = &w->lp;
    if (mode != SVA_FLOW_LP_RESUME) {
        if (!start(w, m, plan, covered, mode == SVA_FLOW_LP_COVER)) {
            return false;
        }
        // The incumbent's routes first: with them the master is feasible without a.
        for (uint16_t u = 0U; u < m->uav_count; u++) {
            const sva_route_t* r = &plan->routes[u];
            if (!r->stranded) {
                (void)add_column(lp, m, u, r->targets, r->target_count);
            }
        }
    }
    bool solved = sva_flow_master_solve(w, m, budget);
    while (solved && (w->work < budget) && price_routes(w, m, plan)) {
        solved = sva_flow_master_solve(w, m, budget);
    }
    if (!solved) {
        return false;
    }
    const int64_t s = SVA_FLOW_PRICE_SCALE;
    const int64_t q = -lp->dual[slack_cover(lp)];  // mu = L q / D
    if (lp->cells_weight == 0) {
        // The coverage phase's prices have mu = S: scale by S / mu.
        if (q <= 0) {
            return false;
        }
        for (uint16_t t = 0U; t < m->target_count; t++) {
            w->lagrange.price[t] = (s * lp->dual[t]) / (q * lp->lcm);
        }
        *mu = s;
        return true;
    }
    for (uint16_t t = 0U; t < m->target_count; t++) {
        w->lagrange.price[t] = (s * lp->dual[t]) / lp->det;
    }
    *mu = (q > 0) ? (((s * q) / lp->det) * lp->lcm) : 0;
    return true;
}

#endif  // SVA_FLOW_LP_ROWS >= 2
