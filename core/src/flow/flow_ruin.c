// flow_ruin.c -- flow's ruin and recreate (DESIGN.md section 8).
//
// The incumbent loses a group of related visits, and the repair
// puts a plan back together (uncovered targets inserted in window order, every other
// round in reverse, ejection, local search when within reach, offer). For each group
// size in turn, each covered target s seeds a group: s and the covered targets
// nearest to it (cells between them plus the ticks between their window starts, in
// cells). With need 2 this is how a target short of its second UAV finds one: the
// group's visits leave room. Then swaps: one covered target out, one uncovered in.
#include "flow.h"

#define RUIN_ROUND_UNITS 8U  // work units per round and per target x UAV (insertions)

static int64_t relatedness(const sva_mission_t* m, uint16_t a, uint16_t b)
{
    const sva_target_t* ta = &m->targets[a];
    const sva_target_t* tb = &m->targets[b];
    const int64_t ticks = (int64_t)ta->start_ticks - (int64_t)tb->start_ticks;
    return sva_distance(ta->x, ta->y, tb->x, tb->y) +
           (((ticks < 0) ? -ticks : ticks) / m->ticks_per_cell);
}

// The incumbent without s and the size - 1 covered targets most related to it.
static void ruin(sva_planner_priv_t* priv, const sva_mission_t* m, sva_plan_t* plan, uint16_t s,
                 uint8_t size)
{
    sva_flow_work_t* w = &priv->flow;
    for (uint16_t u = 0U; u < m->uav_count; u++) {
        w->route_cells[u] = sva_route_cells(m, u, &plan->routes[u]);
    }
    sva_flow_remove_target(priv, m, plan, s);
    for (uint8_t k = 1U; k < size; k++) {
        int32_t pick = -1;
        int64_t pick_rel = 0;
        for (uint16_t t = 0U; t < m->target_count; t++) {
            const int64_t rel = relatedness(m, s, t);
            if ((priv->target_served[t] > 0U) && ((pick < 0) || (rel < pick_rel))) {
                pick = (int32_t)t;
                pick_rel = rel;
            }
        }
        if (pick >= 0) {
            sva_flow_remove_target(priv, m, plan, (uint16_t)pick);
        }
    }
}

bool sva_flow_ruin_recreate(sva_planner_priv_t* priv, const sva_mission_t* m, sva_plan_t* plan,
                            uint64_t end, int64_t proven_bound)
{
    static const uint8_t ruin_sizes[] = {6U, 8U, 10U, 3U};  // group sizes, in turn
    sva_flow_work_t* w = &priv->flow;
    int64_t cost = 0;
    int64_t covered = 0;
    sva_flow_incumbent(priv, m, plan, &cost, &covered);
    if (proven_bound >= cost) {
        return true;  // proven optimal: nothing to find
    }
    // Not when the coverage is proven and the plan within 1/64 of the bound: the
    // search, with the rest of the budget, may prove it.
    const bool near = (proven_bound >= 0) && ((cost - proven_bound) <= (cost / 64));
    const uint64_t rest = ((end > w->work) && !near) ? (end - w->work) : 0U;
    const uint64_t budget = w->work + (rest - (rest / 4U));
    const uint64_t round_units =
        (uint64_t)m->target_count * (uint64_t)m->uav_count * RUIN_ROUND_UNITS;
    // *plan holds the incumbent whenever a round is chosen (sva_flow_incumbent above,
    // then a write after each round).
    for (size_t i = 0U; i < (sizeof(ruin_sizes) / sizeof(ruin_sizes[0])); i++) {
        for (uint16_t s = 0U; (s < m->target_count) && (w->work < budget); s++) {
            if ((int32_t)priv->target_served[s] == m->targets[s].need) {
                ruin(priv, m, plan, s, ruin_sizes[i]);
                w->insert_backwards = ((s + i) % 2U) == 1U;
                sva_flow_repair(priv, m, plan, true);
                w->insert_backwards = false;
                w->work += round_units;
                plan->stats.flow_ruin_rounds++;
                sva_flow_write_incumbent(priv, m, plan);
            }
        }
    }
    // Swaps: a covered target c leaves, an uncovered target t goes in first (all its
    // need at once), and the repair puts the rest back. With need 2 a plan may cover
    // the right number of targets but the wrong ones; groups reinserted in window
    // order rarely change which.
    for (uint16_t c = 0U; (c < m->target_count) && (w->work < budget); c++) {
        for (uint16_t t = 0U; (t < m->target_count) && (w->work < budget); t++) {
            if (((int32_t)priv->target_served[c] == m->targets[c].need) &&
                (priv->target_served[t] == 0U)) {
                ruin(priv, m, plan, c, 1U);
                sva_flow_try_insert(priv, m, plan, t);
                if (priv->target_served[t] != 0U) {
                    sva_flow_repair(priv, m, plan, true);
                    plan->stats.flow_ruin_rounds++;
                }
                w->work += round_units;
                sva_flow_write_incumbent(priv, m, plan);
            }
        }
    }
    return false;
}
