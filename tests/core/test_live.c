// test_live.c -- the live-mission module (docs/SPEC.md section 12): the clock and the
// visit states, the flight model, every event and every rejected event (the live state
// byte for byte unchanged), and the replan's candidates and objective. Random live
// missions check every replan's plan with the independent SPEC checker.
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "live_gen.h"
#include "mission_gen.h"
#include "spec_checker.h"
#include "sva/sva.h"

static sva_live_t live;
static sva_live_t before;
static sva_planner_t planner;
static sva_mission_t mission;
static sva_plan_t plan;

// Two UAVs at the depot; T1 needs both at (5, 0) in [10, 20]; T2 at (5, 5) and T3 at
// (1, 6) in [30, 40] need one each. Plan in force: UAV 1 T1 then T2, UAV 2 T1 then T3.
static void start_hand(int32_t change_penalty)
{
    sva_mission_init(&mission);
    mission.change_penalty = change_penalty;
    mission.uav_count = 2U;
    for (uint16_t u = 0U; u < 2U; u++) {
        mission.uavs[u] = (sva_uav_t){.id = (int32_t)u + 1, .x = 0, .y = 0, .fuel = 100};
    }
    mission.target_count = 3U;
    mission.targets[0] = (sva_target_t){1, 5, 0, 10, 20, 2};
    mission.targets[1] = (sva_target_t){2, 5, 5, 30, 40, 1};
    mission.targets[2] = (sva_target_t){3, 1, 6, 30, 40, 1};
    (void)memset(&plan, 0, sizeof(plan));
    plan.route_count = 2U;
    plan.routes[0] = (sva_route_t){.uav_id = 1, .target_count = 2U, .targets = {0U, 1U}};
    plan.routes[1] = (sva_route_t){.uav_id = 2, .target_count = 2U, .targets = {0U, 2U}};
    sva_diag_t diag;
    assert_int_equal(sva_live_init(&live, &mission, &plan, &diag), SVA_OK);
    assert_int_equal(sva_planner_init(&planner), SVA_OK);
}

static void apply_ok(sva_event_t e)
{
    sva_diag_t diag;
    char msg[160];
    const sva_status_t status = sva_live_apply(&live, &e, &diag);
    (void)sva_diag_format(&diag, msg, sizeof msg);
    if (status != SVA_OK) {
        fail_msg("event %s at %d rejected: %s", sva_event_type_name(e.type), (int)e.at_ticks, msg);
    }
}

static sva_target_state_t state_of(int32_t id)
{
    for (uint16_t i = 0U; i < live.mission.target_count; i++) {
        if (live.mission.targets[i].id == id) {
            return (sva_target_state_t)live.target_state[i];
        }
    }
    fail_msg("no target %d", (int)id);
    return SVA_TARGET_STATE_COUNT_;
}

static void replan_ok(sva_algorithm_t algo, sva_live_result_t* result)
{
    sva_diag_t diag;
    char msg[200];
    assert_int_equal(sva_live_replan(&live, &planner, algo, result, &diag), SVA_OK);
    if (spec_check_plan(result->residual, result->plan, msg, sizeof msg) != 0) {
        fail_msg("replan (%s) breaks SPEC: %s", sva_algorithm_name(algo), msg);
    }
    assert_int_equal(result->covered, result->under_way + result->plan->covered);
}

// The residual target index of target `id`, or -1.
static int residual_index(const sva_live_result_t* r, int32_t id)
{
    for (uint16_t i = 0U; i < r->residual->target_count; i++) {
        if (r->residual->targets[i].id == id) {
            return (int)i;
        }
    }
    return -1;
}

