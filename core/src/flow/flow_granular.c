// flow_granular.c -- the granular local search's quick tests (large missions' rounds,
// flow_repair.c): whether a relocation or a tail exchange can save cells,
// from the stops around the places they touch (and, for an exchange, the index of the
// routes' pieces), with time checked and fuel not. Most moves fail them; the few that
// pass are evaluated and made by the repair's own moves, so the moves made and the
// work charged are the same as without the tests (DESIGN.md section 8).
#include "flow.h"

#if SVA_FLOW_GRANULAR

// Route r of UAV u cut after its first i targets, to go on with route `next`'s stops
// from j on: the cells up to the cut (its first target's leg, then the pieces) plus the
// joint, or -1 when the joint breaks time. pre_i: cells from r's first target to its
// i-th (the scratch pieces).
static inline int64_t cut_cells(const sva_mission_t* m, uint16_t u, const sva_route_t* r,
                                uint16_t i, int32_t pre_i, const sva_route_t* next, uint16_t j)
{
    const sva_uav_t* uav = &m->uavs[u];
    int32_t x = uav->x;
    int32_t y = uav->y;
    int64_t free_at = uav->ready_at_ticks;
    int64_t cells = 0;
    if (i > 0U) {
        const sva_target_t* first = &m->targets[r->targets[0]];
        const sva_target_t* last = &m->targets[r->targets[i - 1U]];
        cells = (int64_t)sva_distance(x, y, first->x, first->y) + pre_i;
        x = last->x;
        y = last->y;
        free_at = last->end_ticks;
    }
    if (j >= next->target_count) {
        return cells + sva_distance(x, y, m->depot_x, m->depot_y);
    }
    const sva_target_t* to = &m->targets[next->targets[j]];
    const int64_t joint = sva_distance(x, y, to->x, to->y);
    if ((free_at + (joint * m->ticks_per_cell)) > to->start_ticks) {
        return -1;
    }
    return cells + joint;
}

// Target tg flown after route r's first p targets (UAV u) and before its stop `next`
// (the depot at its end): the detour in *cells, as sva_flow_detour finds it, and
// whether both windows are met.
static inline bool detour(const sva_mission_t* m, uint16_t u, const sva_route_t* r, uint16_t p,
                          uint16_t next, const sva_target_t* tg, int64_t* cells)
{
    int32_t px = m->uavs[u].x;
    int32_t py = m->uavs[u].y;
    int64_t free_at = m->uavs[u].ready_at_ticks;
    if (p > 0U) {
        const sva_target_t* prev = &m->targets[r->targets[p - 1U]];
        px = prev->x;
        py = prev->y;
        free_at = prev->end_ticks;
    }
    const sva_target_t* after = (next < r->target_count) ? &m->targets[r->targets[next]] : NULL;
    const int32_t nx = (after != NULL) ? after->x : m->depot_x;
    const int32_t ny = (after != NULL) ? after->y : m->depot_y;
    const int64_t in = sva_distance(px, py, tg->x, tg->y);
    const int64_t out = sva_distance(tg->x, tg->y, nx, ny);
    *cells = (in + out) - sva_distance(px, py, nx, ny);
    return ((free_at + (in * m->ticks_per_cell)) <= tg->start_ticks) &&
           ((after == NULL) || ((tg->end_ticks + (out * m->ticks_per_cell)) <= after->start_ticks));
}

bool sva_flow_place_may_save(const sva_mission_t* m, const sva_plan_t* plan, uint16_t u, uint16_t t,
                             int64_t saving)
{
    const sva_route_t* r = &plan->routes[u];
    const sva_target_t* tg = &m->targets[t];
    uint16_t p = 0U;
    while ((p < r->target_count) && (m->targets[r->targets[p]].start_ticks < tg->end_ticks)) {
        p++;  // sva_flow_best_place's places: from the first stop that starts after t ends
    }
    for (; p <= r->target_count; p++) {
        if ((p > 0U) && (m->targets[r->targets[p - 1U]].end_ticks > tg->start_ticks)) {
            break;
        }
        int64_t cells = 0;
        if (detour(m, u, r, p, p, tg, &cells) && (cells < saving)) {
            return true;
        }
    }
    return false;
}

bool sva_flow_cut_may_save(const sva_flow_work_t* w, const sva_mission_t* m, const sva_plan_t* plan,
                           uint16_t a, uint16_t b, uint16_t i, uint16_t j, int64_t before)
{
    const sva_route_t* ra = &plan->routes[a];
    const sva_route_t* rb = &plan->routes[b];
    const int64_t ca = cut_cells(m, a, ra, i, w->piece_pre[0][i], rb, j);
    if (ca < 0) {
        return false;
    }
    const int64_t cb = cut_cells(m, b, rb, j, w->piece_pre[1][j], ra, i);
    return (cb >= 0) && (((ca + w->piece_post[1][j]) + (cb + w->piece_post[0][i])) < before);
}

#endif  // SVA_FLOW_GRANULAR
