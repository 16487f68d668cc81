// test_live.c -- the live-mission module (docs/SPEC.md section 12): the clock and the
// visit states, the flight model, every event and every rejected event (the live state
// byte for byte unchanged), and the replan's candidates and objective. Random live
// missions check every replan's plan with the independent SPEC checker.
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "sva_unity.h"

#include "live_gen.h"
#include "mission_gen.h"
#include "spec_checker.h"
#include "sva/sva_live.h"

static sva_live_t live;
static sva_live_t before;
static sva_planner_t planner;
static sva_mission_t mission;
static sva_plan_t plan;

// Two UAVs at the depot; T1 needs both at (5, 0) in [10, 20]; T2 at (5, 5) and T3 at
// (1, 6) in [30, 40] need one each. Plan in force: UAV 1 T1 then T2, UAV 2 T1 then T3.
static void start_hand_taking_off(int32_t change_penalty, int32_t takeoff_ticks)
{
    sva_mission_init(&mission);
    mission.change_penalty = change_penalty;
    mission.takeoff_ticks = takeoff_ticks;
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
    TEST_ASSERT_EQUAL_INT(SVA_OK, sva_live_init(&live, &mission, &plan, &diag));
    TEST_ASSERT_EQUAL_INT(SVA_OK, sva_planner_init(&planner));
}

static void start_hand(int32_t change_penalty)
{
    start_hand_taking_off(change_penalty, 0);
}

static void apply_ok(sva_event_t e)
{
    sva_diag_t diag;
    char msg[160];
    const sva_status_t status = sva_live_apply(&live, &e, &diag);
    (void)sva_diag_format(&diag, msg, sizeof msg);
    if (status != SVA_OK) {
        SVA_TEST_FAIL("event %s at %d rejected: %s", sva_event_type_name(e.type), (int)e.at_ticks,
                      msg);
    }
}

static sva_target_state_t state_of(int32_t id)
{
    for (uint16_t i = 0U; i < live.mission.target_count; i++) {
        if (live.mission.targets[i].id == id) {
            return (sva_target_state_t)live.target_state[i];
        }
    }
    SVA_TEST_FAIL("no target %d", (int)id);
    return SVA_TARGET_STATE_COUNT_;
}

