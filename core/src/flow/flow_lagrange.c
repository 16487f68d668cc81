// flow_lagrange.c -- flow's Lagrangian phase: a lower bound that knows the fuel rule,
// and plans built from it (DESIGN.md section 8).
//
// Relax "target t is served by need_t routes or by none" with a price pi_t per target.
// What is left splits: every UAV flies its own best route under the prices, and every
// target is taken (y_t = 1) when need_t pi_t < mu. A UAV's best route is a
// resource-constrained shortest path over the time-feasibility DAG of targets (the
// first copies of flow_graph.c's graph), fuel being the resource: labels (reduced
// cost, fuel used), Pareto-best, at most SVA_FLOW_LABELS per target; past that two
// merge into one that dominates both, which can only weaken the bound. With S =
// SVA_FLOW_PRICE_SCALE, for every plan p covering at least c targets, every pi and
// every mu >= 0:
//   cost phase:      S cost(p) >= sum_u min_r (S cost(r) - sum_{t in r} pi_t)
//                                 + sum_t min(0, need_t pi_t - mu) + mu c;
//   coverage phase:  -S covered(p) >= sum_u min_r (- sum_{t in r} pi_t)
//                                 + sum_t min(0, need_t pi_t - S),
// the second proving that no plan covers more targets than the incumbent. Prices move
// by subgradient steps (Polyak's rule in integers: deterministic). Every few steps
// the heuristic flies the UAVs one after another on their best routes under the
// prices (a large mission's on real paths, flow_label.c, when the flight fits its
// budget), a target's price growing with the UAVs already committed to it and a fully
// served target closed, then repairs the result (flow_repair.c) and offers it.
// Before the steps, the route master's duals (flow_lp.c) are tried as prices, in
// both phases: they are the LP's best, which the steps approach only slowly. After
// them, a dive on the master (flow_lp.c) offers one more plan.
#include "flow.h"

#define THETA_ONE       1024
#define THETA_START     (2 * THETA_ONE)
#define THETA_MIN       4
#define STALL_STEPS     20
#define HEURISTIC_EVERY 4
#define GAP_CAP         INT64_C(68719476736)  // 2^36: keeps theta * gap * grad within int64
#define NO_BOUND        (-INT64_MAX)

typedef struct {
    int64_t alpha;    // S in the cost phase, 0 in the coverage phase
    int64_t mu;       // reward of a taken target (prices' units)
    int64_t covered;  // c: the incumbent's coverage
    int64_t best;     // best bound found (prices' units)
    int64_t target;   // Polyak's target value
    int32_t theta;    // step factor, THETA_ONE = 1
    int32_t stall;    // steps since the bound last improved
    uint32_t iters;
} phase_t;

static int64_t floor_div(int64_t a, int64_t b)
{
    int64_t q = a / b;
    if (((a % b) != 0) && ((a < 0) != (b < 0))) {
        q--;
    }
    return q;
}

static int64_t ceil_div(int64_t a, int64_t b)
{
    return -floor_div(-a, b);
}

// Whether the steps may stop: the bound `best` (prices' units) reaches the incumbent's
// cost, or comes within one of it when every target is covered (no plan costs one less:
// all plans of a mission cost the same modulo 2, sva_flow_cost_floor). Short of full
// coverage the steps' flights may still find a plan covering more.
static bool cost_reached(int64_t best, int64_t cost, bool full)
{
    return full ? (best > (SVA_FLOW_PRICE_SCALE * (cost - 2)))
                : (best >= (SVA_FLOW_PRICE_SCALE * cost));
}

static int64_t clamp64(int64_t v, int64_t lo, int64_t hi)
{
    return (v < lo) ? lo : ((v > hi) ? hi : v);
}

