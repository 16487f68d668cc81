// flow.c -- the `flow` planner: a min-cost flow relaxation inside a depth-first
// branch and bound, with a certified lower bound (DESIGN.md section 8).
//
// Objective: cost - W * covered, with W above any flow's cost (flow_graph.c), which
// orders plans exactly as SPEC section 1 does. Without fuel the relaxation (flow_ssp.c)
// is the problem itself once every target is covered by all or none of its copies.
// Two rules can fail in a relaxation, and each has its branching:
//   a target half covered      -> child 1: all its copies forced; child 2: banned;
//   a route over fuel/length   -> partition over where the UAV first leaves it: child
//       i keeps the route's first i arcs for this UAV and bans its step i+1 (to any
//       copy of that target: copies are interchangeable). Every copy carries one
//       unit, so the kept arcs are this UAV's, and a banned arc out of a kept copy
//       concerns no one else. Children whose kept prefix already breaks the
//       fuel rule are skipped, as is the one keeping the whole route: adding targets
//       never shortens a route (triangle inequality).
// Every node's relaxation is rounded into a plan (flow_round.c, flow_repair.c); the plans of `ga`
// and `sva` are the first incumbents, so flow never plans worse than either (a
// replan's standing plan, repaired, comes before them: flow_standing.c). The search
// gets a sixteenth of the work budget (SVA_FLOW_MAX_WORK units, deterministic; a
// replan has its own, flow_replan_work, and gives the search half);
// if it does not finish, the Lagrangian phase (flow_lagrange.c) improves the bound
// and the plan, ruin and recreate (flow_ruin.c) improves the plan, and the search
// runs again on what is left (not in a plan with a need above 1). The bound comes
// from the nodes left open and from the Lagrangian phase. With a need above 1 the
// pooled graph (one node per target) is solved first: its routes are taken when
// they are a plan, and past SVA_FLOW_MAX_ARCS it gives the bound and the first plan.
// No recursion: the path is an explicit stack of frames.
#include "flow.h"
#include "../paper/paper.h"

#define BRANCH_TARGET 1U
#define BRANCH_ROUTE  2U
// The first search's share of the budget: 1/16, and 1/2 in a replan, whose incumbent
// (the standing plan repaired) is good from the start.
#define SEARCH_SHARE        16U
#define REPLAN_SEARCH_SHARE 2U
// The coverage search's share, after the first search when that does not finish: a
// sixteenth, and a quarter in a replan, whose residual missions (UAVs scattered, fuel
// spent) are where the other phases stay a target short. With a target of need 2 or
// more, a plan (not a replan) runs the search again at the end with half the budget: the
// plan covering one more target pairs the UAVs anew, and the search's bound (pooled over
// needs) prunes little there, so finding it takes many nodes. At the end, what comes
// before is as it was, so the plan covers at least as many targets.
#define COVER_SHARE        16U
#define REPLAN_COVER_SHARE 4U
#define SYNC_COVER_SHARE   2U
// With a target of need 2 or more, a plan does not run the search again; it ends with
// rounds of ruin and recreate that accept a slightly dearer plan on the way
// (flow_ruin.c), a quarter of the budget on top (DESIGN.md section 8).
#define ACCEPTING_SHARE 4U
// With a target of need 2 or more, the coverage master's proof after ruin and recreate
// (the Lagrangian phase asks it only once the cost is proven): at most a quarter.
#define COVER_PROOF_SHARE 4U

static uint32_t find_arc(const sva_flow_work_t* w, uint16_t tail, uint16_t head)
{
    for (uint32_t e = w->out_start[tail]; e < w->out_start[tail + 1U]; e++) {
        if (w->arc_head[e] == head) {
            return e;
        }
    }
    SVA_ASSERT(false);  // the route was read off these arcs
    return w->out_start[tail];
}

static void ban(sva_flow_work_t* w, uint32_t e, int32_t delta)
{
    const int32_t level = (int32_t)w->arc_ban[e] + delta;
    w->arc_ban[e] = (uint8_t)level;
}

