// flow_cover.c -- flow's coverage search: a plan covering more targets than the
// incumbent, or the proof that none does (DESIGN.md section 8, "Coverage search").
//
// Coverage comes first (SPEC section 1). Where fuel binds and targets need two UAVs,
// the relaxation's search and its repairs can stay a target short for long: the plan
// covering one more pairs the UAVs differently from the first target on. This search
// decides the targets one by one in window order (start, end, id): each is served by
// `need` UAVs able to reach it by its start with the fuel to get home after it, or
// left. A UAV's route is its chosen targets in that order, feasible by construction.
//
// Bound: fuel_after[j][k] is the least fuel that, leaving the j-th target, serves k
// more targets and gets home (a backward pass over the window order). A UAV in state
// s can still serve at most K(s) targets: the most k + 1 for which some target j ahead
// is reachable from s and fuel_after[j][k] fits the fuel left once there (the first
// target a route flies to bounds the rest). The targets ahead that their need of UAVs
// can reach, fewest UAVs needed first, cover c more only if the c smallest needs sum
// to at most sum K(s), and to at most sum min(K(s), c): no UAV serves a target twice.
// And c is at most what u / q chains of the targets ahead hold, u the UAVs able to serve
// one, q the least need among them (flow_cover_chains.c: the time windows' bound).
// UAVs in one state are interchangeable: a combination taking the second of two alike
// UAVs must take the first. Combinations are tried in the order of their legs'
// lengths, the target left last; in the last third of the coverage search that flow
// runs last at need 2 and more, a target the incumbent leaves is left first: the
// plan covering one more target mostly keeps the incumbent's choices, and serving every
// target first spends the fuel on the first targets, so that the search only reaches
// such plans after many nodes. No recursion: the path is the UAV states per depth.
//
// Neighbourhoods: the same search over a few of the incumbent's UAVs set free, the
// others' routes kept. A target the kept routes cover is covered; one they serve in
// part needs only the rest of its UAVs. need + 1 UAVs (the mission's largest need) set
// free, every such set in turn, each within a sixteenth of the work left: the plan
// covering one more target often moves a UAV from a pair to a new one, and a small
// neighbourhood finds it in few nodes, where the whole search takes many thousands. It
// finds plans; it proves nothing.
#include "flow.h"

#if SVA_FLOW_COVER_TARGETS > 0

#    define STEP_COMBOS         0U  // the next combination in pick[d], then the target left
#    define STEP_LEAVE          1U  // the target left
#    define STEP_DONE           2U
#    define STEP_LEAVE_FIRST    3U  // the target left, then the combinations
#    define STEP_COMBOS_LAST    4U  // the next combination in pick[d], then done
#    define NO_FUEL             INT32_MAX
#    define NEIGHBOURHOOD_SHARE 16U  // of the work left, for each neighbourhood

// fuel_after for the n targets in window order; returns the work (pairs x counts).
static uint64_t fill_fuel_after(sva_flow_cover_t* c, const sva_planner_priv_t* priv,
                                const sva_mission_t* m)
{
    const int32_t n = (int32_t)m->target_count;
    uint64_t work = 0U;
    for (int32_t i = n - 1; i >= 0; i--) {
        const sva_target_t* a = &m->targets[priv->target_order[i]];
        int32_t* row = c->fuel_after[i];
        row[0] = sva_distance(a->x, a->y, m->depot_x, m->depot_y);
        for (int32_t k = 1; k <= n; k++) {
            row[k] = NO_FUEL;
        }
        for (int32_t l = i + 1; l < n; l++) {
            const sva_target_t* b = &m->targets[priv->target_order[l]];
            const int32_t leg = sva_distance(a->x, a->y, b->x, b->y);
            if (((int64_t)a->end_ticks + ((int64_t)leg * m->ticks_per_cell)) >
                (int64_t)b->start_ticks) {
                continue;
            }
            const int32_t* next = c->fuel_after[l];
            // A route serving k targets after b can drop one (triangle inequality): the
            // finite entries come first.
            for (int32_t k = 0; (k < (n - l)) && (next[k] != NO_FUEL); k++) {
                const int64_t v = (int64_t)next[k] + leg + m->hover_fuel;
                if ((v <= (int64_t)SVA_MAX_FUEL) && (v < (int64_t)row[k + 1])) {
                    row[k + 1] = (int32_t)v;
                }
            }
            work += (uint64_t)n - (uint64_t)l;
        }
    }
    return work;
}