// One evaluation of the Lagrangian at the current prices (prices' units); fills
// lg->grad, and the visits of every target.
static int64_t evaluate(sva_flow_work_t* w, const sva_mission_t* m, const sva_plan_t* plan,
                        const phase_t* ph, int64_t* grad_mu)
{
    sva_flow_lagrange_t* lg = &w->lagrange;
    for (uint16_t t = 0U; t < m->target_count; t++) {
        lg->visits[t] = 0U;
        lg->closed[t] = 0U;
        lg->path_price[t] = lg->price[t];
    }
    int64_t value = 0;
#if SVA_FLOW_LARGE
    lg->evaluation_work = w->work;
#endif
    for (uint16_t u = 0U; u < m->uav_count; u++) {
        if (plan->routes[u].stranded || (lg->group[u] != u)) {
            continue;
        }
        const int64_t v = sva_flow_best_route(w, m, u, ph->alpha);
        uint16_t members = 0U;
        for (uint16_t k = u; k < m->uav_count; k++) {
            members = (uint16_t)(members + ((lg->group[k] == u) ? 1U : 0U));
        }
        value += v * (int64_t)members;
        for (uint16_t i = 0U; i < lg->path_len; i++) {
            lg->visits[lg->path[i]] = (uint16_t)(lg->visits[lg->path[i]] + members);
        }
    }
    int64_t taken = 0;
    for (uint16_t t = 0U; t < m->target_count; t++) {
        const int64_t need = m->targets[t].need;
        const bool y = (need * lg->price[t]) < ph->mu;
        value += y ? ((need * lg->price[t]) - ph->mu) : 0;
        taken += y ? 1 : 0;
        lg->grad[t] = (y ? need : 0) - (int64_t)lg->visits[t];
    }
    *grad_mu = ph->covered - taken;
#if SVA_FLOW_LARGE
    lg->evaluation_work = w->work - lg->evaluation_work;
#endif
    return value + (ph->mu * ph->covered);
}

// Heuristic: the UAVs fly one after another on their best routes under the prices,
// when the flight fits (the incumbent stays as it is otherwise).
static void fly_on_prices(sva_planner_priv_t* priv, const sva_mission_t* m, sva_plan_t* plan,
                          uint16_t first)
{
    sva_flow_work_t* w = &priv->flow;
    sva_flow_lagrange_t* lg = &w->lagrange;
    if (!sva_flow_flight_begins(w, m)) {
        return;
    }
    for (uint16_t t = 0U; t < m->target_count; t++) {
        priv->target_served[t] = 0U;
        lg->closed[t] = 0U;
    }
    for (uint16_t u = 0U; u < m->uav_count; u++) {
        plan->routes[u].target_count = 0U;
    }
    for (uint16_t k = 0U; k < m->uav_count; k++) {
        const uint16_t u = (uint16_t)((first + k) % m->uav_count);
        sva_route_t* r = &plan->routes[u];
        if (r->stranded) {
            continue;
        }
        for (uint16_t t = 0U; t < m->target_count; t++) {
            const int64_t served = priv->target_served[t];
            lg->path_price[t] = lg->price[t] * (1 + served);
            lg->closed[t] = (served >= m->targets[t].need) ? 1U : 0U;
        }
        (void)sva_flow_best_route(w, m, u, SVA_FLOW_PRICE_SCALE);
        // A path longer than SVA_MAX_ROUTE_TARGETS keeps its head (still a route).
        r->target_count = 0U;
        while ((r->target_count < lg->path_len) &&
               (r->target_count < (uint16_t)SVA_MAX_ROUTE_TARGETS)) {
            const uint16_t t = lg->path[r->target_count];
            r->targets[r->target_count] = t;
            priv->target_served[t]++;
            r->target_count++;
        }
    }
#if SVA_FLOW_LARGE
    lg->real_paths = false;  // every other shortest path is a bound's
#endif
    sva_flow_repair(priv, m, plan, true);
}

