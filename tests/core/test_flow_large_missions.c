// Tests of flow on large missions (more than SVA_FLOW_LARGE_FROM targets; DESIGN.md
// section 8): 100 targets x 20 UAVs where fuel binds.
// - every plan passes the SPEC checker and its bound holds;
// - the work budget grows with the targets: the work spent passes flow_max_work and
//   stays within flow_max_work x (targets / SVA_FLOW_LARGE_FROM)^2, at most 2.5 times
//   flow_max_work, and one round more;
// - ruin and recreate runs (unless the plan is optimal or within 1/SVA_FLOW_CLOSE of its
//   bound), and flow covers as many targets as sva and ga and costs no more than the
//   better of them at equal coverage (their plans seed it);
// - the same mission gives the same plan after another was planned: the index of the
//   granular moves carries nothing over;
// - a round's ruin takes strings of consecutive visits, one per route at most, through
//   its seed, and the same preparation draws the same rounds;
// - string rounds turn shallow only when at their rate they fall short of one round
//   per target, and a shallow round's repair searches less than a full one;
// - a plan ends where the full local search finds nothing;
// - the Lagrangian heuristic's shortest paths on real paths are routes within fuel whose
//   value is the one returned, never below the bound's (merged labels), and the flight
//   flies only when its predicted work fits the plan's budget.
// Seeds are printed and replayable (SVA_TEST_SEED=...).
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>
#include "sva_unity.h"

#include "flow/flow.h"
#include "flow_certificate.h"
#include "mission_gen.h"
#include "sva/sva.h"

#define LARGE_TARGETS 100
#define LARGE_UAVS    20
#define MISSIONS      4
// What a run may spend past its budget: the step under way when it is reached (a
// ruin round and its local search, a flow solve).
#define OVERSHOOT_NUM 3U
#define OVERSHOOT_DEN 10U

static sva_planner_t planner;
static sva_mission_t mission;
static sva_mission_t second;
static sva_plan_t plan;
static sva_plan_t other;
static sva_plan_t again;

static test_gen_params_t params(int targets)
{
    const test_gen_params_t p = {targets, LARGE_UAVS, 40, 20, 40, 300, 1, 80, 80, 0, 1, 0, 0};
    return p;
}

static bool fits_the_profile(void)
{
    return (SVA_MAX_TARGETS >= LARGE_TARGETS) && (SVA_MAX_UAVS >= LARGE_UAVS) &&
           (SVA_FLOW_MAX_ARCS >= 8000L);
}

void test_large_missions_plan_checked_within_their_grown_budget(void)
{
    if (!fits_the_profile()) {
        TEST_IGNORE_MESSAGE("the profile holds no 100 x 20 mission with flow's graph");
    }
    const uint64_t seed = test_seed(0x1A26EULL);
    test_rng_t rng;
    test_rng_seed(&rng, seed);
    uint64_t past_base = 0U;
    uint64_t past_linear = 0U;  // 1/5 past flow_max_work x targets / SVA_FLOW_LARGE_FROM
    for (int round = 0; round < MISSIONS; round++) {
        const test_gen_params_t p = params(LARGE_TARGETS);
        test_gen_mission(&rng, &p, &mission);
        TEST_ASSERT_EQUAL_INT(SVA_OK, sva_planner_init(&planner));
        must_plan_checked(&planner, &mission, SVA_ALGO_FLOW, &plan, seed, round);
        check_certificate(&plan, seed, round);
        const uint64_t base = planner.flow_max_work;
        const uint64_t from = (uint64_t)SVA_FLOW_LARGE_FROM;
        const uint64_t square = (base * LARGE_TARGETS * LARGE_TARGETS) / (from * from);
        const uint64_t most = (5U * base) / 2U;  // 2.5 times, from 102 targets
        const uint64_t grown = (square < most) ? square : most;
        printf("# round %d: covered %d cost %lld bound %lld work %llu (budget %llu) ruin %u\n",
               round, plan.covered, (long long)plan.cost, (long long)plan.stats.lower_bound,
               (unsigned long long)plan.stats.flow_work, (unsigned long long)grown,
               (unsigned)plan.stats.flow_ruin_rounds);
        TEST_ASSERT_TRUE(plan.stats.flow_work <= grown + (grown * OVERSHOOT_NUM) / OVERSHOOT_DEN);
        past_base += (plan.stats.flow_work > base) ? 1U : 0U;
        const uint64_t linear = (base * LARGE_TARGETS) / from;
        past_linear += (plan.stats.flow_work > (linear + (linear / 5U))) ? 1U : 0U;
        // Rounds ran, unless the plan is optimal or within 1/SVA_FLOW_CLOSE of its bound.
        TEST_ASSERT_TRUE(plan.stats.optimal || (plan.stats.flow_ruin_rounds > 0U) ||
                         sva_flow_close(plan.cost, plan.stats.lower_bound));
        const sva_algorithm_t seeds[] = {SVA_ALGO_SVA, SVA_ALGO_GA};
        for (size_t i = 0U; i < (sizeof(seeds) / sizeof(seeds[0])); i++) {
            must_plan_checked(&planner, &mission, seeds[i], &other, seed, round);
            TEST_ASSERT_TRUE(plan.covered >= other.covered);
            TEST_ASSERT_TRUE((plan.covered > other.covered) || (plan.cost <= other.cost));
        }
    }
    // Fuel binds here: a 100-target mission is not solved within the small budget, and
    // its budget grows faster than its targets.
    TEST_ASSERT_TRUE(past_base > 0U);
    TEST_ASSERT_TRUE(past_linear > 0U);
}

