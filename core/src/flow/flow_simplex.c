// flow_simplex.c -- the simplex of flow's route master (flow_lp.c), revised and
// fraction-free: exact in integers (DESIGN.md section 8).
//
// It keeps D = |det(B)| and adj = D * B^-1, and pivots by the Bareiss update (each new
// entry is a 2x2 determinant divided exactly by the old D), so every number is a minor
// of the constraint matrix: exact, no rounding. The division is a multiplication by the
// inverse of D's odd part modulo 2^64 and a shift (exact quotients only, checked by
// multiplying back): no hardware divide on the pivot's path. The duals follow each pivot
// by the same update while their products stay within int64, and are recomputed from
// the basis when not. The solve gives up (no prices) when an entry outgrows ENTRY_MAX,
// which keeps every product inside int64. Dantzig's rule, Bland's after DEGENERATE_RUN
// degenerate pivots in a row (no cycling).
#include "flow_master.h"

#if SVA_FLOW_LP_ROWS >= 2

#    define ENTRY_MAX      (INT64_C(1) << 26)  // adj, x, alpha, D
#    define DUAL_MAX       (INT64_C(1) << 50)  // D * dual: labels stay within int64
#    define STEP_MAX       (INT64_C(1) << 36)  // duals and reduced cost the update may take
#    define DEGENERATE_RUN 8U

static int64_t abs64(int64_t v)
{
    return (v < 0) ? -v : v;
}

// D > 0 as 2^shift * odd, with odd's inverse modulo 2^64: num / D for any num that D
// divides is exact_quotient(num, &divisor).
typedef struct {
    uint64_t inverse;
    uint32_t shift;
} sva_divisor_t;

static sva_divisor_t divisor_of(int64_t d)
{
    sva_divisor_t v = {0U, 0U};
    uint64_t odd = (uint64_t)d;
    while (((odd & 1U) == 0U) && (v.shift < 63U)) {  // D > 0: its odd part is found
        odd >>= 1U;
        v.shift++;
    }
    // Newton's iteration doubles the correct low bits: 3 (odd * odd = 1 mod 8), then
    // 6, 12, 24, 48, 96.
    uint64_t x = odd;
    for (uint32_t i = 0U; i < 5U; i++) {
        x *= UINT64_C(2) - (odd * x);
    }
    v.inverse = x;
    return v;
}

// The int64 whose two's complement is u: its low 63 bits, less 2^63 when the top bit is
// set (as twice 2^62, within int64), without a branch (the quotients' signs vary).
static int64_t from_twos(uint64_t u)
{
    const uint64_t low_bits = u & (uint64_t)INT64_MAX;
    const uint64_t top = (u >> 63U) << 62U;
    const int64_t low = (int64_t)low_bits;
    const int64_t half = (int64_t)top;
    return (low - half) - half;
}

// num / D when D divides num: num shifted right (arithmetically) by D's power of two,
// times its odd part's inverse, modulo 2^64. Otherwise some other number, which
// fits_product refuses.
static int64_t exact_quotient(int64_t num, const sva_divisor_t* d)
{
    const uint64_t u = (uint64_t)num;
    const uint64_t sign = UINT64_C(0) - (u >> 63U);  // all ones when num < 0
    const uint64_t shifted = (u >> d->shift) | (sign & ~(UINT64_MAX >> d->shift));
    return from_twos(shifted * d->inverse);
}

// True if q = num / D exactly with |q| <= limit (ENTRY_MAX or STEP_MAX): then |q D| <
// 2^63 cannot wrap, so equal modulo 2^64 is equal.
static bool fits_product(int64_t q, int64_t d, int64_t num, int64_t limit)
{
    return (q >= -limit) && (q <= limit) && (((uint64_t)q * (uint64_t)d) == (uint64_t)num);
}

