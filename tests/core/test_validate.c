// Validation (SPEC section 4) and bounds: every rule fills the diagnostic with the
// field, the rule and the limit; exactly at a bound succeeds, one over fails naming it.
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>
#include <cmocka.h>

#include "mission_gen.h"
#include "spec_checker.h"
#include "sva/sva.h"

static sva_mission_t mission;
static sva_plan_t plan;
static sva_planner_t planner;

static void small_mission(sva_mission_t* m)
{
    sva_mission_init(m);
    m->uav_count = 2;
    m->uavs[0] = (sva_uav_t){.id = 1, .x = 0, .y = 0, .fuel = 60, .ready_at_ticks = 0};
    m->uavs[1] = (sva_uav_t){.id = 2, .x = 0, .y = 0, .fuel = 60, .ready_at_ticks = 0};
    m->target_count = 2;
    m->targets[0] =
        (sva_target_t){.id = 1, .x = 5, .y = 7, .start_ticks = 12, .end_ticks = 20, .need = 2};
    m->targets[1] =
        (sva_target_t){.id = 2, .x = 3, .y = 1, .start_ticks = 30, .end_ticks = 40, .need = 1};
}

// Validates and checks status and the formatted message.
static void expect_invalid(const sva_mission_t* m, const char* message)
{
    sva_diag_t diag;
    char buf[160];
    assert_int_equal(sva_mission_validate(m, &diag), SVA_ERR_INVALID);
    (void)sva_diag_format(&diag, buf, sizeof(buf));
    assert_string_equal(buf, message);
    // sva_plan rejects it the same way and leaves no plan (all-or-nothing).
    assert_int_equal(sva_plan(&planner, m, SVA_ALGO_SVA, &plan, &diag), SVA_ERR_INVALID);
    assert_int_equal(plan.status, SVA_PLAN_NONE);
    assert_int_equal(plan.route_count, 0);
}

static void test_valid_mission_passes(void** state)
{
    (void)state;
    sva_diag_t diag;
    small_mission(&mission);
    assert_int_equal(sva_mission_validate(&mission, &diag), SVA_OK);
    assert_int_equal(diag.rule, SVA_RULE_NONE);
}

static void test_each_rule_names_field_rule_and_limit(void** state)
{
    (void)state;
    char expect[160];
    small_mission(&mission);
    mission.targets[1].need = 0;
    expect_invalid(&mission, "targets[1].need: must be >= 1, got 0");

    small_mission(&mission);
    mission.targets[0].end_ticks = 12;
    expect_invalid(&mission, "targets[0].end: must be > start (12), got 12");

    small_mission(&mission);
    mission.uavs[1].id = 1;
    expect_invalid(&mission, "uavs[1].id: duplicate id 1 (first at index 0)");

    small_mission(&mission);
    mission.targets[1].id = 1;
    expect_invalid(&mission, "targets[1].id: duplicate id 1 (first at index 0)");

    small_mission(&mission);
    mission.uavs[0].fuel = -1;
    expect_invalid(&mission, "uavs[0].fuel: must be >= 0, got -1");

    small_mission(&mission);
    mission.uavs[1].x = 32768;
    expect_invalid(&mission, "uavs[1].x: must be <= 32767, got 32768");

    small_mission(&mission);
    mission.depot_y = -32769;
    expect_invalid(&mission, "depot.y: must be >= -32768, got -32769");

    small_mission(&mission);
    mission.uavs[0].ready_at_ticks = -5;
    expect_invalid(&mission, "uavs[0].ready_at: must be >= 0, got -5");

    small_mission(&mission);
    mission.targets[0].id = 0;
    expect_invalid(&mission, "targets[0].id: must be >= 1, got 0");

    small_mission(&mission);
    mission.ticks_per_cell = 0;
    expect_invalid(&mission, "ticks_per_cell: must be >= 1, got 0");

    small_mission(&mission);
    mission.overlap_percent = 101;
    expect_invalid(&mission, "overlap_percent: must be <= 100, got 101");

    small_mission(&mission);
    mission.hover_fuel = (int32_t)SVA_MAX_HOVER_FUEL + 1;
    snprintf(expect, sizeof(expect), "hover_fuel: must be <= SVA_MAX_HOVER_FUEL (%ld), got %ld",
             (long)SVA_MAX_HOVER_FUEL, (long)SVA_MAX_HOVER_FUEL + 1);
    expect_invalid(&mission, expect);

    small_mission(&mission);
    mission.targets[0].need = SVA_MAX_UAVS + 1;
    snprintf(expect, sizeof(expect), "targets[0].need: must be <= SVA_MAX_UAVS (%d), got %d",
             SVA_MAX_UAVS, SVA_MAX_UAVS + 1);
    expect_invalid(&mission, expect);

    small_mission(&mission);
    mission.uavs[0].fuel = (int32_t)SVA_MAX_FUEL + 1;
    snprintf(expect, sizeof(expect), "uavs[0].fuel: must be <= SVA_MAX_FUEL (%ld), got %ld",
             (long)SVA_MAX_FUEL, (long)SVA_MAX_FUEL + 1);
    expect_invalid(&mission, expect);
}