void test_large_plans_do_not_depend_on_the_planners_history(void)
{
    if (!fits_the_profile()) {
        TEST_IGNORE_MESSAGE("the profile holds no 100 x 20 mission with flow's graph");
    }
    const uint64_t seed = test_seed(0x1A26FULL);
    test_rng_t rng;
    test_rng_seed(&rng, seed);
    const test_gen_params_t p = params(LARGE_TARGETS);
    test_gen_mission(&rng, &p, &mission);
    test_gen_mission(&rng, &p, &second);
    TEST_ASSERT_EQUAL_INT(SVA_OK, sva_planner_init(&planner));
    must_plan_checked(&planner, &mission, SVA_ALGO_FLOW, &plan, seed, 0);
    const sva_mission_t kept = mission;
    mission = second;
    must_plan_checked(&planner, &mission, SVA_ALGO_FLOW, &other, seed, 1);
    mission = kept;
    must_plan_checked(&planner, &mission, SVA_ALGO_FLOW, &again, seed, 2);
    check_same_plan(&again, &plan);
}

#if SVA_FLOW_LARGE
// Fuel of UAV u's route over the last shortest path (to the first target, between,
// home, and hover at each).
static int64_t path_fuel(const sva_mission_t* m, uint16_t u, const sva_flow_lagrange_t* lg)
{
    return sva_path_cells(m, u, lg->path, lg->path_len) +
           ((int64_t)m->hover_fuel * (int64_t)lg->path_len);
}

// alpha * cells - the prices of the last shortest path's targets.
static int64_t path_value(const sva_mission_t* m, uint16_t u, const sva_flow_lagrange_t* lg,
                          int64_t alpha)
{
    int64_t value = alpha * sva_path_cells(m, u, lg->path, lg->path_len);
    for (uint16_t i = 0U; i < lg->path_len; i++) {
        value -= lg->path_price[lg->path[i]];
    }
    return value;
}
#endif