// delta +1 applies child i of frame f, -1 takes it back (same arcs, same order).
static void apply_child(sva_flow_work_t* w, const sva_flow_frame_t* f, int16_t i, int32_t delta)
{
    if (f->kind == (uint8_t)BRANCH_TARGET) {
        const uint16_t first = w->target_first_copy[f->subject];
        for (uint16_t c = first; (c < w->copies) && (w->copy_target[c] == f->subject); c++) {
            uint8_t* level = (i == 0) ? &w->copy_forced[c] : &w->copy_banned[c];
            const int32_t updated = (int32_t)*level + delta;
            *level = (uint8_t)updated;
        }
        return;
    }
    uint16_t tail = f->subject;
    for (int16_t j = 0; j <= i; j++) {
        const uint16_t head = (uint16_t)(w->uavs + f->path[j]);
        const uint32_t kept = find_arc(w, tail, head);
        if (j == i) {
            // Copies of one target are interchangeable: ban the step to all of them.
            const uint16_t target = w->copy_target[f->path[j]];
            for (uint32_t e = w->out_start[tail]; e < w->out_start[tail + 1U]; e++) {
                const uint16_t h = w->arc_head[e];
                if ((h >= w->uavs) && (h < (uint16_t)(w->uavs + w->copies)) &&
                    (w->copy_target[h - w->uavs] == target)) {
                    ban(w, e, delta);
                }
            }
            break;
        }
        for (uint32_t e = w->out_start[tail]; e < w->out_start[tail + 1U]; e++) {
            if (e != kept) {
                ban(w, e, delta);
            }
        }
        for (uint32_t k = w->in_start[head]; k < w->in_start[head + 1U]; k++) {
            if (w->in_arc[k] != kept) {
                ban(w, w->in_arc[k], delta);
            }
        }
        tail = (uint16_t)(w->uavs + w->copies + f->path[j]);
    }
}

// Picks the rule the current relaxation breaks and fills frame f; false if none (the
// relaxation is a plan).
static bool choose_branch(sva_planner_priv_t* priv, const sva_mission_t* m, const sva_plan_t* plan,
                          sva_flow_frame_t* f)
{
    sva_flow_work_t* w = &priv->flow;
    f->next_child = 0;
    f->active_child = -1;
    for (uint16_t i = 0U; i < m->target_count; i++) {
        const uint16_t t = priv->target_order[i];
        int32_t covered = 0;
        for (int32_t k = 0; k < m->targets[t].need; k++) {
            const int32_t copy = (int32_t)w->target_first_copy[t] + k;
            covered += sva_flow_covered(w, (uint16_t)copy) ? 1 : 0;
        }
        if ((covered > 0) && (covered < m->targets[t].need)) {
            f->kind = (uint8_t)BRANCH_TARGET;
            f->subject = t;
            f->path_len = 0U;
            f->child_count = 2U;
            return true;
        }
    }
    for (uint16_t u = 0U; u < m->uav_count; u++) {
        if (plan->routes[u].stranded) {
            continue;
        }
        const uint16_t n = sva_flow_route(w, u, f->path, SVA_FLOW_MAX_COPIES);
        if (sva_flow_route_fits(m, u, f->path, n, w)) {
            continue;
        }
        uint16_t children = 0U;
        while ((children < n) && sva_flow_route_fits(m, u, f->path, children, w)) {
            children++;
        }
        f->kind = (uint8_t)BRANCH_ROUTE;
        f->subject = u;
        f->path_len = n;
        f->child_count = children;
        return true;
    }
    return false;
}

// sva's plan into *plan (from a reset state) without the caller's observer: it is
// flow's working material, not a plan the caller asked for.
static bool run_sva_quietly(sva_planner_t* self, const sva_mission_t* m, sva_plan_t* plan)
{
    const sva_tp_observer_t observer = self->on_transport;
    self->on_transport = NULL;
    const bool ok = sva_run_pipeline(self, m, SVA_ALGO_SVA, plan) == SVA_OK;
    self->on_transport = observer;
    return ok;
}

