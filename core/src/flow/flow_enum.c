// flow_enum.c -- a proof, or a cheaper plan, from the route master's prices when its
// bound comes near the incumbent's cost (DESIGN.md section 8, "Route enumeration").
//
// Prices pi (the master's duals), a covered target's reward mu >= 0 and, for each UAV
// state g, a lower bound B_g on the value of its routes (value(r) = S x cells(r) - the
// prices of r's targets, S the prices' scale; the labels' shortest path, merged labels
// included) give, for every plan P (need 1) covering a set C of at least k targets:
//     S x cost(P) - mu (|C| - k) = L + E(P),
//     L = sum_g n_g B_g + sum_t min(0, pi_t - mu) + mu k,
//     E(P) = sum over P's routes of (value(r) - B_g) + sum_{t in C} max(0, pi_t - mu)
//            + sum_{t not in C} max(0, mu - pi_t),
// every term of E at least 0. With k the incumbent's coverage, a plan covering as many
// targets or more and cheaper than the incumbent costs at most its cost - 2 (every plan
// of a mission has one parity, sva_flow_cost_floor), so its E is at most gap = S x
// (cost - 2) - L. mu is the one that makes L largest: the (k+1)-th least price, or above
// every price when k is every target (then E is the routes' slacks alone).
// A route's slack (value(r) - B_g, plus its targets' excess) is then at most gap. The
// routes' search lists every route with a slack that small, depth first over the DAG of
// targets, pruned by a completion bound that ignores fuel; the cover's search then
// takes, depth first, for the first target in window order not yet decided, one route
// that starts there (every target before it is decided), or leaves it (at most as many
// as k allows), within the UAVs of each state and the gap, which shrinks to a cover's
// own sum less 2 S each time it finds one. The last cover it finds is the cheapest of
// coverage k or more; if it finds none, the incumbent is. It gives up (no claim) when
// the routes outgrow SVA_FLOW_ENUM_ROUTES, the work reaches its end, or a cover covers
// more than k (a better plan, offered, but not proven the best). Arc steps and the
// routes tried count as work.
#include "flow.h"

#if SVA_FLOW_ENUM_ROUTES > 0

#    define COST_ROUTES 512  // the list's bound for cost; coverage may take all of it

static int64_t least(int64_t a, int64_t b)
{
    return (a < b) ? a : b;
}

// The cells from copy c's target home.
static int64_t home_of(const sva_flow_work_t* w, const sva_mission_t* m, uint16_t c)
{
    const sva_target_t* t = &m->targets[w->copy_target[c]];
    return sva_distance(t->x, t->y, m->depot_x, m->depot_y);
}

// The cells from copy a's target to copy b's.
static int64_t leg_of(const sva_flow_work_t* w, const sva_mission_t* m, uint16_t a, uint16_t b)
{
    const sva_target_t* s = &m->targets[w->copy_target[a]];
    const sva_target_t* t = &m->targets[w->copy_target[b]];
    return sva_distance(s->x, s->y, t->x, t->y);
}

// The reward's excess of copy c's target when covered, and when left.
static int64_t covered_excess(const sva_flow_enum_t* e, const sva_flow_work_t* w, uint16_t c)
{
    const int64_t d = e->pi[w->copy_target[c]] - e->mu;
    return (d > 0) ? d : 0;
}

static int64_t left_excess(const sva_flow_enum_t* e, const sva_flow_work_t* w, uint16_t c)
{
    const int64_t d = e->mu - e->pi[w->copy_target[c]];
    return (d > 0) ? d : 0;
}

// Each state's best route value and UAVs; returns L (prices' units).
static int64_t state_bounds(sva_flow_work_t* w, const sva_mission_t* m, const sva_plan_t* plan)
{
    sva_flow_lagrange_t* lg = &w->lagrange;
    sva_flow_enum_t* e = &w->enumeration;
    int64_t value = e->mu * e->least;
    for (uint16_t t = 0U; t < m->target_count; t++) {
        lg->closed[t] = 0U;
        lg->path_price[t] = e->pi[t];
        value += least(0, e->pi[t] - e->mu);
    }
    for (uint16_t u = 0U; u < m->uav_count; u++) {
        e->members[u] = 0U;
        e->used[u] = 0U;
    }
    for (uint16_t u = 0U; u < m->uav_count; u++) {
        if (!plan->routes[u].stranded) {
            e->members[lg->group[u]]++;
        }
    }
    for (uint16_t u = 0U; u < m->uav_count; u++) {
        if ((e->members[u] > 0U) && (lg->group[u] == u)) {
            e->best[u] = sva_flow_best_route(w, m, u, e->alpha);
            const sva_uav_t* uav = &m->uavs[u];
            const int64_t home = sva_distance(uav->x, uav->y, m->depot_x, m->depot_y);
            e->empty[u] = (e->alpha * home) - e->best[u];
            value += (int64_t)e->members[u] * e->best[u];
        }
    }
    return value;
}

