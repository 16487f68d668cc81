// transport.c -- one cluster chunk plus the ready UAVs as a transportation problem
// (SPEC section 2), and committing its solution.
#include "paper.h"

#include <string.h>

static bool same_reach(const sva_tp_t* tp, uint16_t a, uint16_t b)
{
    for (uint16_t k = 0U; k < tp->sink_count; k++) {
        if (tp->uav_reach[((uint32_t)a * SVA_MAX_TP_SINKS) + k] !=
            tp->uav_reach[((uint32_t)b * SVA_MAX_TP_SINKS) + k]) {
            return false;
        }
    }
    return true;
}

// Pass 1: which sinks each UAV can serve; UAVs that can serve none are not ready.
// Returns the number of ready UAVs; each gets uav_rep = itself for now.
static uint16_t mark_ready(sva_planner_priv_t* priv, const sva_mission_t* mission,
                           const sva_plan_t* plan)
{
    sva_tp_t* tp = &priv->tp;
    uint16_t ready = 0U;
    for (uint16_t i = 0U; i < mission->uav_count; i++) {
        const uint16_t u = priv->uav_order[i];
        bool any = false;
        tp->uav_group[u] = -1;
        tp->uav_rep[u] = -1;
        for (uint16_t k = 0U; k < tp->sink_count; k++) {
            const bool can = sva_can_serve(priv, mission, plan, u, tp->sink_target[k]);
            tp->uav_reach[((uint32_t)u * SVA_MAX_TP_SINKS) + k] = can;
            any = any || can;
        }
        if (any) {
            tp->uav_rep[u] = (int16_t)u;
            ready++;
        }
    }
    return ready;
}

// Pass 2: UAVs at one position that can serve the same sinks are one source. The
// paper groups by position alone; UAVs there may differ in fuel or ready time, and a
// shared source would offer arcs not all of them can fly (DESIGN.md section 3).
// Returns the number of groups; each representative gets its nearest-sink cost.
static uint16_t group_ready(sva_planner_priv_t* priv, const sva_mission_t* mission)
{
    sva_tp_t* tp = &priv->tp;
    uint16_t groups = 0U;
    for (uint16_t i = 0U; i < mission->uav_count; i++) {
        const uint16_t u = priv->uav_order[i];
        if (tp->uav_rep[u] < 0) {
            continue;
        }
        for (uint16_t j = 0U; j < i; j++) {
            const uint16_t v = priv->uav_order[j];
            if ((tp->uav_rep[v] == (int16_t)v) && (priv->uav_x[v] == priv->uav_x[u]) &&
                (priv->uav_y[v] == priv->uav_y[u]) && same_reach(tp, u, v)) {
                tp->uav_rep[u] = (int16_t)v;
                break;
            }
        }
        if (tp->uav_rep[u] == (int16_t)u) {
            int32_t nearest = INT32_MAX;
            for (uint16_t k = 0U; k < tp->sink_count; k++) {
                if (tp->uav_reach[((uint32_t)u * SVA_MAX_TP_SINKS) + k]) {
                    const sva_target_t* t = &mission->targets[tp->sink_target[k]];
                    const int32_t d = sva_distance(priv->uav_x[u], priv->uav_y[u], t->x, t->y);
                    nearest = (d < nearest) ? d : nearest;
                }
            }
            tp->rep_cost[u] = nearest;
            groups++;
        }
    }
    return groups;
}

// Pass 3: when more groups are ready than SVA_MAX_TP_SOURCES, keep those with the
// nearest reachable sink (ties: lower UAV id); number the kept ones in id order.
static void select_sources(sva_planner_priv_t* priv, const sva_mission_t* mission, uint16_t groups,
                           sva_stats_t* stats)
{
    sva_tp_t* tp = &priv->tp;
    int32_t cutoff = INT32_MAX;
    uint16_t cutoff_rank = 0U;  // how many groups at exactly `cutoff` cost are kept
    if (groups > SVA_MAX_TP_SOURCES) {
        // The SVA_MAX_TP_SOURCES-th smallest cost, and how many at that cost fit.
        uint16_t below = 0U;
        cutoff = -1;
        while (below < SVA_MAX_TP_SOURCES) {
            int32_t next = INT32_MAX;
            uint16_t at_next = 0U;
            for (uint16_t i = 0U; i < mission->uav_count; i++) {
                const uint16_t u = priv->uav_order[i];
                if ((tp->uav_rep[u] == (int16_t)u) && (tp->rep_cost[u] > cutoff)) {
                    if (tp->rep_cost[u] < next) {
                        next = tp->rep_cost[u];
                        at_next = 1U;
                    } else if (tp->rep_cost[u] == next) {
                        at_next++;
                    } else {
                        // farther than the nearest so far: not at this cost level
                    }
                }
            }
            cutoff = next;
            cutoff_rank = (uint16_t)(SVA_MAX_TP_SOURCES - below);
            below = (uint16_t)(below + at_next);
        }
        stats->dropped_sources += (uint32_t)(groups - SVA_MAX_TP_SOURCES);
    }
    tp->source_count = 0U;
    for (uint16_t i = 0U; i < mission->uav_count; i++) {
        const uint16_t u = priv->uav_order[i];
        if (tp->uav_rep[u] != (int16_t)u) {
            continue;
        }
        bool keep = tp->rep_cost[u] < cutoff;
        if (tp->rep_cost[u] == cutoff) {
            keep = cutoff_rank > 0U;
            cutoff_rank = keep ? (uint16_t)(cutoff_rank - 1U) : 0U;
        }
        if (keep) {
            const uint16_t s = tp->source_count;
            tp->source_first_uav[s] = u;
            tp->source_x[s] = priv->uav_x[u];
            tp->source_y[s] = priv->uav_y[u];
            tp->supply[s] = 0;
            tp->uav_group[u] = (int16_t)s;
            tp->source_count++;
        }
    }
    // Members follow their representative's source.
    for (uint16_t u = 0U; u < mission->uav_count; u++) {
        if ((tp->uav_rep[u] >= 0) && (tp->uav_group[tp->uav_rep[u]] >= 0)) {
            tp->uav_group[u] = tp->uav_group[tp->uav_rep[u]];
            tp->supply[tp->uav_group[u]]++;
        }
    }
}

