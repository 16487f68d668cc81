// flow_repair.c -- flow's repair: any routes (a rounded relaxation, a dive's fixed
// routes, a ruined plan) made a plan, improved by local search, and offered to the
// incumbent (DESIGN.md section 8).
//
// The repair: drop every target served by fewer than `need` UAVs; while a route breaks
// its fuel (or SVA_MAX_ROUTE_TARGETS), drop from every route the target whose removal
// shortens that route most; insert each uncovered target (a large mission's round: its
// strings' first), in (start, end, id) order, at the cheapest time- and fuel-feasible
// place of its `need` cheapest UAVs, or leave it out (flow_insert.c); then the local
// search below. Removing a target keeps a route feasible in time (triangle
// inequality), so every result is a plan. The plan under construction lives in the
// caller's sva_plan_t (its routes and priv->target_served), as the other algorithms
// build theirs. The local search is here so that the compiler can fold it into the
// repair's frame: flow's worst stack path runs through it (docs/embedded.md).
//
// Local search: move one UAV's visit to another UAV, swap two UAVs' visits (each in
// the other's slot), swap two routes' tails, or trade a covered target for an
// uncovered one of the same need, whenever the plan gets shorter. First improvement;
// passes until none helps, at most sva_flow_local_passes (flow.h), and no new pass once
// a call has used w->local_work. Coverage never changes; every step keeps a plan.
#include "flow.h"

static bool serves(const sva_route_t* r, uint16_t t)
{
    for (uint16_t k = 0U; k < r->target_count; k++) {
        if (r->targets[k] == t) {
            return true;
        }
    }
    return false;
}

// Puts target t back at position k of route u (undoing remove_at).
static void put_back(const sva_mission_t* m, sva_flow_work_t* w, sva_route_t* r, uint16_t u,
                     uint16_t k, uint16_t t)
{
    w->insert_pos[u] = k;
    w->insert_delta[u] = 0;
    sva_flow_insert_at(w, r, u, t);
    w->route_cells[u] = sva_route_cells(m, u, r);
}

// Moves the k-th visit of route a to another UAV when that saves cells.
static bool relocate(sva_flow_work_t* w, const sva_mission_t* m, sva_plan_t* plan, uint16_t a,
                     uint16_t k)
{
    sva_route_t* ra = &plan->routes[a];
    const uint16_t t = ra->targets[k];
    const int64_t saving = sva_flow_stop_saving(m, a, ra, k);
    for (uint16_t b = 0U; b < m->uav_count; b++) {
        sva_route_t* rb = &plan->routes[b];
        w->work += 1U + rb->target_count;
        if ((b == a) || rb->stranded || serves(rb, t) || !sva_flow_best_place(w, m, plan, b, t) ||
            (w->insert_delta[b] >= saving)) {
            continue;
        }
        sva_flow_remove_at(m, w, ra, a, k);
        sva_flow_insert_at(w, rb, b, t);
        return true;
    }
    return false;
}

// Swaps the k-th visit of route a with the j-th of route b, each taking the other's
// slot, when that saves cells.
static bool swap_pair(sva_flow_work_t* w, const sva_mission_t* m, sva_plan_t* plan, uint16_t a,
                      uint16_t k, uint16_t b, uint16_t j)
{
    sva_route_t* ra = &plan->routes[a];
    sva_route_t* rb = &plan->routes[b];
    const uint16_t s = ra->targets[k];
    const uint16_t t = rb->targets[j];
    w->work++;
    int64_t da = 0;
    int64_t db = 0;
    if (!sva_flow_slot_delta(m, a, ra, k, &m->targets[t], &da) ||
        !sva_flow_slot_delta(m, b, rb, j, &m->targets[s], &db) || ((da + db) >= 0) ||
        !sva_flow_fits(m, a, w->route_cells[a] + da, ra->target_count) ||
        !sva_flow_fits(m, b, w->route_cells[b] + db, rb->target_count) || serves(ra, t) ||
        serves(rb, s)) {
        return false;
    }
    ra->targets[k] = t;
    rb->targets[j] = s;
    w->route_cells[a] += da;
    w->route_cells[b] += db;
    sva_flow_changed(w, a, ra, k);
    sva_flow_changed(w, b, rb, j);
    return true;
}