// The plans of ga and sva as the first incumbents, then each repaired and improved
// by the local search (stats kept).
static void seed(sva_planner_t* self, const sva_mission_t* m, sva_plan_t* plan)
{
    sva_planner_priv_t* priv = &self->priv;
    const sva_stats_t kept = plan->stats;
    sva_run_ga(priv, m, plan);
    (void)sva_flow_offer_plan(priv, m, plan);
    sva_flow_repair(priv, m, plan, true);
    sva_state_reset(priv, m, plan);
    if (run_sva_quietly(self, m, plan)) {
        (void)sva_flow_offer_plan(priv, m, plan);
        sva_flow_repair(priv, m, plan, true);
    }
    sva_state_reset(priv, m, plan);
    plan->stats = kept;
}

static int64_t min64(int64_t a, int64_t b)
{
    return (a < b) ? a : b;
}

// Solves the root's relaxation (*solved: it is in the graph now). When it is a plan it
// is the optimum: it becomes the incumbent, and neither the seeds nor the search are
// needed (most missions where fuel does not bind). Only with exact rewards, where the
// search's own claim would hold.
static bool root_is_plan(sva_planner_priv_t* priv, const sva_mission_t* m, sva_plan_t* plan,
                         bool* solved)
{
    sva_flow_work_t* w = &priv->flow;
    plan->stats.search_nodes++;
    *solved = sva_flow_solve(w, &plan->stats);
    if (!*solved || !w->reward_exact || choose_branch(priv, m, plan, &w->stack[0])) {
        return false;
    }
    sva_flow_take_relaxation(priv, m, plan);
    return true;
}

// Whether the node's relaxation shows no plan under it better than the incumbent. Its
// value bounds theirs; with exact rewards (W even) every plan's value has the parity of
// its cost, which is the same for all plans (sva_flow_cost_floor), so none is worth one
// less than the incumbent and a bound one below it is enough.
static bool no_better(const sva_flow_work_t* w)
{
    return w->value >= (w->inc_value - (w->reward_exact ? 1 : 0));
}

// Depth-first search from the root relaxation (already solved and still in the graph
// when root_solved); returns the least bound left open (INT64_MAX when the search
// finished, -INT64_MAX when the budget was already spent) and sets *incomplete.
static int64_t search(sva_planner_priv_t* priv, const sva_mission_t* m, sva_plan_t* plan,
                      uint64_t budget, bool root_solved, sva_flow_incomplete_t* incomplete)
{
    sva_flow_work_t* w = &priv->flow;
    sva_stats_t* stats = &plan->stats;
    int64_t open = INT64_MAX;
    w->depth = 0U;
    if (!root_solved) {
        if (w->work >= budget) {
            *incomplete = SVA_FLOW_INCOMPLETE_WORK;
            return -INT64_MAX;  // nothing searched: no bound
        }
        stats->search_nodes++;
        if (!sva_flow_solve(w, stats)) {
            // Cannot happen: every UAV that is not stranded may fly home, and the root
            // forces nothing. Claim nothing if it does.
            SVA_ASSERT(false);
            *incomplete = SVA_FLOW_INCOMPLETE_DEPTH;
            return INT64_MIN / 4;
        }
    }
    if (no_better(w)) {
        return open;
    }
    sva_flow_round(priv, m, plan, true);  // the root's plan is worth polishing
    if (!no_better(w) && choose_branch(priv, m, plan, &w->stack[0])) {
        w->stack[0].bound = w->value;
        w->depth = 1U;
        stats->flow_max_depth = 1U;
    }
    while (w->depth > 0U) {
        sva_flow_frame_t* f = &w->stack[w->depth - 1U];
        if (f->active_child >= 0) {
            apply_child(w, f, f->active_child, -1);
            f->active_child = -1;
        }
        if (f->next_child >= (int16_t)f->child_count) {
            w->depth--;
            continue;
        }
        if (w->work > budget) {
            for (uint16_t d = 0U; d < w->depth; d++) {
                if (w->stack[d].next_child < (int16_t)w->stack[d].child_count) {
                    open = min64(open, w->stack[d].bound);
                }
            }
            *incomplete = SVA_FLOW_INCOMPLETE_WORK;
            break;
        }
        // Route frames try the longest kept prefix first: the plan that drops the
        // fewest of the route's targets is the likeliest good one.
        int16_t child = f->next_child;
        if (f->kind == (uint8_t)BRANCH_ROUTE) {
            child = (int16_t)((int32_t)f->child_count - 1 - (int32_t)f->next_child);
        }
        f->next_child++;
        apply_child(w, f, child, 1);
        f->active_child = child;
        stats->search_nodes++;
        if (!sva_flow_solve(w, stats) || no_better(w)) {
            continue;  // infeasible, or no better than the best plan
        }
        sva_flow_round(priv, m, plan, false);
        if (no_better(w)) {
            continue;  // the relaxation was a plan, or rounding reached its bound
        }
        if (w->depth >= (uint16_t)SVA_FLOW_MAX_DEPTH) {
            open = min64(open, w->value);
            *incomplete = SVA_FLOW_INCOMPLETE_DEPTH;
            continue;
        }
        if (choose_branch(priv, m, plan, &w->stack[w->depth])) {
            w->stack[w->depth].bound = w->value;
            w->depth++;
            stats->flow_max_depth =
                (w->depth > stats->flow_max_depth) ? w->depth : stats->flow_max_depth;
        }
    }
    // Stopped on the budget: take back the branching rules still applied, so the
    // graph is the root's again (the next search starts from it).
    while (w->depth > 0U) {
        const sva_flow_frame_t* f = &w->stack[w->depth - 1U];
        if (f->active_child >= 0) {
            apply_child(w, f, f->active_child, -1);
        }
        w->depth--;
    }
    return open;
}

