// sva_internal.h -- private interfaces between the core's source files.
// Not installed; never included by ports or tools.
#ifndef SVA_INTERNAL_H
#define SVA_INTERNAL_H

#include "sva/sva.h"

// Asserts guard API misuse and internal invariants only, never untrusted input
// (STYLE: Errors). Default: the C library's assert (so NDEBUG turns it off, as
// anywhere in C); SVA_ENABLE_ASSERT=0 compiles them out; firmware may define
// SVA_ASSERT(x) to its own handler. Disabled, the expression is still type-checked.
#ifndef SVA_ASSERT
#if SVA_ENABLE_ASSERT && !defined(NDEBUG)
#include <assert.h>
#define SVA_ASSERT(x) assert(x)
#else
#define SVA_ASSERT(x) ((void)sizeof((x) ? 1 : 0))
#endif
#endif

// C99 static assertion (negative array size on failure).
#define SVA_STATIC_ASSERT(cond, name) typedef char sva_static_assert_##name[(cond) ? 1 : -1]

// Integer headroom (DESIGN.md section 5): the longest leg is 2 * 65535 cells; every
// leg, supply, demand and tableau index fits the types that hold it.
#define SVA_MAX_LEG_CELLS (2L * (SVA_COORD_MAX - SVA_COORD_MIN))
SVA_STATIC_ASSERT(SVA_MAX_LEG_CELLS <= 2147483647L, leg_fits_int32);
SVA_STATIC_ASSERT(SVA_MAX_LEG_CELLS * SVA_MAX_TICKS_PER_CELL + SVA_MAX_TICK <= 2147483647L,
                  arrival_fits_int32);
SVA_STATIC_ASSERT(SVA_TABLEAU_COLS <= 32767L, tableau_cols_fit_int16);
SVA_STATIC_ASSERT(SVA_MAX_TARGETS <= 65535L && SVA_MAX_UAVS <= 65535L, indices_fit_uint16);
SVA_STATIC_ASSERT(SVA_MAX_UAVS <= 2147483647L / SVA_MAX_TP_SINKS, reach_index_fits);
// flow: node ids and heap positions are uint16 (0xFFFF is "none"); pred codes int32.
SVA_STATIC_ASSERT(SVA_FLOW_NODES < 65535L, flow_nodes_fit_uint16);
SVA_STATIC_ASSERT(SVA_FLOW_MAX_ARCS <= (2147483647L / 2L) - SVA_FLOW_MAX_COPIES, flow_pred_fits);
// arc_ban counts levels: at most 3 bans of one arc per level.
SVA_STATIC_ASSERT(3L * SVA_FLOW_MAX_DEPTH <= 255L, flow_ban_levels_fit_uint8);

/// Manhattan distance in cells (SPEC section 1); at most SVA_MAX_LEG_CELLS.
static inline int32_t sva_distance(int32_t ax, int32_t ay, int32_t bx, int32_t by)
{
    const int32_t dx = (ax > bx) ? (ax - bx) : (bx - ax);
    const int32_t dy = (ay > by) ? (ay - by) : (by - ay);
    return dx + dy;
}

/// Greatest common divisor (gcd(a, 0) = a), for the needs' lcm (tableau.c, flow_graph.c).
static inline int64_t sva_gcd64(int64_t a, int64_t b)
{
    int64_t x = a;
    int64_t y = b;
    while (y != 0) {
        const int64_t r = x % y;
        x = y;
        y = r;
    }
    return x;
}

// cluster.c: targets by (start, end, id) into priv->target_order, then clusters.
void sva_sort_targets(sva_planner_priv_t* priv, const sva_mission_t* mission);
void sva_sort_uavs(sva_planner_priv_t* priv, const sva_mission_t* mission);
bool sva_windows_overlap(const sva_target_t* a, const sva_target_t* b, int32_t overlap_percent);
void sva_cluster_targets(sva_planner_priv_t* priv, const sva_mission_t* mission);

// plan.c: the planning state shared by every algorithm.
void sva_state_reset(sva_planner_priv_t* priv, const sva_mission_t* mission, sva_plan_t* plan);
bool sva_can_serve(const sva_planner_priv_t* priv, const sva_mission_t* mission,
                   const sva_plan_t* plan, uint16_t uav, uint16_t target);
/// Extra route distance if `uav` serves `target` next instead of flying home now.
int64_t sva_insertion_cells(const sva_planner_priv_t* priv, const sva_mission_t* mission,
                            uint16_t uav, uint16_t target);
void sva_commit(sva_planner_priv_t* priv, const sva_mission_t* mission, sva_plan_t* plan,
                uint16_t uav, uint16_t target);
