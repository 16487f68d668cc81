// paper.h -- private interfaces of the paper's pipeline (core/src/paper/): clusters,
// transportation problems, their exact solvers (tableau, hga) and the greedy and
// brute-force algorithms. Builds on the model only (DESIGN.md section 9).
#ifndef SVA_PAPER_H
#define SVA_PAPER_H

#include "../model/model.h"

// Tableau and transportation-problem indices fit the types that hold them.
SVA_STATIC_ASSERT(SVA_TABLEAU_COLS <= 32767L, tableau_cols_fit_int16);
SVA_STATIC_ASSERT(SVA_MAX_UAVS <= 2147483647L / SVA_MAX_TP_SINKS, reach_index_fits);

// cluster.c: clusters of priv->target_order by window overlap (SPEC section 2).
bool sva_windows_overlap(const sva_target_t* a, const sva_target_t* b, int32_t overlap_percent);
void sva_cluster_targets(sva_planner_priv_t* priv, const sva_mission_t* mission);

// transport.c: build one problem from a chunk of a cluster, commit its flow.
void sva_tp_build(sva_planner_priv_t* priv, const sva_mission_t* mission, const sva_plan_t* plan,
                  const uint16_t* targets, uint16_t target_count, sva_stats_t* stats);
void sva_tp_commit(sva_planner_priv_t* priv, const sva_mission_t* mission, sva_plan_t* plan);
int64_t sva_tp_flow_cost(const sva_tp_t* tp);
uint16_t sva_tp_covered(const sva_tp_t* tp);

// tableau.c: min-cost flow of tp over its sinks not dropped; unmet demand allowed at a
// big-M price. Fills tp->flow; *unmet (per sink) gets the shortfall.
sva_status_t sva_tableau_solve(sva_tableau_t* tab, sva_tp_t* tp, int32_t* unmet,
                               sva_stats_t* stats);

// hga.c: exact enumeration of tp (max covered sinks, then min cost), node-bounded.
void sva_hga_solve(sva_hga_work_t* work, sva_tp_t* tp, sva_stats_t* stats);

// pipeline.c, ga.c, bfa.c: the paper's algorithms (sva and hga; ga; bfa).
sva_status_t sva_run_pipeline(sva_planner_t* self, const sva_mission_t* mission,
                              sva_algorithm_t algorithm, sva_plan_t* plan);
void sva_run_ga(sva_planner_priv_t* priv, const sva_mission_t* mission, sva_plan_t* plan);
sva_status_t sva_run_bfa(sva_planner_priv_t* priv, const sva_mission_t* mission, sva_plan_t* plan,
                         sva_diag_t* diag);

#endif  // SVA_PAPER_H
