// hga.c -- the paper's hybrid greedy algorithm solves each transportation problem by
// enumeration: every way to fill or skip each sink, best = most sinks covered in full,
// then least cost. Depth-first over sinks with an explicit stack (no recursion); a
// sink is filled by a vector of units per source, enumerated greedy-first.
// Deterministic node budget SVA_HGA_MAX_NODES: past it the best assignment found is
// kept and counted in sva_stats_t.truncated_searches.
#include "paper.h"

enum { PHASE_FRESH = 0, PHASE_FILLED = 1, PHASE_SKIPPED = 2 };

static int32_t cap(const sva_hga_work_t* w, const sva_tp_t* tp, uint16_t s, uint16_t k)
{
    return (tp->cost[(s * tp->sink_count) + k] == (int32_t)SVA_TP_NO_ARC) ? 0 : w->left[s];
}

static int32_t* pick(sva_hga_work_t* w, uint16_t k)
{
    return &w->pick[(size_t)k * (size_t)SVA_MAX_TP_SOURCES];
}

// The first fill of sink k: as many units as possible from the lowest sources.
static bool first_fill(sva_hga_work_t* w, const sva_tp_t* tp, uint16_t k)
{
    int32_t need = tp->demand[k];
    int32_t* p = pick(w, k);
    for (uint16_t s = 0U; s < tp->source_count; s++) {
        const int32_t c = cap(w, tp, s, k);
        p[s] = (c < need) ? c : need;
        need -= p[s];
    }
    return need == 0;
}

// The next fill in decreasing lexicographic order: move one unit from the rightmost
// source that can give one to the sources after it, refilled greedily.
static bool next_fill(sva_hga_work_t* w, const sva_tp_t* tp, uint16_t k)
{
    int32_t* p = pick(w, k);
    int32_t after = 0;       // units picked from sources after s
    int32_t room_after = 0;  // their capacity
    for (int32_t s = (int32_t)tp->source_count - 1; s >= 0; s--) {
        if ((p[s] > 0) && ((after + 1) <= room_after)) {
            p[s]--;
            int32_t r = after + 1;
            for (uint16_t j = (uint16_t)(s + 1); j < tp->source_count; j++) {
                const int32_t c = cap(w, tp, j, k);
                p[j] = (c < r) ? c : r;
                r -= p[j];
            }
            return true;
        }
        after += p[s];
        room_after += cap(w, tp, (uint16_t)s, k);
    }
    return false;
}

static int64_t apply(sva_hga_work_t* w, const sva_tp_t* tp, uint16_t k, int32_t sign)
{
    const int32_t* p = pick(w, k);
    int64_t cost = 0;
    for (uint16_t s = 0U; s < tp->source_count; s++) {
        w->left[s] -= sign * p[s];
        if (p[s] > 0) {
            cost += (int64_t)p[s] * tp->cost[(s * tp->sink_count) + k];
        }
    }
    return cost;
}

void sva_hga_solve(sva_hga_work_t* w, sva_tp_t* tp, sva_stats_t* stats)
{
    const uint16_t n = tp->sink_count;
    const uint16_t m = tp->source_count;
    for (uint16_t s = 0U; s < m; s++) {
        w->left[s] = tp->supply[s];
    }
    for (uint32_t i = 0U; i < ((uint32_t)m * n); i++) {
        w->best[i] = 0;
    }
    int32_t best_covered = -1;
    int64_t best_cost = 0;
    int32_t covered = 0;
    int64_t cost = 0;
    uint64_t nodes = 0U;
    bool truncated = false;
    int32_t depth = 0;
    w->phase[0] = PHASE_FRESH;
    while (depth >= 0) {
        if (depth == (int32_t)n) {  // leaf: a complete assignment
            if ((covered > best_covered) || ((covered == best_covered) && (cost < best_cost))) {
                best_covered = covered;
                best_cost = cost;
                for (uint16_t k = 0U; k < n; k++) {
                    for (uint16_t s = 0U; s < m; s++) {
                        w->best[(s * n) + k] = (w->phase[k] == PHASE_FILLED) ? pick(w, k)[s] : 0;
                    }
                }
            }
            depth--;
            continue;
        }
        const uint16_t k = (uint16_t)depth;
        bool filled = false;
        if (w->phase[k] == PHASE_FILLED) {  // back at this depth: undo, then next fill
            (void)apply(w, tp, k, -1);
            cost = w->cost_before[k];
            covered--;
            filled = next_fill(w, tp, k);
        } else if (w->phase[k] == PHASE_FRESH) {
            filled = !tp->sink_dropped[k] && first_fill(w, tp, k);
        } else {
            depth--;  // skip was the last option
            continue;
        }
        if (filled) {
            w->cost_before[k] = cost;
            cost += apply(w, tp, k, 1);
            covered++;
            w->phase[k] = PHASE_FILLED;
        } else {
            w->phase[k] = PHASE_SKIPPED;
        }
        nodes++;
        if ((nodes > (uint64_t)SVA_HGA_MAX_NODES) && (best_covered >= 0)) {
            truncated = true;
            break;
        }
        // Bound: costs are non-negative, so a branch that cannot cover more than the
        // best, or covers as many at no lower cost, cannot win.
        const int32_t reachable = covered + ((int32_t)n - depth - 1);
        if ((reachable < best_covered) || ((reachable == best_covered) && (cost >= best_cost))) {
            continue;  // try this depth's next option
        }
        depth++;
        if (depth < (int32_t)n) {
            w->phase[depth] = PHASE_FRESH;
        }
    }
    for (uint32_t i = 0U; i < ((uint32_t)m * n); i++) {
        tp->flow[i] = w->best[i];
    }
    for (uint16_t k = 0U; k < n; k++) {
        int32_t got = 0;
        for (uint16_t s = 0U; s < m; s++) {
            got += tp->flow[(s * n) + k];
        }
        tp->sink_dropped[k] = got < tp->demand[k];
    }
    stats->search_nodes += nodes;
    if (truncated) {
        stats->truncated_searches++;
    }
}
