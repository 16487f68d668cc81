// flow_repair.c -- flow's plans: the best plan found so far (the incumbent), and the
// rounding heuristic that turns a relaxation into a plan (DESIGN.md section 7).
//
// Rounding: read each UAV's route off the flow; then the repair (also used by the
// Lagrangian heuristic, flow_lagrange.c): drop every target served by fewer
// than `need` UAVs; while a route breaks its fuel (or SVA_MAX_ROUTE_TARGETS), drop
// from every route the target whose removal shortens that route most; then insert
// each uncovered target, in (start, end, id) order, at the cheapest time- and
// fuel-feasible place of its `need` cheapest UAVs, or leave it out. Removing a target
// keeps a route feasible in time (triangle inequality), so every result is a plan.
// The plan under construction lives in the caller's sva_plan_t (its routes and
// priv->target_served), exactly as the other algorithms build theirs.
#include "sva_internal.h"

#define ROUTE_END 0xFFFFU

static void leg_ends(const sva_mission_t* m, uint16_t u, const sva_route_t* r, uint16_t p,
                     int32_t* x, int32_t* y, int64_t* free_at)
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

bool sva_flow_fits(const sva_mission_t* m, uint16_t u, int64_t cells, uint32_t targets)
{
    return (targets <= (uint32_t)SVA_MAX_ROUTE_TARGETS) &&
           ((cells + ((int64_t)m->hover_fuel * (int64_t)targets)) <= m->uavs[u].fuel);
}

bool sva_flow_route_fits(const sva_mission_t* m, uint16_t u, const uint16_t* copies,
                         uint16_t n, const sva_flow_work_t* w)
{
    int32_t x = m->uavs[u].x;
    int32_t y = m->uavs[u].y;
    int64_t cells = 0;
    for (uint16_t k = 0U; k < n; k++) {
        const sva_target_t* t = &m->targets[w->copy_target[copies[k]]];
        cells += sva_distance(x, y, t->x, t->y);
        x = t->x;
        y = t->y;
    }
    cells += sva_distance(x, y, m->depot_x, m->depot_y);
    return sva_flow_fits(m, u, cells, n);
}

// ---------------------------------------------------------------------------------
// The incumbent.

static int64_t plan_value(const sva_planner_priv_t* priv, const sva_mission_t* m,
                          const sva_plan_t* plan)
{
    const sva_flow_work_t* w = &priv->flow;
    int64_t value = 0;
    for (uint16_t u = 0U; u < m->uav_count; u++) {
        if (!plan->routes[u].stranded) {
            value += sva_route_cells(m, u, &plan->routes[u]);
        }
    }
    for (uint16_t t = 0U; t < m->target_count; t++) {
        if ((int32_t)priv->target_served[t] == m->targets[t].need) {
            value -= (int64_t)m->targets[t].need * w->copy_reward[w->target_first_copy[t]];
        }
    }
    return value;
}

bool sva_flow_offer_plan(sva_planner_priv_t* priv, const sva_mission_t* m, const sva_plan_t* plan)
{
    sva_flow_work_t* w = &priv->flow;
    const int64_t value = plan_value(priv, m, plan);
    if (w->has_inc && (value >= w->inc_value)) {
        return false;
    }
    for (uint16_t t = 0U; t < m->target_count; t++) {
        w->target_taken[t] = 0U;
    }
    for (uint16_t u = 0U; u < m->uav_count; u++) {
        const sva_route_t* r = &plan->routes[u];
        uint16_t* link = &w->inc_first[u];
        for (uint16_t k = 0U; k < r->target_count; k++) {
            const uint16_t t = r->targets[k];
            const uint16_t c = (uint16_t)(w->target_first_copy[t] + w->target_taken[t]);
            w->target_taken[t]++;
            *link = c;
            link = &w->inc_next[c];
        }
        *link = ROUTE_END;
    }
    w->inc_value = value;
    w->has_inc = true;
    return true;
}

