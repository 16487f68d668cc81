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
// flow_lagrange.c run with the cells weighted by det(B) and the prices det(B) * pi,
// in integers.
//
// The simplex is revised and fraction-free: it keeps D = |det(B)| and adj = D * B^-1,
// and pivots by the Bareiss update (each new entry is a 2x2 determinant divided
// exactly by the old D), so every number is a minor of the constraint matrix: exact,
// no rounding. The solve gives up (no prices) when an entry outgrows ENTRY_MAX, which
// keeps every product inside int64. Dantzig's rule, Bland's after DEGENERATE_RUN
// degenerate pivots in a row (no cycling).
//
// The dive turns the cost master into a plan: fix the route of largest value (its
// whole part, at least one UAV), lower the right-hand sides by it, generate columns
// again, and so on. A fixed fraction leaves a deficit (its column negated, cost M) in
// the basis, and a target partly served gets cost M on w_t: the basis stays feasible
// and the primal simplex goes on; both leave for good. The fixed routes go through
// the repair and the local search (flow_repair.c) like every other plan.
//
// Nothing here is trusted for a claim: the prices are only proposed, and the bound is
// the Lagrangian's value at them (flow_lagrange.c), valid for any prices.
#include "sva_internal.h"

#if SVA_FLOW_LP_ROWS >= 2

#define ENTRY_MAX (INT64_C(1) << 26)   // adj, x, alpha, D
#define DUAL_MAX (INT64_C(1) << 50)    // D * dual: labels stay within int64
#define COST_MAX (INT64_C(1) << 24)    // cells of a route, and M
#define LCM_MAX INT64_C(64)
#define DEGENERATE_RUN 8U
#define NO_COLUMN 0xFFFFU
#define ENTER_PER_STATE 8U  // columns one pricing round may add per UAV state
#define PICKS_PER_STATE 32U // labels one pricing round may read back per UAV state

static uint16_t slack_cover(const sva_flow_lp_t* lp)
{
    return (uint16_t)(lp->targets + lp->groups);
}

static uint16_t artificial(const sva_flow_lp_t* lp)
{
    return (uint16_t)(slack_cover(lp) + 1U);
}

static uint16_t first_route(const sva_flow_lp_t* lp)
{
    return (uint16_t)(slack_cover(lp) + 2U);
}

// Row i of adj.
static int64_t* adj_row(sva_flow_lp_t* lp, uint16_t i)
{
    return &lp->adj[(size_t)i * (size_t)SVA_FLOW_LP_ROWS];
}

// Route column col's row set.
static uint32_t* col_bits(sva_flow_lp_t* lp, uint16_t col)
{
    return &lp->col_rows[(size_t)col * SVA_FLOW_LP_WORDS];
}

static int64_t abs64(int64_t v)
{
    return (v < 0) ? -v : v;
}

// Index of the one bit set in `bit` (de Bruijn multiplication).
static uint32_t lowest_bit_index(uint32_t bit)
{
    static const uint8_t index_of[32] = {0U,  1U,  28U, 2U,  29U, 14U, 24U, 3U,  30U, 22U, 20U,
                                         15U, 25U, 17U, 4U,  8U,  31U, 27U, 13U, 23U, 21U, 19U,
                                         16U, 7U,  26U, 12U, 18U, 6U,  11U, 5U,  10U, 9U};
    return index_of[(uint32_t)(bit * UINT32_C(0x077CB531)) >> 27U];
}

static bool has_row(const sva_flow_lp_t* lp, uint16_t col, uint16_t row)
{
    const uint32_t word = lp->col_rows[((size_t)col * SVA_FLOW_LP_WORDS) + ((size_t)row / 32U)];
    return ((word >> ((uint32_t)row % 32U)) & 1U) != 0U;
}

static int64_t column_cost(const sva_flow_lp_t* lp, uint16_t j)
{
    if (j >= first_route(lp)) {
        const uint16_t col = (uint16_t)(j - first_route(lp));
        return (lp->col_deficit[col] != 0U) ? lp->big_m : (lp->cells_weight * lp->col_cost[col]);
    }
    if (j < lp->targets) {
        return (lp->forced[j] != 0U) ? lp->big_m : 0;  // the dive: a target partly served
    }
    return (j == artificial(lp)) ? lp->big_m : 0;
}