// Whether UAV state s reaches target t (the j-th) by its start and still gets home
// from there; *leg gets the cells flown.
static inline bool reaches(const sva_flow_cover_t* c, const sva_mission_t* m,
                           const sva_flow_cover_uav_t* s, uint16_t j, const sva_target_t* t,
                           int32_t* leg)
{
    *leg = sva_distance(s->x, s->y, t->x, t->y);
    return ((int32_t)s->served < (int32_t)SVA_MAX_ROUTE_TARGETS) &&
           (((int64_t)s->free_at + ((int64_t)*leg * m->ticks_per_cell)) <=
            (int64_t)t->start_ticks) &&
           (((int64_t)s->fuel - *leg - m->hover_fuel) >= (int64_t)c->fuel_after[j][0]);
}

// Whether the targets from depth d on may still cover `more` of them (the bound in the
// header comment).
static bool may_cover(sva_flow_cover_t* c, const sva_planner_priv_t* priv, const sva_mission_t* m,
                      uint16_t d, uint16_t uavs, int32_t more, uint64_t* work)
{
    const uint16_t n = m->target_count;
    for (uint16_t j = d; j < n; j++) {
        c->reach[j] = 0U;
    }
    int64_t total = 0;
    for (uint16_t k = 0U; k < uavs; k++) {
        const sva_flow_cover_uav_t* s = &c->at[d][k];
        int32_t most = 0;
        for (uint16_t j = d; j < n; j++) {
            int32_t leg = 0;
            if (!reaches(c, m, s, j, &m->targets[priv->target_order[j]], &leg)) {
                continue;
            }
            c->reach[j]++;
            const int64_t left = (int64_t)s->fuel - leg - m->hover_fuel;
            // The most k with fuel_after[j][k] <= left (k = 0 fits: reaches), sought
            // only when it passes `most`: from `most` on, if that fits.
            int32_t lo = most;
            int32_t hi = (int32_t)n - 1 - (int32_t)j;
            if ((lo > hi) || ((int64_t)c->fuel_after[j][lo] > left)) {
                continue;
            }
            while (lo < hi) {
                const int32_t mid = (lo + hi + 1) / 2;
                if ((int64_t)c->fuel_after[j][mid] <= left) {
                    lo = mid;
                } else {
                    hi = mid - 1;
                }
            }
            most = lo + 1;
        }
        const int32_t room = (int32_t)SVA_MAX_ROUTE_TARGETS - (int32_t)s->served;
        most = (most < room) ? most : room;
        c->most[k] = (uint16_t)most;
        total += most;
        *work += (uint64_t)n - (uint64_t)d;
    }
    // The targets their need of UAVs can reach, counted by need (at most `uavs`).
    uint16_t* by_need = c->by_need;
    for (uint16_t k = 0U; k <= uavs; k++) {
        by_need[k] = 0U;
    }
    for (uint16_t j = d; j < n; j++) {
        const int32_t need = (int32_t)c->need_left[j];
        if ((need > 0) && ((int32_t)c->reach[j] >= need) && (need <= (int32_t)uavs)) {
            by_need[need]++;
        }
    }
    // The chain bound: the least need among those targets, and the UAVs able to serve
    // any target, give the chains (flow_cover_chains.c). At need 1 only at the root:
    // deeper, its rows cost more work than they save (the pooled bound below holds
    // the fuel, which binds there).
    uint16_t least = 0U;
    for (uint16_t need = 1U; (need <= uavs) && (least == 0U); need++) {
        least = (by_need[need] > 0U) ? need : 0U;
    }
    uint16_t able = 0U;
    for (uint16_t k = 0U; k < uavs; k++) {
        able = (uint16_t)(able + ((c->most[k] > 0U) ? 1U : 0U));
    }
    if (((least > 1U) || ((least == 1U) && (d == 0U))) &&
        ((int32_t)sva_flow_cover_chains(&c->chains, priv, m, d, (uint16_t)(able / least), work) <
         more)) {
        return false;
    }
    int32_t got = 0;
    int64_t needs = 0;
    for (int32_t need = 1; (need <= (int32_t)uavs) && (got < more); need++) {
        for (uint16_t i = 0U; (i < by_need[need]) && (got < more); i++) {
            got++;
            needs += need;
            int64_t spread = 0;
            for (uint16_t k = 0U; k < uavs; k++) {
                const int32_t most = (int32_t)c->most[k];
                spread += (most < got) ? most : got;
            }
            if ((needs > total) || (spread < needs)) {
                return false;
            }
        }
    }
    return got >= more;
}