// Prices' clamp: far above any useful price, far below int64 overflow.
static int64_t price_limit(const sva_flow_work_t* w)
{
    return (int64_t)SVA_FLOW_PRICE_SCALE * (w->max_cost + 1) * 4;
}

// One Polyak step; false when the step is zero (the prices cannot move).
static bool step(sva_flow_work_t* w, const sva_mission_t* m, phase_t* ph, int64_t value,
                 int64_t grad_mu, bool move_mu)
{
    sva_flow_lagrange_t* lg = &w->lagrange;
    int64_t norm = 0;
    if (move_mu) {
        norm = grad_mu * grad_mu;
    }
    for (uint16_t t = 0U; t < m->target_count; t++) {
        norm += lg->grad[t] * lg->grad[t];
    }
    if (norm == 0) {
        return false;
    }
    const int64_t gap = clamp64(ph->target - value, 1, GAP_CAP);
    const int64_t q = ((int64_t)ph->theta * gap) / norm;  // step * THETA_ONE
    const int64_t limit = price_limit(w);
    bool moved = false;
    for (uint16_t t = 0U; t < m->target_count; t++) {
        const int64_t d = (q * lg->grad[t]) / THETA_ONE;
        moved = moved || (d != 0);
        lg->price[t] = clamp64(lg->price[t] + d, -limit, limit);
    }
    if (move_mu) {
        const int64_t d = (q * grad_mu) / THETA_ONE;
        moved = moved || (d != 0);
        ph->mu = clamp64(ph->mu + d, 0, limit);
    }
    return moved;
}

// Tracks the best value; halves theta after STALL_STEPS steps without progress.
static void progress(phase_t* ph, int64_t value)
{
    ph->iters++;
    if (value > ph->best) {
        ph->best = value;
        ph->stall = 0;
    } else {
        ph->stall++;
        if (ph->stall >= STALL_STEPS) {
            ph->theta /= 2;
            ph->stall = 0;
        }
    }
}

static void start_prices(sva_flow_work_t* w, const sva_mission_t* m)
{
    for (uint16_t t = 0U; t < m->target_count; t++) {
        const sva_target_t* tg = &m->targets[t];
        const int64_t trip = 2 * (int64_t)sva_distance(m->depot_x, m->depot_y, tg->x, tg->y);
        w->lagrange.price[t] = ((int64_t)SVA_FLOW_PRICE_SCALE * trip) / tg->need;
    }
}

// The Lagrangian's value at the duals of the cost master for coverage c (prices'
// units), or NO_BOUND when the master gives none; its routes go to the stats.
static int64_t master_value(sva_flow_work_t* w, const sva_mission_t* m, sva_plan_t* plan,
                            int64_t covered, uint64_t budget)
{
    int64_t value = NO_BOUND;
    int64_t mu = 0;
    if (sva_flow_lp_prices(w, m, plan, covered, SVA_FLOW_LP_COST, budget, &mu)) {
        plan->stats.flow_lp_columns = w->lp.cols;
        const phase_t at = {SVA_FLOW_PRICE_SCALE, mu, covered, NO_BOUND, 0, 0, 0, 0U};
        int64_t grad_mu = 0;
        value = evaluate(w, m, plan, &at, &grad_mu);
    }
    return value;
}

// The coverage master's prices for `covered` + 1 targets (left in lg->price): true
// when its Lagrangian proves that no plan covers more; *priced: the master gave prices.
static bool cover_master(sva_flow_work_t* w, const sva_mission_t* m, const sva_plan_t* plan,
                         int64_t covered, uint64_t budget, bool* priced)
{
    const int64_t s = SVA_FLOW_PRICE_SCALE;
    const phase_t ph = {0, s, 0, NO_BOUND, -s * covered, THETA_START, 0, 0U};
    int64_t mu = 0;
    *priced = sva_flow_lp_prices(w, m, plan, covered + 1, SVA_FLOW_LP_COVER, budget, &mu);
    int64_t grad_mu = 0;
    return *priced && (evaluate(w, m, plan, &ph, &grad_mu) > (-s * (covered + 1)));
}