// tail[c]: the least value from copy c's target home over the DAG, fuel ignored (a
// bound on any route's rest from there), by the copies' topological order backwards.
static void completion_bounds(sva_flow_work_t* w, const sva_mission_t* m)
{
    sva_flow_enum_t* e = &w->enumeration;
    const uint16_t out_base = (uint16_t)(w->uavs + w->copies);
    for (uint16_t k = w->copies; k > 0U; k--) {
        const uint16_t c = (uint16_t)(k - 1U);
        int64_t best = e->alpha * home_of(w, m, c);
        for (uint32_t a = w->out_start[out_base + c]; a < w->out_start[out_base + c + 1U]; a++) {
            const uint16_t h = w->arc_head[a];
            if (h < out_base) {
                const uint16_t d = (uint16_t)(h - w->uavs);
                best = least(best, (e->alpha * leg_of(w, m, c, d)) - e->pi[w->copy_target[d]] +
                                       e->tail[d]);
            }
        }
        e->tail[c] = best;
    }
}

// Keeps the route of depth `depth` (its copies: e->at[0..depth]) when its slack, its
// targets' excess added, is at most gap; false when the list is full.
static bool keep(const sva_flow_work_t* w, sva_flow_enum_t* e, uint16_t state, uint16_t depth,
                 int64_t slack, int64_t gap)
{
    uint64_t mask = 0U;
    int64_t sum = slack;
    for (uint16_t k = 0U; k <= depth; k++) {
        mask |= (uint64_t)1U << e->at[k];
        sum += covered_excess(e, w, e->at[k]);
    }
    if (sum > gap) {
        return true;
    }
    if (e->count >= e->cap) {
        return false;
    }
    e->mask[e->count] = mask;
    e->slack[e->count] = sum;
    e->state[e->count] = state;
    e->count++;
    return true;
}

// Every route of state u that starts with copy c, of slack at most gap, into the list;
// false when the list is full or the work reaches `end`.
static bool routes_from(sva_flow_work_t* w, const sva_mission_t* m, uint16_t u, uint16_t c,
                        int64_t gap, uint64_t end)
{
    sva_flow_enum_t* e = &w->enumeration;
    const sva_uav_t* uav = &m->uavs[u];
    const int64_t s = e->alpha;
    const int64_t hover = m->hover_fuel;
    const uint16_t out_base = (uint16_t)(w->uavs + w->copies);
    const sva_target_t* first = &m->targets[w->copy_target[c]];
    const int64_t leg = sva_distance(uav->x, uav->y, first->x, first->y);
    if ((leg + w->target_tail[w->copy_target[c]]) > uav->fuel) {
        return true;
    }
    e->at[0] = c;
    e->value[0] = (s * leg) - e->pi[w->copy_target[c]];
    e->fuel[0] = leg + hover;
    e->arc[0] = w->out_start[out_base + c];
    if ((e->value[0] + e->tail[c] - e->best[u]) > gap) {
        return true;
    }
    const int64_t slack0 = e->value[0] + (s * home_of(w, m, c)) - e->best[u];
    if ((slack0 <= gap) && !keep(w, e, u, 0U, slack0, gap)) {
        return false;
    }
    uint16_t depth = 0U;
    bool going = true;
    while (going) {
        const uint16_t a = e->at[depth];
        const uint32_t arc = e->arc[depth];
        if ((arc >= w->out_start[out_base + a + 1U]) || (w->arc_head[arc] >= out_base) ||
            (((uint32_t)depth + 1U) >= (uint32_t)SVA_MAX_ROUTE_TARGETS)) {
            // This copy's arcs are done (the depot's comes last): back up.
            going = depth > 0U;
            depth = going ? (uint16_t)(depth - 1U) : 0U;
            continue;
        }
        e->arc[depth] = arc + 1U;
        w->work++;
        const uint16_t d = (uint16_t)(w->arc_head[arc] - w->uavs);
        const uint16_t t = w->copy_target[d];
        const int64_t step = leg_of(w, m, a, d);
        const int64_t value = e->value[depth] + (s * step) - e->pi[t];
        if (((e->fuel[depth] + step + w->target_tail[t]) > uav->fuel) ||
            ((value + e->tail[d] - e->best[u]) > gap)) {
            continue;
        }
        depth++;
        e->at[depth] = d;
        e->value[depth] = value;
        e->fuel[depth] = e->fuel[depth - 1U] + step + hover;
        e->arc[depth] = w->out_start[out_base + d];
        const int64_t slack = value + (s * home_of(w, m, d)) - e->best[u];
        if (((slack <= gap) && !keep(w, e, u, depth, slack, gap)) || (w->work >= end)) {
            return false;
        }
    }
    return w->work < end;
}