static bool cover_alike(const sva_flow_cover_uav_t* a, const sva_flow_cover_uav_t* b)
{
    return (a->x == b->x) && (a->y == b->y) && (a->free_at == b->free_at) && (a->fuel == b->fuel) &&
           (a->served == b->served);
}

// Candidate order: shorter leg first; alike states next to each other, lower index
// first among them.
static bool cand_before(const sva_flow_cover_uav_t* at, const int32_t* leg, uint8_t a, uint8_t b)
{
    const sva_flow_cover_uav_t* p = &at[a];
    const sva_flow_cover_uav_t* q = &at[b];
    if (leg[a] != leg[b]) {
        return leg[a] < leg[b];
    }
    if ((p->x != q->x) || (p->y != q->y)) {
        return (p->x != q->x) ? (p->x < q->x) : (p->y < q->y);
    }
    if ((p->free_at != q->free_at) || (p->fuel != q->fuel)) {
        return (p->free_at != q->free_at) ? (p->free_at < q->free_at) : (p->fuel < q->fuel);
    }
    return (p->served != q->served) ? (p->served < q->served) : (a < b);
}

// The UAVs able to serve depth d's target t into cand[d], in candidate order.
static void cover_candidates(sva_flow_cover_t* c, const sva_mission_t* m, uint16_t d,
                             const sva_target_t* t, uint16_t uavs)
{
    int32_t* leg = c->leg;
    uint8_t count = 0U;
    for (uint16_t k = 0U; k < uavs; k++) {
        if (!reaches(c, m, &c->at[d][k], d, t, &leg[k])) {
            continue;
        }
        uint8_t i = count;
        while ((i > 0U) && cand_before(c->at[d], leg, (uint8_t)k, c->cand[d][i - 1U])) {
            c->cand[d][i] = c->cand[d][i - 1U];
            i--;
        }
        c->cand[d][i] = (uint8_t)k;
        count++;
    }
    c->cand_count[d] = count;
}

// The combination after pick[0..need) over `count` positions; false after the last.
static bool cover_advance(uint8_t* pick, uint8_t need, uint8_t count)
{
    int32_t i = (int32_t)need - 1;
    while ((i >= 0) && ((int32_t)pick[i] == ((int32_t)count - (int32_t)need + i))) {
        i--;
    }
    if (i < 0) {
        return false;
    }
    pick[i]++;
    for (int32_t j = i + 1; j < (int32_t)need; j++) {
        pick[j] = (uint8_t)(pick[j - 1] + 1U);
    }
    return true;
}

// Whether pick[d] takes, of alike UAVs, the first ones.
static bool cover_canonical(const sva_flow_cover_t* c, uint16_t d, uint8_t need)
{
    for (uint8_t i = 0U; i < need; i++) {
        const uint8_t p = c->pick[d][i];
        if ((p > 0U) && ((i == 0U) || (c->pick[d][i - 1U] != (uint8_t)(p - 1U))) &&
            cover_alike(&c->at[d][c->cand[d][p]], &c->at[d][c->cand[d][p - 1U]])) {
            return false;
        }
    }
    return true;
}

