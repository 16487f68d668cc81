// Tests of the granular moves' quick tests (flow_granular.c; DESIGN.md section 8): the
// local search of a large mission's rounds skips a relocation or a tail exchange they
// turn down, so they must turn down only moves that cannot save cells. Each must
// answer exactly as the routes the move would make, built out and checked stop by stop
// here:
// - a relocation: some place of the route where the target meets time (every
//   place, not only those the search tries) with a detour below the saving;
// - a tail exchange: both spliced routes meet time, and fly fewer cells together.
// Fuel is no part of either (the moves check it). Both answers must come up. The plans
// are flow's on 100 targets x 20 UAVs, UAVs at the depot and scattered (a route's
// first leg from where its UAV is, free from its ready time).
// The search looks only at visits an edit came next to (don't-look bits): every edit of
// a route must wake exactly the visits whose neighbours it changed.
// Seeds are printed and replayable (SVA_TEST_SEED=...).
#include <stdint.h>
#include <stdio.h>
#include "sva_unity.h"

#include "flow/flow.h"
#include "flow_certificate.h"
#include "mission_gen.h"
#include "sva/sva.h"

#define TARGETS  100
#define UAVS     20
#define MISSIONS 2

static sva_planner_t planner;
static sva_mission_t mission;
static sva_plan_t plan;

#if SVA_FLOW_GRANULAR
// A route built out: its stops, in order.
typedef struct {
    uint16_t n;
    uint16_t stop[2U * SVA_MAX_ROUTE_TARGETS + 1U];
} stops_t;

static int64_t manhattan(int64_t ax, int64_t ay, int64_t bx, int64_t by)
{
    return ((ax > bx) ? (ax - bx) : (bx - ax)) + ((ay > by) ? (ay - by) : (by - ay));
}

// Whether UAV u flying the stops meets every window (it leaves a target at its end),
// and in *cells its flight from where it is, home to the depot.
static bool flies(const sva_mission_t* m, uint16_t u, const stops_t* s, int64_t* cells)
{
    int64_t x = m->uavs[u].x;
    int64_t y = m->uavs[u].y;
    int64_t free_at = m->uavs[u].ready_at_ticks;
    bool in_time = true;
    *cells = 0;
    for (uint16_t k = 0U; k < s->n; k++) {
        const sva_target_t* t = &m->targets[s->stop[k]];
        const int64_t leg = manhattan(x, y, t->x, t->y);
        in_time = in_time && ((free_at + (leg * m->ticks_per_cell)) <= t->start_ticks);
        *cells += leg;
        x = t->x;
        y = t->y;
        free_at = t->end_ticks;
    }
    *cells += manhattan(x, y, m->depot_x, m->depot_y);
    return in_time;
}

static void take(stops_t* s, const sva_route_t* r, uint16_t from, uint16_t to)
{
    for (uint16_t k = from; k < to; k++) {
        s->stop[s->n] = r->targets[k];
        s->n++;
    }
}

// The cells route u of the plan flies now.
static int64_t cells_now(uint16_t u)
{
    const sva_route_t* r = &plan.routes[u];
    stops_t s = {0U, {0U}};
    take(&s, r, 0U, r->target_count);
    int64_t cells = 0;
    (void)flies(&mission, u, &s, &cells);
    return cells;
}

// Whether target t fits some place of route u in time with a detour below `saving`.
static bool some_place_saves(uint16_t u, uint16_t t, int64_t saving)
{
    const sva_route_t* r = &plan.routes[u];
    const int64_t cells = cells_now(u);
    for (uint16_t p = 0U; p <= r->target_count; p++) {
        stops_t with = {0U, {0U}};
        take(&with, r, 0U, p);
        with.stop[with.n] = t;
        with.n++;
        take(&with, r, p, r->target_count);
        int64_t longer = 0;
        if (flies(&mission, u, &with, &longer) && ((longer - cells) < saving)) {
            return true;
        }
    }
    return false;
}

// Route u's index as the local search keeps it (flow_repair.c), built out here: for
// each of its targets the cells from the UAV to it and from it on to the depot.
static void index_route(sva_flow_work_t* w, uint16_t u)
{
    const sva_route_t* r = &plan.routes[u];
    int64_t x = mission.uavs[u].x;
    int64_t y = mission.uavs[u].y;
    int64_t lead = 0;
    for (uint16_t k = 0U; k < r->target_count; k++) {
        const sva_target_t* t = &mission.targets[r->targets[k]];
        lead += manhattan(x, y, t->x, t->y);
        w->lead_of[r->targets[k]] = (int32_t)lead;
        x = t->x;
        y = t->y;
    }
    int64_t post = 0;
    x = mission.depot_x;
    y = mission.depot_y;
    for (uint16_t k = r->target_count; k > 0U; k--) {
        const sva_target_t* t = &mission.targets[r->targets[k - 1U]];
        post += manhattan(t->x, t->y, x, y);
        w->post_of[r->targets[k - 1U]] = (int32_t)post;
        x = t->x;
        y = t->y;
    }
}

