// flow.h -- private interfaces of the flow planner (core/src/flow/): its graph, the
// relaxation, the incumbent and the repair, the Lagrangian bound and the route master.
// Builds on the model; flow.c alone also seeds from the paper's algorithms
// (DESIGN.md section 9).
#ifndef SVA_FLOW_H
#define SVA_FLOW_H

#include "../model/model.h"

// flow: node ids and heap positions are uint16 (0xFFFF is "none"); pred codes int32.
SVA_STATIC_ASSERT(SVA_FLOW_NODES < 65535L, flow_nodes_fit_uint16);
SVA_STATIC_ASSERT(SVA_FLOW_MAX_ARCS <= (2147483647L / 2L) - SVA_FLOW_MAX_COPIES, flow_pred_fits);
// arc_ban counts levels: at most 3 bans of one arc per level.
SVA_STATIC_ASSERT(3L * SVA_FLOW_MAX_DEPTH <= 255L, flow_ban_levels_fit_uint8);

// flow_graph.c: the graph.
/// Builds the graph (pooled: one copy per target carrying its need, for the root
/// relaxation alone; needs up to UINT8_MAX); SVA_FLOW_COMPLETE, or SVA_FLOW_OVER_COPIES /
/// SVA_FLOW_OVER_ARCS.
sva_flow_incomplete_t sva_flow_build(sva_planner_priv_t* priv, const sva_mission_t* m,
                                     const sva_plan_t* plan, bool pooled, sva_stats_t* stats);
int32_t sva_flow_arc_cost(const sva_flow_work_t* w, uint32_t arc);
/// Whether one UAV can serve targets a and b (mission indices), a first: a's end plus the
/// flight from a to b is at most b's start.
bool sva_flow_targets_chain(const sva_mission_t* m, uint16_t a, uint16_t b);

// flow_ssp.c: the relaxation (successive shortest paths).
/// Min-cost flow under the current branching rules; false if no flow meets them.
bool sva_flow_solve(sva_flow_work_t* w, sva_stats_t* stats);
bool sva_flow_covered(const sva_flow_work_t* w, uint16_t copy);
/// The copies UAV u visits in the current flow, in order; returns how many (<= cap).
uint16_t sva_flow_route(const sva_flow_work_t* w, uint16_t u, uint16_t* out, uint16_t cap);

// flow_incumbent.c: plans, and the best one found so far.
/// An incumbent's route ends here (its links are copies of the graph).
#define SVA_FLOW_ROUTE_END 0xFFFFU
/// Whether UAV u can fly a route of `targets` targets and `cells` cells: its fuel
/// (hovering included) and SVA_MAX_ROUTE_TARGETS.
bool sva_flow_fits(const sva_mission_t* m, uint16_t u, int64_t cells, uint32_t targets);
bool sva_flow_route_fits(const sva_mission_t* m, uint16_t u, const uint16_t* copies, uint16_t n,
                         const sva_flow_work_t* w);
/// The value of *plan (routes + priv->target_served) the incumbent is compared by: its
/// cells less the rewards of the targets it covers.
int64_t sva_flow_plan_value(const sva_planner_priv_t* priv, const sva_mission_t* m,
                            const sva_plan_t* plan);
/// The targets priv->target_served shows covered (each served by its need of UAVs).
uint16_t sva_flow_covered_now(const sva_planner_priv_t* priv, const sva_mission_t* m);
/// Keeps the plan in *plan (routes + priv->target_served) if it beats the incumbent
/// (offering it to sva_flow_offer_standing first).
bool sva_flow_offer_plan(sva_planner_priv_t* priv, const sva_mission_t* m, const sva_plan_t* plan);
/// With a standing plan (w->standing, set only while change_penalty > 0): keeps the
/// plan in *plan (routes + priv->target_served) in pen_first/pen_next if it covers more
/// targets than the one kept there, or as many at a smaller cost + change_penalty *
/// changed visits against the standing plan. Nothing otherwise.
void sva_flow_offer_standing(sva_planner_priv_t* priv, const sva_mission_t* m,
                             const sva_plan_t* plan);
