// flow_ruin.c -- flow's ruin and recreate (DESIGN.md section 8).
//
// The incumbent loses a group of related visits, and the repair
// puts a plan back together (uncovered targets inserted in window order, every other
// round in reverse, ejection, local search when within reach, offer). For each group
// size in turn, each covered target s seeds a group: s and the covered targets
// nearest to it (cells between them plus the ticks between their window starts, in
// cells). With need 2 this is how a target short of its second UAV finds one: the
// group's visits leave room. Then swaps: one covered target out, one uncovered in.
// A large mission's rounds take strings of visits out instead (after SISR, Christiaens
// and Vanden Berghe, 2020), put them back in an order drawn for the round, and start
// from a current plan instead of the incumbent, which a round's plan replaces when
// within a falling threshold of it (threshold accepting); the incumbent they leave gets
// the full local search last, again while it betters it (their own search is granular).
// A plan with a need above 1 ends with accepting rounds of groups
// (sva_flow_ruin_accepting); both kinds run in accepting_passes.
#include "flow.h"

#define RUIN_ROUND_UNITS 8U   // work units per round, per target inserted x UAV
#define ACCEPT_SHARE     100  // the threshold starts at the incumbent's cost / ACCEPT_SHARE
// A large mission's string rounds: visits taken out on average (SISR's c-bar), a
// string's longest, and a round's charge in targets inserted (as for a group of 7: a
// unit's time stays near the search's, about 15 ns at 200 x 40).
#define STRING_MEAN    15U
#define STRING_LONGEST 10U
#define STRING_CHARGE  7U
#define RANDOM_SEED    0x9E3779B9U  // the draws' first state, the same for every plan
#define ORDER_CHOICES  11U          // SISR's weights: random 4, window 4, far 2, near 1
#define ORDER_RANDOM   4U
#define ORDER_WINDOW   8U
#define ORDER_FAR      10U

static int64_t relatedness(const sva_mission_t* m, uint16_t a, uint16_t b)
{
    const sva_target_t* ta = &m->targets[a];
    const sva_target_t* tb = &m->targets[b];
    const int64_t ticks = (int64_t)ta->start_ticks - (int64_t)tb->start_ticks;
    return sva_distance(ta->x, ta->y, tb->x, tb->y) +
           (((ticks < 0) ? -ticks : ticks) / m->ticks_per_cell);
}

#if SVA_FLOW_GRANULAR
// Each target's SVA_FLOW_NEAR most related targets, nearest first (ties: lower index),
// the local search's granular neighbourhood and the strings' seeds during ruin and
// recreate; and the draws' first state.
void sva_flow_ruin_prepare(sva_flow_work_t* w, const sva_mission_t* m)
{
    const uint16_t k_max = (m->target_count > (uint16_t)SVA_FLOW_NEAR)
                               ? (uint16_t)SVA_FLOW_NEAR
                               : (uint16_t)(m->target_count - 1U);
    w->near_count = k_max;
    for (uint16_t s = 0U; s < m->target_count; s++) {
        uint16_t n = 0U;
        for (uint16_t t = 0U; t < m->target_count; t++) {
            if (t == s) {
                continue;
            }
            const int64_t rel = relatedness(m, s, t);
            uint16_t at = n;
            while ((at > 0U) && (relatedness(m, s, w->near[s][at - 1U]) > rel)) {
                at--;
            }
            if (at >= k_max) {
                continue;
            }
            const uint16_t last = (n < k_max) ? n : (uint16_t)(k_max - 1U);
            for (uint16_t j = last; j > at; j--) {
                w->near[s][j] = w->near[s][j - 1U];
            }
            w->near[s][at] = t;
            n = (n < k_max) ? (uint16_t)(n + 1U) : n;
        }
    }
    for (uint16_t u = 0U; u < m->uav_count; u++) {
        w->uav_tried[u] = 0U;
    }
    w->try_epoch = 0U;
    w->ruin_random = RANDOM_SEED;
    w->work += (uint64_t)m->target_count * m->target_count;
}