// sum over rows k of v[k] * (column j's entry in row k).
static int64_t dot(const sva_flow_lp_t* lp, const sva_mission_t* m, const int64_t* v, uint16_t j)
{
    const uint16_t cover = slack_cover(lp);
    if (j < lp->targets) {
        return v[j] + ((lp->lcm / m->targets[j].need) * v[cover]);
    }
    if (j < cover) {
        return v[j];
    }
    if (j == cover) {
        return v[cover];
    }
    if (j == artificial(lp)) {
        return -v[cover];
    }
    // A route's rows are a few set bits: visit those alone, lowest bit first.
    int64_t sum = 0;
    const uint16_t col = (uint16_t)(j - first_route(lp));
    const uint32_t* bits = &lp->col_rows[(size_t)col * SVA_FLOW_LP_WORDS];
    for (uint32_t word = 0U; word < SVA_FLOW_LP_WORDS; word++) {
        uint32_t left = bits[word];
        while (left != 0U) {
            const uint32_t lowest = left & (~left + 1U);
            sum += v[(word * 32U) + lowest_bit_index(lowest)];
            left ^= lowest;
        }
    }
    return (lp->col_deficit[col] != 0U) ? -sum : sum;
}

// Duals of the basis (scaled by D); false if one outgrows DUAL_MAX.
static bool compute_duals(sva_flow_lp_t* lp)
{
    // dual = c_B^T adj, row by row of adj: most basic columns are slacks of cost 0.
    const uint16_t n = lp->rows;
    for (uint16_t k = 0U; k < n; k++) {
        lp->dual[k] = 0;
    }
    for (uint16_t i = 0U; i < n; i++) {
        const int64_t cost = column_cost(lp, lp->basic[i]);
        if (cost != 0) {
            const int64_t* row = adj_row(lp, i);
            for (uint16_t k = 0U; k < n; k++) {
                lp->dual[k] += cost * row[k];
            }
        }
    }
    for (uint16_t k = 0U; k < n; k++) {
        if (abs64(lp->dual[k]) > DUAL_MAX) {
            return false;
        }
    }
    return true;
}

// The dive's penalty columns (cost M), which never enter once out: w_t of a target
// partly served, and a fixed route's deficit.
static bool penalty(const sva_flow_lp_t* lp, uint16_t j)
{
    if (j >= first_route(lp)) {
        return lp->col_deficit[j - first_route(lp)] != 0U;
    }
    return (j < lp->targets) && (lp->forced[j] != 0U);
}

// The entering column: the most negative reduced cost (Dantzig), or the first
// negative one (Bland); NO_COLUMN when the basis is optimal.
static uint16_t lp_entering(const sva_flow_lp_t* lp, const sva_mission_t* m, bool bland)
{
    const uint16_t end = (uint16_t)(first_route(lp) + lp->cols);
    uint16_t best = NO_COLUMN;
    int64_t best_rc = 0;
    for (uint16_t j = 0U; j < end; j++) {
        if ((lp->in_basis[j] != 0U) || penalty(lp, j)) {
            continue;
        }
        const int64_t rc = (lp->det * column_cost(lp, j)) - dot(lp, m, lp->dual, j);
        if (rc < best_rc) {
            best = j;
            best_rc = rc;
            if (bland) {
                break;
            }
        }
    }
    return best;
}

// The leaving position for entering column j (alpha filled): least x_i / alpha_i
// over alpha_i > 0, ties to the lowest column (Bland); NO_COLUMN if none, or if a
// number outgrows ENTRY_MAX.
static uint16_t lp_leaving(sva_flow_lp_t* lp, const sva_mission_t* m, uint16_t j)
{
    uint16_t r = NO_COLUMN;
    for (uint16_t i = 0U; i < lp->rows; i++) {
        const int64_t a = dot(lp, m, adj_row(lp, i), j);
        if (abs64(a) > ENTRY_MAX) {
            return NO_COLUMN;
        }
        lp->alpha[i] = a;
        if (a <= 0) {
            continue;
        }
        if (r == NO_COLUMN) {
            r = i;
            continue;
        }
        const int64_t lhs = lp->x[i] * lp->alpha[r];
        const int64_t rhs = lp->x[r] * a;
        if ((lhs < rhs) || ((lhs == rhs) && (lp->basic[i] < lp->basic[r]))) {
            r = i;
        }
    }
    return r;
}

// Column j enters at position r (Bareiss); false if a division is not exact or a
// number outgrows ENTRY_MAX (neither happens in exact arithmetic within the guards).
static bool lp_pivot(sva_flow_lp_t* lp, uint16_t r, uint16_t j)
{
    const int64_t ar = lp->alpha[r];
    const int64_t d = lp->det;
    const int64_t* row_r = adj_row(lp, r);
    bool ok = true;
    for (uint16_t i = 0U; i < lp->rows; i++) {
        if (i == r) {
            continue;
        }
        const int64_t ai = lp->alpha[i];
        if ((ai == 0) && (ar == d)) {
            continue;  // the row and x_i stay as they are
        }
        int64_t* row_i = adj_row(lp, i);
        for (uint16_t k = 0U; k < lp->rows; k++) {
            const int64_t num = (ar * row_i[k]) - (ai * row_r[k]);
            if (num == 0) {
                row_i[k] = 0;  // adj is mostly zeros: no division
            } else {
                ok = ok && ((num % d) == 0);
                row_i[k] = num / d;
                ok = ok && (abs64(row_i[k]) <= ENTRY_MAX);
            }
        }
        const int64_t num = (ar * lp->x[i]) - (ai * lp->x[r]);
        ok = ok && ((num % d) == 0);
        lp->x[i] = num / d;
        ok = ok && (abs64(lp->x[i]) <= ENTRY_MAX);
    }
    lp->in_basis[lp->basic[r]] = 0U;
    lp->in_basis[j] = 1U;
    lp->basic[r] = j;
    lp->det = ar;
    return ok;
}