// The coverage phase's steps: true when they prove that no plan covers more.
static bool cover_steps(sva_flow_work_t* w, const sva_mission_t* m, const sva_plan_t* plan,
                        int64_t covered, uint64_t budget, uint32_t* iters)
{
    sva_flow_lagrange_t* lg = &w->lagrange;
    const int64_t s = SVA_FLOW_PRICE_SCALE;
    phase_t ph = {0, s, 0, NO_BOUND, -s * covered, THETA_START, 0, 0U};
    for (uint16_t t = 0U; t < m->target_count; t++) {
        lg->price[t] = s / m->targets[t].need;
    }
    while ((ph.iters < (uint32_t)SVA_FLOW_LAGRANGE_ITERS) && (w->work < budget) &&
           (ph.theta >= THETA_MIN)) {
        int64_t grad_mu = 0;
        const int64_t value = evaluate(w, m, plan, &ph, &grad_mu);
        progress(&ph, value);
        if (value > (-s * (covered + 1))) {
            *iters += ph.iters;
            return true;
        }
        if (!step(w, m, &ph, value, 0, false)) {
            break;
        }
    }
    *iters += ph.iters;
    return false;
}

// Coverage phase: true if no plan covers more than `covered` targets. After the coverage
// master's prices, the route enumeration (flow_enum.c) under them may prove it, or offer
// a plan covering more (then false); then the steps, whose count goes to *iters. With
// iters NULL, the master alone, within phase_end (sva_flow_cover_proof).
static bool prove_coverage(sva_planner_priv_t* priv, const sva_mission_t* m, sva_plan_t* plan,
                           int64_t covered, uint64_t phase_end, uint32_t* iters)
{
    sva_flow_work_t* w = &priv->flow;
    // Called at the plan's proven cost: a proof ends the planning, so it may go on to
    // w->proof_end (flow.c).
    const uint64_t budget =
        ((iters != NULL) && (w->proof_end > phase_end)) ? w->proof_end : phase_end;
    bool priced = false;
    if (cover_master(w, m, plan, covered, budget, &priced)) {
        return true;
    }
    if (iters == NULL) {
        return false;  // the master alone
    }
#if SVA_FLOW_ENUM_ROUTES > 0
    if (priced) {
        const uint64_t room = (budget > w->work) ? (budget - w->work) : 0U;
        bool more = false;
        if (sva_flow_enum_cover(priv, m, plan, covered, w->work + (room / 2U), &more) || more) {
            return !more;  // proven, or a plan covering more found
        }
    }
#endif
    return cover_steps(w, m, plan, covered, budget, iters);
}

#if SVA_FLOW_LP_ROWS >= 2
bool sva_flow_cover_proof(sva_planner_priv_t* priv, const sva_mission_t* m, sva_plan_t* plan,
                          uint64_t budget)
{
    int64_t cost = 0;
    int64_t covered = 0;
    sva_flow_incumbent(priv, m, plan, &cost, &covered);
    if (covered == (int64_t)m->target_count) {
        return true;
    }
    return prove_coverage(priv, m, plan, covered, budget, NULL);
}
#endif

#if SVA_FLOW_ENUM_ROUTES > 0
// The proof of flow_enum.c for the incumbent's cost among plans covering as many targets
// or more, within a quarter of the phase's work (`left`); *cost and *covered become the
// incumbent's (a cover it finds is cheaper).
static bool enum_proves(sva_planner_priv_t* priv, const sva_mission_t* m, sva_plan_t* plan,
                        int64_t* cost, int64_t* covered, uint64_t left)
{
    sva_flow_incumbent(priv, m, plan, cost, covered);
    const bool proved =
        sva_flow_enum_prove(priv, m, plan, *cost, *covered, priv->flow.work + (left / 4U));
    sva_flow_incumbent(priv, m, plan, cost, covered);
    return proved;
}
#endif