// A draw in [0, below), below > 0: xorshift32 (Marsaglia, 2003), so that a mission
// and a budget always give the same plan.
static uint32_t draw(sva_flow_work_t* w, uint32_t below)
{
    uint32_t x = w->ruin_random;
    x ^= x << 13U;
    x ^= x >> 17U;
    x ^= x << 5U;
    w->ruin_random = x;
    uint32_t drawn = 0U;
    if (below > 0U) {
        drawn = x % below;
    }
    return drawn;
}

// Where the repair puts target t back, by the round's order (smallest key first).
static int64_t order_key(const sva_mission_t* m, uint16_t t, uint32_t order)
{
    const sva_target_t* tg = &m->targets[t];
    const int64_t depot = sva_distance(m->depot_x, m->depot_y, tg->x, tg->y);
    int64_t key = depot;
    if (order < ORDER_WINDOW) {
        key = tg->start_ticks;
    } else if (order < ORDER_FAR) {
        key = -depot;
    } else {
        // nearest the depot first
    }
    return key;
}

// The order the repair puts a round's visits back in, drawn for the round: at random,
// by window start, farthest from the depot first, or nearest first.
static void order_ruined(sva_flow_work_t* w, const sva_mission_t* m)
{
    const uint32_t order = draw(w, ORDER_CHOICES);
    for (uint16_t i = 1U; i < w->ruined_count; i++) {
        const uint16_t t = w->ruined[i];
        uint16_t at = i;
        if (order < ORDER_RANDOM) {
            at = (uint16_t)draw(w, (uint32_t)i + 1U);  // Fisher-Yates, grown one by one
            w->ruined[i] = w->ruined[at];
        } else {
            const int64_t key = order_key(m, t, order);
            while ((at > 0U) && (order_key(m, w->ruined[at - 1U], order) > key)) {
                w->ruined[at] = w->ruined[at - 1U];
                at--;
            }
        }
        w->ruined[at] = t;
    }
}

// The route and place of a visit to t, the first route serving it; false when none.
static bool find_visit(const sva_mission_t* m, const sva_plan_t* plan, uint16_t t, uint16_t* u,
                       uint16_t* k)
{
    bool found = false;
    for (uint16_t v = 0U; (v < m->uav_count) && !found; v++) {
        const sva_route_t* r = &plan->routes[v];
        for (uint16_t j = 0U; (j < r->target_count) && !found; j++) {
            if (r->targets[j] == t) {
                *u = v;
                *k = j;
                found = true;
            }
        }
    }
    return found;
}

// Threshold accepting (Dueck and Scheuer, 1990) for a large mission's rounds: a round's
// plan becomes the current one when its value is at most the current's plus a threshold
// that falls linearly from the incumbent's cost / ACCEPT_SHARE, when the rounds start,
// to 0 when their budget [from, to) is spent. Descent alone (each round from the
// incumbent) stalls on 100-target missions where fuel binds (docs/results.md). The
// incumbent, which the repair offered the plan to, keeps the best.
static void accept(sva_planner_priv_t* priv, const sva_mission_t* m, sva_plan_t* plan,
                   uint64_t from, uint64_t to, int64_t start_cost)
{
    const sva_flow_work_t* w = &priv->flow;
    int64_t threshold = 0;
    if ((to > from) && (to > w->work)) {
        const uint64_t span = to - from;
        const uint64_t left = to - w->work;
        const uint64_t share = (left < span) ? left : span;
        const uint64_t top = (uint64_t)start_cost / (uint64_t)ACCEPT_SHARE;
        const uint64_t part = (top * share) / span;
        threshold = (int64_t)part;
    }
    const int64_t value = sva_flow_plan_value(priv, m, plan);
    if (value <= (w->cur_value + threshold)) {
        sva_flow_keep_current(priv, m, plan, value);
    }
}
#endif

// Before a ruin: every route's cells, and no route changed yet, no visit awake.
static void ruin_begin(sva_flow_work_t* w, const sva_mission_t* m, const sva_plan_t* plan)
{
    for (uint16_t u = 0U; u < m->uav_count; u++) {
        w->route_cells[u] = sva_route_cells(m, u, &plan->routes[u]);
#if SVA_FLOW_GRANULAR
        w->route_changed[u] = 0U;
#endif
    }
#if SVA_FLOW_GRANULAR
    for (uint16_t t = 0U; t < m->target_count; t++) {
        w->visit_awake[t] = 0U;
    }
#endif
}