static void test_flight_model_and_clock(void** state)
{
    (void)state;
    start_hand(0);
    int32_t x = 0;
    int32_t y = 0;
    int32_t fuel = 0;
    int32_t ready = 0;
    // x first: 3 cells east at tick 3.
    assert_true(sva_live_uav_at(&live, 0U, 3, &x, &y, &fuel, &ready));
    assert_int_equal(x, 3);
    assert_int_equal(y, 0);
    assert_int_equal(fuel, 97);
    assert_int_equal(ready, 3);
    assert_int_equal(state_of(1), SVA_TARGET_WAITING);
    apply_ok(test_event_at(SVA_EVENT_CLOCK, 10));
    assert_int_equal(state_of(1), SVA_TARGET_UNDER_WAY);
    // Under way: at the target until the window ends.
    assert_true(sva_live_uav_at(&live, 1U, 12, &x, &y, &fuel, &ready));
    assert_int_equal(x, 5);
    assert_int_equal(ready, 20);
    apply_ok(test_event_at(SVA_EVENT_CLOCK, 20));
    assert_int_equal(state_of(1), SVA_TARGET_DONE);
    // UAV 2 leaves T1 at 20 for T3 (1, 6): 4 cells west first, then north.
    assert_true(sva_live_uav_at(&live, 1U, 27, &x, &y, &fuel, &ready));
    assert_int_equal(x, 1);
    assert_int_equal(y, 3);
    apply_ok(test_event_at(SVA_EVENT_CLOCK, 45));
    assert_int_equal(state_of(2), SVA_TARGET_DONE);
    assert_int_equal(state_of(3), SVA_TARGET_DONE);
    assert_int_equal(live.revision, 3U);
}

static void test_lost_uav_breaks_visit_under_way(void** state)
{
    (void)state;
    start_hand(0);
    sva_event_t lost = test_event_at(SVA_EVENT_UAV_LOST, 15);
    lost.uav_id = 1;
    apply_ok(lost);
    // T1 was under way with both UAVs: it can no longer be covered; UAV 2 is free now.
    assert_int_equal(state_of(1), SVA_TARGET_LOST);
    int32_t x = 0;
    int32_t y = 0;
    int32_t fuel = 0;
    int32_t ready = 0;
    assert_true(sva_live_uav_at(&live, 1U, 15, &x, &y, &fuel, &ready));
    assert_int_equal(x, 5);
    assert_int_equal(y, 0);
    assert_int_equal(ready, 15);
    assert_false(sva_live_uav_at(&live, 0U, 15, &x, &y, &fuel, &ready));
    sva_live_result_t r;
    replan_ok(SVA_ALGO_FLOW, &r);
    assert_int_equal(r.residual->uav_count, 1);
    assert_int_equal(r.residual->uavs[0].ready_at_ticks, 15);
    assert_int_equal(r.residual->target_count, 2);
    // One UAV, two windows at once: one target. Change penalty 0: the cheaper T2
    // (5 + 10) beats keeping T3 (10 + 7): two changed visits.
    assert_int_equal(r.plan->covered, 1);
    assert_false(r.kept);
    assert_int_equal(r.plan->cost, 15);
    assert_int_equal(r.dropped, 1U);
    assert_int_equal(r.added, 1U);
    assert_int_equal(r.objective, 15);
}

static void test_change_penalty_keeps_standing_visits(void** state)
{
    (void)state;
    start_hand(10);
    sva_event_t lost = test_event_at(SVA_EVENT_UAV_LOST, 15);
    lost.uav_id = 1;
    apply_ok(lost);
    sva_live_result_t r;
    replan_ok(SVA_ALGO_FLOW, &r);
    // 17 for keeping T3 against 15 + 2 * 10 for switching to T2.
    assert_true(r.kept);
    assert_int_equal(r.plan->cost, 17);
    assert_int_equal(r.dropped + r.added, 0U);
    assert_int_equal(r.objective, 17);
    const int t3 = residual_index(&r, 3);
    assert_true(t3 >= 0);
    assert_int_equal(r.plan->routes[0].target_count, 1);
    assert_int_equal(r.plan->routes[0].targets[0], t3);
    // The kept plan is the plan in force now: flying on, T3 is covered.
    apply_ok(test_event_at(SVA_EVENT_CLOCK, 41));
    assert_int_equal(state_of(3), SVA_TARGET_DONE);
    assert_int_equal(state_of(2), SVA_TARGET_EXPIRED);
}