// Index of the one bit set in `bit` (de Bruijn multiplication).
static uint32_t lowest_bit_index(uint32_t bit)
{
    static const uint8_t index_of[32] = {0U,  1U,  28U, 2U,  29U, 14U, 24U, 3U,  30U, 22U, 20U,
                                         15U, 25U, 17U, 4U,  8U,  31U, 27U, 13U, 23U, 21U, 19U,
                                         16U, 7U,  26U, 12U, 18U, 6U,  11U, 5U,  10U, 9U};
    return index_of[(uint32_t)(bit * UINT32_C(0x077CB531)) >> 27U];
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

// True if every dual is within DUAL_MAX.
static bool duals_fit(const sva_flow_lp_t* lp)
{
    for (uint16_t k = 0U; k < lp->rows; k++) {
        if (abs64(lp->dual[k]) > DUAL_MAX) {
            return false;
        }
    }
    return true;
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
    return duals_fit(lp);
}

// The entering column: the most negative reduced cost (Dantzig), or the first
// negative one (Bland), its reduced cost (scaled by D) in *rc_out; NO_COLUMN when the
// basis is optimal.
static uint16_t lp_entering(const sva_flow_lp_t* lp, const sva_mission_t* m, bool bland,
                            int64_t* rc_out)
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
    *rc_out = best_rc;
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

// The duals after column j (reduced cost rc) enters at position r, by the pivot's
// update dual' = (alpha_r dual + rc adj_r) / D (row r of adj stays); false (the duals
// then to be computed from the basis) if a product could leave int64, or a quotient is
// not exact or outgrows STEP_MAX.
static bool update_duals(sva_flow_lp_t* lp, uint16_t r, int64_t rc, const sva_divisor_t* d)
{
    const int64_t ar = lp->alpha[r];
    const int64_t* row_r = adj_row(lp, r);
    if (abs64(rc) > STEP_MAX) {
        return false;
    }
    for (uint16_t k = 0U; k < lp->rows; k++) {
        if (abs64(lp->dual[k]) > STEP_MAX) {
            return false;
        }
    }
    for (uint16_t k = 0U; k < lp->rows; k++) {
        const int64_t num = (ar * lp->dual[k]) + (rc * row_r[k]);
        lp->dual[k] = exact_quotient(num, d);
        if (!fits_product(lp->dual[k], lp->det, num, STEP_MAX)) {
            return false;
        }
    }
    return true;
}

// Column j enters at position r (Bareiss); false if a division is not exact or a
// number outgrows ENTRY_MAX (neither happens in exact arithmetic within the guards).
static bool lp_pivot(sva_flow_lp_t* lp, uint16_t r, uint16_t j, const sva_divisor_t* d)
{
    const int64_t ar = lp->alpha[r];
    const int64_t det = lp->det;
    const int64_t* row_r = adj_row(lp, r);
    bool ok = true;
    for (uint16_t i = 0U; i < lp->rows; i++) {
        if (i == r) {
            continue;
        }
        const int64_t ai = lp->alpha[i];
        if ((ai == 0) && (ar == det)) {
            continue;  // the row and x_i stay as they are
        }
        int64_t* row_i = adj_row(lp, i);
        for (uint16_t k = 0U; k < lp->rows; k++) {
            const int64_t num = (ar * row_i[k]) - (ai * row_r[k]);
            if (num == 0) {
                row_i[k] = 0;  // adj is mostly zeros: nothing to divide
                continue;
            }
            row_i[k] = exact_quotient(num, d);
            if (!fits_product(row_i[k], det, num, ENTRY_MAX)) {
                ok = false;
            }
        }
        const int64_t num = (ar * lp->x[i]) - (ai * lp->x[r]);
        lp->x[i] = exact_quotient(num, d);
        if (!fits_product(lp->x[i], det, num, ENTRY_MAX)) {
            ok = false;
        }
    }
    lp->in_basis[lp->basic[r]] = 0U;
    lp->in_basis[j] = 1U;
    lp->basic[r] = j;
    lp->det = ar;
    return ok;
}

bool sva_flow_master_solve(sva_flow_work_t* w, const sva_mission_t* m, uint64_t budget)
{
    sva_flow_lp_t* lp = &w->lp;
    uint32_t degenerate = 0U;
    const uint64_t per_pivot = (uint64_t)lp->rows * (uint64_t)lp->rows;
    // The columns' costs may have changed since the last solve (the dive): duals from
    // the basis first, then by the pivots' update.
    bool fresh = false;
    while (w->work < budget) {
        if (!fresh && !compute_duals(lp)) {
            return false;
        }
        int64_t rc = 0;
        const uint16_t j = lp_entering(lp, m, degenerate >= DEGENERATE_RUN, &rc);
        if (j == NO_COLUMN) {
            return true;
        }
        const uint16_t r = lp_leaving(lp, m, j);
        if (r == NO_COLUMN) {
            return false;  // a guard, or unbounded (cannot be: every column has a cost >= 0 or is
                           // bounded by a row)
        }
        if (lp->x[r] == 0) {
            degenerate++;
        } else {
            degenerate = 0U;
        }
        const sva_divisor_t d = divisor_of(lp->det);
        fresh = update_duals(lp, r, rc, &d);
        if (!lp_pivot(lp, r, j, &d)) {
            return false;
        }
        fresh = fresh && duals_fit(lp);
        w->work += per_pivot;
    }
    return false;
}

#endif  // SVA_FLOW_LP_ROWS >= 2