void test_real_paths_are_routes_within_fuel(void)
{
#if SVA_FLOW_LARGE
    if (!fits_the_profile()) {
        TEST_IGNORE_MESSAGE("the profile holds no 100 x 20 mission with flow's graph");
    }
    const uint64_t seed = test_seed(0x1A270ULL);
    test_rng_t rng;
    test_rng_seed(&rng, seed);
    sva_flow_work_t* w = &planner.priv.flow;
    sva_flow_lagrange_t* lg = &w->lagrange;
    const int64_t alpha = SVA_FLOW_PRICE_SCALE;
    uint32_t paths = 0U;
    uint32_t merged_over_fuel = 0U;
    // MISSIONS missions, and more (up to 8 times as many) until a merged label's path
    // breaks fuel: on some seeds the first ones' label sets do not fill up.
    int round = 0;
    for (; (round < MISSIONS) || ((merged_over_fuel == 0U) && (round < (8 * MISSIONS))); round++) {
        const test_gen_params_t p = params(LARGE_TARGETS);
        test_gen_mission(&rng, &p, &mission);
        sva_state_reset(&planner.priv, &mission, &plan);
        TEST_ASSERT_EQUAL_INT(SVA_FLOW_COMPLETE,
                              sva_flow_build(&planner.priv, &mission, &plan, false, &plan.stats));
        for (int trial = 0; trial < 4; trial++) {
            // Prices of up to a few round trips' cells: routes of many targets pay.
            for (uint16_t t = 0U; t < mission.target_count; t++) {
                lg->path_price[t] = alpha * test_rng_range(&rng, 0, 120);
                lg->closed[t] = 0U;
            }
            for (uint16_t u = 0U; u < mission.uav_count; u++) {
                lg->real_paths = false;
                const int64_t bound = sva_flow_best_route(w, &mission, u, alpha);
                merged_over_fuel += (path_fuel(&mission, u, lg) > mission.uavs[u].fuel) ? 1U : 0U;
                lg->real_paths = true;
                const int64_t real = sva_flow_best_route(w, &mission, u, alpha);
                lg->real_paths = false;
                TEST_ASSERT_TRUE(path_fuel(&mission, u, lg) <= mission.uavs[u].fuel);
                TEST_ASSERT_EQUAL_INT64(path_value(&mission, u, lg, alpha), real);
                TEST_ASSERT_TRUE(bound <= real);
                paths++;
            }
        }
    }
    printf("# %d missions, %u shortest paths; %u of the bound's (merged labels) over fuel\n", round,
           paths, merged_over_fuel);
    // Label sets fill up on these missions: the merged labels' paths break fuel.
    TEST_ASSERT_TRUE(merged_over_fuel > 0U);
#else
    TEST_IGNORE_MESSAGE("no mission is large in this profile");
#endif
}

void test_flight_flies_only_within_the_budget(void)
{
#if SVA_FLOW_LARGE
    if (!fits_the_profile()) {
        TEST_IGNORE_MESSAGE("the profile holds no 100 x 20 mission with flow's graph");
    }
    const uint64_t seed = test_seed(0x1A271ULL);
    test_rng_t rng;
    test_rng_seed(&rng, seed);
    sva_flow_work_t* w = &planner.priv.flow;
    // A large mission: real paths, and a flight of UAVs / 4 evaluations must fit.
    test_gen_params_t p = params(LARGE_TARGETS);
    test_gen_mission(&rng, &p, &mission);
    w->budget = 1000000U;
    w->lagrange.evaluation_work = (w->budget * 4U) / mission.uav_count;
    TEST_ASSERT_TRUE(sva_flow_flight_begins(w, &mission));
    TEST_ASSERT_TRUE(w->lagrange.real_paths);
    w->lagrange.evaluation_work += 1U;
    TEST_ASSERT_FALSE(sva_flow_flight_begins(w, &mission));
    TEST_ASSERT_FALSE(w->lagrange.real_paths);  // the bound's labels go on
    // A small mission flies whatever its work, on a bound's labels.
    p = params(SVA_FLOW_LARGE_FROM);
    test_gen_mission(&rng, &p, &mission);
    w->lagrange.evaluation_work = w->budget * 16U;
    TEST_ASSERT_TRUE(sva_flow_flight_begins(w, &mission));
    TEST_ASSERT_FALSE(w->lagrange.real_paths);
#else
    TEST_IGNORE_MESSAGE("no mission is large in this profile");
#endif
}

#if SVA_FLOW_GRANULAR
// Whether route `after` is route `before` without one run of consecutive visits, all of
// them in the round's list (`out`) and none of the kept ones; *taken counts the run.
static bool one_string_out(const sva_route_t* before, const sva_route_t* after, const uint8_t* out,
                           uint16_t* taken)
{
    uint16_t k = 0U;
    uint16_t runs = 0U;
    bool in_run = false;
    *taken = 0U;
    for (uint16_t i = 0U; i < before->target_count; i++) {
        const uint16_t t = before->targets[i];
        if (out[t] != 0U) {
            runs += in_run ? 0U : 1U;
            in_run = true;
            (*taken)++;
            continue;
        }
        in_run = false;
        if ((k >= after->target_count) || (after->targets[k] != t)) {
            return false;
        }
        k++;
    }
    return (k == after->target_count) && (runs <= 1U);
}
#endif

