// spec_checker.c -- see spec_checker.h. Deliberately plain: recomputes from scratch.
#include "spec_checker.h"

#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

typedef struct {
    int count;
    char* msg;
    size_t size;
} report_t;

static void fail(report_t* r, const char* fmt, ...)
{
    if (r->count == 0 && r->msg != NULL && r->size > 0) {
        va_list ap;
        va_start(ap, fmt);
        vsnprintf(r->msg, r->size, fmt, ap);
        va_end(ap);
    }
    r->count++;
}

static long long manhattan(long long ax, long long ay, long long bx, long long by)
{
    return llabs(ax - bx) + llabs(ay - by);
}

int spec_better(int covered_a, long long cost_a, int covered_b, long long cost_b)
{
    return covered_a > covered_b || (covered_a == covered_b && cost_a < cost_b);
}

int spec_check_plan(const sva_mission_t* m, const sva_plan_t* p, char* msg, size_t size)
{
    report_t r = {0, msg, size};
    static int served[SVA_MAX_TARGETS];
    memset(served, 0, sizeof(served));
    if (p->status != SVA_PLAN_COMPLETE && p->status != SVA_PLAN_PARTIAL) {
        fail(&r, "status %d is not complete/partial", (int)p->status);
        return r.count;
    }
    if (p->route_count != m->uav_count) {
        fail(&r, "%d routes for %d UAVs", p->route_count, m->uav_count);
        return r.count;
    }
    long long cost = 0;
    int stranded = 0;
    for (int u = 0; u < m->uav_count; u++) {
        const sva_uav_t* uav = &m->uavs[u];
        const sva_route_t* route = &p->routes[u];
        if (route->uav_id != uav->id) {
            fail(&r, "route %d is for UAV %d, expected %d (mission order)", u, route->uav_id,
                 uav->id);
        }
        const long long home = manhattan(uav->x, uav->y, m->depot_x, m->depot_y);
        const int must_strand = uav->fuel < home;
        if (route->stranded != must_strand) {
            fail(&r, "UAV %d stranded=%d, fuel %d home %lld", uav->id, route->stranded, uav->fuel,
                 home);
        }
        if (route->stranded) {
            stranded++;
            if (route->target_count != 0 || route->distance_cells != 0 || route->fuel_used != 0) {
                fail(&r, "stranded UAV %d has a route", uav->id);
            }
            continue;
        }
        long long x = uav->x, y = uav->y, free_at = uav->ready_at_ticks, dist = 0;
        for (int k = 0; k < route->target_count; k++) {
            const int ti = route->targets[k];
            if (ti < 0 || ti >= m->target_count) {
                fail(&r, "UAV %d visits target index %d out of range", uav->id, ti);
                return r.count;
            }
            const sva_target_t* t = &m->targets[ti];
            for (int j = 0; j < k; j++) {
                if (route->targets[j] == ti) {
                    fail(&r, "UAV %d visits target %d twice", uav->id, t->id);
                }
            }
            const long long leg = manhattan(x, y, t->x, t->y);
            if (free_at + leg * m->ticks_per_cell > t->start_ticks) {
                fail(&r, "UAV %d reaches target %d at %lld, after its start %d", uav->id, t->id,
                     free_at + leg * m->ticks_per_cell, t->start_ticks);
            }
            dist += leg;
            x = t->x;
            y = t->y;
            free_at = t->end_ticks;
            served[ti]++;
        }
        dist += manhattan(x, y, m->depot_x, m->depot_y);
        const long long fuel = dist + (long long)m->hover_fuel * route->target_count;
        if (dist != route->distance_cells) {
            fail(&r, "UAV %d distance %lld, recomputed %lld", uav->id,
                 (long long)route->distance_cells, dist);
        }
        if (fuel != route->fuel_used) {
            fail(&r, "UAV %d fuel_used %lld, recomputed %lld", uav->id, (long long)route->fuel_used,
                 fuel);
        }
        if (fuel > uav->fuel) {
            fail(&r, "UAV %d uses %lld fuel of %d", uav->id, fuel, uav->fuel);
        }
        cost += dist;
    }
    if (stranded != p->stranded_count) {
        fail(&r, "stranded_count %d, recomputed %d", p->stranded_count, stranded);
    }
    int covered = 0, listed = 0;
    for (int t = 0; t < m->target_count; t++) {
        if (served[t] != 0 && served[t] != m->targets[t].need) {
            fail(&r, "target %d half-covered: %d of %d UAVs", m->targets[t].id, served[t],
                 m->targets[t].need);
        }
        if (served[t] == m->targets[t].need) {
            covered++;
        } else {
            if (listed >= p->uncovered_count || p->uncovered[listed] != t) {
                fail(&r, "target %d uncovered but not listed in mission order", m->targets[t].id);
            }
            listed++;
        }
    }
    if (listed != p->uncovered_count) {
        fail(&r, "uncovered_count %d, recomputed %d", p->uncovered_count, listed);
    }
    if (covered != p->covered) {
        fail(&r, "covered %d, recomputed %d", p->covered, covered);
    }
    if (cost != p->cost) {
        fail(&r, "cost %lld, recomputed %lld", (long long)p->cost, cost);
    }
    const sva_plan_status_t status =
        covered == m->target_count ? SVA_PLAN_COMPLETE : SVA_PLAN_PARTIAL;
    if (status != p->status) {
        fail(&r, "status %d, expected %d", (int)p->status, (int)status);
    }
    return r.count;
}