// The path's routes above depth d into the search's UAVs' routes of *plan (the others'
// kept), and every route's visits into priv->target_served.
static void cover_routes(sva_planner_priv_t* priv, const sva_mission_t* m, sva_plan_t* plan,
                         uint16_t d, uint16_t uavs)
{
    const sva_flow_cover_t* c = &priv->flow.cover;
    for (uint16_t k = 0U; k < uavs; k++) {
        plan->routes[c->uav[k]].target_count = 0U;
    }
    for (uint16_t e = 0U; e < d; e++) {
        const uint16_t t = priv->target_order[e];
        for (uint16_t k = 0U; k < uavs; k++) {
            if ((c->chosen[e] & ((uint32_t)1U << k)) != 0U) {
                sva_route_t* r = &plan->routes[c->uav[k]];
                r->targets[r->target_count] = t;
                r->target_count++;
            }
        }
    }
    for (uint16_t t = 0U; t < m->target_count; t++) {
        priv->target_served[t] = 0U;
    }
    for (uint16_t u = 0U; u < m->uav_count; u++) {
        const sva_route_t* r = &plan->routes[u];
        for (uint16_t i = 0U; i < r->target_count; i++) {
            priv->target_served[r->targets[i]]++;
        }
    }
}

// Depth d + 1 with depth d's target left: the UAVs as they were, no target more.
static void leave_target(sva_flow_cover_t* c, uint16_t d, uint16_t uavs)
{
    for (uint16_t k = 0U; k < uavs; k++) {
        c->at[d + 1U][k] = c->at[d][k];
    }
    c->chosen[d] = 0U;
    c->covered[d + 1U] = c->covered[d];
}

// Depth d's next child into depth d + 1: its next combination, then the target left.
// False when none is left.
static bool next_child(sva_flow_cover_t* c, const sva_planner_priv_t* priv, const sva_mission_t* m,
                       uint16_t d, uint16_t uavs)
{
    const sva_target_t* t = &m->targets[priv->target_order[d]];
    const uint8_t need = c->need_left[d];  // at most cand_count in STEP_COMBOS(_LAST)
    if (c->step[d] == (uint8_t)STEP_LEAVE_FIRST) {
        c->step[d] = (uint8_t)STEP_COMBOS_LAST;
        leave_target(c, d, uavs);
        return true;
    }
    while ((c->step[d] == (uint8_t)STEP_COMBOS) || (c->step[d] == (uint8_t)STEP_COMBOS_LAST)) {
        const bool take = cover_canonical(c, d, need);
        uint32_t chosen = 0U;
        if (take) {
            for (uint8_t i = 0U; i < need; i++) {
                chosen |= (uint32_t)1U << c->cand[d][c->pick[d][i]];
            }
        }
        if (!cover_advance(c->pick[d], need, c->cand_count[d])) {
            c->step[d] = (uint8_t)((c->step[d] == (uint8_t)STEP_COMBOS) ? STEP_LEAVE : STEP_DONE);
        }
        if (take) {
            for (uint16_t k = 0U; k < uavs; k++) {
                sva_flow_cover_uav_t s = c->at[d][k];
                if ((chosen & ((uint32_t)1U << k)) != 0U) {
                    s.fuel -= sva_distance(s.x, s.y, t->x, t->y) + m->hover_fuel;
                    s.x = t->x;
                    s.y = t->y;
                    s.free_at = t->end_ticks;
                    s.served++;
                }
                c->at[d + 1U][k] = s;
            }
            c->chosen[d] = chosen;
            c->covered[d + 1U] = (uint16_t)(c->covered[d] + 1U);
            return true;
        }
    }
    if (c->step[d] == (uint8_t)STEP_LEAVE) {
        c->step[d] = (uint8_t)STEP_DONE;
        leave_target(c, d, uavs);
        return true;
    }
    return false;
}

