// tableau.c -- the integer tableau simplex for one transportation problem.
//
// Rows: one per source (sum of its arcs + surplus = supply) and one per sink still in
// the problem (sum of its arcs + unmet = demand). Columns: one per arc, one unmet-demand
// slack per sink, one surplus slack per source (price 0: SPEC section 2, "the surplus
// stays put"). The slacks form the starting basis, an identity.
//
// An unmet unit of sink k costs M * L / need_k, where M exceeds the cost of any whole
// assignment and L is the lcm of the needs: leaving any whole target unmet costs M * L
// whatever its need, so the optimum leaves as few targets' worth of demand unmet as the
// LP can, and only then minimises distance. (A plain M per unit would rather fill one
// need-2 target than a cheaper need-1 one.) If L would be too large for int64
// headroom, L = 1 (DESIGN.md section 2).
//
// The constraint matrix is the incidence matrix of a bipartite graph plus an identity,
// hence totally unimodular: every basis inverse is integral and every tableau entry
// stays in {-1, 0, +1}; a ratio-test pivot element is therefore exactly +1 and each
// pivot is integer row additions (DESIGN.md section 2). Anything else is a defect and
// is reported as SVA_ERR_SOLVER rather than planned on.
//
// Anti-cycling: Dantzig's rule (most negative reduced cost), switching to Bland's rule
// (lowest index) after SVA_TABLEAU_BLAND_AFTER consecutive degenerate pivots until a
// pivot makes progress; leaving ties go to the lowest basic column (Bland).
#include "paper.h"

#include <string.h>

#define SVA_TABLEAU_BLAND_AFTER 8U

typedef struct {
    uint16_t rows;
    uint16_t cols;
} shape_t;

static int8_t* cell(sva_tableau_t* tab, shape_t sh, uint16_t row, uint16_t col)
{
    return &tab->cell[((uint32_t)row * sh.cols) + col];
}

// L: the lcm of the kept sinks' needs, or 1 when L * M could overflow the reduced
// costs (each is at most (rows + 1) * max column cost in magnitude).
static int64_t needs_lcm(const sva_tp_t* tp, int64_t big_m, uint16_t rows)
{
    const int64_t limit = (INT64_MAX / 4) / ((int64_t)rows + 1) / big_m;
    int64_t lcm = 1;
    for (uint16_t k = 0U; k < tp->sink_count; k++) {
        if (!tp->sink_dropped[k]) {
            const int64_t d = tp->demand[k];
            lcm = (lcm / sva_gcd64(lcm, d)) * d;
            if (lcm > limit) {
                return 1;
            }
        }
    }
    return lcm;
}

// Lays out the columns and the starting basis; returns the shape.
static shape_t build(sva_tableau_t* tab, const sva_tp_t* tp)
{
    shape_t sh = {0U, 0U};
    const uint16_t m = tp->source_count;
    const uint16_t n = tp->sink_count;
    int32_t max_cost = 0;
    int64_t total_demand = 0;
    sh.rows = m;
    for (uint16_t k = 0U; k < n; k++) {
        tab->sink_row[k] = -1;
        if (!tp->sink_dropped[k]) {
            tab->sink_row[k] = (int16_t)sh.rows;
            sh.rows++;
            total_demand += tp->demand[k];
            for (uint16_t s = 0U; s < m; s++) {
                const int32_t c = tp->cost[(s * n) + k];
                if (c != (int32_t)SVA_TP_NO_ARC) {
                    sh.cols++;
                    max_cost = (c > max_cost) ? c : max_cost;
                }
            }
        }
    }
    const uint16_t arcs = sh.cols;
    sh.cols = (uint16_t)(sh.cols + sh.rows);
    // M exceeds the cost of any assignment of the whole demand (DESIGN.md section 2).
    const int64_t big_m = ((int64_t)max_cost + 1) * (total_demand + 1);
    const int64_t lcm = needs_lcm(tp, big_m, sh.rows);

    (void)memset(tab->cell, 0, (size_t)sh.rows * sh.cols);
    uint16_t j = 0U;
    for (uint16_t k = 0U; k < n; k++) {
        for (uint16_t s = 0U; (s < m) && (tab->sink_row[k] >= 0); s++) {
            const int32_t c = tp->cost[(s * n) + k];
            if (c != (int32_t)SVA_TP_NO_ARC) {
                *cell(tab, sh, s, j) = 1;
                *cell(tab, sh, (uint16_t)tab->sink_row[k], j) = 1;
                tab->col_cost[j] = c;
                tab->col_source[j] = (int16_t)s;
                tab->col_sink[j] = (int16_t)k;
                j++;
            }
        }
    }
    SVA_ASSERT(j == arcs);
    for (uint16_t k = 0U; k < n; k++) {
        if (tab->sink_row[k] >= 0) {
            const uint16_t row = (uint16_t)tab->sink_row[k];
            *cell(tab, sh, row, j) = 1;
            // Per-target pricing: L / need per unit. When needs_lcm fell back to L = 1,
            // L / need is 0 for every need above 1 (an unmet unit would cost nothing):
            // price every unit at big_m instead (maximise the units delivered).
            const int64_t per_unit = lcm / tp->demand[k];
            tab->col_cost[j] = big_m * ((per_unit > 0) ? per_unit : 1);
            tab->col_source[j] = -1;
            tab->col_sink[j] = (int16_t)k;
            tab->basis[row] = (int16_t)j;
            tab->rhs[row] = tp->demand[k];
            j++;
        }
    }
    for (uint16_t s = 0U; s < m; s++) {
        *cell(tab, sh, s, j) = 1;
        tab->col_cost[j] = 0;
        tab->col_source[j] = -1;
        tab->col_sink[j] = -1;
        tab->basis[s] = (int16_t)j;
        tab->rhs[s] = tp->supply[s];
        j++;
    }
    // Reduced costs against the slack basis: c_j - sum over rows of c_B(row) * a_row,j.
    for (uint16_t c = 0U; c < sh.cols; c++) {
        int64_t r = tab->col_cost[c];
        for (uint16_t row = 0U; row < sh.rows; row++) {
            r -= tab->col_cost[tab->basis[row]] * (int64_t)*cell(tab, sh, row, c);
        }
        tab->reduced[c] = r;
    }
    return sh;
}

