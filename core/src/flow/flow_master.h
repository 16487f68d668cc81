// flow_master.h -- the layout of flow's route master (sva_flow_lp_t), shared by its
// simplex (flow_simplex.c), its column generation (flow_lp.c) and its dive
// (flow_dive.c). Private to those three files.
//
// Columns, in order: w_t for the targets' rows, s_g for the UAV states' rows, s for
// the coverage row (slack_cover), a (artificial), then the route columns
// (first_route + col). adj is rows x SVA_FLOW_LP_ROWS; a route column's rows are a
// bit set of SVA_FLOW_LP_WORDS words.
#ifndef SVA_FLOW_MASTER_H
#define SVA_FLOW_MASTER_H

#include "flow.h"

#if SVA_FLOW_LP_ROWS >= 2

#    define NO_COLUMN 0xFFFFU

static inline uint16_t slack_cover(const sva_flow_lp_t* lp)
{
    return (uint16_t)(lp->targets + lp->groups);
}

static inline uint16_t artificial(const sva_flow_lp_t* lp)
{
    return (uint16_t)(slack_cover(lp) + 1U);
}

static inline uint16_t first_route(const sva_flow_lp_t* lp)
{
    return (uint16_t)(slack_cover(lp) + 2U);
}

// Row i of adj.
static inline int64_t* adj_row(sva_flow_lp_t* lp, uint16_t i)
{
    return &lp->adj[(size_t)i * (size_t)SVA_FLOW_LP_ROWS];
}

// Route column col's row set.
static inline uint32_t* col_bits(sva_flow_lp_t* lp, uint16_t col)
{
    return &lp->col_rows[(size_t)col * SVA_FLOW_LP_WORDS];
}

static inline bool has_row(const sva_flow_lp_t* lp, uint16_t col, uint16_t row)
{
    const uint32_t word = lp->col_rows[((size_t)col * SVA_FLOW_LP_WORDS) + ((size_t)row / 32U)];
    return ((word >> ((uint32_t)row % 32U)) & 1U) != 0U;
}

// The dive's penalty columns (cost M), which never enter once out: w_t of a target
// partly served, and a fixed route's deficit.
static inline bool penalty(const sva_flow_lp_t* lp, uint16_t j)
{
    if (j >= first_route(lp)) {
        return lp->col_deficit[j - first_route(lp)] != 0U;
    }
    return (j < lp->targets) && (lp->forced[j] != 0U);
}

/// The simplex on the master's columns so far (flow_simplex.c): Dantzig's rule,
/// Bland's after a run of degenerate pivots; the work grows by rows^2 per pivot.
/// True at an optimal basis (lp->dual then holds its duals, scaled by D); false if it
/// gave up: a number outgrew its guard, or the work reached `budget`.
bool sva_flow_master_solve(sva_flow_work_t* w, const sva_mission_t* m, uint64_t budget);

#endif  // SVA_FLOW_LP_ROWS >= 2
#endif  // SVA_FLOW_MASTER_H