/// The plan sva_flow_offer_standing kept into *plan and priv->target_served; false,
/// nothing written, when there is no standing plan or no such plan.
bool sva_flow_write_standing_pick(sva_planner_priv_t* priv, const sva_mission_t* m,
                                  sva_plan_t* plan);
/// Gives UAVs in the same state (position, fuel, ready time) the incumbent's routes in
/// id order: the route whose targets come first in window order to the lowest id, empty
/// routes to the highest. The same plan whatever order the mission lists them in.
void sva_flow_canonical_incumbent(sva_planner_priv_t* priv, const sva_mission_t* m);
void sva_flow_write_incumbent(sva_planner_priv_t* priv, const sva_mission_t* m, sva_plan_t* plan);
#if SVA_FLOW_GRANULAR
/// Ruin and recreate's current plan (w->cur_first, w->cur_next, w->cur_value): the plan
/// in *plan becomes it, with its value; or it is written into *plan.
void sva_flow_keep_current(sva_planner_priv_t* priv, const sva_mission_t* m, const sva_plan_t* plan,
                           int64_t value);
void sva_flow_write_current(sva_planner_priv_t* priv, const sva_mission_t* m, sva_plan_t* plan);
#endif
/// The incumbent written into *plan, with its cost in cells and the targets it covers.
void sva_flow_incumbent(sva_planner_priv_t* priv, const sva_mission_t* m, sva_plan_t* plan,
                        int64_t* cost, int64_t* covered);

// flow_insert.c: edits of the plan under construction in *plan (its routes,
// priv->target_served, priv->flow.route_cells).
/// Where route r of UAV u is after its first p targets: position and free time
/// (inline: the granular search's quick tests call it for every cut they try).
static inline void sva_flow_leg_ends(const sva_mission_t* m, uint16_t u, const sva_route_t* r,
                                     uint16_t p, int32_t* x, int32_t* y, int64_t* free_at)
{
    if (p == 0U) {
        *x = m->uavs[u].x;
        *y = m->uavs[u].y;
        *free_at = m->uavs[u].ready_at_ticks;
    } else {
        const sva_target_t* t = &m->targets[r->targets[p - 1U]];
        *x = t->x;
        *y = t->y;
        *free_at = t->end_ticks;
    }
}
/// Takes target t out of every route (and its route_cells).
void sva_flow_remove_target(sva_planner_priv_t* priv, const sva_mission_t* m, sva_plan_t* plan,
                            uint16_t t);
/// Cells saved by taking the k-th target out of route u.
int64_t sva_flow_stop_saving(const sva_mission_t* m, uint16_t u, const sva_route_t* r, uint16_t k);
/// Position of the target whose removal shortens route u most (first on ties).
uint16_t sva_flow_costliest_stop(const sva_mission_t* m, uint16_t u, const sva_route_t* r);
/// Whether a UAV free at free_at in (x, y) reaches target tg by its start.
bool sva_flow_arrives_in_time(const sva_mission_t* m, int64_t free_at, int32_t x, int32_t y,
                              const sva_target_t* tg);
/// Whether target t fits route u's k-th slot in time in place of its target there, and
/// in *delta how many cells longer the route gets with t in that slot.
bool sva_flow_slot_delta(const sva_mission_t* m, uint16_t u, const sva_route_t* r, uint16_t k,
                         const sva_target_t* t, int64_t* delta);
/// Cheapest feasible place for t in route u: sets insert_delta/insert_pos, or false.
bool sva_flow_best_place(sva_flow_work_t* w, const sva_mission_t* m, const sva_plan_t* plan,
                         uint16_t u, uint16_t t);
/// Serves t with its `need` cheapest UAVs, if that many can take it.
void sva_flow_try_insert(sva_planner_priv_t* priv, const sva_mission_t* m, sva_plan_t* plan,
                         uint16_t t);