// Past SVA_FLOW_MAX_COPIES flow has no relaxation and no copies: it returns the better
// of the ga and sva plans with the trivial bound 0, never claiming optimality. (Past
// SVA_FLOW_MAX_ARCS the seeds are also improved by the local search and by ruin and
// recreate: sva_run_flow.)
static void fall_back(sva_planner_t* self, const sva_mission_t* m, sva_plan_t* plan,
                      sva_flow_incomplete_t why)
{
    sva_planner_priv_t* priv = &self->priv;
    const sva_stats_t kept = plan->stats;
    sva_run_ga(priv, m, plan);
    sva_plan_finish(priv, m, plan);
    const uint16_t ga_covered = plan->covered;
    const int64_t ga_cost = plan->cost;
    sva_state_reset(priv, m, plan);
    bool use_ga = !run_sva_quietly(self, m, plan);
    if (!use_ga) {
        sva_plan_finish(priv, m, plan);
        use_ga = (ga_covered > plan->covered) ||
                 ((ga_covered == plan->covered) && (ga_cost < plan->cost));
    }
    if (use_ga) {
        sva_state_reset(priv, m, plan);
        sva_run_ga(priv, m, plan);
    }
    plan->stats = kept;
    plan->stats.has_bound = true;
    plan->stats.lower_bound = 0;
    plan->stats.optimal = false;
    plan->stats.coverage_proven = false;
    plan->stats.flow_incomplete = (uint8_t)why;
}

#if SVA_FLOW_COVER_TARGETS > 0
// The targets the incumbent covers.
static int64_t incumbent_covered(sva_planner_priv_t* priv, const sva_mission_t* m, sva_plan_t* plan)
{
    int64_t cost = 0;
    int64_t covered = 0;
    sva_flow_incumbent(priv, m, plan, &cost, &covered);
    return covered;
}
#endif