// Whether the incumbent's route from copy a comes before the one from copy b: their
// targets compared in window order (copy ids follow it: flow_graph.c), a route before
// its own extensions, an empty route (ROUTE_END) last.
static bool route_before(const sva_flow_work_t* w, uint16_t a, uint16_t b)
{
    if ((a == ROUTE_END) || (b == ROUTE_END)) {
        return (a != ROUTE_END) && (b == ROUTE_END);
    }
    uint16_t ca = a;
    uint16_t cb = b;
    while ((ca != ROUTE_END) && (cb != ROUTE_END) && (w->copy_target[ca] == w->copy_target[cb])) {
        ca = w->inc_next[ca];
        cb = w->inc_next[cb];
    }
    if ((ca == ROUTE_END) || (cb == ROUTE_END)) {
        return (ca == ROUTE_END) && (cb != ROUTE_END);  // a proper prefix first
    }
    return ca < cb;
}

void sva_flow_canonical_incumbent(sva_planner_priv_t* priv, const sva_mission_t* m)
{
    sva_flow_work_t* w = &priv->flow;
    for (uint16_t i = 0U; i < m->uav_count; i++) {
        const uint16_t a = priv->uav_order[i];
        for (uint16_t j = (uint16_t)(i + 1U); j < m->uav_count; j++) {
            const uint16_t b = priv->uav_order[j];
            if ((w->lagrange.group[a] == w->lagrange.group[b]) && route_before(w, w->inc_first[b], w->inc_first[a])) {
                const uint16_t first = w->inc_first[a];
                w->inc_first[a] = w->inc_first[b];
                w->inc_first[b] = first;
            }
        }
    }
}

void sva_flow_write_incumbent(sva_planner_priv_t* priv, const sva_mission_t* m, sva_plan_t* plan)
{
    const sva_flow_work_t* w = &priv->flow;
    for (uint16_t t = 0U; t < m->target_count; t++) {
        priv->target_served[t] = 0U;
    }
    for (uint16_t u = 0U; u < m->uav_count; u++) {
        sva_route_t* r = &plan->routes[u];
        r->target_count = 0U;
        for (uint16_t c = w->inc_first[u]; c != ROUTE_END; c = w->inc_next[c]) {
            const uint16_t t = w->copy_target[c];
            SVA_ASSERT(r->target_count < SVA_MAX_ROUTE_TARGETS);
            r->targets[r->target_count] = t;
            r->target_count++;
            priv->target_served[t]++;
        }
    }
}

void sva_flow_incumbent(sva_planner_priv_t* priv, const sva_mission_t* m, sva_plan_t* plan, int64_t* cost,
                        int64_t* covered)
{
    sva_flow_write_incumbent(priv, m, plan);
    *cost = 0;
    *covered = 0;
    for (uint16_t u = 0U; u < m->uav_count; u++) {
        if (!plan->routes[u].stranded) {
            *cost += sva_route_cells(m, u, &plan->routes[u]);
        }
    }
    for (uint16_t t = 0U; t < m->target_count; t++) {
        *covered += ((int32_t)priv->target_served[t] == m->targets[t].need) ? 1 : 0;
    }
}

// ---------------------------------------------------------------------------------
// Rounding.

static void remove_target(sva_planner_priv_t* priv, const sva_mission_t* m, sva_plan_t* plan,
                          uint16_t t)
{
    for (uint16_t u = 0U; u < m->uav_count; u++) {
        sva_route_t* r = &plan->routes[u];
        uint16_t kept = 0U;
        for (uint16_t k = 0U; k < r->target_count; k++) {
            if (r->targets[k] != t) {
                r->targets[kept] = r->targets[k];
                kept++;
            }
        }
        if (kept != r->target_count) {
            r->target_count = kept;
            priv->flow.route_cells[u] = sva_route_cells(m, u, r);
        }
    }
    priv->target_served[t] = 0U;
}

// Cells saved by taking the k-th target out of route u.
static int64_t stop_saving(const sva_mission_t* m, uint16_t u, const sva_route_t* r, uint16_t k)
{
    int32_t px = 0;
    int32_t py = 0;
    int64_t free_at = 0;
    leg_ends(m, u, r, k, &px, &py, &free_at);
    const sva_target_t* t = &m->targets[r->targets[k]];
    int32_t nx = m->depot_x;
    int32_t ny = m->depot_y;
    if ((k + 1U) < r->target_count) {
        nx = m->targets[r->targets[k + 1U]].x;
        ny = m->targets[r->targets[k + 1U]].y;
    }
    return (int64_t)sva_distance(px, py, t->x, t->y) + sva_distance(t->x, t->y, nx, ny) -
           sva_distance(px, py, nx, ny);
}