// Whether routes a and b, a keeping its first i stops and taking b's from j on and b
// the other way round, meet time and fly fewer than `before` cells (what they fly now).
static bool exchange_saves(uint16_t a, uint16_t b, uint16_t i, uint16_t j, int64_t before)
{
    const sva_route_t* ra = &plan.routes[a];
    const sva_route_t* rb = &plan.routes[b];
    stops_t new_a = {0U, {0U}};
    stops_t new_b = {0U, {0U}};
    take(&new_a, ra, 0U, i);
    take(&new_a, rb, j, rb->target_count);
    take(&new_b, rb, 0U, j);
    take(&new_b, ra, i, ra->target_count);
    int64_t cells_a = 0;
    int64_t cells_b = 0;
    const bool in_time =
        flies(&mission, a, &new_a, &cells_a) && flies(&mission, b, &new_b, &cells_b);
    return in_time && ((cells_a + cells_b) < before);
}

static void plan_a_mission(uint64_t seed, int round)
{
    // Fuel binds; UAVs at the depot on even rounds, scattered and busy on odd ones.
    const test_gen_params_t p = {TARGETS, UAVS, 40, 20, 40, 300, 1, 80, 80, 0, 1, round % 2, 0};
    test_rng_t rng;
    test_rng_seed(&rng, seed + (uint64_t)round);
    test_gen_mission(&rng, &p, &mission);
    planner.flow_max_work = 50000U;
    must_plan_checked(&planner, &mission, SVA_ALGO_FLOW, &plan, seed, round);
    TEST_ASSERT_TRUE(plan.covered > 0);
}
#endif

// Every visit against every other route, at its own saving and at savings around it.
void test_relocation_quick_test_turns_down_only_places_that_cannot_save(void)
{
#if SVA_FLOW_GRANULAR
    const uint64_t seed = test_seed(0x6A41ULL);
    int answers[2] = {0, 0};
    for (int round = 0; round < MISSIONS; round++) {
        plan_a_mission(seed, round);
        for (uint16_t a = 0U; a < mission.uav_count; a++) {
            const sva_route_t* ra = &plan.routes[a];
            for (uint16_t k = 0U; k < ra->target_count; k++) {
                const uint16_t t = ra->targets[k];
                const int64_t own = sva_flow_stop_saving(&mission, a, ra, k);
                for (uint16_t b = 0U; b < mission.uav_count; b++) {
                    if ((b == a) || plan.routes[b].stranded) {
                        continue;
                    }
                    for (int64_t saving = own - 2; saving <= (own + 6); saving += 4) {
                        const bool quick = sva_flow_place_may_save(&mission, &plan, b, t, saving);
                        if (quick != some_place_saves(b, t, saving)) {
                            SVA_TEST_FAIL("seed %llu round %d: target %u into UAV %u at saving "
                                          "%lld: the quick test says %d",
                                          (unsigned long long)seed, round, (unsigned)t, (unsigned)b,
                                          (long long)saving, (int)quick);
                        }
                        answers[quick ? 1 : 0]++;
                    }
                }
            }
        }
    }
    printf("# relocations: %d may save, %d cannot\n", answers[1], answers[0]);
    TEST_ASSERT_TRUE(answers[0] > 0);
    TEST_ASSERT_TRUE(answers[1] > 0);
#else
    TEST_IGNORE_MESSAGE("the profile has no granular moves (SVA_FLOW_GRANULAR 0)");
#endif
}