/// Cells flown over targets[0..count-1] from the UAV's mission position, return leg
/// included; sva_route_cells: over a route's targets.
int64_t sva_path_cells(const sva_mission_t* mission, uint16_t uav, const uint16_t* targets, uint16_t count);
int64_t sva_route_cells(const sva_mission_t* mission, uint16_t uav, const sva_route_t* route);
void sva_plan_finish(sva_planner_priv_t* priv, const sva_mission_t* mission, sva_plan_t* plan);

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

// flow_graph.c, flow_ssp.c, flow_repair.c: flow's graph, relaxation and plans.
/// flow's reasons to stop short (sva_stats_t.flow_incomplete).
enum {
    SVA_FLOW_COMPLETE = 0,           ///< the search finished
    SVA_FLOW_INCOMPLETE_WORK = 1,    ///< past the work budget
    SVA_FLOW_INCOMPLETE_DEPTH = 2,   ///< a node deeper than SVA_FLOW_MAX_DEPTH
    SVA_FLOW_INCOMPLETE_REWARD = 3,  ///< needs' lcm too large for exact cost ties
    SVA_FLOW_OVER_COPIES = 4,        ///< needs summed above SVA_FLOW_MAX_COPIES
    SVA_FLOW_OVER_ARCS = 5,          ///< graph above SVA_FLOW_MAX_ARCS
};
/// Builds the graph (pooled: one copy per target carrying its need, for the root
/// relaxation alone; needs up to UINT8_MAX); 0, or SVA_FLOW_OVER_COPIES / SVA_FLOW_OVER_ARCS.
uint8_t sva_flow_build(sva_planner_priv_t* priv, const sva_mission_t* m, const sva_plan_t* plan,
                       bool pooled, sva_stats_t* stats);
int32_t sva_flow_arc_cost(const sva_flow_work_t* w, uint32_t arc);
/// Min-cost flow under the current branching rules; false if no flow meets them.
bool sva_flow_solve(sva_flow_work_t* w, sva_stats_t* stats);
bool sva_flow_covered(const sva_flow_work_t* w, uint16_t copy);
/// The copies UAV u visits in the current flow, in order; returns how many (<= cap).
uint16_t sva_flow_route(const sva_flow_work_t* w, uint16_t u, uint16_t* out, uint16_t cap);
/// Whether UAV u can fly a route of `targets` targets and `cells` cells: its fuel
/// (hovering included) and SVA_MAX_ROUTE_TARGETS.
bool sva_flow_fits(const sva_mission_t* m, uint16_t u, int64_t cells, uint32_t targets);
bool sva_flow_route_fits(const sva_mission_t* m, uint16_t u, const uint16_t* copies,
                         uint16_t n, const sva_flow_work_t* w);
/// Keeps the plan in *plan (routes + priv->target_served) if it beats the incumbent.
bool sva_flow_offer_plan(sva_planner_priv_t* priv, const sva_mission_t* m, const sva_plan_t* plan);
/// Gives UAVs in the same state (position, fuel, ready time) the incumbent's routes in
/// id order: the route whose targets come first in window order to the lowest id, empty
/// routes to the highest. The same plan whatever order the mission lists them in.
void sva_flow_canonical_incumbent(sva_planner_priv_t* priv, const sva_mission_t* m);
void sva_flow_write_incumbent(sva_planner_priv_t* priv, const sva_mission_t* m, sva_plan_t* plan);
/// The incumbent written into *plan, with its cost in cells and the targets it covers.
void sva_flow_incumbent(sva_planner_priv_t* priv, const sva_mission_t* m, sva_plan_t* plan, int64_t* cost,
                        int64_t* covered);
/// Rounds the current relaxation into a plan (scratch: *plan) and offers it
/// (sva_flow_repair, with `polish`).
void sva_flow_round(sva_planner_priv_t* priv, const sva_mission_t* m, sva_plan_t* plan,
                    bool polish);
/// Offers the current relaxation as it is, when it is a plan (no target half covered,
/// every route within fuel and length): then nothing could repair or improve it.
void sva_flow_take_relaxation(sva_planner_priv_t* priv, const sva_mission_t* m, sva_plan_t* plan);
/// The pooled graph's flow (sva_flow_build with pooled) split into one route per UAV,
/// over targets, with priv->target_served; takes the flow off the arcs as it goes.
/// Returns whether the routes are a plan: every target served by none or all of its
/// need, every route within fuel and SVA_MAX_ROUTE_TARGETS.
bool sva_flow_pooled_routes(sva_planner_priv_t* priv, const sva_mission_t* m, sva_plan_t* plan);
/// Makes the routes in *plan (with priv->target_served) a plan: drops half-covered
/// targets and routes' excess, inserts what fits, improves it by local search if it
/// beats the incumbent (or, with `polish`, comes within 1/16), and offers it.
void sva_flow_repair(sva_planner_priv_t* priv, const sva_mission_t* m, sva_plan_t* plan,
                     bool polish);
