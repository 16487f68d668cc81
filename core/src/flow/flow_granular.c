// flow_granular.c -- the granular local search's quick tests (large missions' rounds,
// flow_repair.c): whether a relocation or a tail exchange can save cells,
// from the stops around the places they touch (and, for an exchange, the index of the
// routes' pieces), with time checked and fuel not. Most moves fail them; the few that
// pass are evaluated and made by the repair's own moves, so the moves made and the
// work charged are the same as without the tests (DESIGN.md section 8).
#include "flow.h"

#if SVA_FLOW_GRANULAR

// Target tg flown after route r's first p targets (UAV u) and before its stop `next`
// (the depot at its end): the detour in *cells, as flow_insert.c's place_detour finds
// it, and whether both windows are met.
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

// The joint from UAV u's route r after its first i stops to route `next`'s stop j (the
// depot when j is its length): its cells, or -1 when it is late.
static inline int64_t joint_cells(const sva_mission_t* m, uint16_t u, const sva_route_t* r,
                                  uint16_t i, const sva_route_t* next, uint16_t j)
{
    int32_t x = 0;
    int32_t y = 0;
    int64_t free_at = 0;
    sva_flow_leg_ends(m, u, r, i, &x, &y, &free_at);
    if (j >= next->target_count) {
        return sva_distance(x, y, m->depot_x, m->depot_y);
    }
    const sva_target_t* to = &m->targets[next->targets[j]];
    const int64_t joint = sva_distance(x, y, to->x, to->y);
    return ((free_at + (joint * m->ticks_per_cell)) > to->start_ticks) ? -1 : joint;
}

// Route r's pieces at cut i from the index: the cells from its UAV to its (i-1)-th stop
// plus those from its i-th stop to the depot (0 at either end).
static inline int64_t indexed_cells(const sva_flow_work_t* w, const sva_route_t* r, uint16_t i)
{
    const int64_t lead = (i == 0U) ? 0 : w->lead_of[r->targets[i - 1U]];
    const int64_t tail = (i == r->target_count) ? 0 : w->post_of[r->targets[i]];
    return lead + tail;
}

bool sva_flow_cut_may_save(const sva_flow_work_t* w, const sva_mission_t* m, const sva_plan_t* plan,
                           uint16_t a, uint16_t b, uint16_t i, uint16_t j, int64_t before)
{
    const sva_route_t* ra = &plan->routes[a];
    const sva_route_t* rb = &plan->routes[b];
    const int64_t joint_a = joint_cells(m, a, ra, i, rb, j);
    if (joint_a < 0) {
        return false;
    }
    const int64_t joint_b = joint_cells(m, b, rb, j, ra, i);
    return (joint_b >= 0) &&
           ((((joint_a + joint_b) + indexed_cells(w, ra, i)) + indexed_cells(w, rb, j)) < before);
}

#endif  // SVA_FLOW_GRANULAR
