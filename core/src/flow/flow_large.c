// flow_large.c -- flow's rules for large missions, of more than SVA_FLOW_LARGE_FROM
// targets (DESIGN.md section 8): their work budget grows with their targets (up to
// twice the planner's, at twice SVA_FLOW_LARGE_FROM targets), the Lagrangian phase gets
// an eighth of it (its subgradient steps are long there and its bound gains little from
// them) and one local search an eighth (a half otherwise), and ruin and recreate is
// told the search's bound. The rest of the budget goes to ruin and recreate, whose
// rounds are granular (flow_ruin.c, flow_repair.c). These functions are out of flow.c
// so that sva_run_flow's frame, on the core's deepest stack path, does not grow
// (docs/embedded.md).
#include "flow.h"

#if SVA_FLOW_LARGE

#    define LARGE_LOCAL_SHARE    8U
#    define LARGE_LAGRANGE_SHARE 8U

uint64_t sva_flow_budget(const sva_mission_t* m, uint64_t budget)
{
    const uint64_t most = 2U * (uint64_t)SVA_FLOW_LARGE_FROM;
    const uint64_t targets = (m->target_count < most) ? m->target_count : most;
    uint64_t grown = budget;
    if (sva_flow_large(m)) {
        grown = (budget / (uint64_t)SVA_FLOW_LARGE_FROM) * targets;
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

uint64_t sva_flow_lagrange_work(const sva_mission_t* m, uint64_t budget)
{
    uint64_t work = sva_flow_small_lagrange_work(budget);
    if (sva_flow_large(m)) {
        work = budget / LARGE_LAGRANGE_SHARE;
    }
    return work;
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

#endif  // SVA_FLOW_LARGE