// A large mission's ruin (flow_ruin.c), on flow's own plan of a 100 x 20 mission, from
// every covered target as the seed: the seed's visit goes; every route loses at most
// one string of consecutive visits, no longer than the routes' mean length, and keeps
// the rest in order; the visits taken out are exactly those in the round's list, once
// each, no longer served, fewer than SVA_FLOW_RUINED_MOST; some rounds take strings
// from several routes and some strings are longer than one visit; the same
// preparation gives the same rounds again.
void test_string_ruin_takes_strings_through_the_seed(void)
{
#if SVA_FLOW_GRANULAR
    if (!fits_the_profile()) {
        TEST_IGNORE_MESSAGE("the profile holds no 100 x 20 mission with flow's graph");
    }
    const uint64_t seed = test_seed(0x1A272ULL);
    test_rng_t rng;
    test_rng_seed(&rng, seed);
    sva_flow_work_t* w = &planner.priv.flow;
    static uint8_t out[SVA_MAX_TARGETS];
    static uint16_t first[SVA_MAX_TARGETS][SVA_FLOW_RUINED_MOST];
    int rounds = 0;
    int several_routes = 0;
    int long_strings = 0;
    planner.flow_max_work = 20000U;
    const test_gen_params_t p = params(LARGE_TARGETS);
    test_gen_mission(&rng, &p, &mission);
    must_plan_checked(&planner, &mission, SVA_ALGO_FLOW, &plan, seed, 0);
    TEST_ASSERT_TRUE(plan.covered > 0);
    for (int pass = 0; pass < 2; pass++) {
        sva_flow_ruin_prepare(w, &mission);
        for (uint16_t s = 0U; s < mission.target_count; s++) {
            sva_flow_write_incumbent(&planner.priv, &mission, &again);
            if (planner.priv.target_served[s] == 0U) {
                continue;
            }
            other = again;  // the routes before the ruin
            sva_flow_ruin_strings(&planner.priv, &mission, &again, s);
            const uint16_t n = w->ruined_count;
            TEST_ASSERT_TRUE((n >= 1U) && (n < (uint16_t)SVA_FLOW_RUINED_MOST));
            memset(out, 0, sizeof out);
            for (uint16_t i = 0U; i < n; i++) {
                const uint16_t t = w->ruined[i];
                TEST_ASSERT_EQUAL_UINT8(0U, out[t]);  // once each
                TEST_ASSERT_EQUAL_UINT16(0U, planner.priv.target_served[t]);
                out[t] = 1U;
            }
            TEST_ASSERT_EQUAL_UINT8(1U, out[s]);
            uint16_t routes = 0U;
            uint16_t total = 0U;
            uint16_t visits = 0U;
            uint16_t used = 0U;
            for (uint16_t u = 0U; u < mission.uav_count; u++) {
                visits = (uint16_t)(visits + other.routes[u].target_count);
                used += (other.routes[u].target_count > 0U) ? 1U : 0U;
            }
            for (uint16_t u = 0U; u < mission.uav_count; u++) {
                uint16_t taken = 0U;
                // One string, at most as long as the routes' mean length.
                if (!one_string_out(&other.routes[u], &again.routes[u], out, &taken) ||
                    (taken > (visits / used))) {
                    SVA_TEST_FAIL("seed %llu target %u: route %u lost more than one string (%u)",
                                  (unsigned long long)seed, (unsigned)s, (unsigned)u,
                                  (unsigned)taken);
                }
                routes += (taken > 0U) ? 1U : 0U;
                total = (uint16_t)(total + taken);
                long_strings += (taken > 1U) ? 1 : 0;
            }
            TEST_ASSERT_EQUAL_UINT16(n, total);  // need 1: one visit each
            several_routes += (routes > 1U) ? 1 : 0;
            rounds++;
            if (pass == 0) {
                memcpy(first[s], w->ruined, sizeof first[s]);
            } else {
                TEST_ASSERT_EQUAL_MEMORY(first[s], w->ruined, n * sizeof(uint16_t));
            }
            w->ruined_count = 0U;
        }
    }
    printf("# %d rounds: strings from several routes in %d, longer than one visit %d times\n",
           rounds, several_routes, long_strings);
    TEST_ASSERT_TRUE(rounds > 0);
    TEST_ASSERT_TRUE(several_routes > 0);
    TEST_ASSERT_TRUE(long_strings > 0);
#else
    TEST_IGNORE_MESSAGE("the profile has no string rounds (SVA_FLOW_GRANULAR 0)");
#endif
}