#if SVA_FLOW_GRANULAR
// The plan without strings of consecutive visits, each through one of s and its
// related targets (in that order) in a route no string has touched yet: up to a drawn
// number of strings, of drawn lengths up to the routes' mean length (at most
// STRING_LONGEST), about STRING_MEAN visits in all. The visits are left in w->ruined,
// in the order drawn for the round.
void sva_flow_ruin_strings(sva_planner_priv_t* priv, const sva_mission_t* m, sva_plan_t* plan,
                           uint16_t s)
{
    sva_flow_work_t* w = &priv->flow;
    ruin_begin(w, m, plan);
    uint32_t visits = 0U;
    uint32_t used = 0U;
    for (uint16_t u = 0U; u < m->uav_count; u++) {
        visits += plan->routes[u].target_count;
        used += (plan->routes[u].target_count > 0U) ? 1U : 0U;
    }
    uint32_t longest = STRING_LONGEST;
    if ((used > 0U) && ((visits / used) < STRING_LONGEST)) {
        longest = visits / used;  // at least 1
    }
    // 1 to 4 * STRING_MEAN / (1 + longest) - 1 strings of at most `longest` visits: at
    // most 45 visits in all (longest 5), which SVA_FLOW_RUINED_MOST holds.
    const uint32_t strings = 1U + draw(w, ((4U * STRING_MEAN) / (1U + longest)) - 1U);
    uint32_t taken = 0U;
    w->ruined_count = 0U;
    for (uint16_t i = 0U; (i <= w->near_count) && (taken < strings); i++) {
        const uint16_t c = (i == 0U) ? s : w->near[s][i - 1U];
        uint16_t u = 0U;
        uint16_t k = 0U;
        if (!find_visit(m, plan, c, &u, &k) || (w->route_changed[u] != 0U)) {
            continue;  // not served, or its route gave a string already
        }
        const uint32_t count = plan->routes[u].target_count;
        const uint32_t length = 1U + draw(w, (count < longest) ? count : longest);
        // The string's first place: the string holds k and fits in the route.
        const uint32_t end = (uint32_t)k + 1U;
        uint32_t low = 0U;
        if (end > length) {
            low = end - length;
        }
        uint32_t high = k;
        if ((count - length) < high) {
            high = count - length;
        }
        const uint32_t first = low + draw(w, (high - low) + 1U);
        SVA_ASSERT(((uint32_t)w->ruined_count + length) <= (uint32_t)SVA_FLOW_RUINED_MOST);
        for (uint32_t j = 0U; j < length; j++) {
            w->ruined[w->ruined_count + j] = plan->routes[u].targets[first + j];
        }
        for (uint32_t j = 0U; j < length; j++) {
            sva_flow_remove_target(priv, m, plan, w->ruined[w->ruined_count + j]);
        }
        w->ruined_count = (uint16_t)(w->ruined_count + length);
        taken++;
    }
    order_ruined(w, m);
}
#endif