static void test_replan_keeps_visits_under_way(void** state)
{
    (void)state;
    start_hand(0);
    apply_ok(test_event_at(SVA_EVENT_CLOCK, 12));
    for (int algo = 0; algo < (int)SVA_ALGO_COUNT_; algo++) {
        sva_live_result_t r;
        replan_ok((sva_algorithm_t)algo, &r);
        // T1 is under way: not in the residual mission; both UAVs wait there until 20.
        assert_int_equal(residual_index(&r, 1), -1);
        assert_int_equal(r.under_way, 1);
        for (uint16_t u = 0U; u < 2U; u++) {
            assert_int_equal(r.residual->uavs[u].x, 5);
            assert_int_equal(r.residual->uavs[u].ready_at_ticks, 20);
        }
        assert_int_equal(r.covered, 3);
        assert_int_equal(state_of(1), SVA_TARGET_UNDER_WAY);
    }
    apply_ok(test_event_at(SVA_EVENT_CLOCK, 45));
    assert_int_equal(state_of(1), SVA_TARGET_DONE);
    assert_int_equal(state_of(2), SVA_TARGET_DONE);
    assert_int_equal(state_of(3), SVA_TARGET_DONE);
}

static void test_targets_added_cancelled_changed(void** state)
{
    (void)state;
    start_hand(0);
    sva_event_t added = test_event_at(SVA_EVENT_TARGET_ADDED, 5);
    added.target = (sva_target_t){9, 2, 2, 50, 60, 1};
    apply_ok(added);
    assert_int_equal(live.mission.target_count, 4);
    sva_live_result_t r;
    replan_ok(SVA_ALGO_FLOW, &r);
    assert_true(residual_index(&r, 9) >= 0);
    assert_int_equal(r.covered, 4);
    assert_int_equal(r.added, 1U);
    // Cancel T2 before its start: the UAV going there is free.
    sva_event_t cancel = test_event_at(SVA_EVENT_TARGET_CANCELLED, 25);
    cancel.target.id = 2;
    apply_ok(cancel);
    assert_int_equal(state_of(2), SVA_TARGET_CANCELLED);
    replan_ok(SVA_ALGO_FLOW, &r);
    assert_int_equal(residual_index(&r, 2), -1);
    // T3 moves before its start; the replan flies to its new place.
    sva_event_t moved = test_event_at(SVA_EVENT_TARGET_CHANGED, 26);
    moved.target = (sva_target_t){3, 2, 7, 33, 40, 1};
    apply_ok(moved);
    replan_ok(SVA_ALGO_FLOW, &r);
    const int t3 = residual_index(&r, 3);
    assert_true(t3 >= 0);
    assert_int_equal(r.residual->targets[t3].x, 2);
    assert_int_equal(r.residual->targets[t3].start_ticks, 33);
    apply_ok(test_event_at(SVA_EVENT_CLOCK, 61));
    assert_int_equal(state_of(3), SVA_TARGET_DONE);
    assert_int_equal(state_of(9), SVA_TARGET_DONE);
}

