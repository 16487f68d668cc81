// pipeline.c -- the paper's SVA pipeline (sva, and hga with enumeration): clusters in
// time order, each cut into chunks of at most SVA_MAX_TP_SINKS targets; every chunk
// with the UAVs ready for it is a transportation problem, solved, committed, and the
// UAVs advance (SPEC section 2).
#include "paper.h"

// SPEC section 2: when the problem cannot be covered in full, never half-cover. The
// tableau's optimum delivers as many units as possible; while some sink is short,
// drop the one with the largest shortfall (then the larger need, then the later sink)
// and solve again. At most sink_count rounds.
static sva_status_t solve_by_tableau(sva_planner_priv_t* priv, sva_stats_t* stats)
{
    sva_tp_t* tp = &priv->tp;
    for (;;) {
        const sva_status_t st = sva_tableau_solve(&priv->tableau, tp, tp->unmet, stats);
        if (st != SVA_OK) {
            return st;
        }
        int32_t worst = -1;
        for (uint16_t k = 0U; k < tp->sink_count; k++) {
            if (tp->unmet[k] <= 0) {
                continue;
            }
            if ((worst < 0) || (tp->unmet[k] > tp->unmet[worst]) ||
                ((tp->unmet[k] == tp->unmet[worst]) && (tp->demand[k] >= tp->demand[worst]))) {
                worst = (int32_t)k;
            }
        }
        if (worst < 0) {
            return SVA_OK;
        }
        tp->sink_dropped[worst] = true;
    }
}

static void observe(sva_planner_t* self, sva_algorithm_t algorithm)
{
    const sva_tp_t* tp = &self->priv.tp;
    if (self->on_transport == NULL) {
        return;
    }
    sva_tp_view_t view;
    view.algorithm = algorithm;
    view.source_count = tp->source_count;
    view.sink_count = tp->sink_count;
    view.supply = tp->supply;
    view.demand = tp->demand;
    view.sink_dropped = tp->sink_dropped;
    view.cost = tp->cost;
    view.flow = tp->flow;
    view.sink_targets = tp->sink_target;
    view.source_first_uav = tp->source_first_uav;
    view.cost_total = sva_tp_flow_cost(tp);
    view.covered = sva_tp_covered(tp);
    view.pivots = tp->pivots;
    self->on_transport(self->on_transport_user, &view);
}

sva_status_t sva_run_pipeline(sva_planner_t* self, const sva_mission_t* mission,
                              sva_algorithm_t algorithm, sva_plan_t* plan)
{
    sva_planner_priv_t* priv = &self->priv;
    sva_stats_t* stats = &plan->stats;
    sva_cluster_targets(priv, mission);
    stats->clusters = priv->cluster_count;
    uint16_t begin = 0U;
    for (uint16_t c = 0U; c < priv->cluster_count; c++) {
        const uint16_t end = priv->cluster_end[c];
        const uint16_t size = (uint16_t)(end - begin);
        stats->largest_cluster = (size > stats->largest_cluster) ? size : stats->largest_cluster;
        if (size > SVA_MAX_TP_SINKS) {
            stats->chunked_clusters++;
        }
        for (uint16_t chunk = begin; chunk < end; chunk = (uint16_t)(chunk + SVA_MAX_TP_SINKS)) {
            const uint16_t rest = (uint16_t)(end - chunk);
            const uint16_t n = (rest < SVA_MAX_TP_SINKS) ? rest : (uint16_t)SVA_MAX_TP_SINKS;
            sva_tp_build(priv, mission, plan, &priv->target_order[chunk], n, stats);
            if (algorithm == SVA_ALGO_HGA) {
                sva_hga_solve(&priv->hga, &priv->tp, stats);
            } else {
                const sva_status_t st = solve_by_tableau(priv, stats);
                if (st != SVA_OK) {
                    return st;
                }
            }
            observe(self, algorithm);
            sva_tp_commit(priv, mission, plan);
        }
        begin = end;
    }
    return SVA_OK;
}