// Simplex on the columns so far; false if it gave up (guards, budget).
static bool solve_master(sva_flow_work_t* w, const sva_mission_t* m, uint64_t budget)
{
    sva_flow_lp_t* lp = &w->lp;
    uint32_t degenerate = 0U;
    const uint64_t per_pivot = (uint64_t)lp->rows * (uint64_t)lp->rows;
    while (w->work < budget) {
        if (!compute_duals(lp)) {
            return false;
        }
        const uint16_t j = lp_entering(lp, m, degenerate >= DEGENERATE_RUN);
        if (j == NO_COLUMN) {
            return true;
        }
        const uint16_t r = lp_leaving(lp, m, j);
        if (r == NO_COLUMN) {
            return false;  // a guard, or unbounded (cannot be: every column has a cost >= 0 or is bounded by a row)
        }
        if (lp->x[r] == 0) {
            degenerate++;
        } else {
            degenerate = 0U;
        }
        if (!lp_pivot(lp, r, j)) {
            return false;
        }
        w->work += per_pivot;
    }
    return false;
}

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
static bool start(sva_flow_work_t* w, const sva_mission_t* m, const sva_plan_t* plan, int64_t covered,
                  bool cover)
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
    if ((m->target_count == 0U) || (rows > (uint32_t)SVA_FLOW_LP_ROWS) || (w->max_cost >= COST_MAX)) {
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
    const sva_target_t* t = &m->targets[l / (uint32_t)SVA_FLOW_LABELS];
    const int64_t home = sva_distance(t->x, t->y, m->depot_x, m->depot_y);
    if (((int64_t)lg->label_fuel[l] + home) > m->uavs[u].fuel) {
        return 0;
    }
    return (lg->label_cost[l] + (w->lp.det * w->lp.cells_weight * home)) - w->lp.dual[w->lp.group_row[u]];
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
                const uint32_t base = (uint32_t)t * (uint32_t)SVA_FLOW_LABELS;
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
        w->work += (uint64_t)k * (uint64_t)m->target_count * (uint64_t)SVA_FLOW_LABELS;
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
    bool solved = solve_master(w, m, budget);
    while (solved && (w->work < budget) && price_routes(w, m, plan)) {
        solved = solve_master(w, m, budget);
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
    for (uint16_t t = 0U; t < m->target_count; t++) {
        priv->target_served[t] = 0U;
    }
    for (uint16_t u = 0U; u < m->uav_count; u++) {
        plan->routes[u].target_count = 0U;
    }
    for (uint16_t f = 0U; f < lp->fixed_count; f++) {
        const uint16_t col = lp->fixed[f];
        const uint16_t row = state_row(lp, col);
        uint16_t v = 0U;
        while ((v < m->uav_count) && (plan->routes[v].stranded || (lp->group_row[v] != row) ||
                                      (plan->routes[v].target_count > 0U))) {
            v++;
        }
        if (v == m->uav_count) {
            continue;  // (cannot be: a state's row caps its routes at its UAVs)
        }
        sva_route_t* r = &plan->routes[v];
        for (uint16_t i = 0U; (i < m->target_count) && (r->target_count < (uint16_t)SVA_MAX_ROUTE_TARGETS); i++) {
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

#else  // SVA_FLOW_LP_ROWS 1: no master (a profile with little RAM)

bool sva_flow_lp_prices(sva_flow_work_t* w, const sva_mission_t* m, const sva_plan_t* plan,
                        int64_t covered, sva_flow_lp_mode_t mode, uint64_t budget, int64_t* mu)
{
    (void)w;
    (void)m;
    (void)plan;
    (void)covered;
    (void)mode;
    (void)budget;
    (void)mu;
    return false;
}

bool sva_flow_lp_dive(sva_planner_priv_t* priv, const sva_mission_t* m, sva_plan_t* plan,
                      uint64_t budget)
{
    (void)priv;
    (void)m;
    (void)plan;
    (void)budget;
    return false;
}

#endif