// Swaps the k-th visit of route a with a visit of a later route when that saves cells.
static bool swap(sva_flow_work_t* w, const sva_mission_t* m, sva_plan_t* plan, uint16_t a,
                 uint16_t k)
{
    for (uint16_t b = (uint16_t)(a + 1U); b < m->uav_count; b++) {
        if (plan->routes[b].stranded) {
            continue;
        }
        for (uint16_t j = 0U; j < plan->routes[b].target_count; j++) {
            if (swap_pair(w, m, plan, a, k, b, j)) {
                return true;
            }
        }
    }
    return false;
}

static int64_t plan_cells(const sva_flow_work_t* w, const sva_mission_t* m)
{
    int64_t cells = 0;
    for (uint16_t u = 0U; u < m->uav_count; u++) {
        cells += w->route_cells[u];
    }
    return cells;
}

// Trade: covered target s gives way to an uncovered target t of the same need, served
// by its `need` cheapest UAVs, when that saves cells (coverage unchanged).
static bool trade(sva_planner_priv_t* priv, const sva_mission_t* m, sva_plan_t* plan, uint16_t s)
{
    sva_flow_work_t* w = &priv->flow;
    const int32_t need = m->targets[s].need;
    for (uint16_t t = 0U; t < m->target_count; t++) {
        if ((priv->target_served[t] != 0U) || (m->targets[t].need != need)) {
            continue;
        }
        w->work += (uint64_t)m->uav_count * 4U;
        const int64_t before = plan_cells(w, m);
        for (uint16_t u = 0U; u < m->uav_count; u++) {
            const sva_route_t* r = &plan->routes[u];
            w->trade_pos[u] = SVA_FLOW_ROUTE_END;
            for (uint16_t k = 0U; k < r->target_count; k++) {
                w->trade_pos[u] = (r->targets[k] == s) ? k : w->trade_pos[u];
            }
        }
        sva_flow_remove_target(priv, m, plan, s);
        sva_flow_try_insert(priv, m, plan, t);
        if ((priv->target_served[t] != 0U) && (plan_cells(w, m) < before)) {
            return true;
        }
        if (priv->target_served[t] != 0U) {
            sva_flow_remove_target(priv, m, plan, t);
        }
        for (uint16_t u = 0U; u < m->uav_count; u++) {
            if (w->trade_pos[u] != SVA_FLOW_ROUTE_END) {
                put_back(m, w, &plan->routes[u], u, w->trade_pos[u], s);
            }
        }
        priv->target_served[s] = (uint16_t)need;
    }
    return false;
}

// Cells of route u's pieces: pre[i] from the UAV's start to its i-th target (pre[0] = 0),
// post[i] from its i-th target on to the depot (post[n] = 0).
static void piece_cells(const sva_mission_t* m, uint16_t u, const sva_route_t* r, int32_t* pre,
                        int32_t* post)
{
    int32_t x = m->uavs[u].x;
    int32_t y = m->uavs[u].y;
    pre[0] = 0;
    for (uint16_t k = 0U; k < r->target_count; k++) {
        const sva_target_t* t = &m->targets[r->targets[k]];
        pre[k + 1U] = pre[k] + sva_distance(x, y, t->x, t->y);
        x = t->x;
        y = t->y;
    }
    post[r->target_count] = 0;
    x = m->depot_x;
    y = m->depot_y;
    for (uint16_t k = r->target_count; k > 0U; k--) {
        const sva_target_t* t = &m->targets[r->targets[k - 1U]];
        post[k - 1U] = post[k] + sva_distance(t->x, t->y, x, y);
        x = t->x;
        y = t->y;
    }
}

// The route UAV u would fly taking ra's first i targets, then rb's from j on (pieces'
// cells from piece_cells): its cells, or -1 if the joint breaks time.
static int64_t spliced_cells(const sva_mission_t* m, uint16_t u, const sva_route_t* ra, uint16_t i,
                             const int32_t* pre_a, const sva_route_t* rb, uint16_t j,
                             const int32_t* post_b)
{
    int32_t x = 0;
    int32_t y = 0;
    int64_t free_at = 0;
    sva_flow_leg_ends(m, u, ra, i, &x, &y, &free_at);
    int32_t nx = m->depot_x;
    int32_t ny = m->depot_y;
    if (j < rb->target_count) {
        const sva_target_t* next = &m->targets[rb->targets[j]];
        if (!sva_flow_arrives_in_time(m, free_at, x, y, next)) {
            return -1;
        }
        nx = next->x;
        ny = next->y;
    }
    return (int64_t)pre_a[i] + sva_distance(x, y, nx, ny) + post_b[j];
}

