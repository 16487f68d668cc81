// cluster.c -- the paper's clusters: targets joined by window overlap (SPEC section 2).
#include "paper.h"

// SPEC section 2: 100 * |A n B| >= overlap_percent * min(|A|, |B|), |[s, e]| = e - s.
bool sva_windows_overlap(const sva_target_t* a, const sva_target_t* b, int32_t overlap_percent)
{
    const int64_t lo = (a->start_ticks > b->start_ticks) ? a->start_ticks : b->start_ticks;
    const int64_t hi = (a->end_ticks < b->end_ticks) ? a->end_ticks : b->end_ticks;
    const int64_t common = (hi > lo) ? (hi - lo) : 0;
    const int64_t len_a = (int64_t)a->end_ticks - a->start_ticks;
    const int64_t len_b = (int64_t)b->end_ticks - b->start_ticks;
    const int64_t shorter = (len_a < len_b) ? len_a : len_b;
    return (100 * common) >= ((int64_t)overlap_percent * shorter);
}

// Each next target (in order) joins the current cluster iff it overlaps the cluster's
// last member enough; otherwise it starts a new cluster.
void sva_cluster_targets(sva_planner_priv_t* priv, const sva_mission_t* mission)
{
    priv->cluster_count = 0U;
    for (uint16_t k = 0U; k < mission->target_count; k++) {
        const bool joins =
            (k > 0U) &&
            sva_windows_overlap(&mission->targets[priv->target_order[k - 1U]],
                                &mission->targets[priv->target_order[k]], mission->overlap_percent);
        if (joins) {
            priv->cluster_end[priv->cluster_count - 1U] = (uint16_t)(k + 1U);
        } else {
            priv->cluster_end[priv->cluster_count] = (uint16_t)(k + 1U);
            priv->cluster_count++;
        }
    }
}
