// order.c -- the SPEC section 2 orders of targets and UAVs, shared by every algorithm.
#include "model.h"

// SPEC section 2 sort key: (start, end, id).
static bool target_before(const sva_target_t* a, const sva_target_t* b)
{
    if (a->start_ticks != b->start_ticks) {
        return a->start_ticks < b->start_ticks;
    }
    if (a->end_ticks != b->end_ticks) {
        return a->end_ticks < b->end_ticks;
    }
    return a->id < b->id;
}

// Insertion sorts: O(n^2) worst case on at most SVA_MAX_TARGETS items, no recursion,
// and stable, so the order is the same on every platform.
void sva_sort_targets(sva_planner_priv_t* priv, const sva_mission_t* mission)
{
    for (uint16_t i = 0U; i < mission->target_count; i++) {
        uint16_t j = i;
        while ((j > 0U) &&
               target_before(&mission->targets[i], &mission->targets[priv->target_order[j - 1U]])) {
            priv->target_order[j] = priv->target_order[j - 1U];
            j--;
        }
        priv->target_order[j] = i;
    }
}

void sva_sort_uavs(sva_planner_priv_t* priv, const sva_mission_t* mission)
{
    for (uint16_t i = 0U; i < mission->uav_count; i++) {
        uint16_t j = i;
        while ((j > 0U) && (mission->uavs[i].id < mission->uavs[priv->uav_order[j - 1U]].id)) {
            priv->uav_order[j] = priv->uav_order[j - 1U];
            j--;
        }
        priv->uav_order[j] = i;
    }
}