// A plan (not a replan) with a target of need 2 or more, its coverage unproven at the
// end of its phases: the Lagrangian phase seldom proves the cost there, and so seldom
// asks for the coverage's proof, so the coverage master is asked now, for the incumbent
// the phases left (COVER_PROOF_SHARE); then the coverage search once more, last, from
// it (SYNC_COVER_SHARE), and the master again if that search found a plan covering
// more. True when the coverage is proven the most.
static bool synchronised_coverage(sva_planner_priv_t* priv, const sva_mission_t* m,
                                  sva_plan_t* plan, uint64_t budget)
{
    sva_flow_work_t* w = &priv->flow;
    bool proven = sva_flow_cover_proof(priv, m, plan, w->work + (budget / COVER_PROOF_SHARE));
#if SVA_FLOW_COVER_TARGETS > 0
    if (!proven) {
        const int64_t before = incumbent_covered(priv, m, plan);
        (void)sva_flow_cover_incumbent(priv, m, plan, budget / SYNC_COVER_SHARE, true, &proven);
        if (!proven && (incumbent_covered(priv, m, plan) > before)) {
            proven = sva_flow_cover_proof(priv, m, plan, w->work + (budget / COVER_PROOF_SHARE));
        }
    }
#endif
    return proven;
}

#define NO_POOLED (-(INT64_MAX / 4))  // pooled_first: no pooled relaxation

// The incumbent into *plan with its stats: the lower bound and whether it is proven
// optimal. open: the least bound of the nodes left open (INT64_MAX: none), or any lower
// bound on cost - reward of every plan; lagrange_bound: a bound on the cost (0: none);
// incomplete: why the search stopped short.
static void finish(sva_planner_priv_t* priv, const sva_mission_t* m, sva_plan_t* plan, int64_t open,
                   int64_t lagrange_bound, bool coverage_known, sva_flow_incomplete_t incomplete)
{
    sva_flow_work_t* w = &priv->flow;
    sva_stats_t* stats = &plan->stats;
    sva_flow_canonical_incumbent(priv, m);
    sva_flow_write_incumbent(priv, m, plan);
    int64_t cost = 0;
    int64_t bound = 0;
    const bool coverage_proven =
        sva_flow_cost_bound(priv, m, open, lagrange_bound, coverage_known, &cost, &bound);
    stats->has_bound = true;
    stats->lower_bound = (bound > cost) ? cost : bound;
    stats->optimal =
        w->reward_exact && (((incomplete == SVA_FLOW_COMPLETE) && (open == INT64_MAX)) ||
                            (coverage_proven && (bound >= cost)));
    stats->coverage_proven = coverage_proven || stats->optimal;
    stats->flow_incomplete = stats->optimal ? (uint8_t)SVA_FLOW_COMPLETE : (uint8_t)incomplete;
    stats->flow_work = w->work;
    sva_flow_standing_finish(priv, m, plan);
}

// With a need above 1 (and none above UINT8_MAX), the pooled graph's relaxation comes
// first (about a quarter of the copies' arcs at need 2). When its flow's routes are a
// plan they carry its value: the optimum, taken as root_is_plan takes a root. Past the
// arc bound (`past`) they are otherwise repaired into the first incumbent; under it
// nothing is kept, and the mission plans as it would without this step. Returns the
// pooled value, a lower bound on cost - reward of every plan (NO_POOLED: none, when no
// need calls for it or the pooled graph does not fit either), with the graph of copies
// in place again; *proven: the incumbent reaches it.
static int64_t pooled_first(sva_planner_priv_t* priv, const sva_mission_t* m, sva_plan_t* plan,
                            bool past, bool* proven)
{
    sva_flow_work_t* w = &priv->flow;
    *proven = false;
    if ((w->need_max == 1) || (w->need_max > (int32_t)UINT8_MAX)) {
        return NO_POOLED;  // the pooled graph would be the copies' (or its units overflow)
    }
    int64_t pooled = NO_POOLED;
    bool whole = false;
    // The solve cannot fail at the root; claim nothing if it does.
    if ((sva_flow_build(priv, m, plan, true, &plan->stats) == SVA_FLOW_COMPLETE) &&
        sva_flow_solve(w, &plan->stats)) {
        pooled = w->value;
        whole = sva_flow_pooled_routes(priv, m, plan);
    }
    const sva_flow_incomplete_t over = sva_flow_build(priv, m, plan, false, &plan->stats);
    SVA_ASSERT(past ? (over == SVA_FLOW_OVER_ARCS)
                    : (over == SVA_FLOW_COMPLETE));  // as before the pooled graph
    if (pooled == NO_POOLED) {
        return pooled;
    }
    const sva_stats_t kept = plan->stats;
    if (whole && (past || w->reward_exact)) {
        (void)sva_flow_offer_plan(priv, m, plan);
    } else if (past) {
        sva_flow_repair(priv, m, plan, true);
    } else {
        // under the arc bound: no incumbent from here
    }
    plan->stats = kept;
    sva_state_reset(priv, m, plan);
    // With exact rewards no plan is worth one less than the incumbent (no_better).
    *proven = w->has_inc && w->reward_exact && (w->inc_value <= (pooled + 1));
    return pooled;
}