// No target both in ra's first i and in rb's from j on (needs above 1).
static bool splice_distinct(const sva_route_t* ra, uint16_t i, const sva_route_t* rb, uint16_t j)
{
    for (uint16_t k = 0U; k < i; k++) {
        for (uint16_t l = j; l < rb->target_count; l++) {
            if (ra->targets[k] == rb->targets[l]) {
                return false;
            }
        }
    }
    return true;
}

// Cut (i, j) of routes a and b (pieces' cells in piece_pre/post[0] for a, [1] for b):
// a keeps its first i targets and takes b's from j on, b the other way round, when the
// result is a plan and shorter than `before` cells.
static bool cut_saves(sva_flow_work_t* w, const sva_mission_t* m, sva_plan_t* plan, uint16_t a,
                      uint16_t b, uint16_t i, uint16_t j, int64_t before)
{
    sva_route_t* ra = &plan->routes[a];
    sva_route_t* rb = &plan->routes[b];
    const uint16_t na = (uint16_t)(i + (rb->target_count - j));
    const uint16_t nb = (uint16_t)(j + (ra->target_count - i));
    const int64_t ca = spliced_cells(m, a, ra, i, w->piece_pre[0], rb, j, w->piece_post[1]);
    const int64_t cb =
        (ca < 0) ? -1 : spliced_cells(m, b, rb, j, w->piece_pre[1], ra, i, w->piece_post[0]);
    if ((cb < 0) || ((ca + cb) >= before) || !sva_flow_fits(m, a, ca, na) ||
        !sva_flow_fits(m, b, cb, nb) || !splice_distinct(ra, i, rb, j) ||
        !splice_distinct(rb, j, ra, i)) {
        return false;
    }
    const uint16_t tail = (uint16_t)(ra->target_count - i);
    for (uint16_t k = 0U; k < tail; k++) {
        w->spare_route[k] = ra->targets[i + k];
    }
    for (uint16_t k = j; k < rb->target_count; k++) {
        ra->targets[i + (k - j)] = rb->targets[k];
    }
    for (uint16_t k = 0U; k < tail; k++) {
        rb->targets[j + k] = w->spare_route[k];
    }
    ra->target_count = na;
    rb->target_count = nb;
    w->route_cells[a] = ca;
    w->route_cells[b] = cb;
    sva_flow_changed(w, a, ra, i);
    sva_flow_changed(w, b, rb, j);
    return true;
}

#if SVA_FLOW_LARGE
// When route u is free after its first i targets (sva_flow_leg_ends' free_at).
static int64_t free_after(const sva_mission_t* m, uint16_t u, const sva_route_t* r, uint16_t i)
{
    return (i == 0U) ? m->uavs[u].ready_at_ticks : m->targets[r->targets[i - 1U]].end_ticks;
}
#endif