/// Serves the visits a large mission's round took out (w->ruined), in the order drawn
/// for the round, as far as they fit; then none are left for the next repair.
#if SVA_FLOW_GRANULAR
void sva_flow_insert_ruined(sva_planner_priv_t* priv, const sva_mission_t* m, sva_plan_t* plan);
#else
static inline void sva_flow_insert_ruined(sva_planner_priv_t* priv, const sva_mission_t* m,
                                          sva_plan_t* plan)
{
    (void)priv;
    (void)m;
    (void)plan;
}
#endif
/// Puts t into route r of UAV u at the place sva_flow_best_place found.
void sva_flow_insert_at(sva_flow_work_t* w, sva_route_t* r, uint16_t u, uint16_t t);
/// Takes the k-th target out of route r of UAV u.
void sva_flow_remove_at(const sva_mission_t* m, sva_flow_work_t* w, sva_route_t* r, uint16_t u,
                        uint16_t k);
/// Ejection: uncovered single-UAV target t takes the place of a single-UAV target that
/// moves to another UAV. Covers one more target (true) or changes nothing.
bool sva_flow_eject_for(sva_planner_priv_t* priv, const sva_mission_t* m, sva_plan_t* plan,
                        uint16_t t);

// flow_round.c, flow_repair.c: rounding, and the repair (with the local search).
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
/// beats the incumbent (or, with `polish`, comes within reach: below), and offers it.
void sva_flow_repair(sva_planner_priv_t* priv, const sva_mission_t* m, sva_plan_t* plan,
                     bool polish);
/// The repair's local search: at most SVA_FLOW_LOCAL_PASSES passes, and (with `polish`)
/// only for a plan at most 1/SVA_FLOW_LOCAL_REACH of its routes' cells worse than the
/// incumbent; in a large mission's shallow string rounds (w->local_shallow, flow_ruin.c)
/// one pass, within 1/SVA_FLOW_SHALLOW_REACH.
#define SVA_FLOW_LOCAL_PASSES  8U
#define SVA_FLOW_LOCAL_REACH   16
#define SVA_FLOW_SHALLOW_REACH 32
static inline uint32_t sva_flow_local_passes(const sva_flow_work_t* w)
{
#if SVA_FLOW_GRANULAR
    return w->local_shallow ? 1U : SVA_FLOW_LOCAL_PASSES;
#else
    (void)w;
    return SVA_FLOW_LOCAL_PASSES;
#endif
}

static inline int64_t sva_flow_local_reach(const sva_flow_work_t* w)
{
#if SVA_FLOW_GRANULAR
    return w->local_shallow ? SVA_FLOW_SHALLOW_REACH : SVA_FLOW_LOCAL_REACH;
#else
    (void)w;
    return SVA_FLOW_LOCAL_REACH;
#endif
}

// flow_ruin.c: ruin and recreate.
/// Ruin and recreate: groups of related visits taken out of the incumbent (a large
/// mission's: strings of visits out of the current plan, until the work runs out), then
/// swaps (one covered target out, one uncovered in first); the repair completes and
/// offers each plan. With three quarters of the work left before `end` (a large
/// mission's rounds, with no target uncovered for the swaps: all of it), unless the
/// incumbent is within 1/SVA_FLOW_CLOSE of `proven_bound`, a bound with its coverage
/// proven the most (-1: none). A large mission's rounds end with the full local search
/// from the incumbent, again while it betters it. Leaves the incumbent in *plan.
/// Returns true, doing nothing, when the bound reaches the incumbent's cost: it is
/// proven optimal.
bool sva_flow_ruin_recreate(sva_planner_priv_t* priv, const sva_mission_t* m, sva_plan_t* plan,
                            uint64_t end, int64_t proven_bound);
#if SVA_FLOW_GRANULAR
/// Rounds of ruin and recreate with threshold accepting, from the incumbent, until
/// `end`: passes over the covered targets as seeds, group sizes 4, 7, 2, 9, 5, 12, 3, 6
/// in turn, each round charged as a small mission's. Nothing when `proven_bound` (as
/// above) reaches the incumbent's cost or the incumbent covers no target. Leaves the
/// incumbent, never worse, in *plan.
void sva_flow_ruin_accepting(sva_planner_priv_t* priv, const sva_mission_t* m, sva_plan_t* plan,
                             uint64_t end, int64_t proven_bound);