// Position of the target whose removal shortens route u most (first on ties).
static uint16_t costliest_stop(const sva_mission_t* m, uint16_t u, const sva_route_t* r)
{
    uint16_t best = 0U;
    int64_t best_saving = -1;
    for (uint16_t k = 0U; k < r->target_count; k++) {
        const int64_t saving = stop_saving(m, u, r, k);
        if (saving > best_saving) {
            best_saving = saving;
            best = k;
        }
    }
    return best;
}

// Whether a UAV free at free_at in (x, y) reaches target tg by its start.
static bool arrives_in_time(const sva_mission_t* m, int64_t free_at, int32_t x, int32_t y,
                            const sva_target_t* tg)
{
    return (free_at + ((int64_t)sva_distance(x, y, tg->x, tg->y) * m->ticks_per_cell)) <= tg->start_ticks;
}

// Target t flown between where route u is after its first p targets and its stop
// `next` (the depot when next is its length): whether both windows are still met in
// time, and in *cells how much longer the route gets than flying that leg directly.
static bool detour(const sva_mission_t* m, uint16_t u, const sva_route_t* r, uint16_t p, uint16_t next,
                   uint16_t t, int64_t* cells)
{
    int32_t px = 0;
    int32_t py = 0;
    int64_t free_at = 0;
    leg_ends(m, u, r, p, &px, &py, &free_at);
    const sva_target_t* tg = &m->targets[t];
    if (!arrives_in_time(m, free_at, px, py, tg)) {
        return false;
    }
    int32_t nx = m->depot_x;
    int32_t ny = m->depot_y;
    if (next < r->target_count) {
        const sva_target_t* after = &m->targets[r->targets[next]];
        if (!arrives_in_time(m, tg->end_ticks, tg->x, tg->y, after)) {
            return false;
        }
        nx = after->x;
        ny = after->y;
    }
    *cells = (int64_t)sva_distance(px, py, tg->x, tg->y) + sva_distance(tg->x, tg->y, nx, ny) -
             sva_distance(px, py, nx, ny);
    return true;
}

// Cheapest feasible place for t in route u: sets insert_delta/insert_pos, or false.
static bool best_place(sva_flow_work_t* w, const sva_mission_t* m, const sva_plan_t* plan,
                       uint16_t u, uint16_t t)
{
    const sva_route_t* r = &plan->routes[u];
    bool found = false;
    for (uint16_t p = 0U; p <= r->target_count; p++) {
        if ((p > 0U) && (m->targets[r->targets[p - 1U]].end_ticks > m->targets[t].start_ticks)) {
            break;  // routes keep time order: no later place is free by t's start either
        }
        int64_t delta = 0;
        if (!detour(m, u, r, p, p, t, &delta) ||
            !sva_flow_fits(m, u, w->route_cells[u] + delta, (uint32_t)r->target_count + 1U)) {
            continue;
        }
        if (!found || (delta < w->insert_delta[u])) {
            w->insert_delta[u] = delta;
            w->insert_pos[u] = p;
            found = true;
        }
    }
    return found;
}

static void insert_at(sva_flow_work_t* w, sva_route_t* r, uint16_t u, uint16_t t);

static void try_insert(sva_planner_priv_t* priv, const sva_mission_t* m, sva_plan_t* plan,
                       uint16_t t)
{
    sva_flow_work_t* w = &priv->flow;
    int32_t candidates = 0;
    for (uint16_t u = 0U; u < m->uav_count; u++) {
        w->uav_pick[u] = 0U;
        if (!plan->routes[u].stranded && best_place(w, m, plan, u, t)) {
            w->uav_pick[u] = 1U;
            candidates++;
        }
    }
    const int32_t need = m->targets[t].need;
    if (candidates < need) {
        return;
    }
    for (int32_t n = 0; n < need; n++) {
        int32_t pick = -1;
        for (uint16_t u = 0U; u < m->uav_count; u++) {
            if ((w->uav_pick[u] == 1U) &&
                ((pick < 0) || (w->insert_delta[u] < w->insert_delta[pick]))) {
                pick = (int32_t)u;
            }
        }
        SVA_ASSERT(pick >= 0);
        w->uav_pick[pick] = 0U;
        insert_at(w, &plan->routes[pick], (uint16_t)pick, t);
    }
    priv->target_served[t] = (uint16_t)need;
}