// The search from the root set up in c (its UAVs c->uav[0..uavs) at c->at[0], the UAVs
// each target still needs, the targets covered before it) for `goal` targets covered.
static sva_flow_cover_result_t cover_search(sva_planner_priv_t* priv, const sva_mission_t* m,
                                            sva_plan_t* plan, uint16_t uavs, int32_t goal,
                                            uint64_t budget, uint16_t* nodes)
{
    sva_flow_work_t* w = &priv->flow;
    sva_flow_cover_t* c = &w->cover;
    const uint16_t n = m->target_count;
    uint16_t d = 0U;
    bool enter = true;
    for (;;) {
        if (enter) {
            enter = false;
            *nodes = (*nodes < UINT16_MAX) ? (uint16_t)(*nodes + 1U) : (uint16_t)UINT16_MAX;
            if ((int32_t)c->covered[d] >= goal) {
                cover_routes(priv, m, plan, d, uavs);
                return SVA_FLOW_COVER_FOUND;
            }
            if (w->work >= budget) {
                return SVA_FLOW_COVER_OPEN;
            }
            if ((d == n) ||
                !may_cover(c, priv, m, d, uavs, goal - (int32_t)c->covered[d], &w->work)) {
                if (d == 0U) {
                    return SVA_FLOW_COVER_PROVEN;
                }
                d--;
                continue;
            }
            const sva_target_t* t = &m->targets[priv->target_order[d]];
            cover_candidates(c, m, d, t, uavs);
            w->work += uavs;
            c->step[d] = (uint8_t)STEP_LEAVE;
            if ((c->need_left[d] > 0U) && (c->cand_count[d] >= c->need_left[d])) {
                // In the last third, the incumbent's choice first: a target it leaves
                // is left first.
                c->step[d] = (uint8_t)((c->incumbent_first &&
                                        (priv->target_served[priv->target_order[d]] == 0U))
                                           ? STEP_LEAVE_FIRST
                                           : STEP_COMBOS);
                for (uint8_t i = 0U; i < c->need_left[d]; i++) {
                    c->pick[d][i] = i;
                }
            }
        }
        if (next_child(c, priv, m, d, uavs)) {
            d++;
            enter = true;
            continue;
        }
        if (d == 0U) {
            return SVA_FLOW_COVER_PROVEN;
        }
        d--;
    }
}

// UAVs a target still needs, as c->need_left holds it: a need past the search's UAVs
// (up to SVA_MAX_UAVS) stays one that no combination meets.
static uint8_t still_needed(int32_t left)
{
    const int32_t most = (int32_t)SVA_FLOW_COVER_U + 1;
    return (uint8_t)((left < 0) ? 0 : ((left > most) ? most : left));
}

// The UAVs that are not stranded, in id order (the plan does not depend on the
// mission's order), into c->all; false past SVA_FLOW_COVER_UAVS.
static bool list_uavs(sva_flow_cover_t* c, const sva_planner_priv_t* priv, const sva_mission_t* m,
                      uint16_t* uavs)
{
    *uavs = 0U;
    for (uint16_t i = 0U; i < m->uav_count; i++) {
        const uint16_t u = priv->uav_order[i];
        const sva_uav_t* uav = &m->uavs[u];
        if ((int64_t)uav->fuel < sva_distance(uav->x, uav->y, m->depot_x, m->depot_y)) {
            continue;
        }
        if ((int32_t)*uavs == (int32_t)SVA_FLOW_COVER_UAVS) {
            return false;
        }
        c->all[*uavs] = u;
        (*uavs)++;
    }
    return true;
}

// The search's UAVs as the mission starts them.
static void start_states(sva_flow_cover_t* c, const sva_mission_t* m, uint16_t uavs)
{
    for (uint16_t k = 0U; k < uavs; k++) {
        const sva_uav_t* uav = &m->uavs[c->uav[k]];
        c->at[0][k] = (sva_flow_cover_uav_t){uav->x, uav->y, uav->ready_at_ticks, uav->fuel, 0U};
    }
}

