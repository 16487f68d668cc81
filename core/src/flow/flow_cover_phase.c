// flow_cover_phase.c -- how flow spends the coverage search's work (DESIGN.md section 8,
// "Coverage search"): the search (flow_cover.c) for one target more than the incumbent
// covers, again after each plan it finds; at need 2 and more, last, in three thirds:
// the search in window order, neighbourhoods of the incumbent, the search with the
// incumbent's choices first.
#include "flow.h"

#if SVA_FLOW_COVER_TARGETS > 0

// One part of sva_flow_cover_incumbent: the search (or its neighbourhoods), again after
// each plan it finds, until `end`.
static sva_flow_cover_result_t cover_until(sva_planner_priv_t* priv, const sva_mission_t* m,
                                           sva_plan_t* plan, uint64_t end, bool around)
{
    sva_flow_cover_result_t r = SVA_FLOW_COVER_FOUND;
    while (r == SVA_FLOW_COVER_FOUND) {
        int64_t cost = 0;
        int64_t covered = 0;
        sva_flow_incumbent(priv, m, plan, &cost, &covered);
        if (around) {
            const int32_t size = priv->flow.need_max + 1;
            r = sva_flow_cover_around(priv, m, plan, covered, (uint16_t)size, end,
                                      &plan->stats.flow_cover_nodes);
        } else {
            r = sva_flow_cover(priv, m, plan, covered, end, &plan->stats.flow_cover_nodes);
        }
        if (r == SVA_FLOW_COVER_FOUND) {
            sva_flow_repair(priv, m, plan, true);
        }
    }
    return r;
}

uint64_t sva_flow_cover_incumbent(sva_planner_priv_t* priv, const sva_mission_t* m,
                                  sva_plan_t* plan, uint64_t work, bool incumbent_first,
                                  bool* proven)
{
    const uint64_t from = priv->flow.work;
    // incumbent_first: three thirds, the search in its own order, the neighbourhoods,
    // the search with the incumbent's choices first; otherwise the first order only.
    uint64_t parts = 1U;
    if (incumbent_first) {
        parts = 3U;
    }
    sva_flow_cover_result_t r = SVA_FLOW_COVER_OPEN;
    for (uint64_t part = 0U; (part < parts) && (r == SVA_FLOW_COVER_OPEN); part++) {
        priv->flow.cover.incumbent_first = incumbent_first && (part == 2U);
        uint64_t end = from + work;
        if ((part + 1U) < parts) {
            end = from + ((work / parts) * (part + 1U));
        }
        r = cover_until(priv, m, plan, end, incumbent_first && (part == 1U));
        if (incumbent_first && (part == 1U)) {
            r = SVA_FLOW_COVER_OPEN;  // the neighbourhoods prove nothing
        }
    }
    priv->flow.cover.incumbent_first = false;
    *proven = r == SVA_FLOW_COVER_PROVEN;
    return priv->flow.work - from;
}

#else  // the profile turns the search off

uint64_t sva_flow_cover_incumbent(sva_planner_priv_t* priv, const sva_mission_t* m,
                                  sva_plan_t* plan, uint64_t work, bool incumbent_first,
                                  bool* proven)
{
    (void)priv;
    (void)m;
    (void)plan;
    (void)work;
    (void)incumbent_first;
    *proven = false;
    return 0U;
}

#endif