static void insert_at(sva_flow_work_t* w, sva_route_t* r, uint16_t u, uint16_t t)
{
    for (uint16_t k = r->target_count; k > w->insert_pos[u]; k--) {
        r->targets[k] = r->targets[k - 1U];
    }
    r->targets[w->insert_pos[u]] = t;
    r->target_count++;
    w->route_cells[u] += w->insert_delta[u];
}

static void remove_at(const sva_mission_t* m, sva_flow_work_t* w, sva_route_t* r, uint16_t u,
                      uint16_t k)
{
    for (uint16_t j = k; (j + 1U) < r->target_count; j++) {
        r->targets[j] = r->targets[j + 1U];
    }
    r->target_count--;
    w->route_cells[u] = sva_route_cells(m, u, r);
}

// Cheapest UAV other than `skip` that can take single-UAV target t; -1 if none.
static int32_t cheapest_taker(sva_flow_work_t* w, const sva_mission_t* m, const sva_plan_t* plan,
                              uint16_t t, int32_t skip)
{
    int32_t pick = -1;
    for (uint16_t v = 0U; v < m->uav_count; v++) {
        if (((int32_t)v != skip) && !plan->routes[v].stranded && best_place(w, m, plan, v, t) &&
            ((pick < 0) || (w->insert_delta[v] < w->insert_delta[pick]))) {
            pick = (int32_t)v;
        }
    }
    return pick;
}

// Ejection: an uncovered single-UAV target t takes the place of a single-UAV target s
// in some route, and s moves to another UAV. Covers one more target or changes nothing.
static bool eject_for(sva_planner_priv_t* priv, const sva_mission_t* m, sva_plan_t* plan, uint16_t t)
{
    sva_flow_work_t* w = &priv->flow;
    for (uint16_t u = 0U; u < m->uav_count; u++) {
        sva_route_t* r = &plan->routes[u];
        for (uint16_t k = 0U; k < r->target_count; k++) {
            const uint16_t s = r->targets[k];
            if (m->targets[s].need != 1) {
                continue;
            }
            remove_at(m, w, r, u, k);
            if (best_place(w, m, plan, u, t)) {
                insert_at(w, r, u, t);
                const int32_t v = cheapest_taker(w, m, plan, s, (int32_t)u);
                if (v >= 0) {
                    insert_at(w, &plan->routes[v], (uint16_t)v, s);
                    priv->target_served[t] = 1U;
                    return true;
                }
                // Undo: t out again.
                for (uint16_t j = 0U; j < r->target_count; j++) {
                    if (r->targets[j] == t) {
                        remove_at(m, w, r, u, j);
                        break;
                    }
                }
            }
            w->insert_pos[u] = k;
            w->insert_delta[u] = 0;
            insert_at(w, r, u, s);
            w->route_cells[u] = sva_route_cells(m, u, r);
        }
    }
    return false;
}

// ---------------------------------------------------------------------------------
// Local search: move one UAV's visit to another UAV, swap two UAVs' visits (each in
// the other's slot), swap two routes' tails, or trade a covered target for an
// uncovered one of the same need, whenever the plan gets shorter. First improvement;
// passes until none helps, at most LOCAL_PASSES, and no new pass once a call has used
// w->local_work. Coverage never changes; every step keeps a plan.

#define LOCAL_PASSES 8U

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
    insert_at(w, r, u, t);
    w->route_cells[u] = sva_route_cells(m, u, r);
}

// Moves the k-th visit of route a to another UAV when that saves cells.
static bool relocate(sva_flow_work_t* w, const sva_mission_t* m, sva_plan_t* plan, uint16_t a, uint16_t k)
{
    sva_route_t* ra = &plan->routes[a];
    const uint16_t t = ra->targets[k];
    const int64_t saving = stop_saving(m, a, ra, k);
    for (uint16_t b = 0U; b < m->uav_count; b++) {
        sva_route_t* rb = &plan->routes[b];
        w->work += 1U + rb->target_count;
        if ((b == a) || rb->stranded || serves(rb, t) || !best_place(w, m, plan, b, t) ||
            (w->insert_delta[b] >= saving)) {
            continue;
        }
        remove_at(m, w, ra, a, k);
        insert_at(w, rb, b, t);
        return true;
    }
    return false;
}