// The rule that turns string rounds shallow: only after SVA_FLOW_SHALLOW_PROBE rounds,
// and only when the rounds left at the rate so far would not reach one per target.
void test_string_rounds_turn_shallow_only_when_they_fall_short(void)
{
#if SVA_FLOW_GRANULAR
    const uint32_t probe = SVA_FLOW_SHALLOW_PROBE;
    // Before the probe: never, even with no work left.
    TEST_ASSERT_FALSE(sva_flow_rounds_fall_short(probe - 1U, 1000U, 0U, 100U));
    // probe rounds of 1,000 units each (1 unit of rounding up): probe + 91 rounds left
    // reach 99 of 100 targets; probe + 92 reach all 100.
    const uint64_t used = (uint64_t)probe * 999U;
    TEST_ASSERT_TRUE(sva_flow_rounds_fall_short(probe, used, (100U - probe - 1U) * 1000U, 100U));
    TEST_ASSERT_FALSE(sva_flow_rounds_fall_short(probe, used, (100U - probe) * 1000U, 100U));
    // More rounds done than targets: never.
    TEST_ASSERT_FALSE(sva_flow_rounds_fall_short(probe * 2U, used, 0U, (uint16_t)probe));
    // Shallow: one pass, within 1/SVA_FLOW_SHALLOW_REACH; else the full local search.
    sva_flow_work_t* w = &planner.priv.flow;
    w->local_shallow = true;
    TEST_ASSERT_EQUAL_UINT32(1U, sva_flow_local_passes(w));
    TEST_ASSERT_EQUAL_INT64(SVA_FLOW_SHALLOW_REACH, sva_flow_local_reach(w));
    w->local_shallow = false;
    TEST_ASSERT_EQUAL_UINT32(SVA_FLOW_LOCAL_PASSES, sva_flow_local_passes(w));
    TEST_ASSERT_EQUAL_INT64(SVA_FLOW_LOCAL_REACH, sva_flow_local_reach(w));
    TEST_ASSERT_TRUE(SVA_FLOW_SHALLOW_REACH > SVA_FLOW_LOCAL_REACH);
#else
    TEST_IGNORE_MESSAGE("the profile has no string rounds (SVA_FLOW_GRANULAR 0)");
#endif
}

#if SVA_FLOW_GRANULAR
#    define LOCAL_WORK 1000000U
// A round's ruined plan, kept so that its repair can run twice from it.
static uint16_t kept_served[SVA_MAX_TARGETS];
static uint16_t kept_ruined[SVA_FLOW_RUINED_MOST];
static uint8_t kept_changed[SVA_MAX_UAVS];

// The repair of a string round on `ruined` (kept as above), shallow or not, in *out:
// the work it spent. Without `reach` it forgets the incumbent first, so that its local
// search runs whatever the plan's value.
static uint64_t round_repair(const sva_plan_t* ruined, uint16_t ruined_count, bool shallow,
                             bool reach, sva_plan_t* out)
{
    sva_flow_work_t* w = &planner.priv.flow;
    *out = *ruined;
    memcpy(planner.priv.target_served, kept_served, sizeof kept_served);
    memcpy(w->ruined, kept_ruined, sizeof kept_ruined);
    memcpy(w->route_changed, kept_changed, sizeof kept_changed);
    w->ruined_count = ruined_count;
    w->local_changed_only = true;
    w->local_shallow = shallow;
    w->local_work = LOCAL_WORK;  // room for every pass
    const uint64_t before = w->work;
    w->has_inc = w->has_inc && reach;  // no incumbent: the local search runs on any plan
    sva_flow_repair(&planner.priv, &mission, out, true);
    w->local_changed_only = false;
    w->local_shallow = false;
    return w->work - before;
}
#endif