static void test_uav_back_and_fuel(void** state)
{
    (void)state;
    start_hand(0);
    sva_event_t lost = test_event_at(SVA_EVENT_UAV_LOST, 2);
    lost.uav_id = 2;
    apply_ok(lost);
    // T1 needs two UAVs: with one lost before its start it can no longer be covered.
    assert_int_equal(state_of(1), SVA_TARGET_EXPIRED);
    sva_event_t back = test_event_at(SVA_EVENT_UAV_BACK, 3);
    back.uav_id = 2;
    back.x = 4;
    back.y = 0;
    back.fuel = 50;
    apply_ok(back);
    assert_int_equal(state_of(1), SVA_TARGET_WAITING);
    sva_live_result_t r;
    replan_ok(SVA_ALGO_FLOW, &r);
    assert_int_equal(r.residual->uavs[1].x, 4);
    assert_int_equal(r.residual->uavs[1].fuel, 50);
    assert_int_equal(r.covered, 3);
    // A fuel reading too low for the rest of a route: the replan drops what does not fit.
    sva_event_t fuel = test_event_at(SVA_EVENT_FUEL, 4);
    fuel.uav_id = 1;
    fuel.fuel = 12;
    apply_ok(fuel);
    int32_t x = 0;
    int32_t y = 0;
    int32_t f = 0;
    int32_t ready = 0;
    assert_true(sva_live_uav_at(&live, 0U, 4, &x, &y, &f, &ready));
    assert_int_equal(f, 12);
    replan_ok(SVA_ALGO_FLOW, &r);
    assert_true(r.plan->routes[0].fuel_used <= 12);
    assert_int_equal(r.residual->uavs[0].fuel, 12);
}

static void position_ok(int32_t at, int32_t uav, int32_t x, int32_t y, int32_t fuel)
{
    sva_event_t e = test_event_at(SVA_EVENT_POSITION, at);
    e.uav_id = uav;
    e.x = x;
    e.y = y;
    e.fuel = fuel;
    apply_ok(e);
}

static void assert_uav_at(uint16_t u, int32_t at, int32_t x, int32_t y, int32_t fuel, int32_t ready)
{
    int32_t gx = 0;
    int32_t gy = 0;
    int32_t gf = 0;
    int32_t gr = 0;
    assert_true(sva_live_uav_at(&live, u, at, &gx, &gy, &gf, &gr));
    assert_int_equal(gx, x);
    assert_int_equal(gy, y);
    assert_int_equal(gf, fuel);
    assert_int_equal(gr, ready);
}

// A position report rebases the UAV: its route goes on from there, and a UAV reported
// off its target's cell during a visit under way breaks that visit.
static void test_position_event(void** state)
{
    (void)state;
    start_hand(0);
    assert_uav_at(0U, 3, 3, 0, 97, 3);
    position_ok(3, 1, 0, 3, 90);
    assert_uav_at(0U, 3, 0, 3, 90, 3);
    // x first, then y, from the reported cell and fuel.
    assert_uav_at(0U, 4, 1, 3, 89, 4);
    // 8 cells from (0, 3) to T1 at (5, 0): arriving at 11, after T1's start; with one
    // UAV able to be there in time, T1 (need 2) can no longer be covered.
    assert_int_equal(state_of(1), SVA_TARGET_EXPIRED);
    sva_live_result_t r;
    replan_ok(SVA_ALGO_FLOW, &r);
    assert_int_equal(r.residual->uavs[0].x, 0);
    assert_int_equal(r.residual->uavs[0].y, 3);
    assert_int_equal(r.residual->uavs[0].fuel, 90);

    start_hand(0);
    apply_ok(test_event_at(SVA_EVENT_CLOCK, 12));
    assert_int_equal(state_of(1), SVA_TARGET_UNDER_WAY);
    // On station: only the fuel changes; the visit goes on until its end.
    position_ok(13, 2, 5, 0, 70);
    assert_int_equal(state_of(1), SVA_TARGET_UNDER_WAY);
    assert_uav_at(1U, 13, 5, 0, 70, 20);
    // Off station during the visit: T1 is lost, both UAVs are free now.
    position_ok(14, 1, 6, 0, 80);
    assert_int_equal(state_of(1), SVA_TARGET_LOST);
    assert_uav_at(0U, 14, 6, 0, 80, 14);
    assert_uav_at(1U, 14, 5, 0, 70, 14);
    replan_ok(SVA_ALGO_FLOW, &r);
    assert_int_equal(residual_index(&r, 1), -1);
    assert_int_equal(r.under_way, 0);
    assert_int_equal(r.covered, 2);
    assert_int_equal(live.revision, 3U);
}

