// plan_check.c -- a plan in force read from a document, against its mission: the
// layout a live mission needs (the core's rules of sva_live_init(), in the core's words)
// and every rule of SPEC section 1 (serving times, fuel, exact coverage). First error
// wins: routes in mission order, each its layout, then its visits in order, then its
// fuel; then the coverage of the targets in mission order.
#include "plan_check.h"

#include "input.h"

#include <stdint.h>
#include <stdio.h>

// A rule the core words (sva_diag_format()), on the plan document.
static sva_json_status_t fail_diag(char* err, size_t size, sva_field_t field, sva_rule_t rule,
                                   int32_t index, int64_t value, int64_t limit,
                                   const char* limit_name)
{
    sva_diag_t diag;
    char text[SVA_JSON_ERROR_SIZE];
    sva_diag_set(&diag, field, rule, index, value, limit, limit_name);
    (void)sva_diag_format(&diag, text, sizeof text);
    return sva_json_refuse(err, size, "plan.%s", text);
}

static int64_t cells(int32_t ax, int32_t ay, int32_t bx, int32_t by)
{
    const int64_t dx = (int64_t)ax - bx;
    const int64_t dy = (int64_t)ay - by;
    return (dx < 0 ? -dx : dx) + (dy < 0 ? -dy : dy);
}

// One route's layout: its UAV in mission order, known targets, none twice.
static sva_json_status_t check_layout(const sva_mission_t* m, const sva_route_t* r, uint16_t u,
                                      char* err, size_t size)
{
    if (r->uav_id != m->uavs[u].id) {
        return fail_diag(err, size, SVA_FIELD_ROUTE_UAV, SVA_RULE_ROUTE, (int32_t)u, r->uav_id,
                         m->uavs[u].id, NULL);
    }
    if ((uint32_t)r->target_count > (uint32_t)SVA_MAX_ROUTE_TARGETS) {
        return fail_diag(err, size, SVA_FIELD_ROUTE_TARGETS, SVA_RULE_COUNT, (int32_t)u,
                         r->target_count, SVA_MAX_ROUTE_TARGETS, "SVA_MAX_ROUTE_TARGETS");
    }
    for (uint16_t k = 0; k < r->target_count; ++k) {
        if (r->targets[k] >= m->target_count) {
            return fail_diag(err, size, SVA_FIELD_ROUTE_TARGETS, SVA_RULE_MAX, (int32_t)u,
                             r->targets[k], (int64_t)m->target_count - 1, NULL);
        }
        for (uint16_t j = 0; j < k; ++j) {
            if (r->targets[j] == r->targets[k]) {
                return fail_diag(err, size, SVA_FIELD_ROUTE_TARGETS, SVA_RULE_DUPLICATE, (int32_t)u,
                                 m->targets[r->targets[k]].id, j, NULL);
            }
        }
    }
    return SVA_JSON_OK;
}

// SPEC section 1 on one route: each visit reached by its window's start (from the
// UAV's position and ready_at, then from the previous window's end), and the fuel of
// the whole route, return leg and hovers included. An empty route flies nothing the
// plan chose (a UAV that cannot get home is stranded).
static sva_json_status_t check_route(const sva_mission_t* m, const sva_route_t* r, uint16_t u,
                                     char* err, size_t size)
{
    const sva_uav_t* uav = &m->uavs[u];
    if (r->target_count == 0) {
        return SVA_JSON_OK;
    }
    int32_t x = uav->x;
    int32_t y = uav->y;
    int64_t free_at = uav->ready_at_ticks;
    int64_t distance = 0;
    for (uint16_t k = 0; k < r->target_count; ++k) {
        const sva_target_t* t = &m->targets[r->targets[k]];
        const int64_t leg = cells(x, y, t->x, t->y);
        const int64_t arrive = free_at + leg * m->ticks_per_cell;
        if (arrive > t->start_ticks && k == 0) {
            return sva_json_refuse(
                err, size,
                "plan.routes[%u].targets[0]: uav %ld reaches target %ld at tick %lld, "
                "after its start %ld (ready_at %ld, %lld cells)",
                (unsigned)u, (long)uav->id, (long)t->id, (long long)arrive, (long)t->start_ticks,
                (long)uav->ready_at_ticks, (long long)leg);
        }
        if (arrive > t->start_ticks) {
            const sva_target_t* a = &m->targets[r->targets[k - 1]];
            return sva_json_refuse(
                err, size,
                "plan.routes[%u].targets[%u]: uav %ld leaves target %ld at its end %ld "
                "and reaches target %ld at tick %lld, after its start %ld",
                (unsigned)u, (unsigned)k, (long)uav->id, (long)a->id, (long)a->end_ticks,
                (long)t->id, (long long)arrive, (long)t->start_ticks);
        }
        distance += leg;
        x = t->x;
        y = t->y;
        free_at = t->end_ticks;
    }
    distance += cells(x, y, m->depot_x, m->depot_y);
    const int64_t fuel = distance + (int64_t)m->hover_fuel * r->target_count;
    if (fuel > uav->fuel) {
        return sva_json_refuse(
            err, size,
            "plan.routes[%u]: the route of uav %ld needs %lld fuel (return leg and hover "
            "included), more than its fuel %ld",
            (unsigned)u, (long)uav->id, (long long)fuel, (long)uav->fuel);
    }
    return SVA_JSON_OK;
}

sva_json_status_t sva_json_check_plan(const sva_mission_t* m, const sva_plan_t* plan, char* err,
                                      size_t size)
{
    if (plan->route_count != m->uav_count) {
        return fail_diag(err, size, SVA_FIELD_ROUTES, SVA_RULE_ROUTE, -1, plan->route_count,
                         m->uav_count, NULL);
    }
    uint16_t served[SVA_MAX_TARGETS] = {0};
    for (uint16_t u = 0; u < m->uav_count; ++u) {
        const sva_route_t* r = &plan->routes[u];
        if (check_layout(m, r, u, err, size) != SVA_JSON_OK ||
            check_route(m, r, u, err, size) != SVA_JSON_OK) {
            return SVA_JSON_ERR_INPUT;
        }
        for (uint16_t k = 0; k < r->target_count; ++k) {
            served[r->targets[k]]++;
        }
    }
    // SPEC section 1: covered iff exactly `need` UAVs serve it; no UAV goes to a target
    // the plan leaves uncovered.
    for (uint16_t t = 0; t < m->target_count; ++t) {
        const sva_target_t* target = &m->targets[t];
        if (served[t] != 0 && served[t] != target->need) {
            return sva_json_refuse(
                err, size,
                "plan.routes: target %ld is served by %u UAV%s, must be served by "
                "exactly its need (%ld) or by none",
                (long)target->id, (unsigned)served[t], served[t] == 1 ? "" : "s",
                (long)target->need);
        }
    }
    return SVA_JSON_OK;
}