// Neighbourhood c->freed (of c->all's `count`): those UAVs searched from their start,
// what the kept routes of *plan leave to them in c->need_left and c->covered[0]. The
// whole search frees them all.
static void set_free(sva_flow_cover_t* c, const sva_planner_priv_t* priv, const sva_mission_t* m,
                     const sva_plan_t* plan, uint16_t count, uint16_t size)
{
    for (uint16_t k = 0U; k < size; k++) {
        c->uav[k] = c->all[c->freed[k]];
    }
    start_states(c, m, size);
    for (uint16_t t = 0U; t < m->target_count; t++) {
        c->reach[t] = 0U;  // here: the kept routes' visits of target t
    }
    uint16_t next = 0U;  // the next freed UAV (c->freed ascends)
    for (uint16_t k = 0U; k < count; k++) {
        if ((next < size) && (c->freed[next] == (uint8_t)k)) {
            next++;
            continue;
        }
        const sva_route_t* r = &plan->routes[c->all[k]];
        for (uint16_t i = 0U; i < r->target_count; i++) {
            c->reach[r->targets[i]]++;
        }
    }
    c->covered[0] = 0U;
    for (uint16_t j = 0U; j < m->target_count; j++) {
        const uint16_t t = priv->target_order[j];
        const int32_t left = (int32_t)m->targets[t].need - (int32_t)c->reach[t];
        c->need_left[j] = still_needed(left);
        c->covered[0] = (uint16_t)(c->covered[0] + ((left <= 0) ? 1U : 0U));
    }
}

sva_flow_cover_result_t sva_flow_cover(sva_planner_priv_t* priv, const sva_mission_t* m,
                                       sva_plan_t* plan, int64_t covered, uint64_t budget,
                                       uint16_t* nodes)
{
    sva_flow_work_t* w = &priv->flow;
    sva_flow_cover_t* c = &w->cover;
    const uint16_t n = m->target_count;
    if (covered >= (int64_t)n) {
        return SVA_FLOW_COVER_PROVEN;  // nothing is left to cover
    }
    uint16_t uavs = 0U;
    if (((int32_t)n > (int32_t)SVA_FLOW_COVER_TARGETS) || !list_uavs(c, priv, m, &uavs)) {
        return SVA_FLOW_COVER_OPEN;
    }
    for (uint16_t k = 0U; k < uavs; k++) {
        c->freed[k] = (uint8_t)k;
    }
    set_free(c, priv, m, plan, uavs, uavs);
    w->work += fill_fuel_after(c, priv, m);
    return cover_search(priv, m, plan, uavs, (int32_t)covered + 1, budget, nodes);
}

sva_flow_cover_result_t sva_flow_cover_around(sva_planner_priv_t* priv, const sva_mission_t* m,
                                              sva_plan_t* plan, int64_t covered, uint16_t size,
                                              uint64_t budget, uint16_t* nodes)
{
    sva_flow_work_t* w = &priv->flow;
    sva_flow_cover_t* c = &w->cover;
    const uint16_t n = m->target_count;
    uint16_t count = 0U;
    if ((covered >= (int64_t)n) || (size == 0U) || ((int32_t)n > (int32_t)SVA_FLOW_COVER_TARGETS) ||
        !list_uavs(c, priv, m, &count) || (count <= size)) {
        return SVA_FLOW_COVER_OPEN;
    }
    for (uint16_t i = 0U; i < size; i++) {
        c->freed[i] = (uint8_t)i;
    }
    w->work += fill_fuel_after(c, priv, m);
    const uint64_t share = (budget > w->work) ? ((budget - w->work) / NEIGHBOURHOOD_SHARE) : 0U;
    do {
        if (w->work >= budget) {
            return SVA_FLOW_COVER_OPEN;
        }
        set_free(c, priv, m, plan, count, size);
        w->work += (uint64_t)n + (uint64_t)count;
        const uint64_t room = (budget > w->work) ? (budget - w->work) : 0U;
        const uint64_t end = w->work + ((room < share) ? room : share);
        if (cover_search(priv, m, plan, size, (int32_t)covered + 1, end, nodes) ==
            SVA_FLOW_COVER_FOUND) {
            return SVA_FLOW_COVER_FOUND;
        }
    } while (cover_advance(c->freed, (uint8_t)size, (uint8_t)count));
    return SVA_FLOW_COVER_OPEN;
}

#endif