// Whether target t fits the slot of route u's k-th target in time; *delta gets the
// cells the route grows by with t in that slot.
static bool slot_delta(const sva_mission_t* m, uint16_t u, const sva_route_t* r, uint16_t k, uint16_t t,
                       int64_t* delta)
{
    int64_t cells = 0;
    if (!detour(m, u, r, k, (uint16_t)(k + 1U), t, &cells)) {
        return false;
    }
    *delta = cells - stop_saving(m, u, r, k);
    return true;
}

// Swaps the k-th visit of route a with a visit of a later route, each taking the
// other's slot, when that saves cells.
static bool swap(sva_flow_work_t* w, const sva_mission_t* m, sva_plan_t* plan, uint16_t a, uint16_t k)
{
    sva_route_t* ra = &plan->routes[a];
    const uint16_t s = ra->targets[k];
    for (uint16_t b = (uint16_t)(a + 1U); b < m->uav_count; b++) {
        sva_route_t* rb = &plan->routes[b];
        if (rb->stranded) {
            continue;
        }
        for (uint16_t j = 0U; j < rb->target_count; j++) {
            const uint16_t t = rb->targets[j];
            w->work++;
            int64_t da = 0;
            int64_t db = 0;
            if (!slot_delta(m, a, ra, k, t, &da) || !slot_delta(m, b, rb, j, s, &db) || ((da + db) >= 0) ||
                !sva_flow_fits(m, a, w->route_cells[a] + da, ra->target_count) ||
                !sva_flow_fits(m, b, w->route_cells[b] + db, rb->target_count) || serves(ra, t) ||
                serves(rb, s)) {
                continue;
            }
            ra->targets[k] = t;
            rb->targets[j] = s;
            w->route_cells[a] += da;
            w->route_cells[b] += db;
            return true;
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
            w->trade_pos[u] = ROUTE_END;
            for (uint16_t k = 0U; k < r->target_count; k++) {
                w->trade_pos[u] = (r->targets[k] == s) ? k : w->trade_pos[u];
            }
        }
        remove_target(priv, m, plan, s);
        try_insert(priv, m, plan, t);
        if ((priv->target_served[t] != 0U) && (plan_cells(w, m) < before)) {
            return true;
        }
        if (priv->target_served[t] != 0U) {
            remove_target(priv, m, plan, t);
        }
        for (uint16_t u = 0U; u < m->uav_count; u++) {
            if (w->trade_pos[u] != ROUTE_END) {
                put_back(m, w, &plan->routes[u], u, w->trade_pos[u], s);
            }
        }
        priv->target_served[s] = (uint16_t)need;
    }
    return false;
}