void sva_tp_build(sva_planner_priv_t* priv, const sva_mission_t* mission, const sva_plan_t* plan,
                  const uint16_t* targets, uint16_t target_count, sva_stats_t* stats)
{
    sva_tp_t* tp = &priv->tp;
    SVA_ASSERT((target_count > 0U) && (target_count <= SVA_MAX_TP_SINKS));
    tp->sink_count = target_count;
    tp->pivots = 0U;
    for (uint16_t k = 0U; k < target_count; k++) {
        tp->sink_target[k] = targets[k];
        tp->demand[k] = mission->targets[targets[k]].need;
        tp->sink_dropped[k] = false;
    }
    const uint16_t ready = mark_ready(priv, mission, plan);
    const uint16_t groups = (ready > 0U) ? group_ready(priv, mission) : 0U;
    select_sources(priv, mission, groups, stats);
    for (uint16_t s = 0U; s < tp->source_count; s++) {
        const uint16_t rep = tp->source_first_uav[s];
        for (uint16_t k = 0U; k < target_count; k++) {
            const sva_target_t* t = &mission->targets[targets[k]];
            tp->cost[(s * target_count) + k] =
                tp->uav_reach[((uint32_t)rep * SVA_MAX_TP_SINKS) + k]
                    ? sva_distance(tp->source_x[s], tp->source_y[s], t->x, t->y)
                    : (int32_t)SVA_TP_NO_ARC;
            tp->flow[(s * target_count) + k] = 0;
        }
    }
    // A sink that all its reachable supply together cannot fill is never coverable.
    for (uint16_t k = 0U; k < target_count; k++) {
        int32_t reachable = 0;
        for (uint16_t s = 0U; s < tp->source_count; s++) {
            if (tp->cost[(s * target_count) + k] != (int32_t)SVA_TP_NO_ARC) {
                reachable += tp->supply[s];
            }
        }
        tp->sink_dropped[k] = reachable < tp->demand[k];
    }
    stats->transport_problems++;
    stats->largest_sources =
        (tp->source_count > stats->largest_sources) ? tp->source_count : stats->largest_sources;
    stats->largest_sinks =
        (tp->sink_count > stats->largest_sinks) ? tp->sink_count : stats->largest_sinks;
}

int64_t sva_tp_flow_cost(const sva_tp_t* tp)
{
    int64_t total = 0;
    for (uint32_t i = 0U; i < ((uint32_t)tp->source_count * tp->sink_count); i++) {
        if (tp->flow[i] > 0) {
            total += (int64_t)tp->flow[i] * tp->cost[i];
        }
    }
    return total;
}

uint16_t sva_tp_covered(const sva_tp_t* tp)
{
    uint16_t covered = 0U;
    for (uint16_t k = 0U; k < tp->sink_count; k++) {
        int32_t got = 0;
        for (uint16_t s = 0U; s < tp->source_count; s++) {
            got += tp->flow[(s * tp->sink_count) + k];
        }
        if (!tp->sink_dropped[k] && (got == tp->demand[k])) {
            covered++;
        }
    }
    return covered;
}

// Sinks in order; each takes its UAVs from their groups in id order.
void sva_tp_commit(sva_planner_priv_t* priv, const sva_mission_t* mission, sva_plan_t* plan)
{
    sva_tp_t* tp = &priv->tp;
    for (uint16_t k = 0U; k < tp->sink_count; k++) {
        if (tp->sink_dropped[k]) {
            continue;
        }
        for (uint16_t s = 0U; s < tp->source_count; s++) {
            int32_t units = tp->flow[(s * tp->sink_count) + k];
            for (uint16_t i = 0U; (i < mission->uav_count) && (units > 0); i++) {
                const uint16_t u = priv->uav_order[i];
                if (tp->uav_group[u] == (int16_t)s) {
                    tp->uav_group[u] = -1;  // capacity one: used for this problem
                    sva_commit(priv, mission, plan, u, tp->sink_target[k]);
                    units--;
                }
            }
            SVA_ASSERT(units == 0);
        }
    }
}