/// A large mission's rounds' preparation (each target's related targets,
/// the draws' first state), and their ruin of the plan in *plan (with
/// priv->target_served): strings of consecutive visits, one per route at most, through
/// s and its related targets, left in w->ruined in the order drawn for the round.
void sva_flow_ruin_prepare(sva_flow_work_t* w, const sva_mission_t* m);
void sva_flow_ruin_strings(sva_planner_priv_t* priv, const sva_mission_t* m, sva_plan_t* plan,
                           uint16_t s);
/// flow_granular.c: the granular moves' quick tests, exact where they say no (time
/// checked, fuel not). Whether target t fits some place of route u that
/// sva_flow_best_place tries for fewer than `saving` more cells.
bool sva_flow_place_may_save(const sva_mission_t* m, const sva_plan_t* plan, uint16_t u, uint16_t t,
                             int64_t saving);
/// Whether the tail exchange of routes a and b at cut (i, j) (a keeps its first i
/// targets and takes b's from j on, b the other way round; the routes' pieces in their
/// index, w->lead_of and w->post_of, flow_repair.c) meets time at both joints and flies
/// fewer than `before` cells. Fuel, route length and repeated targets are left to the
/// exchange itself.
bool sva_flow_cut_may_save(const sva_flow_work_t* w, const sva_mission_t* m, const sva_plan_t* plan,
                           uint16_t a, uint16_t b, uint16_t i, uint16_t j, int64_t before);
/// String rounds measured before they may turn shallow.
#    define SVA_FLOW_SHALLOW_PROBE 8U
/// Whether a large mission's string rounds, `done` so far on `used` work, would at that
/// rate spend the `left` work before one round per target: then the rest are shallow
/// (w->local_shallow; sva_flow_local_passes). Never before SVA_FLOW_SHALLOW_PROBE rounds.
static inline bool sva_flow_rounds_fall_short(uint32_t done, uint64_t used, uint64_t left,
                                              uint16_t targets)
{
    if (done < SVA_FLOW_SHALLOW_PROBE) {
        return false;
    }
    const uint64_t each = (used / done) + 1U;  // work per round, never 0
    return ((uint64_t)done + (left / each)) < (uint64_t)targets;
}
#endif

// flow_label.c: a UAV's best route under target prices.
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
/// With w->lagrange.real_paths (a large mission's heuristic sets it) a full label set
/// keeps the cheaper of two labels instead of merging them, so the route is within fuel
/// but not always the best: no bound.
int64_t sva_flow_best_route(sva_flow_work_t* w, const sva_mission_t* m, uint16_t u, int64_t alpha);

// flow_lagrange.c: flow's Lagrangian bound and heuristic.
/// Subgradient phases until the work reaches `budget`: improves the incumbent, and
/// returns a lower bound on the cost of every plan covering at least as many targets
/// as the incumbent (0 when it has none); *coverage_proven: no plan covers more (true
/// on entry: known already, and not sought again). Once the bound reaches the plan's
/// cost, the proof of its coverage, which would end the planning, may go on to
/// w->proof_end when that is later than `budget`. *iters gets the subgradient steps taken.
int64_t sva_flow_lagrange(sva_planner_priv_t* priv, const sva_mission_t* m, sva_plan_t* plan,
                          uint64_t budget, bool* coverage_proven, uint32_t* iters);

#if SVA_FLOW_LP_ROWS >= 2
/// Whether the coverage master (its Lagrangian at the duals of "cover c + 1 targets",
/// costs left out) proves that no plan covers more than the incumbent's c targets,
/// within the work `budget`; true at once when every target is covered.
bool sva_flow_cover_proof(sva_planner_priv_t* priv, const sva_mission_t* m, sva_plan_t* plan,
                          uint64_t budget);
/// Labels kept per target by the last shortest path (more than SVA_FLOW_LABELS with
/// cells at no cost: flow_label.c).
static inline uint32_t sva_flow_label_stride(const sva_flow_lagrange_t* lg)
{
    return lg->labels;
}
#else
static inline bool sva_flow_cover_proof(sva_planner_priv_t* priv, const sva_mission_t* m,
                                        sva_plan_t* plan, uint64_t budget)
{
    (void)priv;
    (void)m;
    (void)plan;
    (void)budget;
    return false;  // no route master: no proof
}
static inline uint32_t sva_flow_label_stride(const sva_flow_lagrange_t* lg)
{
    (void)lg;
    return (uint32_t)SVA_FLOW_LABELS;
}
#endif