// The list: for each copy in order, every state's routes that start there.
static bool list_routes(sva_flow_work_t* w, const sva_mission_t* m, int64_t gap, uint64_t end)
{
    sva_flow_enum_t* e = &w->enumeration;
    e->count = 0U;
    for (uint16_t c = 0U; c < w->copies; c++) {
        e->first[c] = e->count;
        for (uint16_t u = 0U; u < m->uav_count; u++) {
            if ((e->members[u] == 0U) || (w->lagrange.group[u] != u)) {
                continue;
            }
            for (uint32_t a = w->out_start[u]; a < w->out_start[u + 1U]; a++) {
                if ((w->arc_head[a] == (uint16_t)(w->uavs + c)) &&
                    !routes_from(w, m, u, c, gap, end)) {
                    return false;
                }
            }
        }
    }
    e->first[w->copies] = e->count;
    return true;
}

#    define NO_SHARE (INT64_C(1) << 50)  // a copy no route covers and no cover may leave

// share[c]: a lower bound on what deciding copy c adds to a cover's sum (a route's slack
// split evenly over its copies, or the excess of leaving c); then each route's slack
// less its copies' shares, so that the cover's sum, started at the sum of the shares,
// is at every depth a lower bound on the sum of any cover it leads to. Returns that
// start.
static int64_t shares(sva_flow_work_t* w)
{
    sva_flow_enum_t* e = &w->enumeration;
    int64_t start = 0;
    for (uint16_t c = 0U; c < w->copies; c++) {
        e->share[c] = (e->skips > 0U) ? left_excess(e, w, c) : NO_SHARE;
    }
    for (uint16_t r = 0U; r < e->count; r++) {
        int64_t size = 0;
        for (uint16_t c = 0U; c < w->copies; c++) {
            size += (((e->mask[r] >> c) & 1U) != 0U) ? 1 : 0;
        }
        // Rounded down (a slack is at least 0 with a true bound B_g; below, still down).
        const int64_t part =
            (e->slack[r] >= 0) ? (e->slack[r] / size) : -(((-e->slack[r]) + size - 1) / size);
        for (uint16_t c = 0U; c < w->copies; c++) {
            if (((e->mask[r] >> c) & 1U) != 0U) {
                e->share[c] = least(e->share[c], part);
            }
        }
    }
    for (uint16_t r = 0U; r < e->count; r++) {
        for (uint16_t c = 0U; c < w->copies; c++) {
            if (((e->mask[r] >> c) & 1U) != 0U) {
                e->slack[r] -= e->share[c];
            }
        }
    }
    for (uint16_t c = 0U; c < w->copies; c++) {
        start += e->share[c];
    }
    w->work += 2U * (uint64_t)e->count * (uint64_t)w->copies;
    return start;
}

// The first copy not in `decided` (w->copies when all are).
static uint16_t first_open(const sva_flow_work_t* w, uint64_t decided)
{
    uint16_t c = 0U;
    while ((c < w->copies) && (((decided >> c) & 1U) != 0U)) {
        c++;
    }
    return c;
}

#    define LEAVE 0xFFFFU  // the cover's search leaves the copy of this depth

// The copy left last (leaves go in copy order): the highest of e->skipped, not empty.
static uint16_t last_left(const sva_flow_enum_t* e)
{
    uint16_t c = (uint16_t)SVA_FLOW_ENUM_TARGETS;
    c--;
    while ((c > 0U) && (((e->skipped >> c) & 1U) == 0U)) {
        c--;
    }
    return c;
}

