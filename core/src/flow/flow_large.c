// flow_large.c -- flow's rules for large missions, of more than SVA_FLOW_LARGE_FROM
// targets (DESIGN.md section 8): their work budget grows with the square of their
// targets (up to 2.5 times the planner's, from 102 targets: a round's work grows with
// the targets and with the fleet, which grows with them); the Lagrangian phase gets
// an eighth of it from its own start (its subgradient steps are long there and
// its bound gains little from them, but its heuristic's flight finds good plans), and
// none when the search's bound already certifies the plan; one local search gets an
// eighth (a half otherwise); ruin and recreate is told the search's bound, and the
// rest of the budget goes to it, at least half of the budget, its rounds granular
// (flow_ruin.c, flow_repair.c); no search follows it.
// These functions are out of flow.c so that sva_run_flow's frame, on the core's
// deepest stack path, does not grow (docs/embedded.md).
#include "flow.h"

#if SVA_FLOW_LARGE

#    define LARGE_LOCAL_SHARE    8U
#    define LARGE_LAGRANGE_SHARE 8U
#    define FLIGHT_SHRINK        4U  // a flight's work: UAVs / FLIGHT_SHRINK evaluations

uint64_t sva_flow_budget(const sva_mission_t* m, uint64_t budget)
{
    const uint64_t from = (uint64_t)SVA_FLOW_LARGE_FROM;
    const uint64_t targets = m->target_count;
    uint64_t grown = budget;
    if (sva_flow_large(m)) {
        const uint64_t most = (5U * budget) / 2U;
        grown = ((budget * targets) * targets) / (from * from);  // budget <= SVA_FLOW_MAX_WORK
        grown = (grown > most) ? most : grown;
    }
    return grown;
}

uint64_t sva_flow_local_work(const sva_mission_t* m, uint64_t budget)
{
    uint64_t work = sva_flow_small_local_work(budget);
    if (sva_flow_large(m)) {
        work = budget / LARGE_LOCAL_SHARE;
    }
    return work;
}

uint64_t sva_flow_lagrange_end(const sva_mission_t* m, uint64_t start, uint64_t now,
                               uint64_t budget)
{
    uint64_t end = sva_flow_small_lagrange_end(start, budget);
    if (sva_flow_large(m)) {
        // From the phase's own start: the root flow and the first search can outgrow
        // their share (about 2.2 million units at 200 x 40), which left no step.
        end = now + (budget / LARGE_LAGRANGE_SHARE);
    }
    return end;
}

uint64_t sva_flow_ruin_end(const sva_mission_t* m, uint64_t end, uint64_t now, uint64_t budget)
{
    uint64_t grown = end;
    const uint64_t half = now + (budget / 2U);
    if (sva_flow_large(m) && (grown < half)) {
        grown = half;  // at 200 x 40 the phases before leave it a tenth of the budget
    }
    return grown;
}

int64_t sva_flow_known_bound(int64_t open, int64_t lagrange_bound, sva_planner_priv_t* priv,
                             const sva_mission_t* m, sva_plan_t* plan, bool coverage_known)
{
    int64_t cost = 0;
    int64_t bound = 0;
    sva_flow_write_incumbent(priv, m, plan);  // target_served as the incumbent's
    const bool proven =
        sva_flow_cost_bound(priv, m, open, lagrange_bound, coverage_known, &cost, &bound);
    return (proven && priv->flow.reward_exact) ? bound : -1;
}

bool sva_flow_near_bound(int64_t open, sva_planner_priv_t* priv, const sva_mission_t* m,
                         sva_plan_t* plan)
{
    int64_t cost = 0;
    int64_t bound = 0;
    sva_flow_write_incumbent(priv, m, plan);  // target_served as the incumbent's
    const bool proven = sva_flow_cost_bound(priv, m, open, 0, false, &cost, &bound);
    return proven && priv->flow.reward_exact && sva_flow_close(cost, bound);
}

// A flight runs a shortest path per UAV, most of them over fewer open targets than an
// evaluation's: about UAVs / 4 evaluations (measured 1/3 to 1/5 at 100 to 1,000
// targets). At 1,000 x 100 it would take about 70 million units, 17 times the budget.
bool sva_flow_flight_begins(sva_flow_work_t* w, const sva_mission_t* m)
{
    const bool large = sva_flow_large(m);
    const bool fits =
        !large || (((w->lagrange.evaluation_work * m->uav_count) / FLIGHT_SHRINK) <= w->budget);
    // A large mission's UAVs fly real paths: there most label sets fill up, and a merged
    // label's path, over fuel, left its route to the repair's cuts. No flight: the
    // shortest paths stay a bound's.
    w->lagrange.real_paths = large && fits;
    return fits;
}

#endif  // SVA_FLOW_LARGE