// flow_lp.c, flow_simplex.c, flow_dive.c: the route master (its layout: flow_master.h).
typedef enum {
    SVA_FLOW_LP_COST,   ///< a new cost master
    SVA_FLOW_LP_COVER,  ///< a new cover master (costs left out)
    SVA_FLOW_LP_RESUME  ///< the master as the last call (or the dive) left it
} sva_flow_lp_mode_t;

/// Column generation on the route master at coverage `covered`, starting from the
/// routes of *plan (the incumbent), until no route prices out or the work reaches
/// `budget`. On success fills w->lagrange.price and *mu (1/SVA_FLOW_PRICE_SCALE cells)
/// and returns true; false, prices untouched, when the master exceeds
/// SVA_FLOW_LP_ROWS, a need lcm of 64, route costs of 2^24, or a number guard.
/// SVA_FLOW_LP_COVER: the master of "cover `covered` targets" without costs, whose
/// prices (mu = S) are for the coverage phase. SVA_FLOW_LP_RESUME: no new master
/// (`covered` unused), the last one solved again from its basis.
#if SVA_FLOW_LP_ROWS >= 2
bool sva_flow_lp_prices(sva_flow_work_t* w, const sva_mission_t* m, const sva_plan_t* plan,
                        int64_t covered, sva_flow_lp_mode_t mode, uint64_t budget, int64_t* mu);
#else
// SVA_FLOW_LP_ROWS 1 (a profile with little RAM): no master, so no prices and no dive,
// inline here so that their callers' code for them compiles away.
static inline bool sva_flow_lp_prices(sva_flow_work_t* w, const sva_mission_t* m,
                                      const sva_plan_t* plan, int64_t covered,
                                      sva_flow_lp_mode_t mode, uint64_t budget, int64_t* mu)
{
    (void)w;
    (void)m;
    (void)plan;
    (void)covered;
    (void)mode;
    (void)budget;
    (void)mu;
    return false;
}
#endif

/// flow_dive.c: a dive on the route master as sva_flow_lp_prices last left it (cost master, after a
/// true return): the route with the largest value is fixed (as many UAVs as its whole
/// part, at least one; a fraction's deficit enters the basis at cost M, as does the
/// unserved part of a target now partly served), column generation again, and so on
/// until no route is left in the master's solution or the work reaches `budget`. The
/// fixed routes go to *plan's routes and priv->target_served, for the caller's
/// sva_flow_repair to complete and offer. False if nothing was fixed.
#if SVA_FLOW_LP_ROWS >= 2
bool sva_flow_lp_dive(sva_planner_priv_t* priv, const sva_mission_t* m, sva_plan_t* plan,
                      uint64_t budget);
#else
static inline bool sva_flow_lp_dive(sva_planner_priv_t* priv, const sva_mission_t* m,
                                    sva_plan_t* plan, uint64_t budget)
{
    (void)priv;
    (void)m;
    (void)plan;
    (void)budget;
    return false;
}
#endif

#if SVA_FLOW_ENUM_ROUTES > 0
/// flow_enum.c: keeps w->lagrange.price, the cost master's prices, when `taken` (else
/// forgets any kept before), for sva_flow_enum_prove.
void sva_flow_enum_prices(sva_flow_work_t* w, const sva_mission_t* m, bool taken);

/// flow_enum.c: with the prices kept and an incumbent of this cost covering `covered`
/// targets (need 1, at most 64 targets), every route a cheaper plan covering as many or
/// more could fly, then a cover of the targets by them; the cheapest cover found is
/// offered as the incumbent. True when no plan covering `covered` targets or more costs
/// less than the incumbent then (its cost is a bound); false (no claim) without prices,
/// past its bounds, when a cover found covers more, when the routes outgrow
/// SVA_FLOW_ENUM_ROUTES or when the work reaches `end`.
bool sva_flow_enum_prove(sva_planner_priv_t* priv, const sva_mission_t* m, sva_plan_t* plan,
                         int64_t cost, int64_t covered, uint64_t end);

