// brute_force.c -- see brute_force.h. Recursion is fine here: host tests only.
#include "brute_force.h"

#include <stdlib.h>

#define BF_MAX_TARGETS 6
#define BF_MAX_UAVS    4

static long long dist(long long ax, long long ay, long long bx, long long by)
{
    return llabs(ax - bx) + llabs(ay - by);
}

// Route cost of UAV u over the targets in `mask` (bit per target), or -1 if infeasible.
static long long route_cost(const sva_mission_t* m, int u, unsigned mask)
{
    const sva_uav_t* uav = &m->uavs[u];
    const long long home = dist(uav->x, uav->y, m->depot_x, m->depot_y);
    if (uav->fuel < home) {
        return mask ? -1 : 0;  // stranded: serves nothing, flies nothing
    }
    int order[BF_MAX_TARGETS], n = 0;
    for (int t = 0; t < m->target_count; t++) {
        if (mask & (1u << t)) {
            int i = n++;
            while (i > 0 && m->targets[order[i - 1]].start_ticks > m->targets[t].start_ticks) {
                order[i] = order[i - 1];
                i--;
            }
            order[i] = t;
        }
    }
    long long x = uav->x, y = uav->y, free_at = uav->ready_at_ticks, d = 0;
    for (int i = 0; i < n; i++) {
        const sva_target_t* t = &m->targets[order[i]];
        const long long leg = dist(x, y, t->x, t->y);
        if (free_at + leg * m->ticks_per_cell > t->start_ticks) {
            return -1;
        }
        d += leg;
        x = t->x;
        y = t->y;
        free_at = t->end_ticks;
    }
    d += dist(x, y, m->depot_x, m->depot_y);
    if (d + (long long)m->hover_fuel * n > uav->fuel) {
        return -1;
    }
    return d;
}

static void search(const sva_mission_t* m, int t, unsigned* per_uav, int covered,
                   brute_result_t* best)
{
    if (t == m->target_count) {
        long long cost = 0;
        for (int u = 0; u < m->uav_count; u++) {
            const long long c = route_cost(m, u, per_uav[u]);
            if (c < 0) {
                return;
            }
            cost += c;
        }
        if (covered > best->covered || (covered == best->covered && cost < best->cost)) {
            best->covered = covered;
            best->cost = cost;
        }
        return;
    }
    search(m, t + 1, per_uav, covered, best);  // leave target t uncovered
    for (unsigned set = 1; set < (1u << m->uav_count); set++) {
        if (__builtin_popcount(set) != m->targets[t].need) {
            continue;
        }
        for (int u = 0; u < m->uav_count; u++) {
            if (set & (1u << u)) {
                per_uav[u] |= 1u << t;
            }
        }
        search(m, t + 1, per_uav, covered + 1, best);
        for (int u = 0; u < m->uav_count; u++) {
            per_uav[u] &= ~(1u << t);
        }
    }
}

brute_result_t brute_force_optimum(const sva_mission_t* m)
{
    brute_result_t best = {-1, 0};
    unsigned per_uav[BF_MAX_UAVS] = {0};
    if (m->target_count > BF_MAX_TARGETS || m->uav_count > BF_MAX_UAVS) {
        abort();  // test misuse
    }
    search(m, 0, per_uav, 0, &best);
    return best;
}
