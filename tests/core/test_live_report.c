// test_live_report.c -- the report rule (sva_live_report, docs/live.md "Vehicle
// reports"): what a vehicle says of itself becomes uav_lost, uav_back, position, fuel
// or nothing, judged against the flight model; the rule never changes the live mission.
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>

#include <cmocka.h>

#include "sva/sva.h"

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
    assert_int_equal(sva_live_init(&live, &mission, &plan, &diag), SVA_OK);
}

static void clock_to(int32_t at)
{
    sva_event_t e;
    (void)memset(&e, 0, sizeof e);
    e.type = SVA_EVENT_CLOCK;
    e.at_ticks = at;
    assert_int_equal(sva_live_apply(&live, &e, NULL), SVA_OK);
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
    assert_memory_equal(&before, &live, sizeof live);
    if (out != NULL) {
        *out = e;
    }
    if (got) {
        assert_int_equal(e.at_ticks, live.now_ticks);
        assert_int_equal(e.uav_id, uav);
    }
    return got ? (int)e.type : -1;
}

static void test_agreeing_reports_give_nothing(void** state)
{
    (void)state;
    start();
    assert_int_equal(verdict(1, true, 0, 0, SVA_REPORT_FUEL_UNKNOWN, NULL), -1);
    assert_int_equal(verdict(1, true, 0, 0, 100, NULL), -1);
    // Within the tolerance beside the leg (0,0)->(5,0), and no farther from its end.
    assert_int_equal(verdict(1, true, 2, 2, SVA_REPORT_FUEL_UNKNOWN, NULL), -1);
    // Ahead of the model: at the target already.
    clock_to(3);
    assert_int_equal(verdict(1, true, 5, 0, SVA_REPORT_FUEL_UNKNOWN, NULL), -1);
    // Unknown UAV, NULL arguments: nothing.
    assert_int_equal(verdict(9, false, 0, 0, 0, NULL), -1);
    const sva_report_t r = {1, false, 0, 0, 0};
    sva_event_t e;
    assert_false(sva_live_report(NULL, &r, 2, &e));
    assert_false(sva_live_report(&live, NULL, 2, &e));
    assert_false(sva_live_report(&live, &r, 2, NULL));
}

static void test_lost_and_back(void** state)
{
    (void)state;
    start();
    sva_event_t e;
    assert_int_equal(verdict(2, false, 0, 0, 50, &e), SVA_EVENT_UAV_LOST);
    assert_int_equal(sva_live_apply(&live, &e, NULL), SVA_OK);
    // Silent again: nothing more. Heard again: back where it says, with its fuel, or
    // with the fuel it started with when it does not know.
    assert_int_equal(verdict(2, false, 0, 0, 50, NULL), -1);
    assert_int_equal(verdict(2, true, 3, -4, 60, &e), SVA_EVENT_UAV_BACK);
    assert_int_equal(e.x, 3);
    assert_int_equal(e.y, -4);
    assert_int_equal(e.fuel, 60);
    assert_int_equal(verdict(2, true, 3, -4, SVA_REPORT_FUEL_UNKNOWN, &e), SVA_EVENT_UAV_BACK);
    assert_int_equal(e.fuel, 100);
    assert_int_equal(sva_live_apply(&live, &e, NULL), SVA_OK);
}