// A rejected event: the status, the message, and the live state byte for byte.
static void rejected(sva_event_t e, const char* message)
{
    sva_diag_t diag;
    char msg[200];
    (void)memcpy(&before, &live, sizeof(live));
    assert_int_equal(sva_live_apply(&live, &e, &diag), SVA_ERR_INVALID);
    (void)sva_diag_format(&diag, msg, sizeof msg);
    assert_string_equal(msg, message);
    assert_memory_equal(&live, &before, sizeof(live));
}

static void test_rejected_events_change_nothing(void** state)
{
    (void)state;
    start_hand(0);
    apply_ok(test_event_at(SVA_EVENT_CLOCK, 12));
    sva_event_t lost = test_event_at(SVA_EVENT_UAV_LOST, 13);
    lost.uav_id = 2;
    apply_ok(lost);
    rejected(test_event_at(SVA_EVENT_CLOCK, 11), "event.at: 11 is before now (13)");
    sva_event_t e = test_event_at(SVA_EVENT_UAV_LOST, 14);
    e.uav_id = 7;
    rejected(e, "event.uav: unknown id 7");
    e.uav_id = 2;
    rejected(e, "event.uav: the UAV is lost");
    e = test_event_at(SVA_EVENT_FUEL, 14);
    e.uav_id = 2;
    e.fuel = 5;
    rejected(e, "event.uav: the UAV is lost");
    e.uav_id = 1;
    e.fuel = -1;
    rejected(e, "event.fuel: must be >= 0, got -1");
    e = test_event_at(SVA_EVENT_POSITION, 14);
    e.uav_id = 2;
    rejected(e, "event.uav: the UAV is lost");
    e.uav_id = 9;
    rejected(e, "event.uav: unknown id 9");
    e.uav_id = 1;
    e.y = -40000;
    rejected(e, "event.y: must be >= -32768, got -40000");
    e.y = 0;
    e.fuel = 1000000001;
    rejected(e, "event.fuel: must be <= SVA_MAX_FUEL (1000000000), got 1000000001");
    // Off station during T1's visit under way, but at a tick before now.
    e = test_event_at(SVA_EVENT_POSITION, 12);
    e.uav_id = 1;
    e.x = 9;
    rejected(e, "event.at: 12 is before now (13)");
    e = test_event_at(SVA_EVENT_UAV_BACK, 14);
    e.uav_id = 1;
    rejected(e, "event.uav: the UAV is in service");
    e.uav_id = 2;
    e.x = 40000;
    rejected(e, "event.x: must be <= 32767, got 40000");
    e = test_event_at(SVA_EVENT_TARGET_ADDED, 14);
    e.target = (sva_target_t){3, 1, 1, 50, 60, 1};
    rejected(e, "event.target: duplicate id 3 (first at index 2)");
    e.target.id = 4;
    e.target.start_ticks = 10;
    rejected(e, "targets[3].start: 10 is before now (14)");
    e.target.start_ticks = 50;
    e.target.end_ticks = 50;
    rejected(e, "targets[3].end: must be > start (50), got 50");
    e = test_event_at(SVA_EVENT_TARGET_CANCELLED, 14);
    e.target.id = 1;
    rejected(e, "event.target: the target is lost");
    e.target.id = 8;
    rejected(e, "event.target: unknown id 8");
    e = test_event_at(SVA_EVENT_TARGET_CHANGED, 31);
    e.target = (sva_target_t){2, 1, 1, 50, 60, 1};
    rejected(e, "event.target: its window started at 30 (now 31): only a target not yet "
                "started may change");
    e = test_event_at(SVA_EVENT_CLOCK, 14);
    e.type = SVA_EVENT_COUNT_;
    rejected(e, "event.type: must be <= 7, got 8");
    // Done targets cannot be cancelled.
    apply_ok(test_event_at(SVA_EVENT_CLOCK, 45));
    e = test_event_at(SVA_EVENT_TARGET_CANCELLED, 46);
    e.target.id = 2;
    rejected(e, "event.target: the target is done");
}

