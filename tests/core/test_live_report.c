// test_live_report.c -- the report rule (sva_live_report, docs/live.md "Vehicle
// reports"): what a vehicle says of itself becomes uav_lost, uav_back, position, fuel
// or nothing, judged against the flight model; the rule never changes the live mission.
#include <stddef.h>
#include <stdint.h>
#include <string.h>

#include "unity.h"

#include "sva/sva_live.h"

static sva_live_t live;
static sva_live_t before;
static sva_mission_t mission;
static sva_plan_t plan;

// Two UAVs at the depot (0, 0), fuel 100; T1 needs both at (5, 0) in [10, 20]; T2 at
// (5, 5) and T3 at (1, 6) in [30, 40] need one each. UAV 1 flies T1 then T2, UAV 2 T1
// then T3. One cell per tick, no hover fuel.
static void start(void)
{
    sva_mission_init(&mission);
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
}

static void clock_to(int32_t at)
{
    sva_event_t e;
    (void)memset(&e, 0, sizeof e);
    e.type = SVA_EVENT_CLOCK;
    e.at_ticks = at;
    TEST_ASSERT_EQUAL_INT(SVA_OK, sva_live_apply(&live, &e, NULL));
}

// The rule's verdict on a report (tolerance 2), checking it leaves the live mission as
// it was: the event type, or -1 for none.
static int verdict(int32_t uav, bool in_service, int32_t x, int32_t y, int32_t fuel,
                   sva_event_t* out)
{
    const sva_report_t r = {uav, in_service, x, y, fuel};
    sva_event_t e;
    (void)memset(&e, 0, sizeof e);
    (void)memcpy(&before, &live, sizeof live);
    const bool got = sva_live_report(&live, &r, 2, &e);
    TEST_ASSERT_EQUAL_MEMORY(&live, &before, sizeof live);
    if (out != NULL) {
        *out = e;
    }
    if (got) {
        TEST_ASSERT_EQUAL_INT(live.now_ticks, e.at_ticks);
        TEST_ASSERT_EQUAL_INT(uav, e.uav_id);
    }
    return got ? (int)e.type : -1;
}

void test_agreeing_reports_give_nothing(void)
{
    start();
    TEST_ASSERT_EQUAL_INT(-1, verdict(1, true, 0, 0, SVA_REPORT_FUEL_UNKNOWN, NULL));
    TEST_ASSERT_EQUAL_INT(-1, verdict(1, true, 0, 0, 100, NULL));
    // Within the tolerance beside the leg (0,0)->(5,0), and no farther from its end.
    TEST_ASSERT_EQUAL_INT(-1, verdict(1, true, 2, 2, SVA_REPORT_FUEL_UNKNOWN, NULL));
    // Ahead of the model: at the target already.
    clock_to(3);
    TEST_ASSERT_EQUAL_INT(-1, verdict(1, true, 5, 0, SVA_REPORT_FUEL_UNKNOWN, NULL));
    // Unknown UAV, NULL arguments: nothing.
    TEST_ASSERT_EQUAL_INT(-1, verdict(9, false, 0, 0, 0, NULL));
    const sva_report_t r = {1, false, 0, 0, 0};
    sva_event_t e;
    TEST_ASSERT_FALSE(sva_live_report(NULL, &r, 2, &e));
    TEST_ASSERT_FALSE(sva_live_report(&live, NULL, 2, &e));
    TEST_ASSERT_FALSE(sva_live_report(&live, &r, 2, NULL));
}

void test_lost_and_back(void)
{
    start();
    sva_event_t e;
    TEST_ASSERT_EQUAL_INT(SVA_EVENT_UAV_LOST, verdict(2, false, 0, 0, 50, &e));
    TEST_ASSERT_EQUAL_INT(SVA_OK, sva_live_apply(&live, &e, NULL));
    // Silent again: nothing more. Heard again: back where it says, with its fuel, or
    // with the fuel it started with when it does not know.
    TEST_ASSERT_EQUAL_INT(-1, verdict(2, false, 0, 0, 50, NULL));
    TEST_ASSERT_EQUAL_INT(SVA_EVENT_UAV_BACK, verdict(2, true, 3, -4, 60, &e));
    TEST_ASSERT_EQUAL_INT(3, e.x);
    TEST_ASSERT_EQUAL_INT(-4, e.y);
    TEST_ASSERT_EQUAL_INT(60, e.fuel);
    TEST_ASSERT_EQUAL_INT(SVA_EVENT_UAV_BACK, verdict(2, true, 3, -4, SVA_REPORT_FUEL_UNKNOWN, &e));
    TEST_ASSERT_EQUAL_INT(100, e.fuel);
    TEST_ASSERT_EQUAL_INT(SVA_OK, sva_live_apply(&live, &e, NULL));
}

