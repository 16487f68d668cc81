// flow_repair.c -- flow's plans: the best plan found so far (the incumbent), and the
// rounding heuristic that turns a relaxation into a plan (DESIGN.md section 7).
//
// Rounding: read each UAV's route off the flow; drop every target served by fewer
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

static bool route_fits(const sva_mission_t* m, uint16_t u, int64_t cells, uint32_t targets)
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
    return route_fits(m, u, cells, n);
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

// Position of the target whose removal shortens route u most (first on ties).
static uint16_t costliest_stop(const sva_mission_t* m, uint16_t u, const sva_route_t* r)
{
    uint16_t best = 0U;
    int64_t best_saving = -1;
    for (uint16_t k = 0U; k < r->target_count; k++) {
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
        const int64_t saving = (int64_t)sva_distance(px, py, t->x, t->y) +
                               sva_distance(t->x, t->y, nx, ny) - sva_distance(px, py, nx, ny);
        if (saving > best_saving) {
            best_saving = saving;
            best = k;
        }
    }
    return best;
}

// Cheapest feasible place for t in route u: sets insert_delta/insert_pos, or false.
static bool best_place(sva_flow_work_t* w, const sva_mission_t* m, const sva_plan_t* plan,
                       uint16_t u, uint16_t t)
{
    const sva_route_t* r = &plan->routes[u];
    const sva_target_t* tg = &m->targets[t];
    bool found = false;
    for (uint16_t p = 0U; p <= r->target_count; p++) {
        int32_t px = 0;
        int32_t py = 0;
        int64_t free_at = 0;
        leg_ends(m, u, r, p, &px, &py, &free_at);
        const int64_t in = sva_distance(px, py, tg->x, tg->y);
        if ((free_at + (in * m->ticks_per_cell)) > tg->start_ticks) {
            continue;
        }
        int32_t nx = m->depot_x;
        int32_t ny = m->depot_y;
        if (p < r->target_count) {
            const sva_target_t* next = &m->targets[r->targets[p]];
            nx = next->x;
            ny = next->y;
            const int64_t out = sva_distance(tg->x, tg->y, nx, ny);
            if ((tg->end_ticks + (out * m->ticks_per_cell)) > next->start_ticks) {
                continue;
            }
        }
        const int64_t delta = in + sva_distance(tg->x, tg->y, nx, ny) - sva_distance(px, py, nx, ny);
        if (!route_fits(m, u, w->route_cells[u] + delta, (uint32_t)r->target_count + 1U)) {
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

void sva_flow_round(sva_planner_priv_t* priv, const sva_mission_t* m, sva_plan_t* plan)
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
        // targets then count as short of their need and are dropped below.
        r->target_count = sva_flow_route(w, u, r->targets, SVA_MAX_ROUTE_TARGETS);
        for (uint16_t k = 0U; k < r->target_count; k++) {
            r->targets[k] = w->copy_target[r->targets[k]];
            priv->target_served[r->targets[k]]++;
        }
        w->route_cells[u] = sva_route_cells(m, u, r);
    }
    for (uint16_t t = 0U; t < m->target_count; t++) {
        if ((priv->target_served[t] > 0U) && ((int32_t)priv->target_served[t] < m->targets[t].need)) {
            remove_target(priv, m, plan, t);
        }
    }
    for (uint16_t u = 0U; u < m->uav_count; u++) {
        sva_route_t* r = &plan->routes[u];
        while ((r->target_count > 0U) && !route_fits(m, u, w->route_cells[u], r->target_count)) {
            remove_target(priv, m, plan, r->targets[costliest_stop(m, u, r)]);
        }
    }
    for (uint16_t i = 0U; i < m->target_count; i++) {
        const uint16_t t = priv->target_order[i];
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
    (void)sva_flow_offer_plan(priv, m, plan);
}