static void replan_ok(sva_algorithm_t algo, sva_live_result_t* result)
{
    sva_diag_t diag;
    char msg[200];
    TEST_ASSERT_EQUAL_INT(SVA_OK, sva_live_replan(&live, &planner, algo, result, &diag));
    if (spec_check_plan(result->residual, result->plan, msg, sizeof msg) != 0) {
        SVA_TEST_FAIL("replan (%s) breaks SPEC: %s", sva_algorithm_name(algo), msg);
    }
    TEST_ASSERT_EQUAL_INT(result->under_way + result->plan->covered, result->covered);
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

void test_flight_model_and_clock(void)
{
    start_hand(0);
    int32_t x = 0;
    int32_t y = 0;
    int32_t fuel = 0;
    int32_t ready = 0;
    // x first: 3 cells east at tick 3.
    TEST_ASSERT_TRUE(sva_live_uav_at(&live, 0U, 3, &x, &y, &fuel, &ready));
    TEST_ASSERT_EQUAL_INT(3, x);
    TEST_ASSERT_EQUAL_INT(0, y);
    TEST_ASSERT_EQUAL_INT(97, fuel);
    TEST_ASSERT_EQUAL_INT(3, ready);
    TEST_ASSERT_EQUAL_INT(SVA_TARGET_WAITING, state_of(1));
    apply_ok(test_event_at(SVA_EVENT_CLOCK, 10));
    TEST_ASSERT_EQUAL_INT(SVA_TARGET_UNDER_WAY, state_of(1));
    // Under way: at the target until the window ends.
    TEST_ASSERT_TRUE(sva_live_uav_at(&live, 1U, 12, &x, &y, &fuel, &ready));
    TEST_ASSERT_EQUAL_INT(5, x);
    TEST_ASSERT_EQUAL_INT(20, ready);
    apply_ok(test_event_at(SVA_EVENT_CLOCK, 20));
    TEST_ASSERT_EQUAL_INT(SVA_TARGET_DONE, state_of(1));
    // UAV 2 leaves T1 at 20 for T3 (1, 6): 4 cells west first, then north.
    TEST_ASSERT_TRUE(sva_live_uav_at(&live, 1U, 27, &x, &y, &fuel, &ready));
    TEST_ASSERT_EQUAL_INT(1, x);
    TEST_ASSERT_EQUAL_INT(3, y);
    apply_ok(test_event_at(SVA_EVENT_CLOCK, 45));
    TEST_ASSERT_EQUAL_INT(SVA_TARGET_DONE, state_of(2));
    TEST_ASSERT_EQUAL_INT(SVA_TARGET_DONE, state_of(3));
    TEST_ASSERT_EQUAL_INT(3U, live.revision);
}

void test_lost_uav_breaks_visit_under_way(void)
{
    start_hand(0);
    sva_event_t lost = test_event_at(SVA_EVENT_UAV_LOST, 15);
    lost.uav_id = 1;
    apply_ok(lost);
    // T1 was under way with both UAVs: it can no longer be covered; UAV 2 is free now.
    TEST_ASSERT_EQUAL_INT(SVA_TARGET_LOST, state_of(1));
    int32_t x = 0;
    int32_t y = 0;
    int32_t fuel = 0;
    int32_t ready = 0;
    TEST_ASSERT_TRUE(sva_live_uav_at(&live, 1U, 15, &x, &y, &fuel, &ready));
    TEST_ASSERT_EQUAL_INT(5, x);
    TEST_ASSERT_EQUAL_INT(0, y);
    TEST_ASSERT_EQUAL_INT(15, ready);
    TEST_ASSERT_FALSE(sva_live_uav_at(&live, 0U, 15, &x, &y, &fuel, &ready));
    sva_live_result_t r;
    replan_ok(SVA_ALGO_FLOW, &r);
    TEST_ASSERT_EQUAL_INT(1, r.residual->uav_count);
    TEST_ASSERT_EQUAL_INT(15, r.residual->uavs[0].ready_at_ticks);
    TEST_ASSERT_EQUAL_INT(2, r.residual->target_count);
    // One UAV, two windows at once: one target. Change penalty 0: the cheaper T2
    // (5 + 10) beats keeping T3 (10 + 7): two changed visits.
    TEST_ASSERT_EQUAL_INT(1, r.plan->covered);
    TEST_ASSERT_FALSE(r.kept);
    TEST_ASSERT_EQUAL_INT(15, r.plan->cost);
    TEST_ASSERT_EQUAL_INT(1U, r.dropped);
    TEST_ASSERT_EQUAL_INT(1U, r.added);
    TEST_ASSERT_EQUAL_INT(15, r.objective);
}

void test_change_penalty_keeps_standing_visits(void)
{
    start_hand(10);
    sva_event_t lost = test_event_at(SVA_EVENT_UAV_LOST, 15);
    lost.uav_id = 1;
    apply_ok(lost);
    sva_live_result_t r;
    replan_ok(SVA_ALGO_FLOW, &r);
    // 17 for keeping T3 against 15 + 2 * 10 for switching to T2.
    TEST_ASSERT_TRUE(r.kept);
    TEST_ASSERT_EQUAL_INT(17, r.plan->cost);
    TEST_ASSERT_EQUAL_INT(0U, r.dropped + r.added);
    TEST_ASSERT_EQUAL_INT(17, r.objective);
    const int t3 = residual_index(&r, 3);
    TEST_ASSERT_TRUE(t3 >= 0);
    TEST_ASSERT_EQUAL_INT(1, r.plan->routes[0].target_count);
    TEST_ASSERT_EQUAL_INT(t3, r.plan->routes[0].targets[0]);
    // The kept plan is the plan in force now: flying on, T3 is covered.
    apply_ok(test_event_at(SVA_EVENT_CLOCK, 41));
    TEST_ASSERT_EQUAL_INT(SVA_TARGET_DONE, state_of(3));
    TEST_ASSERT_EQUAL_INT(SVA_TARGET_EXPIRED, state_of(2));
}

void test_replan_keeps_visits_under_way(void)
{
    start_hand(0);
    apply_ok(test_event_at(SVA_EVENT_CLOCK, 12));
    for (int algo = 0; algo < (int)SVA_ALGO_COUNT_; algo++) {
        sva_live_result_t r;
        replan_ok((sva_algorithm_t)algo, &r);
        // T1 is under way: not in the residual mission; both UAVs wait there until 20.
        TEST_ASSERT_EQUAL_INT(-1, residual_index(&r, 1));
        TEST_ASSERT_EQUAL_INT(1, r.under_way);
        for (uint16_t u = 0U; u < 2U; u++) {
            TEST_ASSERT_EQUAL_INT(5, r.residual->uavs[u].x);
            TEST_ASSERT_EQUAL_INT(20, r.residual->uavs[u].ready_at_ticks);
        }
        TEST_ASSERT_EQUAL_INT(3, r.covered);
        TEST_ASSERT_EQUAL_INT(SVA_TARGET_UNDER_WAY, state_of(1));
    }
    apply_ok(test_event_at(SVA_EVENT_CLOCK, 45));
    TEST_ASSERT_EQUAL_INT(SVA_TARGET_DONE, state_of(1));
    TEST_ASSERT_EQUAL_INT(SVA_TARGET_DONE, state_of(2));
    TEST_ASSERT_EQUAL_INT(SVA_TARGET_DONE, state_of(3));
}

void test_targets_added_cancelled_changed(void)
{
    start_hand(0);
    sva_event_t added = test_event_at(SVA_EVENT_TARGET_ADDED, 5);
    added.target = (sva_target_t){9, 2, 2, 50, 60, 1};
    apply_ok(added);
    TEST_ASSERT_EQUAL_INT(4, live.mission.target_count);
    sva_live_result_t r;
    replan_ok(SVA_ALGO_FLOW, &r);
    TEST_ASSERT_TRUE(residual_index(&r, 9) >= 0);
    TEST_ASSERT_EQUAL_INT(4, r.covered);
    TEST_ASSERT_EQUAL_INT(1U, r.added);
    // Cancel T2 before its start: the UAV going there is free.
    sva_event_t cancel = test_event_at(SVA_EVENT_TARGET_CANCELLED, 25);
    cancel.target.id = 2;
    apply_ok(cancel);
    TEST_ASSERT_EQUAL_INT(SVA_TARGET_CANCELLED, state_of(2));
    replan_ok(SVA_ALGO_FLOW, &r);
    TEST_ASSERT_EQUAL_INT(-1, residual_index(&r, 2));
    // T3 moves before its start; the replan flies to its new place.
    sva_event_t moved = test_event_at(SVA_EVENT_TARGET_CHANGED, 26);
    moved.target = (sva_target_t){3, 2, 7, 33, 40, 1};
    apply_ok(moved);
    replan_ok(SVA_ALGO_FLOW, &r);
    const int t3 = residual_index(&r, 3);
    TEST_ASSERT_TRUE(t3 >= 0);
    TEST_ASSERT_EQUAL_INT(2, r.residual->targets[t3].x);
    TEST_ASSERT_EQUAL_INT(33, r.residual->targets[t3].start_ticks);
    apply_ok(test_event_at(SVA_EVENT_CLOCK, 61));
    TEST_ASSERT_EQUAL_INT(SVA_TARGET_DONE, state_of(3));
    TEST_ASSERT_EQUAL_INT(SVA_TARGET_DONE, state_of(9));
}

void test_uav_back_and_fuel(void)
{
    start_hand(0);
    sva_event_t lost = test_event_at(SVA_EVENT_UAV_LOST, 2);
    lost.uav_id = 2;
    apply_ok(lost);
    // T1 needs two UAVs: with one lost before its start it can no longer be covered.
    TEST_ASSERT_EQUAL_INT(SVA_TARGET_EXPIRED, state_of(1));
    sva_event_t back = test_event_at(SVA_EVENT_UAV_BACK, 3);
    back.uav_id = 2;
    back.x = 4;
    back.y = 0;
    back.fuel = 50;
    apply_ok(back);
    TEST_ASSERT_EQUAL_INT(SVA_TARGET_WAITING, state_of(1));
    sva_live_result_t r;
    replan_ok(SVA_ALGO_FLOW, &r);
    TEST_ASSERT_EQUAL_INT(4, r.residual->uavs[1].x);
    TEST_ASSERT_EQUAL_INT(50, r.residual->uavs[1].fuel);
    TEST_ASSERT_EQUAL_INT(3, r.covered);
    // A fuel reading too low for the rest of a route: the replan drops what does not fit.
    sva_event_t fuel = test_event_at(SVA_EVENT_FUEL, 4);
    fuel.uav_id = 1;
    fuel.fuel = 12;
    apply_ok(fuel);
    int32_t x = 0;
    int32_t y = 0;
    int32_t f = 0;
    int32_t ready = 0;
    TEST_ASSERT_TRUE(sva_live_uav_at(&live, 0U, 4, &x, &y, &f, &ready));
    TEST_ASSERT_EQUAL_INT(12, f);
    replan_ok(SVA_ALGO_FLOW, &r);
    TEST_ASSERT_TRUE(r.plan->routes[0].fuel_used <= 12);
    TEST_ASSERT_EQUAL_INT(12, r.residual->uavs[0].fuel);
}

// start_hand() with takeoff_ticks; both UAVs are home by 50 (UAV 1 from T2 at 40,
// UAV 2 from T3 at 40), then T9 at (2, 0) in [64, 70] is added at 60: two cells away, so a
// UAV that leaves at once arrives at 62 and one that takes off for k ticks at 62 + k.
static sva_live_result_t home_and_retasked(int32_t takeoff)
{
    start_hand_taking_off(0, takeoff);
    sva_event_t added = test_event_at(SVA_EVENT_TARGET_ADDED, 60);
    added.target = (sva_target_t){9, 2, 0, 64, 70, 1};
    apply_ok(added);
    sva_live_result_t r;
    replan_ok(SVA_ALGO_FLOW, &r);
    return r;
}

// A UAV on the ground takes off before it leaves: home with its route done (landed), or
// back in service (uav_back). In flight, on its way home, it does not.
void test_takeoff_on_the_ground_only(void)
{
    sva_live_result_t r = home_and_retasked(0);
    TEST_ASSERT_EQUAL_INT(60, r.residual->uavs[0].ready_at_ticks);
    TEST_ASSERT_EQUAL_INT(1, r.plan->covered);
    r = home_and_retasked(2);  // arrives at 64: just in time
    TEST_ASSERT_EQUAL_INT(62, r.residual->uavs[0].ready_at_ticks);
    TEST_ASSERT_EQUAL_INT(62, r.residual->uavs[1].ready_at_ticks);
    TEST_ASSERT_EQUAL_INT(1, r.plan->covered);
    r = home_and_retasked(3);  // arrives at 65: too late for the window's start
    TEST_ASSERT_EQUAL_INT(63, r.residual->uavs[0].ready_at_ticks);
    TEST_ASSERT_EQUAL_INT(0, r.plan->covered);

    // On its way home at 45 (T2 left at 40; 5 of 10 cells flown): no take-off.
    start_hand_taking_off(0, 7);
    int32_t x = 0;
    int32_t y = 0;
    int32_t f = 0;
    int32_t ready = 0;
    TEST_ASSERT_TRUE(sva_live_uav_at(&live, 0U, 45, &x, &y, &f, &ready));
    TEST_ASSERT_EQUAL_INT(45, ready);
    TEST_ASSERT_TRUE(sva_live_uav_at(&live, 0U, 50, &x, &y, &f, &ready));  // home now
    TEST_ASSERT_EQUAL_INT(0, x);
    TEST_ASSERT_EQUAL_INT(50, ready);
    TEST_ASSERT_TRUE(sva_live_uav_at(&live, 0U, 51, &x, &y, &f, &ready));  // landed
    TEST_ASSERT_EQUAL_INT(58, ready);

    // Back in service at (4, 0) at 3: free at 3 + 7 = 10, T1 at (5, 0) reached at 11 is
    // past its start at 10; with no take-off it would be in time.
    sva_event_t lost = test_event_at(SVA_EVENT_UAV_LOST, 2);
    lost.uav_id = 2;
    apply_ok(lost);
    sva_event_t back = test_event_at(SVA_EVENT_UAV_BACK, 3);
    back.uav_id = 2;
    back.x = 4;
    back.y = 0;
    back.fuel = 50;
    apply_ok(back);
    TEST_ASSERT_TRUE(sva_live_uav_at(&live, 1U, 3, &x, &y, &f, &ready));
    TEST_ASSERT_EQUAL_INT(10, ready);
    replan_ok(SVA_ALGO_FLOW, &r);
    TEST_ASSERT_EQUAL_INT(10, r.residual->uavs[1].ready_at_ticks);
    TEST_ASSERT_EQUAL_INT(2, r.covered);  // T2 and T3; T1 needs both UAVs at 10
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
    TEST_ASSERT_TRUE(sva_live_uav_at(&live, u, at, &gx, &gy, &gf, &gr));
    TEST_ASSERT_EQUAL_INT(x, gx);
    TEST_ASSERT_EQUAL_INT(y, gy);
    TEST_ASSERT_EQUAL_INT(fuel, gf);
    TEST_ASSERT_EQUAL_INT(ready, gr);
}

// A position report rebases the UAV: its route goes on from there, and a UAV reported
// off its target's cell during a visit under way breaks that visit.
void test_position_event(void)
{
    start_hand(0);
    assert_uav_at(0U, 3, 3, 0, 97, 3);
    position_ok(3, 1, 0, 3, 90);
    assert_uav_at(0U, 3, 0, 3, 90, 3);
    // x first, then y, from the reported cell and fuel.
    assert_uav_at(0U, 4, 1, 3, 89, 4);
    // 8 cells from (0, 3) to T1 at (5, 0): arriving at 11, after T1's start; with one
    // UAV able to be there in time, T1 (need 2) can no longer be covered.
    TEST_ASSERT_EQUAL_INT(SVA_TARGET_EXPIRED, state_of(1));
    sva_live_result_t r;
    replan_ok(SVA_ALGO_FLOW, &r);
    TEST_ASSERT_EQUAL_INT(0, r.residual->uavs[0].x);
    TEST_ASSERT_EQUAL_INT(3, r.residual->uavs[0].y);
    TEST_ASSERT_EQUAL_INT(90, r.residual->uavs[0].fuel);

    start_hand(0);
    apply_ok(test_event_at(SVA_EVENT_CLOCK, 12));
    TEST_ASSERT_EQUAL_INT(SVA_TARGET_UNDER_WAY, state_of(1));
    // On station: only the fuel changes; the visit goes on until its end.
    position_ok(13, 2, 5, 0, 70);
    TEST_ASSERT_EQUAL_INT(SVA_TARGET_UNDER_WAY, state_of(1));
    assert_uav_at(1U, 13, 5, 0, 70, 20);
    // Off station during the visit: T1 is lost, both UAVs are free now.
    position_ok(14, 1, 6, 0, 80);
    TEST_ASSERT_EQUAL_INT(SVA_TARGET_LOST, state_of(1));
    assert_uav_at(0U, 14, 6, 0, 80, 14);
    assert_uav_at(1U, 14, 5, 0, 70, 14);
    replan_ok(SVA_ALGO_FLOW, &r);
    TEST_ASSERT_EQUAL_INT(-1, residual_index(&r, 1));
    TEST_ASSERT_EQUAL_INT(0, r.under_way);
    TEST_ASSERT_EQUAL_INT(2, r.covered);
    TEST_ASSERT_EQUAL_INT(3U, live.revision);
}

// A rejected event: the status, the message, and the live state byte for byte.
static void rejected(sva_event_t e, const char* message)
{
    sva_diag_t diag;
    char msg[200];
    (void)memcpy(&before, &live, sizeof(live));
    TEST_ASSERT_EQUAL_INT(SVA_ERR_INVALID, sva_live_apply(&live, &e, &diag));
    (void)sva_diag_format(&diag, msg, sizeof msg);
    TEST_ASSERT_EQUAL_STRING(message, msg);
    TEST_ASSERT_EQUAL_MEMORY(&before, &live, sizeof(live));
}

void test_rejected_events_change_nothing(void)
{
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

void test_rejected_starts(void)
{
    start_hand(0);
    sva_diag_t diag;
    char msg[160];
    mission.change_penalty = -1;
    TEST_ASSERT_EQUAL_INT(SVA_ERR_INVALID, sva_live_init(&live, &mission, &plan, &diag));
    (void)sva_diag_format(&diag, msg, sizeof msg);
    TEST_ASSERT_EQUAL_STRING("change_penalty: must be >= 0, got -1", msg);
    mission.change_penalty = 2000000;
    TEST_ASSERT_EQUAL_INT(SVA_ERR_INVALID, sva_live_init(&live, &mission, &plan, &diag));
    (void)sva_diag_format(&diag, msg, sizeof msg);
    TEST_ASSERT_EQUAL_STRING(
        "change_penalty: must be <= SVA_MAX_CHANGE_PENALTY (1000000), got 2000000", msg);
    mission.change_penalty = 0;
    mission.takeoff_ticks = -1;
    TEST_ASSERT_EQUAL_INT(SVA_ERR_INVALID, sva_live_init(&live, &mission, &plan, &diag));
    (void)sva_diag_format(&diag, msg, sizeof msg);
    TEST_ASSERT_EQUAL_STRING("takeoff_ticks: must be >= 0, got -1", msg);
    mission.takeoff_ticks = SVA_MAX_TICK + 1;
    TEST_ASSERT_EQUAL_INT(SVA_ERR_INVALID, sva_live_init(&live, &mission, &plan, &diag));
    (void)sva_diag_format(&diag, msg, sizeof msg);
    TEST_ASSERT_TRUE(strstr(msg, "takeoff_ticks: must be <= SVA_MAX_TICK") == msg);
    mission.takeoff_ticks = 0;
    plan.routes[1].targets[1] = 0U;
    TEST_ASSERT_EQUAL_INT(SVA_ERR_INVALID, sva_live_init(&live, &mission, &plan, &diag));
    (void)sva_diag_format(&diag, msg, sizeof msg);
    TEST_ASSERT_EQUAL_STRING("routes[1].targets: duplicate id 1 (first at index 0)", msg);
    plan.routes[1].targets[1] = 7U;
    TEST_ASSERT_EQUAL_INT(SVA_ERR_INVALID, sva_live_init(&live, &mission, &plan, &diag));
    (void)sva_diag_format(&diag, msg, sizeof msg);
    TEST_ASSERT_EQUAL_STRING("routes[1].targets: must be <= 2, got 7", msg);
    plan.routes[1].uav_id = 5;
    TEST_ASSERT_EQUAL_INT(SVA_ERR_INVALID, sva_live_init(&live, &mission, &plan, &diag));
    (void)sva_diag_format(&diag, msg, sizeof msg);
    TEST_ASSERT_EQUAL_STRING("routes[1].uav: must follow the mission's UAVs (2), got 5", msg);
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
void test_random_live_missions(void)
{
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
        TEST_ASSERT_EQUAL_INT(SVA_OK, sva_planner_init(&planner));
        if (sva_plan(&planner, &mission, algo, &plan, NULL) != SVA_OK) {
            continue;
        }
        mission.change_penalty = test_rng_range(&rng, 0, 1) * 50;
        TEST_ASSERT_EQUAL_INT(SVA_OK, sva_live_init(&live, &mission, &plan, NULL));
        int32_t at = 0;
        for (int k = 0; k < 6; k++) {
            at += test_rng_range(&rng, 1, 12);
            sva_event_t e = test_live_random_event(
                &rng, &live, at, k, (sva_event_type_t)((int32_t)SVA_EVENT_COUNT_ - 1));
            sva_diag_t diag;
            (void)memcpy(&before, &live, sizeof(live));
            if (sva_live_apply(&live, &e, &diag) != SVA_OK) {
                TEST_ASSERT_EQUAL_MEMORY(&before, &live, sizeof(live));
                continue;
            }
            sva_live_result_t r;
            if (sva_live_replan(&live, &planner, algo, &r, &diag) != SVA_OK) {
                continue;  // bfa over its limits: the plan in force stays
            }
            char msg[200];
            if (spec_check_plan(r.residual, r.plan, msg, sizeof msg) != 0) {
                SVA_TEST_FAIL("seed %llu mission %d event %d (%s): %s", (unsigned long long)seed, n,
                              k, sva_algorithm_name(algo), msg);
            }
            if ((int)r.plan->covered < carried_coverage(r.residual, r.previous)) {
                SVA_TEST_FAIL("seed %llu mission %d event %d (%s): covers %d, the plan in force %d",
                              (unsigned long long)seed, n, k, sva_algorithm_name(algo),
                              (int)r.plan->covered, carried_coverage(r.residual, r.previous));
            }
            for (uint16_t i = 0U; i < r.residual->target_count; i++) {
                const sva_target_t* t = &r.residual->targets[i];
                TEST_ASSERT_TRUE(t->start_ticks >= r.now_ticks);
                TEST_ASSERT_EQUAL_INT(SVA_TARGET_WAITING, state_of(t->id));
            }
            replans++;
        }
    }
    printf("random live missions (seed %llu): %d replans checked\n", (unsigned long long)seed,
           replans);
    TEST_ASSERT_TRUE(replans > 50);
}

// sva_plan_changes: route r held against route r; a route the other plan lacks is empty;
// the count is exact when the list is cut at cap.
void test_plan_changes_lists_visits_one_way(void)
{
    // Two plans of the live struct's, as scratch (the target's memory holds no more).
    sva_plan_t* a = &live.plan;
    sva_plan_t* b = &live.previous;
    memset(a, 0, sizeof *a);
    memset(b, 0, sizeof *b);
    a->route_count = 3U;
    a->routes[0].target_count = 3U;
    a->routes[0].targets[0] = 1U;
    a->routes[0].targets[1] = 2U;
    a->routes[0].targets[2] = 3U;
    a->routes[1].target_count = 1U;
    a->routes[1].targets[0] = 4U;
    a->routes[2].target_count = 1U;
    a->routes[2].targets[0] = 5U;
    b->route_count = 2U;
    b->routes[0].target_count = 2U;
    b->routes[0].targets[0] = 3U;
    b->routes[0].targets[1] = 1U;
    b->routes[1].target_count = 1U;
    b->routes[1].targets[0] = 5U;
    sva_visit_t v[3];
    memset(v, 0xff, sizeof v);
    TEST_ASSERT_EQUAL_UINT32(3U, sva_plan_changes(a, b, v, 2U));
    TEST_ASSERT_EQUAL_UINT16(0U, v[0].route);
    TEST_ASSERT_EQUAL_UINT16(2U, v[0].target);
    TEST_ASSERT_EQUAL_UINT16(1U, v[1].route);
    TEST_ASSERT_EQUAL_UINT16(4U, v[1].target);
    TEST_ASSERT_EQUAL_UINT16(0xffffU, v[2].route);  // past cap: untouched
    TEST_ASSERT_EQUAL_UINT32(3U, sva_plan_changes(a, b, v, 3U));
    TEST_ASSERT_EQUAL_UINT16(2U, v[2].route);
    TEST_ASSERT_EQUAL_UINT16(5U, v[2].target);
    TEST_ASSERT_EQUAL_UINT32(1U, sva_plan_changes(b, a, v, 3U));
    TEST_ASSERT_EQUAL_UINT16(1U, v[0].route);
    TEST_ASSERT_EQUAL_UINT16(5U, v[0].target);
    TEST_ASSERT_EQUAL_UINT32(0U, sva_plan_changes(a, a, NULL, 0U));
}