// Cells of route u's pieces: pre[i] from the UAV to its i-th target (pre[0] = 0),
// post[i] from its i-th target on to the depot (post[n] = 0).
static void piece_cells(const sva_mission_t* m, uint16_t u, const sva_route_t* r, int32_t* pre,
                        int32_t* post)
{
    int32_t x = m->uavs[u].x;
    int32_t y = m->uavs[u].y;
    pre[0] = 0;
    for (uint16_t k = 0U; k < r->target_count; k++) {
        const sva_target_t* t = &m->targets[r->targets[k]];
        pre[k + 1U] = pre[k] + ((k == 0U) ? 0 : sva_distance(x, y, t->x, t->y));
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
                             const int32_t* pre_a, const sva_route_t* rb, uint16_t j, const int32_t* post_b)
{
    int32_t x = 0;
    int32_t y = 0;
    int64_t free_at = 0;
    leg_ends(m, u, ra, i, &x, &y, &free_at);
    int32_t nx = m->depot_x;
    int32_t ny = m->depot_y;
    if (j < rb->target_count) {
        const sva_target_t* next = &m->targets[rb->targets[j]];
        if (!arrives_in_time(m, free_at, x, y, next)) {
            return -1;
        }
        nx = next->x;
        ny = next->y;
    }
    // pre_a[i] counts from ra's first target; the UAV's first leg is in the joint
    // when i == 0, else it is leg 0 of ra.
    const int64_t first = (i == 0U) ? 0
                                    : sva_distance(m->uavs[u].x, m->uavs[u].y, m->targets[ra->targets[0]].x,
                                                   m->targets[ra->targets[0]].y);
    return first + pre_a[i] + sva_distance(x, y, nx, ny) + post_b[j];
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

// Tail exchange: routes a and b swap everything after a cut each (a keeps its first i
// targets and takes b's from j on; b the other way round) when that saves cells.
static bool exchange_tails(sva_flow_work_t* w, const sva_mission_t* m, sva_plan_t* plan, uint16_t a,
                           uint16_t b)
{
    sva_route_t* ra = &plan->routes[a];
    sva_route_t* rb = &plan->routes[b];
    const int64_t before = w->route_cells[a] + w->route_cells[b];
    piece_cells(m, a, ra, w->piece_pre[0], w->piece_post[0]);
    piece_cells(m, b, rb, w->piece_pre[1], w->piece_post[1]);
    w->work += (uint32_t)ra->target_count + rb->target_count;
    for (uint16_t i = 0U; i <= ra->target_count; i++) {
        for (uint16_t j = 0U; j <= rb->target_count; j++) {
            w->work++;
            const uint16_t na = (uint16_t)(i + (rb->target_count - j));
            const uint16_t nb = (uint16_t)(j + (ra->target_count - i));
            const int64_t ca = spliced_cells(m, a, ra, i, w->piece_pre[0], rb, j, w->piece_post[1]);
            const int64_t cb = (ca < 0) ? -1 : spliced_cells(m, b, rb, j, w->piece_pre[1], ra, i, w->piece_post[0]);
            if ((cb < 0) || ((ca + cb) >= before) || !sva_flow_fits(m, a, ca, na) ||
                !sva_flow_fits(m, b, cb, nb) || !splice_distinct(ra, i, rb, j) ||
                !splice_distinct(rb, j, ra, i)) {
                continue;
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
            return true;
        }
    }
    return false;
}

static void local_search(sva_planner_priv_t* priv, const sva_mission_t* m, sva_plan_t* plan)
{
    sva_flow_work_t* w = &priv->flow;
    const uint64_t stop = w->work + w->local_work;
    bool better = true;
    for (uint32_t pass = 0U; better && (pass < LOCAL_PASSES) && (w->work < stop); pass++) {
        better = false;
        for (uint16_t a = 0U; a < m->uav_count; a++) {
            for (uint16_t k = 0U; k < plan->routes[a].target_count; k++) {
                if (relocate(w, m, plan, a, k) || swap(w, m, plan, a, k)) {
                    better = true;
                }
            }
            for (uint16_t b = (uint16_t)(a + 1U); (b < m->uav_count) && !plan->routes[a].stranded; b++) {
                if (!plan->routes[b].stranded && exchange_tails(w, m, plan, a, b)) {
                    better = true;
                }
            }
        }
        for (uint16_t s = 0U; s < m->target_count; s++) {
            if (((int32_t)priv->target_served[s] == m->targets[s].need) && trade(priv, m, plan, s)) {
                better = true;
            }
        }
    }
}

void sva_flow_repair(sva_planner_priv_t* priv, const sva_mission_t* m, sva_plan_t* plan, bool polish)
{
    sva_flow_work_t* w = &priv->flow;
    for (uint16_t u = 0U; u < m->uav_count; u++) {
        w->route_cells[u] = sva_route_cells(m, u, &plan->routes[u]);
    }
    for (uint16_t t = 0U; t < m->target_count; t++) {
        if ((priv->target_served[t] > 0U) && ((int32_t)priv->target_served[t] < m->targets[t].need)) {
            remove_target(priv, m, plan, t);
        }
    }
    for (uint16_t u = 0U; u < m->uav_count; u++) {
        sva_route_t* r = &plan->routes[u];
        while ((r->target_count > 0U) && !sva_flow_fits(m, u, w->route_cells[u], r->target_count)) {
            remove_target(priv, m, plan, r->targets[costliest_stop(m, u, r)]);
        }
    }
    for (uint16_t i = 0U; i < m->target_count; i++) {
        const uint16_t t = priv->target_order[w->insert_backwards ? ((m->target_count - 1U) - i) : i];
        if (priv->target_served[t] == 0U) {
            try_insert(priv, m, plan, t);
        }
    }
    for (uint16_t i = 0U; i < m->target_count; i++) {
        const uint16_t t = priv->target_order[i];
        if ((priv->target_served[t] == 0U) && (m->targets[t].need == 1)) {
            (void)eject_for(priv, m, plan, t);
        }
    }
    // Local search only for plans within reach of the best: better already, or (when
    // `polish`) at most 1/16 of their length worse.
    int64_t margin = 0;
    for (uint16_t u = 0U; polish && (u < m->uav_count); u++) {
        margin += w->route_cells[u] / 16;
    }
    if (w->has_inc && (plan_value(priv, m, plan) >= (w->inc_value + margin))) {
        (void)sva_flow_offer_plan(priv, m, plan);
        return;
    }
    local_search(priv, m, plan);
    for (uint16_t i = 0U; i < m->target_count; i++) {
        const uint16_t t = priv->target_order[i];
        if (priv->target_served[t] == 0U) {
            try_insert(priv, m, plan, t);
        }
    }
    (void)sva_flow_offer_plan(priv, m, plan);
}

// The current relaxation's routes into *plan, over targets, with priv->target_served.
static void relaxation_routes(sva_planner_priv_t* priv, const sva_mission_t* m, sva_plan_t* plan)
{
    sva_flow_work_t* w = &priv->flow;
    for (uint16_t t = 0U; t < m->target_count; t++) {
        priv->target_served[t] = 0U;
    }
    for (uint16_t u = 0U; u < m->uav_count; u++) {
        sva_route_t* r = &plan->routes[u];
        r->target_count = 0U;
        if (r->stranded) {
            continue;
        }
        // A route longer than SVA_MAX_ROUTE_TARGETS loses its tail here; those
        // targets then count as short of their need and are dropped by the repair.
        r->target_count = sva_flow_route(w, u, r->targets, SVA_MAX_ROUTE_TARGETS);
        for (uint16_t k = 0U; k < r->target_count; k++) {
            r->targets[k] = w->copy_target[r->targets[k]];
            priv->target_served[r->targets[k]]++;
        }
    }
}

void sva_flow_round(sva_planner_priv_t* priv, const sva_mission_t* m, sva_plan_t* plan, bool polish)
{
    relaxation_routes(priv, m, plan);
    sva_flow_repair(priv, m, plan, polish);
}

void sva_flow_take_relaxation(sva_planner_priv_t* priv, const sva_mission_t* m, sva_plan_t* plan)
{
    relaxation_routes(priv, m, plan);
    (void)sva_flow_offer_plan(priv, m, plan);
}

bool sva_flow_pooled_routes(sva_planner_priv_t* priv, const sva_mission_t* m, sva_plan_t* plan)
{
    sva_flow_work_t* w = &priv->flow;
    const uint16_t depot = (uint16_t)(w->uavs + (2U * w->copies));
    bool whole = true;  // no route cut at SVA_MAX_ROUTE_TARGETS
    for (uint16_t t = 0U; t < m->target_count; t++) {
        priv->target_served[t] = 0U;
    }
    for (uint16_t u = 0U; u < m->uav_count; u++) {
        sva_route_t* r = &plan->routes[u];
        r->target_count = 0U;
        // Each unit takes the first arc out of its node that still carries flow, and
        // takes that unit off it: flow conservation leaves one for every unit to come.
        uint16_t v = u;
        while ((v != depot) && !r->stranded) {
            uint16_t next = depot;
            for (uint32_t e = w->out_start[v]; e < w->out_start[v + 1U]; e++) {
                if (w->arc_flow[e] != 0U) {
                    w->arc_flow[e]--;
                    next = w->arc_head[e];
                    break;
                }
            }
            if (next != depot) {
                const uint16_t c = (uint16_t)(next - w->uavs);
                // Past SVA_MAX_ROUTE_TARGETS the route loses its tail, as in
                // relaxation_routes.
                if (r->target_count < (uint16_t)SVA_MAX_ROUTE_TARGETS) {
                    r->targets[r->target_count] = w->copy_target[c];
                    r->target_count++;
                    priv->target_served[w->copy_target[c]]++;
                } else {
                    whole = false;
                }
                next = (uint16_t)(w->uavs + w->copies + c);
            }
            v = next;
        }
        whole = whole && sva_flow_fits(m, u, sva_route_cells(m, u, r), r->target_count);
    }
    for (uint16_t t = 0U; t < m->target_count; t++) {
        const int32_t served = (int32_t)priv->target_served[t];
        whole = whole && ((served == 0) || (served == m->targets[t].need));
    }
    return whole;
}

// ---------------------------------------------------------------------------------
// Ruin and recreate: the incumbent loses a group of related visits, and the repair
// puts a plan back together (uncovered targets inserted in window order, every other
// round in reverse, ejection, local search when within reach, offer). For each group
// size in turn, each covered target s seeds a group: s and the covered targets
// nearest to it (cells between them plus the ticks between their window starts, in
// cells). With need 2 this is how a target short of its second UAV finds one: the
// group's visits leave room. Then swaps: one covered target out, one uncovered in.

#define RUIN_ROUND_UNITS 8U  // work units per round and per target x UAV (insertions)

static int64_t relatedness(const sva_mission_t* m, uint16_t a, uint16_t b)
{
    const sva_target_t* ta = &m->targets[a];
    const sva_target_t* tb = &m->targets[b];
    const int64_t ticks = (int64_t)ta->start_ticks - (int64_t)tb->start_ticks;
    return sva_distance(ta->x, ta->y, tb->x, tb->y) + (((ticks < 0) ? -ticks : ticks) / m->ticks_per_cell);
}

// The incumbent without s and the size - 1 covered targets most related to it.
static void ruin(sva_planner_priv_t* priv, const sva_mission_t* m, sva_plan_t* plan, uint16_t s,
                 uint8_t size)
{
    sva_flow_work_t* w = &priv->flow;
    for (uint16_t u = 0U; u < m->uav_count; u++) {
        w->route_cells[u] = sva_route_cells(m, u, &plan->routes[u]);
    }
    remove_target(priv, m, plan, s);
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
            remove_target(priv, m, plan, (uint16_t)pick);
        }
    }
}

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
    // Not when the coverage is proven and the plan within 1/64 of the bound: the
    // search, with the rest of the budget, may prove it.
    const bool near = (proven_bound >= 0) && ((cost - proven_bound) <= (cost / 64));
    const uint64_t rest = ((end > w->work) && !near) ? (end - w->work) : 0U;
    const uint64_t budget = w->work + (rest - (rest / 4U));
    const uint64_t round_units = (uint64_t)m->target_count * (uint64_t)m->uav_count * RUIN_ROUND_UNITS;
    // *plan holds the incumbent whenever a round is chosen (sva_flow_incumbent above,
    // then a write after each round).
    for (size_t i = 0U; i < (sizeof(ruin_sizes) / sizeof(ruin_sizes[0])); i++) {
        for (uint16_t s = 0U; (s < m->target_count) && (w->work < budget); s++) {
            if ((int32_t)priv->target_served[s] == m->targets[s].need) {
                ruin(priv, m, plan, s, ruin_sizes[i]);
                w->insert_backwards = ((s + i) % 2U) == 1U;
                sva_flow_repair(priv, m, plan, true);
                w->insert_backwards = false;
                w->work += round_units;
                plan->stats.flow_ruin_rounds++;
                sva_flow_write_incumbent(priv, m, plan);
            }
        }
    }
    // Swaps: a covered target c leaves, an uncovered target t goes in first (all its
    // need at once), and the repair puts the rest back. With need 2 a plan may cover
    // the right number of targets but the wrong ones; groups reinserted in window
    // order rarely change which.
    for (uint16_t c = 0U; (c < m->target_count) && (w->work < budget); c++) {
        for (uint16_t t = 0U; (t < m->target_count) && (w->work < budget); t++) {
            if (((int32_t)priv->target_served[c] == m->targets[c].need) && (priv->target_served[t] == 0U)) {
                ruin(priv, m, plan, c, 1U);
                try_insert(priv, m, plan, t);
                if (priv->target_served[t] != 0U) {
                    sva_flow_repair(priv, m, plan, true);
                    plan->stats.flow_ruin_rounds++;
                }
                w->work += round_units;
                sva_flow_write_incumbent(priv, m, plan);
            }
        }
    }
    return false;
}