// Every cut of every pair of routes.
void test_exchange_quick_test_turns_down_only_cuts_that_cannot_save(void)
{
#if SVA_FLOW_GRANULAR
    const uint64_t seed = test_seed(0x6A42ULL);
    sva_flow_work_t* w = &planner.priv.flow;
    int answers[2] = {0, 0};
    for (int round = 0; round < MISSIONS; round++) {
        plan_a_mission(seed, round);
        for (uint16_t a = 0U; a < mission.uav_count; a++) {
            for (uint16_t b = 0U; b < mission.uav_count; b++) {
                const sva_route_t* ra = &plan.routes[a];
                const sva_route_t* rb = &plan.routes[b];
                if ((b == a) || ra->stranded || rb->stranded) {
                    continue;
                }
                const int64_t before = cells_now(a) + cells_now(b);
                index_route(w, a);  // need 1: no target in both routes
                index_route(w, b);
                for (uint16_t i = 0U; i <= ra->target_count; i++) {
                    for (uint16_t j = 0U; j <= rb->target_count; j++) {
                        const bool quick =
                            sva_flow_cut_may_save(w, &mission, &plan, a, b, i, j, before);
                        if (quick != exchange_saves(a, b, i, j, before)) {
                            SVA_TEST_FAIL("seed %llu round %d: UAVs %u and %u cut at %u and %u: "
                                          "the quick test says %d",
                                          (unsigned long long)seed, round, (unsigned)a, (unsigned)b,
                                          (unsigned)i, (unsigned)j, (int)quick);
                        }
                        answers[quick ? 1 : 0]++;
                    }
                }
            }
        }
    }
    printf("# exchanges: %d may save, %d cannot\n", answers[1], answers[0]);
    TEST_ASSERT_TRUE(answers[0] > 0);
    TEST_ASSERT_TRUE(answers[1] > 0);
#else
    TEST_IGNORE_MESSAGE("the profile has no granular moves (SVA_FLOW_GRANULAR 0)");
#endif
}

#if SVA_FLOW_GRANULAR
static void sleep_all(sva_flow_work_t* w)
{
    for (uint16_t t = 0U; t < mission.target_count; t++) {
        w->visit_awake[t] = 0U;
    }
}

// Whether the awake targets are exactly route r's visits at places place - 1 to
// place + 1 (those that exist), and route u is marked changed.
static bool awake_around(const sva_flow_work_t* w, const sva_route_t* r, uint16_t u, int place)
{
    bool exact = w->route_changed[u] != 0U;
    for (uint16_t t = 0U; t < mission.target_count; t++) {
        bool near_edit = false;
        for (int i = place - 1; i <= (place + 1); i++) {
            near_edit =
                near_edit || ((i >= 0) && (i < (int)r->target_count) && (r->targets[i] == t));
        }
        exact = exact && ((w->visit_awake[t] != 0U) == near_edit);
    }
    return exact;
}
#endif

// The granular search looks only at awake visits (don't-look bits): each edit must wake
// the visits whose neighbours it changes, and no other. A removal at place k: the two
// it joins (now at k - 1 and k) and the next; an insertion at k: the visit and both
// its neighbours. Every place of every route, ends included.
void test_edits_wake_the_visits_next_to_them(void)
{
#if SVA_FLOW_GRANULAR
    const uint64_t seed = test_seed(0x6A43ULL);
    sva_flow_work_t* w = &planner.priv.flow;
    plan_a_mission(seed, 1);
    int edits = 0;
    for (uint16_t u = 0U; u < mission.uav_count; u++) {
        sva_route_t* r = &plan.routes[u];
        for (uint16_t k = 0U; k < r->target_count; k++) {
            const uint16_t t = r->targets[k];
            sleep_all(w);
            w->route_changed[u] = 0U;
            sva_flow_remove_at(&mission, w, r, u, k);
            if (!awake_around(w, r, u, (int)k)) {
                SVA_TEST_FAIL("seed %llu: UAV %u, place %u: the removal woke the wrong visits",
                              (unsigned long long)seed, (unsigned)u, (unsigned)k);
            }
            sleep_all(w);
            w->route_changed[u] = 0U;
            w->insert_pos[u] = k;
            w->insert_delta[u] = 0;
            sva_flow_insert_at(w, r, u, t);
            TEST_ASSERT_EQUAL_UINT16(t, r->targets[k]);
            if (!awake_around(w, r, u, (int)k)) {
                SVA_TEST_FAIL("seed %llu: UAV %u, place %u: the insertion woke the wrong visits",
                              (unsigned long long)seed, (unsigned)u, (unsigned)k);
            }
            edits += 2;
        }
    }
    printf("# edits checked: %d\n", edits);
    TEST_ASSERT_TRUE(edits > 0);
#else
    TEST_IGNORE_MESSAGE("the profile has no granular moves (SVA_FLOW_GRANULAR 0)");
#endif
}

// Every test starts from a freshly initialised planner.
void setUp(void)
{
    TEST_ASSERT_EQUAL_INT(SVA_OK, sva_planner_init(&planner));
}