/// flow_enum.c: with w->lagrange.price the coverage master's prices (a covered target
/// worth SVA_FLOW_PRICE_SCALE), whether a plan covers more than `covered` targets (need
/// 1, at most 64 targets): true when none does. False when it finds one (offered as the
/// incumbent; *more), and (no claim) past its bounds, when the routes outgrow
/// SVA_FLOW_ENUM_ROUTES or when the work reaches `end`.
bool sva_flow_enum_cover(sva_planner_priv_t* priv, const sva_mission_t* m, sva_plan_t* plan,
                         int64_t covered, uint64_t end, bool* more);
#endif

// flow_cover.c: the coverage search.// flow_cover.c: the coverage search.
typedef enum {
    SVA_FLOW_COVER_OPEN,   ///< neither: the budget ran out, or the mission is past its bounds
    SVA_FLOW_COVER_FOUND,  ///< a plan covering more is in *plan
    SVA_FLOW_COVER_PROVEN  ///< no plan covers more
} sva_flow_cover_result_t;

#if SVA_FLOW_COVER_TARGETS > 0
/// Depth-first search for a plan covering more than `covered` targets, until the work
/// reaches `budget` (missions of at most SVA_FLOW_COVER_TARGETS targets and
/// SVA_FLOW_COVER_UAVS UAVs not stranded). FOUND: its routes are in *plan and
/// priv->target_served, for the caller's sva_flow_repair. Adds its nodes to *nodes
/// (saturating).
sva_flow_cover_result_t sva_flow_cover(sva_planner_priv_t* priv, const sva_mission_t* m,
                                       sva_plan_t* plan, int64_t covered, uint64_t budget,
                                       uint16_t* nodes);
/// The same search over neighbourhoods of the incumbent in *plan (with
/// priv->target_served): `size` of its UAVs not stranded set free, every such set in
/// turn, the others' routes kept, until a plan covers more than `covered` targets or the
/// work reaches `budget`. FOUND as sva_flow_cover's; otherwise OPEN (it proves nothing).
sva_flow_cover_result_t sva_flow_cover_around(sva_planner_priv_t* priv, const sva_mission_t* m,
                                              sva_plan_t* plan, int64_t covered, uint16_t size,
                                              uint64_t budget, uint16_t* nodes);
#endif
/// The coverage search for one target more than the incumbent covers, again after each
/// plan it finds (repaired and offered: it covers more, so it becomes the incumbent),
/// within `work` units (incumbent_first: a third in the search's own order, a third on
/// neighbourhoods of need + 1 UAVs, the last with the targets the incumbent leaves left
/// first); returns the work it spent.
/// *proven: it proved the incumbent's coverage the most. Off (nothing spent, nothing
/// proven) when SVA_FLOW_COVER_TARGETS is 0.
uint64_t sva_flow_cover_incumbent(sva_planner_priv_t* priv, const sva_mission_t* m,
                                  sva_plan_t* plan, uint64_t work, bool incumbent_first,
                                  bool* proven);

// flow_cover_chains.c: the coverage search's chain bound.
#if SVA_FLOW_COVER_TARGETS > 0
/// The most targets from depth d on (window order) that k chains of the order "a UAV
/// can serve a, then b" hold, k at most SVA_FLOW_COVER_UAVS (each depth computed once
/// per plan as far as the chains asked for, its work added to *work).
uint16_t sva_flow_cover_chains(sva_flow_chains_t* s, const sva_planner_priv_t* priv,
                               const sva_mission_t* m, uint16_t d, uint16_t k, uint64_t* work);
/// Forgets the chain bound's rows: a plan's mission is new (sva_run_flow, and whoever
/// searches a mission after another with the same planner, calls it first).
void sva_flow_cover_chains_forget(sva_planner_priv_t* priv);
#endif