/// Ruin and recreate (flow_repair.c): groups of related visits taken out of the
/// incumbent, then swaps (one covered target out, one uncovered in first); the repair
/// completes and offers each plan. With three quarters of the work left before `end`,
/// unless the incumbent is within 1/64 of `proven_bound`, a bound with its coverage
/// proven the most (-1: none). Leaves the incumbent in *plan. Returns true, doing
/// nothing, when the bound reaches the incumbent's cost: it is proven optimal.
bool sva_flow_ruin_recreate(sva_planner_priv_t* priv, const sva_mission_t* m, sva_plan_t* plan,
                            uint64_t end, int64_t proven_bound);

// flow_lagrange.c: flow's Lagrangian bound and heuristic.
/// Scale of the target prices (1/SVA_FLOW_PRICE_SCALE cells).
#define SVA_FLOW_PRICE_SCALE 256
/// A label's predecessor when it starts the route.
#define SVA_FLOW_NO_LABEL 0xFFFFFFFFU
/// The route ending at label l (none: SVA_FLOW_NO_LABEL) into lg->path, first target
/// first.
void sva_flow_label_path(sva_flow_lagrange_t* lg, uint32_t l);
/// UAV u's best route under w->lagrange.path_price (targets marked closed skipped):
/// min over its routes within fuel of alpha * cells - sum of prices (flying home at
/// once included); the route goes to w->lagrange.path. Label extensions count as work.
int64_t sva_flow_best_route(sva_flow_work_t* w, const sva_mission_t* m, uint16_t u, int64_t alpha);

/// Subgradient phases until the work reaches `budget`: improves the incumbent, and
/// returns a lower bound on the cost of every plan covering at least as many targets
/// as the incumbent (0 when it has none); *coverage_proven: no plan covers more.
/// *iters gets the subgradient steps taken.
int64_t sva_flow_lagrange(sva_planner_priv_t* priv, const sva_mission_t* m, sva_plan_t* plan,
                          uint64_t budget, bool* coverage_proven, uint32_t* iters);

// flow_lp.c: the route master's duals as the Lagrangian's prices.
typedef enum {
    SVA_FLOW_LP_COST,    ///< a new cost master
    SVA_FLOW_LP_COVER,   ///< a new cover master (costs left out)
    SVA_FLOW_LP_RESUME   ///< the master as the last call (or the dive) left it
} sva_flow_lp_mode_t;

/// Column generation on the route master at coverage `covered`, starting from the
/// routes of *plan (the incumbent), until no route prices out or the work reaches
/// `budget`. On success fills w->lagrange.price and *mu (1/SVA_FLOW_PRICE_SCALE cells)
/// and returns true; false, prices untouched, when the master exceeds
/// SVA_FLOW_LP_ROWS, a need lcm of 64, route costs of 2^24, or a number guard.
/// SVA_FLOW_LP_COVER: the master of "cover `covered` targets" without costs, whose
/// prices (mu = S) are for the coverage phase. SVA_FLOW_LP_RESUME: no new master
/// (`covered` unused), the last one solved again from its basis.
bool sva_flow_lp_prices(sva_flow_work_t* w, const sva_mission_t* m, const sva_plan_t* plan,
                        int64_t covered, sva_flow_lp_mode_t mode, uint64_t budget, int64_t* mu);

/// A dive on the route master as sva_flow_lp_prices last left it (cost master, after a
/// true return): the route with the largest value is fixed (as many UAVs as its whole
/// part, at least one; a fraction's deficit enters the basis at cost M, as does the
/// unserved part of a target now partly served), column generation again, and so on
/// until no route is left in the master's solution or the work reaches `budget`. The
/// fixed routes go to *plan's routes and priv->target_served, for the caller's
/// sva_flow_repair to complete and offer. False if nothing was fixed.
bool sva_flow_lp_dive(sva_planner_priv_t* priv, const sva_mission_t* m, sva_plan_t* plan,
                      uint64_t budget);

// pipeline.c, ga.c, bfa.c, flow.c: the algorithms.
sva_status_t sva_run_pipeline(sva_planner_t* self, const sva_mission_t* mission,
                              sva_algorithm_t algorithm, sva_plan_t* plan);
void sva_run_ga(sva_planner_priv_t* priv, const sva_mission_t* mission, sva_plan_t* plan);
sva_status_t sva_run_bfa(sva_planner_priv_t* priv, const sva_mission_t* mission,
                         sva_plan_t* plan, sva_diag_t* diag);
sva_status_t sva_run_flow(sva_planner_t* self, const sva_mission_t* mission, sva_plan_t* plan);

#endif  // SVA_INTERNAL_H