static void test_rejected_starts(void** state)
{
    (void)state;
    start_hand(0);
    sva_diag_t diag;
    char msg[160];
    mission.change_penalty = -1;
    assert_int_equal(sva_live_init(&live, &mission, &plan, &diag), SVA_ERR_INVALID);
    (void)sva_diag_format(&diag, msg, sizeof msg);
    assert_string_equal(msg, "change_penalty: must be >= 0, got -1");
    mission.change_penalty = 2000000;
    assert_int_equal(sva_live_init(&live, &mission, &plan, &diag), SVA_ERR_INVALID);
    (void)sva_diag_format(&diag, msg, sizeof msg);
    assert_string_equal(msg,
                        "change_penalty: must be <= SVA_MAX_CHANGE_PENALTY (1000000), got 2000000");
    mission.change_penalty = 0;
    plan.routes[1].targets[1] = 0U;
    assert_int_equal(sva_live_init(&live, &mission, &plan, &diag), SVA_ERR_INVALID);
    (void)sva_diag_format(&diag, msg, sizeof msg);
    assert_string_equal(msg, "routes[1].targets: duplicate id 1 (first at index 0)");
    plan.routes[1].targets[1] = 7U;
    assert_int_equal(sva_live_init(&live, &mission, &plan, &diag), SVA_ERR_INVALID);
    (void)sva_diag_format(&diag, msg, sizeof msg);
    assert_string_equal(msg, "routes[1].targets: must be <= 2, got 7");
    plan.routes[1].uav_id = 5;
    assert_int_equal(sva_live_init(&live, &mission, &plan, &diag), SVA_ERR_INVALID);
    (void)sva_diag_format(&diag, msg, sizeof msg);
    assert_string_equal(msg, "routes[1].uav: must follow the mission's UAVs (2), got 5");
}

// The plan in force carried over, recomputed here from SPEC section 1 alone: the
// previous visits of the residual targets, less every target that some UAV can no
// longer serve in time or with fuel to get home, or that lacks part of its need.
static int carried_coverage(const sva_mission_t* m, const sva_plan_t* previous)
{
    static sva_plan_t p;
    p = *previous;
    for (;;) {
        int drop = -1;
        for (uint16_t t = 0U; (t < m->target_count) && (drop < 0); t++) {
            int served = 0;
            for (uint16_t r = 0U; r < p.route_count; r++) {
                for (uint16_t k = 0U; k < p.routes[r].target_count; k++) {
                    served += (p.routes[r].targets[k] == t) ? 1 : 0;
                }
            }
            drop = ((served != 0) && (served != m->targets[t].need)) ? (int)t : -1;
        }
        for (uint16_t r = 0U; (r < p.route_count) && (drop < 0); r++) {
            long long x = m->uavs[r].x;
            long long y = m->uavs[r].y;
            long long free_at = m->uavs[r].ready_at_ticks;
            long long fuel = m->uavs[r].fuel;
            for (uint16_t k = 0U; (k < p.routes[r].target_count) && (drop < 0); k++) {
                const sva_target_t* t = &m->targets[p.routes[r].targets[k]];
                const long long cells = llabs(t->x - x) + llabs(t->y - y);
                fuel -= cells + m->hover_fuel;
                const long long home = llabs(t->x - m->depot_x) + llabs(t->y - m->depot_y);
                if ((free_at + (cells * m->ticks_per_cell) > t->start_ticks) || (fuel < home)) {
                    drop = p.routes[r].targets[k];
                }
                x = t->x;
                y = t->y;
                free_at = t->end_ticks;
            }
        }
        if (drop < 0) {
            break;
        }
        for (uint16_t r = 0U; r < p.route_count; r++) {
            uint16_t kept = 0U;
            for (uint16_t k = 0U; k < p.routes[r].target_count; k++) {
                if (p.routes[r].targets[k] != (uint16_t)drop) {
                    p.routes[r].targets[kept++] = p.routes[r].targets[k];
                }
            }
            p.routes[r].target_count = kept;
        }
    }
    int covered = 0;
    for (uint16_t t = 0U; t < m->target_count; t++) {
        int served = 0;
        for (uint16_t r = 0U; r < p.route_count; r++) {
            for (uint16_t k = 0U; k < p.routes[r].target_count; k++) {
                served += (p.routes[r].targets[k] == t) ? 1 : 0;
            }
        }
        covered += (served == m->targets[t].need) ? 1 : 0;
    }
    return covered;
}

