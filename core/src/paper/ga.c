// ga.c -- the paper's greedy algorithm (section 4.3): targets by (start, end, id); each
// is filled with the nearest ready UAVs (ties: lower id). A target that cannot get its
// whole need is left uncovered and takes no UAV (SPEC section 1).
#include "paper.h"

void sva_run_ga(sva_planner_priv_t* priv, const sva_mission_t* mission, sva_plan_t* plan)
{
    for (uint16_t i = 0U; i < mission->target_count; i++) {
        const uint16_t t = priv->target_order[i];
        const sva_target_t* target = &mission->targets[t];
        int32_t ready = 0;
        for (uint16_t u = 0U; u < mission->uav_count; u++) {
            ready += sva_can_serve(priv, mission, plan, u, t) ? 1 : 0;
        }
        if (ready < target->need) {
            continue;
        }
        // A committed UAV is busy until the window ends, so it is not picked twice.
        for (int32_t n = 0; n < target->need; n++) {
            int32_t best = -1;
            int32_t best_cells = 0;
            for (uint16_t j = 0U; j < mission->uav_count; j++) {
                const uint16_t u = priv->uav_order[j];
                if (sva_can_serve(priv, mission, plan, u, t)) {
                    const int32_t cells =
                        sva_distance(priv->uav_x[u], priv->uav_y[u], target->x, target->y);
                    if ((best < 0) || (cells < best_cells)) {
                        best = (int32_t)u;
                        best_cells = cells;
                    }
                }
            }
            SVA_ASSERT(best >= 0);
            sva_commit(priv, mission, plan, (uint16_t)best, t);
        }
    }
}