void test_off_track(void)
{
    start();
    sva_event_t e;
    // Beside the leg (0,0)->(5,0) by 3 cells: off, with the model's fuel when unknown.
    TEST_ASSERT_EQUAL_INT(SVA_EVENT_POSITION, verdict(1, true, 2, 3, SVA_REPORT_FUEL_UNKNOWN, &e));
    TEST_ASSERT_EQUAL_INT(2, e.x);
    TEST_ASSERT_EQUAL_INT(3, e.y);
    TEST_ASSERT_EQUAL_INT(100, e.fuel);
    // Behind the model: at tick 3 it is at (3, 0), 2 cells from T1; (1, 0) is 4 cells
    // away (2 behind: within), (0, 0) 5 (3 behind: off), with the reported fuel.
    clock_to(3);
    TEST_ASSERT_EQUAL_INT(-1, verdict(1, true, 1, 0, SVA_REPORT_FUEL_UNKNOWN, NULL));
    TEST_ASSERT_EQUAL_INT(SVA_EVENT_POSITION, verdict(1, true, 0, 0, 97, &e));
    TEST_ASSERT_EQUAL_INT(97, e.fuel);
    // The diagonal leg (5,0)->(1,6) of UAV 2 after T1 (left at 20): at 23 the model is at
    // (2, 0), x first; a straight flier at (4, 2) is 7 cells from T3 as the model is:
    // on its track, though 4 cells from the model's cell.
    clock_to(23);
    TEST_ASSERT_EQUAL_INT(-1, verdict(2, true, 4, 2, SVA_REPORT_FUEL_UNKNOWN, NULL));
    // Still at T1 (10 cells to go): 3 behind; (4, 0): 2 behind.
    TEST_ASSERT_EQUAL_INT(SVA_EVENT_POSITION,
                          verdict(2, true, 5, 0, SVA_REPORT_FUEL_UNKNOWN, NULL));
    TEST_ASSERT_EQUAL_INT(-1, verdict(2, true, 4, 0, SVA_REPORT_FUEL_UNKNOWN, NULL));
    // Outside the leg's box x in [1, 5] by 3, and beside it by 1 but 3 behind.
    TEST_ASSERT_EQUAL_INT(SVA_EVENT_POSITION, verdict(2, true, 8, 1, SVA_REPORT_FUEL_UNKNOWN, &e));
    TEST_ASSERT_EQUAL_INT(SVA_EVENT_POSITION,
                          verdict(2, true, 6, 1, SVA_REPORT_FUEL_UNKNOWN, NULL));
    TEST_ASSERT_EQUAL_INT(-1, verdict(2, true, 6, 2, SVA_REPORT_FUEL_UNKNOWN, NULL));
    TEST_ASSERT_EQUAL_INT(SVA_EVENT_POSITION, verdict(2, true, 1, 9, SVA_REPORT_FUEL_UNKNOWN, &e));
}

void test_visit_under_way(void)
{
    start();
    clock_to(15);  // both hover over T1 (5, 0) until 20
    TEST_ASSERT_EQUAL_INT(-1, verdict(1, true, 5, 0, SVA_REPORT_FUEL_UNKNOWN, NULL));
    TEST_ASSERT_EQUAL_INT(-1, verdict(1, true, 6, 1, SVA_REPORT_FUEL_UNKNOWN, NULL));
    TEST_ASSERT_EQUAL_INT(SVA_EVENT_POSITION,
                          verdict(1, true, 6, 2, SVA_REPORT_FUEL_UNKNOWN, NULL));
    sva_event_t e;
    TEST_ASSERT_EQUAL_INT(SVA_EVENT_POSITION, verdict(1, true, 5, 3, SVA_REPORT_FUEL_UNKNOWN, &e));
    // Applied, the core breaks the visit (SPEC 12.3: off its target during a visit).
    TEST_ASSERT_EQUAL_INT(SVA_OK, sva_live_apply(&live, &e, NULL));
    TEST_ASSERT_EQUAL_INT(SVA_TARGET_LOST, live.target_state[0]);
}

void test_fuel_below_the_route_need(void)
{
    start();
    // UAV 1 needs 5 + 5 + 10 = 20 cells of fuel for T1, T2 and home.
    TEST_ASSERT_EQUAL_INT(-1, verdict(1, true, 0, 0, 20, NULL));
    sva_event_t e;
    TEST_ASSERT_EQUAL_INT(SVA_EVENT_FUEL, verdict(1, true, 0, 0, 19, &e));
    TEST_ASSERT_EQUAL_INT(19, e.fuel);
    // After 3 ticks it has flown 3 cells: 17 left to fly.
    clock_to(3);
    TEST_ASSERT_EQUAL_INT(-1, verdict(1, true, 3, 0, 17, NULL));
    TEST_ASSERT_EQUAL_INT(SVA_EVENT_FUEL, verdict(1, true, 3, 0, 16, NULL));
    // Off its track and short of fuel: the position comes first, carrying the fuel.
    TEST_ASSERT_EQUAL_INT(SVA_EVENT_POSITION, verdict(1, true, 3, 4, 16, &e));
    TEST_ASSERT_EQUAL_INT(16, e.fuel);
}