// Random live missions: plan, then random events with a replan after each, by every
// algorithm that fits. Every replan's plan passes the SPEC checker on its residual
// mission, never covers fewer targets than the plan in force carried over, and keeps
// the visits under way out of the residual mission.
static void test_random_live_missions(void** state)
{
    (void)state;
    const uint64_t seed = test_seed(20261125U);
    test_rng_t rng;
    test_rng_seed(&rng, seed);
    int replans = 0;
    for (int n = 0; n < 60; n++) {
        test_gen_mission(&rng, &test_live_params, &mission);
        if ((mission.target_count > SVA_MAX_TARGETS - 4) || (mission.uav_count > SVA_MAX_UAVS)) {
            continue;
        }
        const sva_algorithm_t algo = (sva_algorithm_t)(n % (int)SVA_ALGO_COUNT_);
        assert_int_equal(sva_planner_init(&planner), SVA_OK);
        if (sva_plan(&planner, &mission, algo, &plan, NULL) != SVA_OK) {
            continue;
        }
        mission.change_penalty = test_rng_range(&rng, 0, 1) * 50;
        assert_int_equal(sva_live_init(&live, &mission, &plan, NULL), SVA_OK);
        int32_t at = 0;
        for (int k = 0; k < 6; k++) {
            at += test_rng_range(&rng, 1, 12);
            sva_event_t e = test_live_random_event(
                &rng, &live, at, k, (sva_event_type_t)((int32_t)SVA_EVENT_COUNT_ - 1));
            sva_diag_t diag;
            (void)memcpy(&before, &live, sizeof(live));
            if (sva_live_apply(&live, &e, &diag) != SVA_OK) {
                assert_memory_equal(&live, &before, sizeof(live));
                continue;
            }
            sva_live_result_t r;
            if (sva_live_replan(&live, &planner, algo, &r, &diag) != SVA_OK) {
                continue;  // bfa over its limits: the plan in force stays
            }
            char msg[200];
            if (spec_check_plan(r.residual, r.plan, msg, sizeof msg) != 0) {
                fail_msg("seed %llu mission %d event %d (%s): %s", (unsigned long long)seed, n, k,
                         sva_algorithm_name(algo), msg);
            }
            if ((int)r.plan->covered < carried_coverage(r.residual, r.previous)) {
                fail_msg("seed %llu mission %d event %d (%s): covers %d, the plan in force %d",
                         (unsigned long long)seed, n, k, sva_algorithm_name(algo),
                         (int)r.plan->covered, carried_coverage(r.residual, r.previous));
            }
            for (uint16_t i = 0U; i < r.residual->target_count; i++) {
                const sva_target_t* t = &r.residual->targets[i];
                assert_true(t->start_ticks >= r.now_ticks);
                assert_int_equal(state_of(t->id), SVA_TARGET_WAITING);
            }
            replans++;
        }
    }
    printf("random live missions (seed %llu): %d replans checked\n", (unsigned long long)seed,
           replans);
    assert_true(replans > 50);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_flight_model_and_clock),
        cmocka_unit_test(test_lost_uav_breaks_visit_under_way),
        cmocka_unit_test(test_change_penalty_keeps_standing_visits),
        cmocka_unit_test(test_replan_keeps_visits_under_way),
        cmocka_unit_test(test_targets_added_cancelled_changed),
        cmocka_unit_test(test_uav_back_and_fuel),
        cmocka_unit_test(test_position_event),
        cmocka_unit_test(test_rejected_events_change_nothing),
        cmocka_unit_test(test_rejected_starts),
        cmocka_unit_test(test_random_live_missions),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