// The cover's search: sets e->chosen to the last cover found of sum at most gap; *found:
// there is one, *wider: one covers more than e->least.
// False when the work reaches `end` first.
static bool cover(sva_flow_work_t* w, const sva_mission_t* m, int64_t gap, uint64_t end,
                  bool* found, bool* wider)
{
    sva_flow_enum_t* e = &w->enumeration;
    int64_t limit = gap;
    int64_t sum = shares(w);
    uint64_t covered = 0U;
    uint16_t left = 0U;
    uint16_t depth = 0U;
    e->skipped = 0U;
    e->chosen_count = 0U;
    e->pick[0] = e->first[first_open(w, covered)];
    for (;;) {
        const uint16_t c = first_open(w, covered | e->skipped);
        if (c == w->copies) {
            // Every copy decided: the other UAVs fly home. total = S cost - L.
            const int64_t taken = (int64_t)w->copies - (int64_t)left;
            int64_t total = sum + (e->mu * (taken - e->least));
            for (uint16_t u = 0U; u < m->uav_count; u++) {
                if ((e->members[u] > 0U) && (w->lagrange.group[u] == u)) {
                    const int64_t idle = (int64_t)e->members[u] - (int64_t)e->used[u];
                    total += idle * e->empty[u];
                }
            }
            if (total <= limit) {
                e->chosen_count = 0U;
                for (uint16_t k = 0U; k < depth; k++) {
                    if (e->pick[k] != LEAVE) {
                        e->chosen[e->chosen_count] = e->pick[k];
                        e->chosen_count++;
                    }
                }
                *found = true;
                *wider = *wider || (taken > e->least);
                if (e->alpha == 0) {
                    return true;  // coverage: a plan covering more is enough
                }
                limit = total - (2 * (int64_t)SVA_FLOW_PRICE_SCALE);
            }
        } else {
            // The next route for c that fits, from pick[depth] on; then leaving c.
            uint16_t r = e->pick[depth];
            const uint16_t last = e->first[c + 1U];
            while ((r < last) && (((e->mask[r] & covered) != 0U) || ((sum + e->slack[r]) > limit) ||
                                  (e->used[e->state[r]] >= e->members[e->state[r]]))) {
                r++;
                w->work++;
            }
            w->work++;
            if (w->work >= end) {
                return false;
            }
            if (r < last) {
                e->pick[depth] = r;
                covered |= e->mask[r];
                sum += e->slack[r];
                e->used[e->state[r]]++;
                depth++;
                e->pick[depth] = e->first[first_open(w, covered | e->skipped)];
                continue;
            }
            if ((r == last) && (left < e->skips) &&
                ((sum + left_excess(e, w, c) - e->share[c]) <= limit)) {
                e->pick[depth] = LEAVE;
                e->skipped |= (uint64_t)1U << c;
                sum += left_excess(e, w, c) - e->share[c];
                left++;
                depth++;
                e->pick[depth] = e->first[first_open(w, covered | e->skipped)];
                continue;
            }
        }
        // Back up: undo the choices above until one has a next route to try (leaving a
        // copy is its last choice).
        bool next = false;
        while (!next) {
            if (depth == 0U) {
                return true;
            }
            depth--;
            const uint16_t r = e->pick[depth];
            if (r == LEAVE) {
                const uint16_t l = last_left(e);
                e->skipped &= ~((uint64_t)1U << l);
                sum -= left_excess(e, w, l) - e->share[l];
                left--;
            } else {
                covered &= ~e->mask[r];
                sum -= e->slack[r];
                e->used[e->state[r]]--;
                e->pick[depth] = (uint16_t)(r + 1U);
                next = true;
            }
        }
    }
}

// The cover found, as the plan's routes, offered as the incumbent.
static void offer_cover(sva_planner_priv_t* priv, const sva_mission_t* m, sva_plan_t* plan)
{
    sva_flow_work_t* w = &priv->flow;
    const sva_flow_enum_t* e = &w->enumeration;
    sva_flow_clear_routes(priv, m, plan);
    for (uint16_t k = 0U; k < e->chosen_count; k++) {
        const uint16_t r = e->chosen[k];
        const uint16_t v = sva_flow_idle_uav(m, plan, w->lagrange.group, e->state[r]);
        SVA_ASSERT(v < m->uav_count);  // the cover takes at most a state's UAVs
        sva_route_t* route = &plan->routes[v];
        for (uint16_t c = 0U; c < w->copies; c++) {
            if (((e->mask[r] >> c) & 1U) != 0U) {
                const uint16_t t = w->copy_target[c];
                route->targets[route->target_count] = t;
                route->target_count++;
                priv->target_served[t]++;
            }
        }
    }
    (void)sva_flow_offer_plan(priv, m, plan);
}