// flow_standing.c: the standing plan (sva_replan()'s; SVA_FLOW_STANDING).
/// Whether `standing` is a plan of the mission (*plan fresh from sva_state_reset): a
/// replan, which starts from it. Sets w->standing to it when it is and the mission has
/// a change_penalty, else NULL; no plan kept yet.
bool sva_flow_standing_begin(sva_planner_priv_t* priv, const sva_mission_t* m,
                             const sva_plan_t* plan, const sva_plan_t* standing);
/// `standing` (NULL: none) repaired (sva_flow_repair) and offered, from and back to a
/// reset state, stats kept.
void sva_flow_seed_standing(sva_planner_priv_t* priv, const sva_mission_t* m, sva_plan_t* plan,
                            const sva_plan_t* standing);
/// With a standing plan: the plan best against it into *plan (over the incumbent
/// finish wrote), `optimal` kept only if it costs the incumbent's cost, lower_bound at
/// most its cost.
void sva_flow_standing_finish(sva_planner_priv_t* priv, const sva_mission_t* m, sva_plan_t* plan);

// flow.c: the algorithm.
sva_status_t sva_run_flow(sva_planner_t* self, const sva_mission_t* mission,
                          const sva_plan_t* standing, sva_plan_t* plan);

/// The incumbent's cost and a lower bound on any plan's cost with as many targets (from
/// `open`, the least value of the nodes left open, and the Lagrangian bound); true when
/// no plan covers more targets (or coverage_known). priv->target_served must be the
/// incumbent's.
bool sva_flow_cost_bound(const sva_planner_priv_t* priv, const sva_mission_t* m, int64_t open,
                         int64_t lagrange_bound, bool coverage_known, int64_t* cost,
                         int64_t* bound);

/// One local search may start with half the budget, and the Lagrangian phase ends at
/// three quarters of it (a large mission's shares are flow_large.c's).
static inline uint64_t sva_flow_small_local_work(uint64_t budget)
{
    return budget / 2U;
}

static inline uint64_t sva_flow_small_lagrange_end(uint64_t start, uint64_t budget)
{
    return start + (budget - (budget / 4U));
}

#if SVA_FLOW_LARGE
/// flow_large.c: the work budget of mission m given the planner's (scaled when m is
/// large), one local search's work, and where the Lagrangian phase's work ends (the
/// search's share started at start, the phase starts at now).
uint64_t sva_flow_budget(const sva_mission_t* m, uint64_t budget);
uint64_t sva_flow_local_work(const sva_mission_t* m, uint64_t budget);
uint64_t sva_flow_lagrange_end(const sva_mission_t* m, uint64_t start, uint64_t now,
                               uint64_t budget);
/// Where ruin and recreate's work ends, given the end of the phases' shares: a large
/// mission's gets at least half the budget from now (its root relaxation, seeds and
/// Lagrangian phase can outgrow their shares).
uint64_t sva_flow_ruin_end(const sva_mission_t* m, uint64_t end, uint64_t now, uint64_t budget);

/// The incumbent written into *plan, and a bound on its cost that ruin and recreate may
/// trust: sva_flow_cost_bound's when the coverage is proven and the rewards exact, else -1.
/// The two bounds come first, in registers: the caller is on flow's deepest stack path.
int64_t sva_flow_known_bound(int64_t open, int64_t lagrange_bound, sva_planner_priv_t* priv,
                             const sva_mission_t* m, sva_plan_t* plan, bool coverage_known);
/// Whether the Lagrangian heuristic may fly the UAVs (flow_lagrange.c): always, except
/// that a large mission's flight must fit the plan's whole budget (w->budget), as
/// predicted from the last evaluation's work. A large mission's flight asks for real
/// paths (w->lagrange.real_paths, which the flight clears when it lands).
bool sva_flow_flight_begins(sva_flow_work_t* w, const sva_mission_t* m);
/// Whether the search's bound (open, no Lagrangian yet) proves the incumbent's coverage
/// and its cost within 1/SVA_FLOW_CLOSE; the incumbent is written into *plan. (Before the
/// Lagrangian phase only the search proves a large mission's coverage: the coverage
/// search stops at SVA_FLOW_COVER_TARGETS, at most 64.)
bool sva_flow_near_bound(int64_t open, sva_planner_priv_t* priv, const sva_mission_t* m,
                         sva_plan_t* plan);