static void test_first_error_wins(void** state)
{
    (void)state;
    small_mission(&mission);
    mission.targets[0].need = 0;  // later in field order
    mission.uavs[1].fuel = -3;    // earlier: UAVs before targets
    expect_invalid(&mission, "uavs[1].fuel: must be >= 0, got -3");
}

// A mission exactly at SVA_MAX_UAVS and SVA_MAX_TARGETS plans; one more of either fails.
static void test_count_bounds(void** state)
{
    (void)state;
    char expect[160];
    test_rng_t rng;
    test_rng_seed(&rng, 7);
    const test_gen_params_t params = {
        SVA_MAX_TARGETS, SVA_MAX_UAVS, 200, 10, 20, 4 * SVA_MAX_TARGETS, 2, 200, 2000, 2, 1, 0, 0};
    test_gen_mission(&rng, &params, &mission);
    for (int a = 0; a < (int)SVA_ALGO_COUNT_; a++) {
        if (a == SVA_ALGO_BFA) {
            continue;  // bfa has its own, smaller limits (tested below)
        }
        sva_diag_t diag;
        char why[200] = "";
        assert_int_equal(sva_plan(&planner, &mission, (sva_algorithm_t)a, &plan, &diag), SVA_OK);
        if (spec_check_plan(&mission, &plan, why, sizeof(why)) != 0) {
            fail_msg("%s: %s", sva_algorithm_name((sva_algorithm_t)a), why);
        }
        assert_true(plan.covered > 0);
    }
    mission.uav_count = SVA_MAX_UAVS + 1;
    snprintf(expect, sizeof(expect), "uavs: %d entries exceed SVA_MAX_UAVS (%d)", SVA_MAX_UAVS + 1,
             SVA_MAX_UAVS);
    expect_invalid(&mission, expect);
    mission.uav_count = SVA_MAX_UAVS;
    mission.target_count = SVA_MAX_TARGETS + 1;
    snprintf(expect, sizeof(expect), "targets: %d entries exceed SVA_MAX_TARGETS (%d)",
             SVA_MAX_TARGETS + 1, SVA_MAX_TARGETS);
    expect_invalid(&mission, expect);
}

static void test_value_bounds_inclusive(void** state)
{
    (void)state;
    sva_diag_t diag;
    small_mission(&mission);
    mission.depot_x = -32768;
    mission.uavs[0].x = 32767;
    mission.uavs[0].fuel = (int32_t)SVA_MAX_FUEL;
    mission.uavs[1].ready_at_ticks = (int32_t)SVA_MAX_TICK;
    mission.targets[1].start_ticks = (int32_t)SVA_MAX_TICK - 1;
    mission.targets[1].end_ticks = (int32_t)SVA_MAX_TICK;
    mission.ticks_per_cell = (int32_t)SVA_MAX_TICKS_PER_CELL;
    mission.hover_fuel = (int32_t)SVA_MAX_HOVER_FUEL;
    mission.overlap_percent = 100;
    mission.targets[0].need = SVA_MAX_UAVS;
    assert_int_equal(sva_mission_validate(&mission, &diag), SVA_OK);
    assert_int_equal(sva_plan(&planner, &mission, SVA_ALGO_SVA, &plan, &diag), SVA_OK);
    assert_int_equal(spec_check_plan(&mission, &plan, NULL, 0), 0);

    mission.ticks_per_cell = (int32_t)SVA_MAX_TICKS_PER_CELL + 1;
    assert_int_equal(sva_mission_validate(&mission, &diag), SVA_ERR_INVALID);
    assert_string_equal(diag.limit_name, "SVA_MAX_TICKS_PER_CELL");
    mission.ticks_per_cell = 1;
    mission.targets[1].end_ticks = (int32_t)SVA_MAX_TICK + 1;
    assert_int_equal(sva_mission_validate(&mission, &diag), SVA_ERR_INVALID);
    assert_int_equal(diag.field, SVA_FIELD_TARGET_END);
    assert_string_equal(diag.limit_name, "SVA_MAX_TICK");
}