void sva_flow_enum_prices(sva_flow_work_t* w, const sva_mission_t* m, bool taken)
{
    sva_flow_enum_t* e = &w->enumeration;
    e->has_prices = taken && (m->target_count <= (uint16_t)SVA_FLOW_ENUM_TARGETS);
    for (uint16_t t = 0U; e->has_prices && (t < m->target_count); t++) {
        e->price[t] = w->lagrange.price[t];
    }
}

// Whether the searches apply: need 1, exact rewards, at most 64 targets.
static bool applies(const sva_flow_work_t* w, const sva_mission_t* m)
{
    return (w->need_max == 1) && w->reward_exact &&
           (w->copies <= (uint16_t)SVA_FLOW_ENUM_TARGETS) && (w->copies == m->target_count);
}

// Both searches for plans within `gap` (target - L); false (no claim) when they do not
// finish. The callers work out L (state_bounds) and offer the cover found, so that
// neither the labels' stack nor the offer's is under the searches'.
static bool search_covers(sva_flow_work_t* w, const sva_mission_t* m, int64_t gap, uint64_t end,
                          bool* found, bool* wider)
{
    *found = false;
    *wider = false;
    if (gap < 0) {
        return true;  // no such plan
    }
    completion_bounds(w, m);
    return list_routes(w, m, gap, end) && cover(w, m, gap, end, found, wider);
}

// The reward that makes L largest for plans covering at least k targets: the (k+1)-th
// least price (at least 0), or one above every price when k is every target.
static int64_t best_reward(const sva_flow_enum_t* e, uint16_t targets, int64_t k)
{
    int64_t mu = 0;
    for (uint16_t t = 0U; t < targets; t++) {
        if (k == (int64_t)targets) {
            mu = (e->pi[t] > mu) ? e->pi[t] : mu;
        } else {
            int64_t below = 0;
            int64_t at_most = 0;
            for (uint16_t v = 0U; v < targets; v++) {
                below += (e->pi[v] < e->pi[t]) ? 1 : 0;
                at_most += (e->pi[v] <= e->pi[t]) ? 1 : 0;
            }
            if ((below <= k) && (at_most > k)) {
                mu = (e->pi[t] > 0) ? e->pi[t] : 0;
            }
        }
    }
    return mu;
}

bool sva_flow_enum_prove(sva_planner_priv_t* priv, const sva_mission_t* m, sva_plan_t* plan,
                         int64_t cost, int64_t covered, uint64_t end)
{
    sva_flow_work_t* w = &priv->flow;
    sva_flow_enum_t* e = &w->enumeration;
    if (!e->has_prices || !applies(w, m) || (covered < 0) || (covered > (int64_t)m->target_count)) {
        return false;
    }
    e->pi = e->price;
    e->alpha = SVA_FLOW_PRICE_SCALE;
    e->cap = (uint16_t)least(COST_ROUTES, SVA_FLOW_ENUM_ROUTES);
    e->least = covered;
    const int64_t skips = (int64_t)m->target_count - covered;
    e->skips = (uint16_t)skips;
    e->mu = best_reward(e, m->target_count, covered);
    bool found = false;
    bool wider = false;
    const int64_t gap = (SVA_FLOW_PRICE_SCALE * (cost - 2)) - state_bounds(w, m, plan);
    const bool done = search_covers(w, m, gap, end, &found, &wider);
    if (done && found) {
        offer_cover(priv, m, plan);
    }
    return done && !wider;
}

bool sva_flow_enum_cover(sva_planner_priv_t* priv, const sva_mission_t* m, sva_plan_t* plan,
                         int64_t covered, uint64_t end, bool* more)
{
    sva_flow_work_t* w = &priv->flow;
    sva_flow_enum_t* e = &w->enumeration;
    *more = false;
    if (!applies(w, m) || (covered < 0) || (covered >= (int64_t)m->target_count)) {
        return false;
    }
    e->pi = w->lagrange.price;
    e->alpha = 0;
    e->cap = (uint16_t)SVA_FLOW_ENUM_ROUTES;
    const int64_t skips = (int64_t)m->target_count - covered - 1;
    e->least = covered + 1;
    e->skips = (uint16_t)skips;
    e->mu = SVA_FLOW_PRICE_SCALE;
    bool wider = false;
    const int64_t gap = -state_bounds(w, m, plan);
    const bool done = search_covers(w, m, gap, end, more, &wider);
    if (done && *more) {
        offer_cover(priv, m, plan);
    }
    return done && !*more;
}

#endif  // SVA_FLOW_ENUM_ROUTES > 0