#else
// No mission can be large in this profile: the small missions' rules.
static inline uint64_t sva_flow_budget(const sva_mission_t* m, uint64_t budget)
{
    (void)m;
    return budget;
}

static inline uint64_t sva_flow_local_work(const sva_mission_t* m, uint64_t budget)
{
    (void)m;
    return sva_flow_small_local_work(budget);
}

static inline bool sva_flow_flight_begins(sva_flow_work_t* w, const sva_mission_t* m)
{
    (void)w;
    (void)m;
    return true;
}

static inline uint64_t sva_flow_lagrange_end(const sva_mission_t* m, uint64_t start, uint64_t now,
                                             uint64_t budget)
{
    (void)m;
    (void)now;
    return sva_flow_small_lagrange_end(start, budget);
}

static inline uint64_t sva_flow_ruin_end(const sva_mission_t* m, uint64_t end, uint64_t now,
                                         uint64_t budget)
{
    (void)m;
    (void)now;
    (void)budget;
    return end;
}
#endif

/// A plan within cost / SVA_FLOW_CLOSE of a proven bound is close enough that neither
/// ruin and recreate nor a large mission's Lagrangian phase works on it.
#define SVA_FLOW_CLOSE 64

/// Whether some target is served by no UAV (priv->target_served).
static inline bool sva_flow_uncovered_left(const sva_planner_priv_t* priv, const sva_mission_t* m)
{
    bool left = false;
    for (uint16_t t = 0U; (t < m->target_count) && !left; t++) {
        left = priv->target_served[t] == 0U;
    }
    return left;
}

#if SVA_FLOW_LP_ROWS >= 2
/// Empties every route of *plan and priv->target_served, for routes written anew (the
/// master's dive, the route enumeration's cover). O(T + U).
void sva_flow_clear_routes(sva_planner_priv_t* priv, const sva_mission_t* m, sva_plan_t* plan);

/// The first UAV that is not stranded, whose route in *plan is still empty and whose
/// state key state[v] (w->lagrange.group, or the master's group_row) is `want`;
/// m->uav_count when none is left. O(U).
uint16_t sva_flow_idle_uav(const sva_mission_t* m, const sva_plan_t* plan, const uint16_t* state,
                           uint16_t want);
#endif

/// The least number at least `bound` that a plan's cost can be. A route's length has
/// the parity of its UAV's distance home (a closed walk on the grid is even), and a UAV
/// that is not stranded flies home even with no target (SPEC section 1), so all plans of
/// a mission cost the same modulo 2 (w->cost_parity, flow_graph.c). `bound` < INT64_MAX.
/// O(1).
int64_t sva_flow_cost_floor(const sva_flow_work_t* w, int64_t bound);

/// Whether a plan of this cost is that close to `bound` (negative: none proven).
static inline bool sva_flow_close(int64_t cost, int64_t bound)
{
    return (bound >= 0) && ((cost - bound) <= (cost / SVA_FLOW_CLOSE));
}

/// Whether the mission is large for flow (more than SVA_FLOW_LARGE_FROM targets).
static inline bool sva_flow_large(const sva_mission_t* m)
{
#if SVA_FLOW_LARGE
    return m->target_count > (uint16_t)SVA_FLOW_LARGE_FROM;
#else
    (void)m;
    return false;
#endif
}

/// Notes that route u (r) changed at its k-th place, for the granular local search
/// (nothing without it): the route, and the visits now at places k - 1 to k + 1, the
/// ones whose neighbours the edit may have changed, are to be looked at again.
static inline void sva_flow_changed(sva_flow_work_t* w, uint16_t u, const sva_route_t* r,
                                    uint16_t k)
{
#if SVA_FLOW_GRANULAR
    w->route_changed[u] = 1U;
    const uint16_t first = (k > 0U) ? (uint16_t)(k - 1U) : 0U;
    for (uint16_t i = first; (i <= (k + 1U)) && (i < r->target_count); i++) {
        w->visit_awake[r->targets[i]] = 1U;
    }
#else
    (void)w;
    (void)u;
    (void)r;
    (void)k;
#endif
}

#endif  // SVA_FLOW_H