// A shallow round's repair searches less: from the same ruined plan, its local search
// spends at most the work of the full one (its one pass is the full one's first, and
// it starts on fewer plans), and less on some rounds.
void test_shallow_rounds_search_less(void)
{
#if SVA_FLOW_GRANULAR
    if (!fits_the_profile()) {
        TEST_IGNORE_MESSAGE("the profile holds no 100 x 20 mission with flow's graph");
    }
    const uint64_t seed = test_seed(0x1A273ULL);
    test_rng_t rng;
    test_rng_seed(&rng, seed);
    sva_flow_work_t* w = &planner.priv.flow;
    static sva_plan_t ruined;
    planner.flow_max_work = 20000U;
    const test_gen_params_t p = params(LARGE_TARGETS);
    test_gen_mission(&rng, &p, &mission);
    must_plan_checked(&planner, &mission, SVA_ALGO_FLOW, &plan, seed, 0);
    TEST_ASSERT_TRUE(plan.covered > 0);
    sva_flow_ruin_prepare(w, &mission);
    int rounds = 0;
    int less[2] = {0, 0};
    for (uint16_t s = 0U; s < mission.target_count; s++) {
        sva_flow_write_incumbent(&planner.priv, &mission, &ruined);
        if (planner.priv.target_served[s] == 0U) {
            continue;
        }
        sva_flow_ruin_strings(&planner.priv, &mission, &ruined, s);
        const uint16_t n = w->ruined_count;
        memcpy(kept_served, planner.priv.target_served, sizeof kept_served);
        memcpy(kept_ruined, w->ruined, sizeof kept_ruined);
        memcpy(kept_changed, w->route_changed, sizeof kept_changed);
        // The full repair first: the incumbent it may improve only narrows the
        // shallow one's reach.
        // Without the incumbent both search the same plan: only their passes differ.
        // Then against the incumbent: the shallow one's narrower reach, too.
        for (int reach = 0; reach < 2; reach++) {
            const uint64_t full = round_repair(&ruined, n, false, reach == 1, &other);
            const uint64_t part = round_repair(&ruined, n, true, reach == 1, &again);
            if (part > full) {
                SVA_TEST_FAIL("seed %llu target %u: shallow repair spent %llu, the full one %llu",
                              (unsigned long long)seed, (unsigned)s, (unsigned long long)part,
                              (unsigned long long)full);
            }
            less[reach] += (part < full) ? 1 : 0;
        }
        rounds++;
    }
    printf("# %d rounds: the shallow repair spent less on %d (%d against the incumbent)\n", rounds,
           less[0], less[1]);
    TEST_ASSERT_TRUE(rounds > 0);
    TEST_ASSERT_TRUE(less[0] > 0);
    TEST_ASSERT_TRUE(less[1] > 0);
#else
    TEST_IGNORE_MESSAGE("the profile has no string rounds (SVA_FLOW_GRANULAR 0)");
#endif
}

// A large mission's plan ends with the full local search (every move between every
// pair of routes), again while it betters the plan: the full search from the plan flow
// returns finds nothing. 200 targets x 40 UAVs, windows spread over 600 ticks, where a
// plan without that polish is left with a better one next to it.
void test_large_plans_end_where_the_full_local_search_finds_nothing(void)
{
#if SVA_FLOW_GRANULAR
    if ((SVA_MAX_TARGETS < 200) || (SVA_MAX_UAVS < 40) || (SVA_FLOW_MAX_ARCS < 32000L)) {
        TEST_IGNORE_MESSAGE("the profile holds no 200 x 40 mission with flow's graph");
    }
    const uint64_t seed = test_seed(0x1A274ULL);
    test_rng_t rng;
    test_rng_seed(&rng, seed);
    sva_flow_work_t* w = &planner.priv.flow;
    for (int round = 0; round < MISSIONS; round++) {
        test_gen_params_t p = params(200);
        p.uavs = 40;
        p.grid = 20;
        p.horizon = 600;
        test_gen_mission(&rng, &p, &mission);
        TEST_ASSERT_EQUAL_INT(SVA_OK, sva_planner_init(&planner));
        must_plan_checked(&planner, &mission, SVA_ALGO_FLOW, &plan, seed, round);
        sva_flow_write_incumbent(&planner.priv, &mission, &other);
        const int64_t before = sva_flow_plan_value(&planner.priv, &mission, &other);
        w->local_changed_only = false;
        w->local_shallow = false;
        w->has_inc = false;  // the search runs on the plan whatever its value
        sva_flow_repair(&planner.priv, &mission, &other, true);
        const int64_t after = sva_flow_plan_value(&planner.priv, &mission, &other);
        printf("# round %d: covered %d cost %lld, ruin rounds %u; value %lld, after the full "
               "search %lld\n",
               round, plan.covered, (long long)plan.cost, (unsigned)plan.stats.flow_ruin_rounds,
               (long long)before, (long long)after);
        if (after < before) {
            SVA_TEST_FAIL("seed %llu round %d: the full local search took the plan's value from "
                          "%lld to %lld",
                          (unsigned long long)seed, round, (long long)before, (long long)after);
        }
    }
#else
    TEST_IGNORE_MESSAGE("the profile has no string rounds (SVA_FLOW_GRANULAR 0)");
#endif
}

// Every test starts from a freshly initialised planner.
void setUp(void)
{
    TEST_ASSERT_EQUAL_INT(SVA_OK, sva_planner_init(&planner));
}