// The incumbent without s and the size - 1 covered targets most related to it.
static void ruin(sva_planner_priv_t* priv, const sva_mission_t* m, sva_plan_t* plan, uint16_t s,
                 uint8_t size)
{
    ruin_begin(&priv->flow, m, plan);
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

// One round on the plan in *plan: s and the size - 1 covered targets most related to it
// out (when `granular`, a large mission's: strings through s and its related targets),
// then the repair (insertions in reverse window order when `backwards`; its local
// search only from the changed routes when `granular`), charged `units` of work.
static void ruin_round(sva_planner_priv_t* priv, const sva_mission_t* m, sva_plan_t* plan,
                       uint16_t s, uint8_t size, bool backwards, bool granular, uint64_t units)
{
    sva_flow_work_t* w = &priv->flow;
#if SVA_FLOW_GRANULAR
    if (granular) {
        sva_flow_ruin_strings(priv, m, plan, s);
    } else {
        ruin(priv, m, plan, s, size);
    }
#else
    ruin(priv, m, plan, s, size);
#endif
    w->insert_backwards = backwards;
#if SVA_FLOW_GRANULAR
    w->local_changed_only = granular;
#else
    (void)granular;
#endif
    sva_flow_repair(priv, m, plan, true);
#if SVA_FLOW_GRANULAR
    w->local_changed_only = false;
#endif
    w->insert_backwards = false;
    w->work += units;
    plan->stats.flow_ruin_rounds++;
}

#if SVA_FLOW_GRANULAR
// A round from the current plan in *plan (ruin_round), then the threshold's test over
// the rounds' span [from, to) for a plan that started at start_cost; leaves the current
// plan in *plan.
static void accepting_round(sva_planner_priv_t* priv, const sva_mission_t* m, sva_plan_t* plan,
                            uint16_t s, uint8_t size, bool backwards, bool granular, uint64_t units,
                            uint64_t from, uint64_t to, int64_t start_cost)
{
    ruin_round(priv, m, plan, s, size, backwards, granular, units);
    accept(priv, m, plan, from, to, start_cost);
    sva_flow_write_current(priv, m, plan);
}

// Rounds from the current plan (accepting_round), charged `units` each, until `end`:
// passes over the covered targets as seeds, each pass's groups of the next size in
// `sizes` with its seeds three targets further on, or (`strings`) a large mission's
// strings from the first target on. A pass without a covered target to seed a round
// ends them: a plan covering nothing gets none. String rounds that at their rate so far
// would not reach one round per target turn shallow (sva_flow_rounds_fall_short): more
// rounds, each with less local search. At 200 x 40 a deep round costs about 11,000
// units and half the budget affords about 180 of them.
static void accepting_passes(sva_planner_priv_t* priv, const sva_mission_t* m, sva_plan_t* plan,
                             uint64_t end, int64_t start_cost, uint64_t units, bool strings)
{
    static const uint8_t sizes[] = {4U, 7U, 2U, 9U, 5U, 12U, 3U, 6U};
    sva_flow_work_t* w = &priv->flow;
    const uint64_t from = w->work;
    uint32_t pass = 0U;
    uint32_t done = 0U;
    bool seeded = true;
    w->local_shallow = false;
    while (seeded && (w->work < end)) {
        const uint8_t size = sizes[pass % (uint32_t)(sizeof(sizes) / sizeof(sizes[0]))];
        const uint32_t first = strings ? 0U : (pass * 3U);
        seeded = false;
        for (uint16_t k = 0U; (k < m->target_count) && (w->work < end); k++) {
            const uint16_t s = (uint16_t)((first + k) % m->target_count);
            if ((int32_t)priv->target_served[s] == m->targets[s].need) {
                accepting_round(priv, m, plan, s, size, ((k + pass) % 2U) == 1U, strings, units,
                                from, end, start_cost);
                seeded = true;
                done++;
                w->local_shallow = w->local_shallow ||
                                   (strings && (w->work < end) &&
                                    sva_flow_rounds_fall_short(done, w->work - from, end - w->work,
                                                               m->target_count));
            }
        }
        pass++;
    }
    w->local_shallow = false;
}

void sva_flow_ruin_accepting(sva_planner_priv_t* priv, const sva_mission_t* m, sva_plan_t* plan,
                             uint64_t end, int64_t proven_bound)
{
    int64_t cost = 0;
    int64_t covered = 0;
    sva_flow_incumbent(priv, m, plan, &cost, &covered);
    if (proven_bound >= cost) {
        return;  // proven optimal
    }
    sva_flow_keep_current(priv, m, plan, sva_flow_plan_value(priv, m, plan));
    accepting_passes(priv, m, plan, end, cost,
                     (uint64_t)m->target_count * m->uav_count * RUIN_ROUND_UNITS, false);
    sva_flow_write_incumbent(priv, m, plan);
}
#endif

#if SVA_FLOW_GRANULAR
// The incumbent (in *plan) repaired with the full local search, every move between
// every pair of routes: a large mission's rounds search only near their strings. Again
// while that betters it (a repair inserts what it can after its search, which may open
// moves), within one local search's work (w->local_work). Leaves the incumbent in *plan.
static void polish(sva_planner_priv_t* priv, const sva_mission_t* m, sva_plan_t* plan)
{
    sva_flow_work_t* w = &priv->flow;
    const uint64_t end = w->work + w->local_work;
    int64_t before = 0;
    do {
        before = w->inc_value;
        sva_flow_repair(priv, m, plan, true);
        sva_flow_write_incumbent(priv, m, plan);
    } while ((w->inc_value < before) && (w->work < end));
}
#endif

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
    // Not when the coverage is proven and the plan within 1/SVA_FLOW_CLOSE of the bound:
    // the search, with the rest of the budget, may prove it.
    const bool near = sva_flow_close(cost, proven_bound);
    const uint64_t rest = ((end > w->work) && !near) ? (end - w->work) : 0U;
    const bool large = sva_flow_large(m);
    // The rounds stop at three quarters of the rest, for the swaps; they need an
    // uncovered target, and a large mission's rounds take the rest when there is none.
    const bool swaps = !large || sva_flow_uncovered_left(priv, m);
    const uint64_t budget = w->work + (swaps ? (rest - (rest / 4U)) : rest);
    // A round's insertions: every target's, or past SVA_FLOW_LARGE_FROM targets
    // the ruined ones' (a swap round: two) and a scan of the targets.
    const uint64_t uav_units = (uint64_t)m->uav_count * RUIN_ROUND_UNITS;
    const uint64_t whole_units = (uint64_t)m->target_count * uav_units;
    bool grouped = true;  // rounds of groups (a large mission's: of strings, below)
#if SVA_FLOW_GRANULAR
    if (large && (rest > 0U)) {
        sva_flow_ruin_prepare(w, m);
        sva_flow_keep_current(priv, m, plan, sva_flow_plan_value(priv, m, plan));
        accepting_passes(priv, m, plan, budget, cost,
                         (uint64_t)m->target_count + ((uint64_t)STRING_CHARGE * uav_units), true);
        sva_flow_write_incumbent(priv, m, plan);  // the swaps start from the incumbent
    }
    grouped = !large;
#endif
    // *plan holds the incumbent whenever a round is chosen (sva_flow_incumbent above,
    // then a write after each round).
    for (size_t i = 0U; grouped && (i < (sizeof(ruin_sizes) / sizeof(ruin_sizes[0]))); i++) {
        for (uint16_t s = 0U; (s < m->target_count) && (w->work < budget); s++) {
            if ((int32_t)priv->target_served[s] == m->targets[s].need) {
                ruin_round(priv, m, plan, s, ruin_sizes[i], ((s + i) % 2U) == 1U, false,
                           whole_units);
                sva_flow_write_incumbent(priv, m, plan);
            }
        }
    }
    // Swaps: a covered target c leaves, an uncovered target t goes in first (all its
    // need at once), and the repair puts the rest back. With need 2 a plan may cover
    // the right number of targets but the wrong ones; groups reinserted in window
    // order rarely change which.
    for (uint16_t c = 0U; swaps && (c < m->target_count) && (w->work < budget); c++) {
        for (uint16_t t = 0U; (t < m->target_count) && (w->work < budget); t++) {
            if (((int32_t)priv->target_served[c] == m->targets[c].need) &&
                (priv->target_served[t] == 0U)) {
                ruin(priv, m, plan, c, 1U);
                sva_flow_try_insert(priv, m, plan, t);
                if (priv->target_served[t] != 0U) {
                    sva_flow_repair(priv, m, plan, true);
                    plan->stats.flow_ruin_rounds++;
                }
                w->work += large ? ((uint64_t)m->target_count + (2U * uav_units)) : whole_units;
                sva_flow_write_incumbent(priv, m, plan);
            }
        }
    }
#if SVA_FLOW_GRANULAR
    if (large && (rest > 0U)) {
        polish(priv, m, plan);
    }
#endif
    return false;
}