static int32_t choose_entering(const sva_tableau_t* tab, shape_t sh, bool bland)
{
    int32_t best = -1;
    for (uint16_t c = 0U; c < sh.cols; c++) {
        if (tab->reduced[c] < 0) {
            if (bland) {
                return (int32_t)c;
            }
            if ((best < 0) || (tab->reduced[c] < tab->reduced[best])) {
                best = (int32_t)c;
            }
        }
    }
    return best;
}

static int32_t choose_leaving(sva_tableau_t* tab, shape_t sh, uint16_t enter)
{
    int32_t best = -1;
    for (uint16_t row = 0U; row < sh.rows; row++) {
        if (*cell(tab, sh, row, enter) > 0) {
            if ((best < 0) || (tab->rhs[row] < tab->rhs[best]) ||
                ((tab->rhs[row] == tab->rhs[best]) && (tab->basis[row] < tab->basis[best]))) {
                best = (int32_t)row;
            }
        }
    }
    return best;
}

// Gauss-Jordan step on a +1 pivot: integer row additions only.
static sva_status_t pivot(sva_tableau_t* tab, shape_t sh, uint16_t prow, uint16_t enter)
{
    if (*cell(tab, sh, prow, enter) != 1) {
        return SVA_ERR_SOLVER;  // not totally unimodular: a defect, never planned on
    }
    uint16_t nz = 0U;
    for (uint16_t c = 0U; c < sh.cols; c++) {
        if (*cell(tab, sh, prow, c) != 0) {
            tab->nonzero[nz] = (int16_t)c;
            nz++;
        }
    }
    for (uint16_t row = 0U; row < sh.rows; row++) {
        const int8_t f = *cell(tab, sh, row, enter);
        if ((row == prow) || (f == 0)) {
            continue;
        }
        for (uint16_t i = 0U; i < nz; i++) {
            const uint16_t c = (uint16_t)tab->nonzero[i];
            const int32_t v =
                (int32_t)*cell(tab, sh, row, c) - ((int32_t)f * *cell(tab, sh, prow, c));
            if ((v < -1) || (v > 1)) {
                return SVA_ERR_SOLVER;
            }
            *cell(tab, sh, row, c) = (int8_t)v;
        }
        tab->rhs[row] -= (int32_t)f * tab->rhs[prow];
    }
    const int64_t f = tab->reduced[enter];
    for (uint16_t i = 0U; i < nz; i++) {
        const uint16_t c = (uint16_t)tab->nonzero[i];
        tab->reduced[c] -= f * *cell(tab, sh, prow, c);
    }
    tab->basis[prow] = (int16_t)enter;
    return SVA_OK;
}

sva_status_t sva_tableau_solve(sva_tableau_t* tab, sva_tp_t* tp, int32_t* unmet, sva_stats_t* stats)
{
    const shape_t sh = build(tab, tp);
    const uint32_t cells = (uint32_t)sh.rows * sh.cols;
    stats->largest_tableau_cells =
        (cells > stats->largest_tableau_cells) ? cells : stats->largest_tableau_cells;
    uint32_t pivots = 0U;
    uint32_t degenerate_run = 0U;
    for (;;) {
        const int32_t enter = choose_entering(tab, sh, degenerate_run >= SVA_TABLEAU_BLAND_AFTER);
        if (enter < 0) {
            break;  // optimal: no negative reduced cost
        }
        if (pivots >= (uint32_t)SVA_MAX_PIVOTS) {
            return SVA_ERR_SOLVER;
        }
        const int32_t leave = choose_leaving(tab, sh, (uint16_t)enter);
        if (leave < 0) {
            return SVA_ERR_SOLVER;  // unbounded: impossible with bounded supply
        }
        degenerate_run = (tab->rhs[leave] == 0) ? (degenerate_run + 1U) : 0U;
        const sva_status_t st = pivot(tab, sh, (uint16_t)leave, (uint16_t)enter);
        if (st != SVA_OK) {
            return st;
        }
        pivots++;
    }
    const uint32_t flows = (uint32_t)tp->source_count * tp->sink_count;
    for (uint32_t i = 0U; i < flows; i++) {
        tp->flow[i] = 0;
    }
    for (uint16_t k = 0U; k < tp->sink_count; k++) {
        unmet[k] = 0;
    }
    for (uint16_t row = 0U; row < sh.rows; row++) {
        const int16_t c = tab->basis[row];
        if (tab->col_source[c] >= 0) {
            tp->flow[((uint32_t)tab->col_source[c] * tp->sink_count) + (uint32_t)tab->col_sink[c]] =
                tab->rhs[row];
        } else if (tab->col_sink[c] >= 0) {
            unmet[tab->col_sink[c]] = tab->rhs[row];
        } else {
            // surplus slack: those UAVs stay put
        }
    }
    tp->pivots += pivots;
    stats->pivots += pivots;
    stats->max_pivots = (pivots > stats->max_pivots) ? pivots : stats->max_pivots;
    return SVA_OK;
}