sva_status_t sva_run_flow(sva_planner_t* self, const sva_mission_t* m, const sva_plan_t* standing,
                          sva_plan_t* plan)
{
    sva_planner_priv_t* priv = &self->priv;
    sva_flow_work_t* w = &priv->flow;
    sva_stats_t* stats = &plan->stats;
    w->has_inc = false;
    // A replan starts from the standing plan, under its own budget.
#if SVA_FLOW_STANDING
    const bool replan = sva_flow_standing_begin(priv, m, plan, standing);
#else
    const bool replan = false;  // the standing plan is ignored
    (void)sva_flow_standing_begin(priv, m, plan, standing);
#endif
    const sva_plan_t* seed_plan = replan ? standing : NULL;
    uint64_t budget = self->flow_max_work;
    if (replan && (self->flow_replan_work < budget)) {
        budget = self->flow_replan_work;
    }
    budget = (budget < 1000U) ? 1000U : budget;
    budget = (budget > (uint64_t)SVA_FLOW_MAX_WORK) ? (uint64_t)SVA_FLOW_MAX_WORK : budget;
    budget = sva_flow_budget(m, budget);
    w->insert_backwards = false;
#if SVA_FLOW_GRANULAR
    w->local_changed_only = false;
    w->local_shallow = false;
    w->ruined_count = 0U;
#endif
    w->work = 0U;
#if SVA_FLOW_COVER_TARGETS > 0
    sva_flow_cover_chains_forget(priv);  // a new mission: the chain bound's rows again
#endif
    w->local_work = sva_flow_local_work(m, budget);
#if SVA_FLOW_LARGE
    w->budget = budget;
#endif
    stats->search_nodes = 0U;
    const sva_flow_incomplete_t over = sva_flow_build(priv, m, plan, false, stats);
    if (over == SVA_FLOW_OVER_COPIES) {
        fall_back(self, m, plan, over);
        return SVA_OK;
    }
    const bool past = over == SVA_FLOW_OVER_ARCS;
    bool pooled_proven = false;
    const int64_t pooled = pooled_first(priv, m, plan, past, &pooled_proven);
    if (past || pooled_proven) {
        // Past the arc bound, no search: unless the pooled plan is proven, the seeds go
        // through the repair and the local search, then ruin and recreate.
        sva_flow_seed_standing(priv, m, plan, seed_plan);
        if (!pooled_proven) {
            seed(self, m, plan);
            (void)sva_flow_ruin_recreate(priv, m, plan, w->work + budget, -1);
        }
        finish(priv, m, plan, pooled, 0, false, over);
        return SVA_OK;
    }
    const sva_flow_incomplete_t finished =
        w->reward_exact ? SVA_FLOW_COMPLETE : SVA_FLOW_INCOMPLETE_REWARD;
    sva_flow_incomplete_t incomplete = finished;
    int64_t open = INT64_MAX;
    int64_t lagrange_bound = 0;
    bool coverage_proven = false;
    uint64_t start = w->work;
    bool root_solved = false;
    if (!root_is_plan(priv, m, plan, &root_solved)) {
        const uint64_t root_work = w->work - start;
        // A sixteenth of the budget to the search (half in a replan); if it does not
        // finish, the Lagrangian phase (fuel-aware bound, new plans), then the search
        // again with the better incumbent. The phases' budgets count from here: seeding
        // (three local searches at most, each within w->local_work) does not eat into
        // the search.
        sva_flow_seed_standing(priv, m, plan, seed_plan);
        seed(self, m, plan);
        start = w->work - root_work;  // the root counts in the search's share, as before
        uint64_t share = SEARCH_SHARE;
        if (replan) {
            share = REPLAN_SEARCH_SHARE;
        }
        open = search(priv, m, plan, start + (budget / share), root_solved, &incomplete);
    } else {
        sva_flow_seed_standing(priv, m, plan, seed_plan);
    }
    if (open != INT64_MAX) {
#if SVA_FLOW_COVER_TARGETS > 0
        // Coverage first: its own share of the budget, on top of the phases below
        // (their ends move by the work it spent).
        const uint64_t share = replan ? (uint64_t)REPLAN_COVER_SHARE : (uint64_t)COVER_SHARE;
        start += sva_flow_cover_incumbent(priv, m, plan, budget / share, false, &coverage_proven);
#endif
        uint64_t lagrange_end = sva_flow_lagrange_end(m, start, w->work, budget);
#if SVA_FLOW_LARGE
        if (sva_flow_large(m) && sva_flow_near_bound(open, priv, m, plan)) {
            lagrange_end = w->work;  // the search's bound nearly certifies the plan
        }
#endif
        // A proof of coverage at the plan's proven cost ends the planning: it may take the
        // work of the phases after it (not a large mission's: ruin and recreate needs it).
        w->proof_end = sva_flow_large(m) ? lagrange_end : (start + budget);
        lagrange_bound = sva_flow_lagrange(priv, m, plan, lagrange_end, &coverage_proven,
                                           &stats->flow_lagrange_iters);
        int64_t proven_bound = coverage_proven ? lagrange_bound : -1;
#if SVA_FLOW_LARGE
        if (sva_flow_large(m)) {
            // A large mission's ruin and recreate also knows the search's bound, so that
            // a plan already near it is not worked on with the large budget.
            proven_bound =
                sva_flow_known_bound(open, lagrange_bound, priv, m, plan, coverage_proven);
        }
#endif
        const bool proven = sva_flow_ruin_recreate(
            priv, m, plan, sva_flow_ruin_end(m, start + budget, w->work, budget), proven_bound);
        // Proven optimal already (the claim below): no second search. Nor in a plan with
        // a target of need 2 or more: its copies are paired only by branching, so the
        // search closes no gap there and finds no plan the phases before it missed
        // (DESIGN.md section 8); the rounds below (ACCEPTING_SHARE) do. Nor in a large
        // mission's plan: ruin and recreate had the work the search would take.
        const bool search_pays = replan || ((w->need_max == 1) && !sva_flow_large(m));
        if ((!proven || !w->reward_exact) && search_pays) {
            sva_flow_incomplete_t again = finished;
            const int64_t open_again = search(priv, m, plan, start + budget, false, &again);
            open = (open_again > open) ? open_again : open;
            incomplete = (open_again == INT64_MAX) ? again : incomplete;
        }
        // With a target of need 2 or more: the coverage's proof, and the search for more.
        if ((w->need_max > 1) && !replan && !coverage_proven && (open != INT64_MAX)) {
            coverage_proven = synchronised_coverage(priv, m, plan, budget);
        }
#if SVA_FLOW_GRANULAR
        // With a target of need 2 or more, last, the accepting rounds (ACCEPTING_SHARE):
        // after the coverage search, so that a plan it finds is theirs to start from.
        if ((w->need_max > 1) && !replan && !sva_flow_large(m)) {
            sva_flow_ruin_accepting(priv, m, plan, w->work + (budget / ACCEPTING_SHARE),
                                    coverage_proven ? lagrange_bound : -1);
        }
#endif
    }
    finish(priv, m, plan, open, lagrange_bound, coverage_proven, incomplete);
    return SVA_OK;
}