static void test_bfa_limits_are_errors_not_hours(void** state)
{
    (void)state;
    char buf[160], expect[160];
    sva_diag_t diag;
    test_rng_t rng;
    test_rng_seed(&rng, 11);
    const test_gen_params_t params = {
        SVA_BFA_MAX_TARGETS + 1, 2, 20, 10, 20, 100, 1, 100, 200, 0, 1, 0, 0};
    test_gen_mission(&rng, &params, &mission);
    assert_int_equal(sva_plan(&planner, &mission, SVA_ALGO_BFA, &plan, &diag), SVA_ERR_LIMIT);
    assert_int_equal(plan.status, SVA_PLAN_NONE);
    (void)sva_diag_format(&diag, buf, sizeof(buf));
    snprintf(expect, sizeof(expect), "targets: %d entries exceed SVA_BFA_MAX_TARGETS (%d)",
             SVA_BFA_MAX_TARGETS + 1, SVA_BFA_MAX_TARGETS);
    assert_string_equal(buf, expect);

    const test_gen_params_t wide = {2, SVA_BFA_MAX_UAVS + 1, 20, 10, 20, 100, 1, 100, 200, 0, 1, 0,
                                    0};
    test_gen_mission(&rng, &wide, &mission);
    assert_int_equal(sva_plan(&planner, &mission, SVA_ALGO_BFA, &plan, &diag), SVA_ERR_LIMIT);
    assert_string_equal(diag.limit_name, "SVA_BFA_MAX_UAVS");
}

static void test_diag_format_truncates_like_snprintf(void** state)
{
    (void)state;
    sva_diag_t diag;
    char small[8], full[160];
    small_mission(&mission);
    mission.targets[1].need = 0;
    assert_int_equal(sva_mission_validate(&mission, &diag), SVA_ERR_INVALID);
    const size_t len = sva_diag_format(&diag, full, sizeof(full));
    assert_int_equal(len, strlen(full));
    assert_int_equal(sva_diag_format(&diag, small, sizeof(small)), len);
    assert_int_equal(strlen(small), sizeof(small) - 1);
    assert_memory_equal(small, full, sizeof(small) - 1);
    assert_int_equal(sva_diag_format(&diag, NULL, 0), len);
    // INT64 extremes format exactly.
    diag.rule = SVA_RULE_MIN;
    diag.value = INT64_MIN;
    diag.limit = INT64_MAX;
    (void)sva_diag_format(&diag, full, sizeof(full));
    assert_string_equal(
        full, "targets[1].need: must be >= 9223372036854775807, got -9223372036854775808");
}

static void test_algorithm_names(void** state)
{
    (void)state;
    for (int a = 0; a < (int)SVA_ALGO_COUNT_; a++) {
        sva_algorithm_t back;
        assert_int_equal(sva_algorithm_from_name(sva_algorithm_name((sva_algorithm_t)a), &back),
                         SVA_OK);
        assert_int_equal(back, a);
    }
    sva_algorithm_t out = SVA_ALGO_GA;
    assert_int_equal(sva_algorithm_from_name("svaa", &out), SVA_ERR_ARGUMENT);
    assert_int_equal(sva_algorithm_from_name("", &out), SVA_ERR_ARGUMENT);
    assert_int_equal(out, SVA_ALGO_GA);
    assert_string_equal(sva_algorithm_name(SVA_ALGO_COUNT_), "");
}

static void test_limits_report_compiled_bounds(void** state)
{
    (void)state;
    const sva_limits_t l = sva_limits();
    assert_int_equal(l.max_uavs, SVA_MAX_UAVS);
    assert_int_equal(l.max_targets, SVA_MAX_TARGETS);
    assert_int_equal(l.planner_bytes, sizeof(sva_planner_t));
    assert_int_equal(l.plan_bytes, sizeof(sva_plan_t));
    printf("# sizes: planner %u B, plan %u B, mission %u B\n", l.planner_bytes, l.plan_bytes,
           l.mission_bytes);
}

int main(void)
{
    assert_int_equal(sva_planner_init(&planner), SVA_OK);
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_valid_mission_passes),
        cmocka_unit_test(test_each_rule_names_field_rule_and_limit),
        cmocka_unit_test(test_first_error_wins),
        cmocka_unit_test(test_count_bounds),
        cmocka_unit_test(test_value_bounds_inclusive),
        cmocka_unit_test(test_bfa_limits_are_errors_not_hours),
        cmocka_unit_test(test_diag_format_truncates_like_snprintf),
        cmocka_unit_test(test_algorithm_names),
        cmocka_unit_test(test_limits_report_compiled_bounds),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