int64_t sva_flow_lagrange(sva_planner_priv_t* priv, const sva_mission_t* m, sva_plan_t* plan,
                          uint64_t budget, bool* coverage_proven, uint32_t* iters)
{
    sva_flow_work_t* w = &priv->flow;
    const int64_t s = SVA_FLOW_PRICE_SCALE;
    const int64_t targets = (int64_t)m->target_count;
    int64_t cost = 0;
    int64_t covered = 0;
    sva_flow_incumbent(priv, m, plan, &cost, &covered);
    const uint64_t left = (budget > w->work) ? (budget - w->work) : 0U;
    // First the route master's duals (flow_lp.c): for the bound alone, as subgradient
    // steps from them find few new plans. Any bound for coverage c holds for more.
    plan->stats.flow_lp_columns = 0U;
    const int64_t lp_covered = covered;
    int64_t lp_value = master_value(w, m, plan, covered, w->work + (left / 2U));
    bool cost_proven = false;
#if SVA_FLOW_ENUM_ROUTES > 0
    // The master's prices may prove the plan's cost at once, or give a cheaper plan
    // (flow_enum.c). Every target covered, the phase then has nothing left to do. Short
    // of that, the cost holds as the bound; the steps and the dive still run unless the
    // coverage is proven too, for their flights may cover more.
    sva_flow_enum_prices(w, m, lp_value != NO_BOUND);
    cost_proven = enum_proves(priv, m, plan, &cost, &covered, left);
    if (cost_proven && (covered == targets)) {
        *iters = 0U;
        *coverage_proven = true;
        plan->stats.flow_dive_routes = 0U;
        plan->stats.flow_cover_dive = (uint8_t)SVA_FLOW_COVER_DIVE_NOT_RUN;
        return cost;
    }
#endif
    // The bound proven, for plans covering as many targets or more: it stays one when
    // the steps' flights find a plan covering more.
    const int64_t proven_cost = cost_proven ? cost : 0;
    const bool settled = cost_proven && *coverage_proven;
    start_prices(w, m);
    int64_t most = 0;
    for (uint16_t t = 0U; t < m->target_count; t++) {
        const int64_t v = m->targets[t].need * w->lagrange.price[t];
        most = (v > most) ? v : most;
    }
    phase_t ph = {s, most + s, covered, NO_BOUND, s * cost, THETA_START, 0, 0U};
    uint16_t rotate = 0U;
    const uint64_t cost_budget = w->work + ((left / 4U) * 3U);  // the rest: coverage
    while (!settled && (ph.iters < (uint32_t)SVA_FLOW_LAGRANGE_ITERS) && (w->work < cost_budget) &&
           (ph.theta >= THETA_MIN) && !cost_reached(ph.best, cost, covered == targets) &&
           !cost_reached(lp_value, cost, covered == targets)) {
        int64_t grad_mu = 0;
        const int64_t value = evaluate(w, m, plan, &ph, &grad_mu);
        progress(&ph, value);
        if ((ph.iters % (uint32_t)HEURISTIC_EVERY) == 1U) {
            fly_on_prices(priv, m, plan, rotate);
            rotate = (uint16_t)((rotate + 1U) % m->uav_count);
            int64_t new_cost = 0;
            int64_t new_covered = 0;
            sva_flow_incumbent(priv, m, plan, &new_cost, &new_covered);
            if (new_covered != covered) {
                ph.best = NO_BOUND;  // bounds so far hold for the old coverage only
                covered = new_covered;
                ph.covered = covered;
            }
            cost = new_cost;
            ph.target = s * cost;
        }
        if (!step(w, m, &ph, value, grad_mu, true)) {
            break;
        }
    }
    *iters = ph.iters;
    bool master_solved = lp_value != NO_BOUND;
    if (covered != lp_covered) {
        const int64_t again = master_value(w, m, plan, covered, budget);
        master_solved = again != NO_BOUND;
        lp_value = (again > lp_value) ? again : lp_value;
    }
    // A dive on the cost master last solved: a plan from its routes, unless the bound
    // already proves a plan covering every target, or the plan is settled above.
    plan->stats.flow_dive_routes = 0U;
    const int64_t before_dive = (ph.best > lp_value) ? ph.best : lp_value;
    const bool proven_full = (covered == targets) && cost_reached(before_dive, cost, true);
    if (master_solved && !proven_full && !settled &&
        sva_flow_lp_dive(priv, m, plan, w->work + (left / 8U))) {
        plan->stats.flow_dive_routes = w->lp.fixed_count;
        sva_flow_repair(priv, m, plan, true);
        sva_flow_incumbent(priv, m, plan, &cost, &covered);
    }
    const int64_t best = (ph.best > lp_value) ? ph.best : lp_value;
    int64_t bound = (best == NO_BOUND) ? 0 : sva_flow_cost_floor(w, ceil_div(best, s));
    bound = (proven_cost > bound) ? proven_cost : bound;
    // Optimality needs both; the coverage phase runs once the cost is proven. When the
    // enumeration proved it short of full coverage, the dive below goes first: a plan
    // covering more is likely there, and a proof for the old coverage would be wasted.
    const bool dive_first = cost_proven && !*coverage_proven;
    *coverage_proven =
        *coverage_proven || (covered == targets) ||
        (!dive_first && (bound >= cost) && prove_coverage(priv, m, plan, covered, budget, iters));
    // Coverage comes first (SPEC 1): while c is not proven the most, a dive on the
    // cost master for c + 1 targets looks for a plan covering one more. Any bound for
    // coverage c holds for more.
    sva_flow_cover_dive_t dive = SVA_FLOW_COVER_DIVE_NOT_RUN;
    if (!*coverage_proven) {
        const uint64_t room = (budget > w->work) ? (budget - w->work) : 0U;
        const uint64_t up = w->work + ((room < (left / 2U)) ? room : (left / 2U));
        const int64_t before = covered;
        int64_t mu = 0;
        if (sva_flow_lp_prices(w, m, plan, covered + 1, SVA_FLOW_LP_COST, up, &mu) &&
            sva_flow_lp_dive(priv, m, plan, up)) {
            sva_flow_repair(priv, m, plan, true);
            sva_flow_incumbent(priv, m, plan, &cost, &covered);
            dive = (covered > before) ? SVA_FLOW_COVER_DIVE_FOUND : SVA_FLOW_COVER_DIVE_NONE;
        }
    }
    plan->stats.flow_cover_dive = (uint8_t)dive;
    if (dive == SVA_FLOW_COVER_DIVE_FOUND) {
        // The bounds so far hold for fewer targets: the cost master's for the new coverage.
        const int64_t again = master_value(w, m, plan, covered, budget);
        const int64_t raised = (again == NO_BOUND) ? 0 : sva_flow_cost_floor(w, ceil_div(again, s));
        bound = (raised > bound) ? raised : bound;
    }
    *coverage_proven = *coverage_proven || (covered == targets) ||
                       ((dive_first || (dive == SVA_FLOW_COVER_DIVE_FOUND)) && (bound >= cost) &&
                        prove_coverage(priv, m, plan, covered, budget, iters));
#if SVA_FLOW_ENUM_ROUTES > 0
    // Again with the phase's incumbent (its cost is lower now, so fewer routes); a cost
    // so proven short of every target leaves coverage to prove, as above.
    if ((bound < cost) && enum_proves(priv, m, plan, &cost, &covered, left)) {
        *coverage_proven = *coverage_proven || (covered == targets) ||
                           prove_coverage(priv, m, plan, covered, budget, iters);
        return cost;
    }
#endif
    return (bound < 0) ? 0 : bound;
}