// Tail exchange: routes a and b swap everything after a cut each (a keeps its first i
// targets and takes b's from j on; b the other way round) when that saves cells.
static bool exchange_tails(sva_flow_work_t* w, const sva_mission_t* m, sva_plan_t* plan, uint16_t a,
                           uint16_t b)
{
    const sva_route_t* ra = &plan->routes[a];
    const sva_route_t* rb = &plan->routes[b];
    const int64_t before = w->route_cells[a] + w->route_cells[b];
    piece_cells(m, a, ra, w->piece_pre[0], w->piece_post[0]);
    piece_cells(m, b, rb, w->piece_pre[1], w->piece_post[1]);
    const uint16_t la = ra->target_count;
    const uint16_t lb = rb->target_count;
    // Every cut pair (i, j) counts as one unit of work, but where missions can be large
    // only those that can meet time are evaluated: routes keep time order, so b's stop j
    // is reachable after a's first i only if it starts after they end (from j_lo on),
    // and a's stop i after b's first j only if b is free by its start (up to a j that
    // only grows with i). The plans are the same either way.
    w->work += (uint32_t)la + lb;
#if SVA_FLOW_LARGE
    uint16_t j_lo = 0U;
    for (uint16_t i = 0U; i <= la; i++) {
        const int64_t free_a = free_after(m, a, ra, i);
        while ((j_lo < lb) && (m->targets[rb->targets[j_lo]].start_ticks < free_a)) {
            j_lo++;
        }
        for (uint16_t j = j_lo; j <= lb; j++) {
            if ((i < la) && (free_after(m, b, rb, j) > m->targets[ra->targets[i]].start_ticks)) {
                break;  // and every later cut of b is free later still
            }
#else
    for (uint16_t i = 0U; i <= la; i++) {
        for (uint16_t j = 0U; j <= lb; j++) {
            w->work++;
#endif
            if (cut_saves(w, m, plan, a, b, i, j, before)) {
#if SVA_FLOW_LARGE
                w->work += ((uint64_t)i * ((uint64_t)lb + 1U)) + j + 1U;
#endif
                return true;
            }
        }
    }
#if SVA_FLOW_LARGE
    w->work += ((uint64_t)la + 1U) * ((uint64_t)lb + 1U);
#endif
    return false;
}

#if SVA_FLOW_GRANULAR
// Granular moves (ruin and recreate on missions past SVA_FLOW_LARGE_FROM targets):
// a visit meets only the routes that serve one of its SVA_FLOW_NEAR most related
// targets (w->near, flow_ruin.c), found through w->route_of / w->pos_of, an index of
// the routes rebuilt at the start of the local search and after each move.

static void index_route(sva_flow_work_t* w, const sva_mission_t* m, const sva_plan_t* plan,
                        uint16_t u)
{
    const sva_route_t* r = &plan->routes[u];
    piece_cells(m, u, r, w->piece_pre[0], w->piece_post[0]);
    for (uint16_t k = 0U; k < r->target_count; k++) {
        w->route_of[r->targets[k]] = u;
        w->pos_of[r->targets[k]] = k;
        w->lead_of[r->targets[k]] = w->piece_pre[0][k + 1U];
        w->post_of[r->targets[k]] = w->piece_post[0][k];
    }
}

// Route r's pieces at cut i from the index, into entry i of the scratch pieces `side`
// (what cut_saves reads): up to its i-th stop, and from it on.
static void indexed_pieces(sva_flow_work_t* w, const sva_route_t* r, uint16_t i, uint16_t side)
{
    w->piece_pre[side][i] = (i == 0U) ? 0 : w->lead_of[r->targets[i - 1U]];
    w->piece_post[side][i] = (i == r->target_count) ? 0 : w->post_of[r->targets[i]];
}

// Where target v is served (one of its routes when its need is above 1); false if the
// index is stale for v (v no longer served there), or v's route is a or stranded.
static bool located(const sva_flow_work_t* w, const sva_mission_t* m, const sva_plan_t* plan,
                    uint16_t v, uint16_t a, uint16_t* b, uint16_t* j)
{
    const uint16_t u = w->route_of[v];
    if ((u >= m->uav_count) || (u == a) || plan->routes[u].stranded) {
        return false;
    }
    const sva_route_t* r = &plan->routes[u];
    *b = u;
    *j = w->pos_of[v];
    return (*j < r->target_count) && (r->targets[*j] == v);
}

// Whether the index holds route u's pieces around cut i: a target of need above 1 may
// be indexed under another of its routes; every other one is where the index says (each
// edit marks the routes it changes, and they are indexed again after it).
static bool fresh(const sva_flow_work_t* w, const sva_route_t* r, uint16_t u, uint16_t i)
{
    return (w->need_max == 1) || (((i == 0U) || (w->route_of[r->targets[i - 1U]] == u)) &&
                                  ((i == r->target_count) || (w->route_of[r->targets[i]] == u)));
}

// A new mark over the UAVs: none tried yet for the visit at hand.
static void new_try(sva_flow_work_t* w, uint16_t uav_count)
{
    w->try_epoch++;
    if (w->try_epoch == 0U) {
        for (uint16_t u = 0U; u < uav_count; u++) {
            w->uav_tried[u] = 0U;
        }
        w->try_epoch = 1U;
    }
}

// Moves route a's k-th visit t, whose removal saves `saving` cells, into route b when
// that saves cells (b untried so far).
static bool relocate_to(sva_flow_work_t* w, const sva_mission_t* m, sva_plan_t* plan, uint16_t a,
                        uint16_t k, uint16_t b, int64_t saving)
{
    sva_route_t* ra = &plan->routes[a];
    sva_route_t* rb = &plan->routes[b];
    const uint16_t t = ra->targets[k];
    if (w->uav_tried[b] == w->try_epoch) {
        return false;
    }
    w->uav_tried[b] = w->try_epoch;
    w->work += 1U + rb->target_count;
    if (!sva_flow_place_may_save(m, plan, b, t, saving) || serves(rb, t) ||
        !sva_flow_best_place(w, m, plan, b, t) || (w->insert_delta[b] >= saving)) {
        return false;
    }
    sva_flow_remove_at(m, w, ra, a, k);
    sva_flow_insert_at(w, rb, b, t);
    return true;
}

// Route a's k-th visit: relocated into a near route or an empty one, swapped with a
// near visit, or its successor changed by a tail exchange with a near visit's route.
static bool granular_move(sva_flow_work_t* w, const sva_mission_t* m, sva_plan_t* plan, uint16_t a,
                          uint16_t k)
{
    const uint16_t t = plan->routes[a].targets[k];
    const int64_t saving = sva_flow_stop_saving(m, a, &plan->routes[a], k);
    uint16_t b = 0U;
    uint16_t j = 0U;
    new_try(w, m->uav_count);
    for (uint16_t n = 0U; n < w->near_count; n++) {
        if (located(w, m, plan, w->near[t][n], a, &b, &j) &&
            (relocate_to(w, m, plan, a, k, b, saving) || swap_pair(w, m, plan, a, k, b, j))) {
            return true;
        }
    }
    for (b = 0U; b < m->uav_count; b++) {
        if ((b != a) && (plan->routes[b].target_count == 0U) && !plan->routes[b].stranded &&
            relocate_to(w, m, plan, a, k, b, saving)) {
            return true;
        }
    }
    for (uint16_t n = 0U; (n < w->near_count) && !plan->routes[a].stranded; n++) {
        if (!located(w, m, plan, w->near[t][n], a, &b, &j)) {
            continue;
        }
        const int64_t before = w->route_cells[a] + w->route_cells[b];
        w->work += 2U;
        // t then the near visit (a takes b's tail from it), or the near visit then t's
        // successor (b takes a's tail after t).
        for (uint16_t c = 0U; c < 2U; c++) {
            const uint16_t i = (uint16_t)(k + 1U);
            const uint16_t jc = (uint16_t)(j + c);
            if (!fresh(w, &plan->routes[a], a, i) || !fresh(w, &plan->routes[b], b, jc)) {
                continue;
            }
            if (!sva_flow_cut_may_save(w, m, plan, a, b, i, jc, before)) {
                continue;
            }
            indexed_pieces(w, &plan->routes[a], i, 0U);
            indexed_pieces(w, &plan->routes[b], jc, 1U);
            if (cut_saves(w, m, plan, a, b, i, jc, before)) {
                return true;
            }
        }
    }
    return false;
}

// The local search's pass over route a with granular moves, from its awake visits
// (each falls asleep as it is looked at, and wakes at an edit next to it; after
// Bentley, 1992); true if one saved cells.
static bool granular_pass(sva_flow_work_t* w, const sva_mission_t* m, sva_plan_t* plan, uint16_t a)
{
    bool better = false;
    for (uint16_t k = 0U; k < plan->routes[a].target_count; k++) {
        const uint16_t t = plan->routes[a].targets[k];
        if (w->visit_awake[t] == 0U) {
            continue;
        }
        w->visit_awake[t] = 0U;
        if (granular_move(w, m, plan, a, k)) {
            better = true;
            for (uint16_t u = 0U; u < m->uav_count; u++) {
                if (w->route_changed[u] != 0U) {
                    index_route(w, m, plan, u);
                }
            }
        }
    }
    return better;
}
#endif

// Whether the local search starts from route a in this pass (and takes its mark).
static bool starts_from(sva_flow_work_t* w, uint16_t a)
{
#if SVA_FLOW_GRANULAR
    if (!w->local_changed_only) {
        return true;
    }
    const bool changed = w->route_changed[a] != 0U;
    w->route_changed[a] = 0U;
    return changed;
#else
    (void)w;
    (void)a;
    return true;
#endif
}

static void local_search(sva_planner_priv_t* priv, const sva_mission_t* m, sva_plan_t* plan)
{
    sva_flow_work_t* w = &priv->flow;
    const uint64_t stop = w->work + w->local_work;
#if SVA_FLOW_GRANULAR
    const bool granular = w->local_changed_only;
#endif
    bool better = true;
    const uint32_t passes = sva_flow_local_passes(w);
    for (uint32_t pass = 0U; better && (pass < passes) && (w->work < stop); pass++) {
        better = false;
#if SVA_FLOW_GRANULAR
        // The index, fresh for the pass (trades below change routes too).
        for (uint16_t u = 0U; granular && (u < m->uav_count); u++) {
            index_route(w, m, plan, u);
        }
#endif
        for (uint16_t a = 0U; a < m->uav_count; a++) {
            if (!starts_from(w, a)) {
                continue;
            }
#if SVA_FLOW_GRANULAR
            if (granular) {
                better = granular_pass(w, m, plan, a) || better;
                continue;
            }
#endif
            for (uint16_t k = 0U; k < plan->routes[a].target_count; k++) {
                if (relocate(w, m, plan, a, k) || swap(w, m, plan, a, k)) {
                    better = true;
                }
            }
            for (uint16_t b = (uint16_t)(a + 1U); (b < m->uav_count) && !plan->routes[a].stranded;
                 b++) {
                if (!plan->routes[b].stranded && exchange_tails(w, m, plan, a, b)) {
                    better = true;
                }
            }
        }
#if SVA_FLOW_LARGE
        // Trades need an uncovered target: without one, no scan of every pair.
        const bool open = sva_flow_uncovered_left(priv, m);
#else
        const bool open = true;  // a small profile's scan is short, and keeps the flash
#endif
        for (uint16_t s = 0U; open && (s < m->target_count); s++) {
            if (((int32_t)priv->target_served[s] == m->targets[s].need) &&
                trade(priv, m, plan, s)) {
                better = true;
            }
        }
    }
}

void sva_flow_repair(sva_planner_priv_t* priv, const sva_mission_t* m, sva_plan_t* plan,
                     bool polish)
{
    sva_flow_work_t* w = &priv->flow;
    for (uint16_t u = 0U; u < m->uav_count; u++) {
        w->route_cells[u] = sva_route_cells(m, u, &plan->routes[u]);
    }
    for (uint16_t t = 0U; t < m->target_count; t++) {
        if ((priv->target_served[t] > 0U) &&
            ((int32_t)priv->target_served[t] < m->targets[t].need)) {
            sva_flow_remove_target(priv, m, plan, t);
        }
    }
    for (uint16_t u = 0U; u < m->uav_count; u++) {
        sva_route_t* r = &plan->routes[u];
        while ((r->target_count > 0U) && !sva_flow_fits(m, u, w->route_cells[u], r->target_count)) {
            sva_flow_remove_target(priv, m, plan, r->targets[sva_flow_costliest_stop(m, u, r)]);
        }
    }
    sva_flow_insert_ruined(priv, m, plan);  // a large mission's round: its strings first
    for (uint16_t i = 0U; i < m->target_count; i++) {
        const uint16_t t =
            priv->target_order[w->insert_backwards ? ((m->target_count - 1U) - i) : i];
        if (priv->target_served[t] == 0U) {
            sva_flow_try_insert(priv, m, plan, t);
        }
    }
    for (uint16_t i = 0U; i < m->target_count; i++) {
        const uint16_t t = priv->target_order[i];
        if ((priv->target_served[t] == 0U) && (m->targets[t].need == 1)) {
            (void)sva_flow_eject_for(priv, m, plan, t);
        }
    }
    // The plan before its local search, which may trade standing visits for cells.
    sva_flow_offer_standing(priv, m, plan);
    // Local search only for plans within reach of the best: better already, or (when
    // `polish`) at most 1/sva_flow_local_reach of their length worse (flow.h).
    int64_t margin = 0;
    for (uint16_t u = 0U; polish && (u < m->uav_count); u++) {
        margin += w->route_cells[u] / sva_flow_local_reach(w);
    }
    if (w->has_inc && (sva_flow_plan_value(priv, m, plan) >= (w->inc_value + margin))) {
        (void)sva_flow_offer_plan(priv, m, plan);
        return;
    }
    local_search(priv, m, plan);
    for (uint16_t i = 0U; i < m->target_count; i++) {
        const uint16_t t = priv->target_order[i];
        if (priv->target_served[t] == 0U) {
            sva_flow_try_insert(priv, m, plan, t);
        }
    }
    (void)sva_flow_offer_plan(priv, m, plan);
}