static void test_off_track(void** state)
{
    (void)state;
    start();
    sva_event_t e;
    // Beside the leg (0,0)->(5,0) by 3 cells: off, with the model's fuel when unknown.
    assert_int_equal(verdict(1, true, 2, 3, SVA_REPORT_FUEL_UNKNOWN, &e), SVA_EVENT_POSITION);
    assert_int_equal(e.x, 2);
    assert_int_equal(e.y, 3);
    assert_int_equal(e.fuel, 100);
    // Behind the model: at tick 3 it is at (3, 0), 2 cells from T1; (1, 0) is 4 cells
    // away (2 behind: within), (0, 0) 5 (3 behind: off), with the reported fuel.
    clock_to(3);
    assert_int_equal(verdict(1, true, 1, 0, SVA_REPORT_FUEL_UNKNOWN, NULL), -1);
    assert_int_equal(verdict(1, true, 0, 0, 97, &e), SVA_EVENT_POSITION);
    assert_int_equal(e.fuel, 97);
    // The diagonal leg (5,0)->(1,6) of UAV 2 after T1 (left at 20): at 23 the model is at
    // (2, 0), x first; a straight flier at (4, 2) is 7 cells from T3 as the model is:
    // on its track, though 4 cells from the model's cell.
    clock_to(23);
    assert_int_equal(verdict(2, true, 4, 2, SVA_REPORT_FUEL_UNKNOWN, NULL), -1);
    // Still at T1 (10 cells to go): 3 behind; (4, 0): 2 behind.
    assert_int_equal(verdict(2, true, 5, 0, SVA_REPORT_FUEL_UNKNOWN, NULL), SVA_EVENT_POSITION);
    assert_int_equal(verdict(2, true, 4, 0, SVA_REPORT_FUEL_UNKNOWN, NULL), -1);
    // Outside the leg's box x in [1, 5] by 3, and beside it by 1 but 3 behind.
    assert_int_equal(verdict(2, true, 8, 1, SVA_REPORT_FUEL_UNKNOWN, &e), SVA_EVENT_POSITION);
    assert_int_equal(verdict(2, true, 6, 1, SVA_REPORT_FUEL_UNKNOWN, NULL), SVA_EVENT_POSITION);
    assert_int_equal(verdict(2, true, 6, 2, SVA_REPORT_FUEL_UNKNOWN, NULL), -1);
    assert_int_equal(verdict(2, true, 1, 9, SVA_REPORT_FUEL_UNKNOWN, &e), SVA_EVENT_POSITION);
}

static void test_visit_under_way(void** state)
{
    (void)state;
    start();
    clock_to(15);  // both hover over T1 (5, 0) until 20
    assert_int_equal(verdict(1, true, 5, 0, SVA_REPORT_FUEL_UNKNOWN, NULL), -1);
    assert_int_equal(verdict(1, true, 6, 1, SVA_REPORT_FUEL_UNKNOWN, NULL), -1);
    assert_int_equal(verdict(1, true, 6, 2, SVA_REPORT_FUEL_UNKNOWN, NULL), SVA_EVENT_POSITION);
    sva_event_t e;
    assert_int_equal(verdict(1, true, 5, 3, SVA_REPORT_FUEL_UNKNOWN, &e), SVA_EVENT_POSITION);
    // Applied, the core breaks the visit (SPEC 12.3: off its target during a visit).
    assert_int_equal(sva_live_apply(&live, &e, NULL), SVA_OK);
    assert_int_equal(live.target_state[0], SVA_TARGET_LOST);
}

static void test_fuel_below_the_route_need(void** state)
{
    (void)state;
    start();
    // UAV 1 needs 5 + 5 + 10 = 20 cells of fuel for T1, T2 and home.
    assert_int_equal(verdict(1, true, 0, 0, 20, NULL), -1);
    sva_event_t e;
    assert_int_equal(verdict(1, true, 0, 0, 19, &e), SVA_EVENT_FUEL);
    assert_int_equal(e.fuel, 19);
    // After 3 ticks it has flown 3 cells: 17 left to fly.
    clock_to(3);
    assert_int_equal(verdict(1, true, 3, 0, 17, NULL), -1);
    assert_int_equal(verdict(1, true, 3, 0, 16, NULL), SVA_EVENT_FUEL);
    // Off its track and short of fuel: the position comes first, carrying the fuel.
    assert_int_equal(verdict(1, true, 3, 4, 16, &e), SVA_EVENT_POSITION);
    assert_int_equal(e.fuel, 16);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_agreeing_reports_give_nothing),
        cmocka_unit_test(test_lost_and_back),
        cmocka_unit_test(test_off_track),
        cmocka_unit_test(test_visit_under_way),
        cmocka_unit_test(test_fuel_below_the_route_need),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
