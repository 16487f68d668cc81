// flow_insert.c -- the edits every flow heuristic makes to the routes of a plan under
// construction (the caller's sva_plan_t, with priv->target_served and
// priv->flow.route_cells): take a target out, find the cheapest time- and
// fuel-feasible place for one and put it there, and eject a single-UAV target for an
// uncovered one (DESIGN.md section 8). Removing a target keeps a route feasible in
// time (triangle inequality).
#include "flow.h"

void sva_flow_remove_target(sva_planner_priv_t* priv, const sva_mission_t* m, sva_plan_t* plan,
                            uint16_t t)
{
    for (uint16_t u = 0U; u < m->uav_count; u++) {
        sva_route_t* r = &plan->routes[u];
        uint16_t k = 0U;
        while (k < r->target_count) {
            if (r->targets[k] == t) {
                sva_flow_remove_at(m, &priv->flow, r, u, k);
            } else {
                k++;
            }
        }
    }
    priv->target_served[t] = 0U;
}

// Cells saved by taking the k-th target out of route u.
int64_t sva_flow_stop_saving(const sva_mission_t* m, uint16_t u, const sva_route_t* r, uint16_t k)
{
    int32_t px = 0;
    int32_t py = 0;
    int64_t free_at = 0;
    sva_flow_leg_ends(m, u, r, k, &px, &py, &free_at);
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
uint16_t sva_flow_costliest_stop(const sva_mission_t* m, uint16_t u, const sva_route_t* r)
{
    uint16_t best = 0U;
    int64_t best_saving = -1;
    for (uint16_t k = 0U; k < r->target_count; k++) {
        const int64_t saving = sva_flow_stop_saving(m, u, r, k);
        if (saving > best_saving) {
            best_saving = saving;
            best = k;
        }
    }
    return best;
}

// Whether a UAV free at free_at in (x, y) reaches target tg by its start.
bool sva_flow_arrives_in_time(const sva_mission_t* m, int64_t free_at, int32_t x, int32_t y,
                              const sva_target_t* tg)
{
    return (free_at + ((int64_t)sva_distance(x, y, tg->x, tg->y) * m->ticks_per_cell)) <=
           tg->start_ticks;
}

// Target t flown between where route u is after its first p targets and its stop
// `next` (the depot when next is its length): whether both windows are still met in
// time, and in *cells how much longer the route gets than flying that leg directly.
static bool place_detour(const sva_mission_t* m, uint16_t u, const sva_route_t* r, uint16_t p,
                         uint16_t next, uint16_t t, int64_t* cells)
{
    int32_t px = 0;
    int32_t py = 0;
    int64_t free_at = 0;
    sva_flow_leg_ends(m, u, r, p, &px, &py, &free_at);
    const sva_target_t* tg = &m->targets[t];
    if (!sva_flow_arrives_in_time(m, free_at, px, py, tg)) {
        return false;
    }
    int32_t nx = m->depot_x;
    int32_t ny = m->depot_y;
    if (next < r->target_count) {
        const sva_target_t* after = &m->targets[r->targets[next]];
        if (!sva_flow_arrives_in_time(m, tg->end_ticks, tg->x, tg->y, after)) {
            return false;
        }
        nx = after->x;
        ny = after->y;
    }
    *cells = (int64_t)sva_distance(px, py, tg->x, tg->y) + sva_distance(tg->x, tg->y, nx, ny) -
             sva_distance(px, py, nx, ny);
    return true;
}

bool sva_flow_slot_delta(const sva_mission_t* m, uint16_t u, const sva_route_t* r, uint16_t k,
                         const sva_target_t* t, int64_t* delta)
{
    const sva_target_t* s = &m->targets[r->targets[k]];
    int32_t px = 0;
    int32_t py = 0;
    int64_t free_at = 0;
    sva_flow_leg_ends(m, u, r, k, &px, &py, &free_at);
    const int64_t in = sva_distance(px, py, t->x, t->y);
    if ((free_at + (in * m->ticks_per_cell)) > t->start_ticks) {
        return false;
    }
    const sva_target_t* after =
        ((k + 1U) < r->target_count) ? &m->targets[r->targets[k + 1U]] : NULL;
    const int32_t nx = (after != NULL) ? after->x : m->depot_x;
    const int32_t ny = (after != NULL) ? after->y : m->depot_y;
    const int64_t out = sva_distance(t->x, t->y, nx, ny);
    if ((after != NULL) && ((t->end_ticks + (out * m->ticks_per_cell)) > after->start_ticks)) {
        return false;
    }
    // The leg that skips the slot is in both the detour and the saving: it cancels out.
    *delta =
        (in + out) - ((int64_t)sva_distance(px, py, s->x, s->y) + sva_distance(s->x, s->y, nx, ny));
    return true;
}

// Cheapest feasible place for t in route u: sets insert_delta/insert_pos, or false.
bool sva_flow_best_place(sva_flow_work_t* w, const sva_mission_t* m, const sva_plan_t* plan,
                         uint16_t u, uint16_t t)
{
    const sva_route_t* r = &plan->routes[u];
    bool found = false;
    // Routes keep time order: no place before the first stop that starts after t ends
    // (skipped at once where missions can be large; the same places either way).
    uint16_t first = 0U;
#if SVA_FLOW_LARGE
    while ((first < r->target_count) &&
           (m->targets[r->targets[first]].start_ticks < m->targets[t].end_ticks)) {
        first++;
    }
#endif
    for (uint16_t p = first; p <= r->target_count; p++) {
        if ((p > 0U) && (m->targets[r->targets[p - 1U]].end_ticks > m->targets[t].start_ticks)) {
            break;  // routes keep time order: no later place is free by t's start either
        }
        int64_t delta = 0;
        if (!place_detour(m, u, r, p, p, t, &delta) ||
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

void sva_flow_try_insert(sva_planner_priv_t* priv, const sva_mission_t* m, sva_plan_t* plan,
                         uint16_t t)
{
    sva_flow_work_t* w = &priv->flow;
    int32_t candidates = 0;
    for (uint16_t u = 0U; u < m->uav_count; u++) {
        w->uav_pick[u] = 0U;
        if (!plan->routes[u].stranded && sva_flow_best_place(w, m, plan, u, t)) {
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
        sva_flow_insert_at(w, &plan->routes[pick], (uint16_t)pick, t);
    }
    priv->target_served[t] = (uint16_t)need;
}

#if SVA_FLOW_GRANULAR
void sva_flow_insert_ruined(sva_planner_priv_t* priv, const sva_mission_t* m, sva_plan_t* plan)
{
    sva_flow_work_t* w = &priv->flow;
    for (uint16_t i = 0U; i < w->ruined_count; i++) {
        if (priv->target_served[w->ruined[i]] == 0U) {
            sva_flow_try_insert(priv, m, plan, w->ruined[i]);
        }
    }
    w->ruined_count = 0U;
}
#endif

void sva_flow_insert_at(sva_flow_work_t* w, sva_route_t* r, uint16_t u, uint16_t t)
{
    for (uint16_t k = r->target_count; k > w->insert_pos[u]; k--) {
        r->targets[k] = r->targets[k - 1U];
    }
    r->targets[w->insert_pos[u]] = t;
    r->target_count++;
    w->route_cells[u] += w->insert_delta[u];
    sva_flow_changed(w, u, r, w->insert_pos[u]);
}

void sva_flow_remove_at(const sva_mission_t* m, sva_flow_work_t* w, sva_route_t* r, uint16_t u,
                        uint16_t k)
{
    w->route_cells[u] -= sva_flow_stop_saving(m, u, r, k);
    for (uint16_t j = k; (j + 1U) < r->target_count; j++) {
        r->targets[j] = r->targets[j + 1U];
    }
    r->target_count--;
    sva_flow_changed(w, u, r, k);
}

// Cheapest UAV other than `skip` that can take single-UAV target t; -1 if none.
static int32_t cheapest_taker(sva_flow_work_t* w, const sva_mission_t* m, const sva_plan_t* plan,
                              uint16_t t, int32_t skip)
{
    int32_t pick = -1;
    for (uint16_t v = 0U; v < m->uav_count; v++) {
        if (((int32_t)v != skip) && !plan->routes[v].stranded &&
            sva_flow_best_place(w, m, plan, v, t) &&
            ((pick < 0) || (w->insert_delta[v] < w->insert_delta[pick]))) {
            pick = (int32_t)v;
        }
    }
    return pick;
}

// Ejection: an uncovered single-UAV target t takes the place of a single-UAV target s
// in some route, and s moves to another UAV. Covers one more target or changes nothing.
bool sva_flow_eject_for(sva_planner_priv_t* priv, const sva_mission_t* m, sva_plan_t* plan,
                        uint16_t t)
{
    sva_flow_work_t* w = &priv->flow;
    for (uint16_t u = 0U; u < m->uav_count; u++) {
        sva_route_t* r = &plan->routes[u];
        for (uint16_t k = 0U; k < r->target_count; k++) {
            const uint16_t s = r->targets[k];
            if (m->targets[s].need != 1) {
                continue;
            }
            sva_flow_remove_at(m, w, r, u, k);
            if (sva_flow_best_place(w, m, plan, u, t)) {
                sva_flow_insert_at(w, r, u, t);
                const int32_t v = cheapest_taker(w, m, plan, s, (int32_t)u);
                if (v >= 0) {
                    sva_flow_insert_at(w, &plan->routes[v], (uint16_t)v, s);
                    priv->target_served[t] = 1U;
                    return true;
                }
                // Undo: t out again.
                for (uint16_t j = 0U; j < r->target_count; j++) {
                    if (r->targets[j] == t) {
                        sva_flow_remove_at(m, w, r, u, j);
                        break;
                    }
                }
            }
            w->insert_pos[u] = k;
            w->insert_delta[u] = 0;
            sva_flow_insert_at(w, r, u, s);
            w->route_cells[u] = sva_route_cells(m, u, r);
        }
    }
    return false;
}
