// Validation (SPEC section 4) and bounds: every rule fills the diagnostic with the
// field, the rule and the limit; exactly at a bound succeeds, one over fails naming it.
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>
#include "sva_unity.h"

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
    TEST_ASSERT_EQUAL_INT(SVA_ERR_INVALID, sva_mission_validate(m, &diag));
    (void)sva_diag_format(&diag, buf, sizeof(buf));
    TEST_ASSERT_EQUAL_STRING(message, buf);
    // sva_plan rejects it the same way and leaves no plan (all-or-nothing).
    TEST_ASSERT_EQUAL_INT(SVA_ERR_INVALID, sva_plan(&planner, m, SVA_ALGO_SVA, &plan, &diag));
    TEST_ASSERT_EQUAL_INT(SVA_PLAN_NONE, plan.status);
    TEST_ASSERT_EQUAL_INT(0, plan.route_count);
}

void test_valid_mission_passes(void)
{
    sva_diag_t diag;
    small_mission(&mission);
    TEST_ASSERT_EQUAL_INT(SVA_OK, sva_mission_validate(&mission, &diag));
    TEST_ASSERT_EQUAL_INT(SVA_RULE_NONE, diag.rule);
}

void test_each_rule_names_field_rule_and_limit(void)
{
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

void test_first_error_wins(void)
{
    small_mission(&mission);
    mission.targets[0].need = 0;  // later in field order
    mission.uavs[1].fuel = -3;    // earlier: UAVs before targets
    expect_invalid(&mission, "uavs[1].fuel: must be >= 0, got -3");
}

// A mission exactly at SVA_MAX_UAVS and SVA_MAX_TARGETS plans; one more of either fails.
void test_count_bounds(void)
{
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
        TEST_ASSERT_EQUAL_INT(SVA_OK,
                              sva_plan(&planner, &mission, (sva_algorithm_t)a, &plan, &diag));
        if (spec_check_plan(&mission, &plan, why, sizeof(why)) != 0) {
            SVA_TEST_FAIL("%s: %s", sva_algorithm_name((sva_algorithm_t)a), why);
        }
        TEST_ASSERT_TRUE(plan.covered > 0);
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

void test_value_bounds_inclusive(void)
{
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
    TEST_ASSERT_EQUAL_INT(SVA_OK, sva_mission_validate(&mission, &diag));
    TEST_ASSERT_EQUAL_INT(SVA_OK, sva_plan(&planner, &mission, SVA_ALGO_SVA, &plan, &diag));
    TEST_ASSERT_EQUAL_INT(0, spec_check_plan(&mission, &plan, NULL, 0));

    mission.ticks_per_cell = (int32_t)SVA_MAX_TICKS_PER_CELL + 1;
    TEST_ASSERT_EQUAL_INT(SVA_ERR_INVALID, sva_mission_validate(&mission, &diag));
    TEST_ASSERT_EQUAL_STRING("SVA_MAX_TICKS_PER_CELL", diag.limit_name);
    mission.ticks_per_cell = 1;
    mission.targets[1].end_ticks = (int32_t)SVA_MAX_TICK + 1;
    TEST_ASSERT_EQUAL_INT(SVA_ERR_INVALID, sva_mission_validate(&mission, &diag));
    TEST_ASSERT_EQUAL_INT(SVA_FIELD_TARGET_END, diag.field);
    TEST_ASSERT_EQUAL_STRING("SVA_MAX_TICK", diag.limit_name);
}

void test_bfa_limits_are_errors_not_hours(void)
{
    char buf[160], expect[160];
    sva_diag_t diag;
    test_rng_t rng;
    test_rng_seed(&rng, 11);
    const test_gen_params_t params = {
        SVA_BFA_MAX_TARGETS + 1, 2, 20, 10, 20, 100, 1, 100, 200, 0, 1, 0, 0};
    test_gen_mission(&rng, &params, &mission);
    TEST_ASSERT_EQUAL_INT(SVA_ERR_LIMIT, sva_plan(&planner, &mission, SVA_ALGO_BFA, &plan, &diag));
    TEST_ASSERT_EQUAL_INT(SVA_PLAN_NONE, plan.status);
    (void)sva_diag_format(&diag, buf, sizeof(buf));
    snprintf(expect, sizeof(expect), "targets: %d entries exceed SVA_BFA_MAX_TARGETS (%d)",
             SVA_BFA_MAX_TARGETS + 1, SVA_BFA_MAX_TARGETS);
    TEST_ASSERT_EQUAL_STRING(expect, buf);

    const test_gen_params_t wide = {2, SVA_BFA_MAX_UAVS + 1, 20, 10, 20, 100, 1, 100, 200, 0, 1, 0,
                                    0};
    test_gen_mission(&rng, &wide, &mission);
    TEST_ASSERT_EQUAL_INT(SVA_ERR_LIMIT, sva_plan(&planner, &mission, SVA_ALGO_BFA, &plan, &diag));
    TEST_ASSERT_EQUAL_STRING("SVA_BFA_MAX_UAVS", diag.limit_name);
}

void test_diag_format_truncates_like_snprintf(void)
{
    sva_diag_t diag;
    char small[8], full[160];
    small_mission(&mission);
    mission.targets[1].need = 0;
    TEST_ASSERT_EQUAL_INT(SVA_ERR_INVALID, sva_mission_validate(&mission, &diag));
    const size_t len = sva_diag_format(&diag, full, sizeof(full));
    TEST_ASSERT_EQUAL_INT(strlen(full), len);
    TEST_ASSERT_EQUAL_INT(len, sva_diag_format(&diag, small, sizeof(small)));
    TEST_ASSERT_EQUAL_INT(sizeof(small) - 1, strlen(small));
    TEST_ASSERT_EQUAL_MEMORY(full, small, sizeof(small) - 1);
    TEST_ASSERT_EQUAL_INT(len, sva_diag_format(&diag, NULL, 0));
    // INT64 extremes format exactly.
    diag.rule = SVA_RULE_MIN;
    diag.value = INT64_MIN;
    diag.limit = INT64_MAX;
    (void)sva_diag_format(&diag, full, sizeof(full));
    TEST_ASSERT_EQUAL_STRING(
        "targets[1].need: must be >= 9223372036854775807, got -9223372036854775808", full);
}

void test_algorithm_names(void)
{
    for (int a = 0; a < (int)SVA_ALGO_COUNT_; a++) {
        sva_algorithm_t back;
        TEST_ASSERT_EQUAL_INT(
            SVA_OK, sva_algorithm_from_name(sva_algorithm_name((sva_algorithm_t)a), &back));
        TEST_ASSERT_EQUAL_INT(a, back);
    }
    sva_algorithm_t out = SVA_ALGO_GA;
    TEST_ASSERT_EQUAL_INT(SVA_ERR_ARGUMENT, sva_algorithm_from_name("svaa", &out));
    TEST_ASSERT_EQUAL_INT(SVA_ERR_ARGUMENT, sva_algorithm_from_name("", &out));
    TEST_ASSERT_EQUAL_INT(SVA_ALGO_GA, out);
    TEST_ASSERT_EQUAL_STRING("", sva_algorithm_name(SVA_ALGO_COUNT_));
}

void test_limits_report_compiled_bounds(void)
{
    const sva_limits_t l = sva_limits();
    TEST_ASSERT_EQUAL_INT(SVA_MAX_UAVS, l.max_uavs);
    TEST_ASSERT_EQUAL_INT(SVA_MAX_TARGETS, l.max_targets);
    TEST_ASSERT_EQUAL_INT(sizeof(sva_planner_t), l.planner_bytes);
    TEST_ASSERT_EQUAL_INT(sizeof(sva_plan_t), l.plan_bytes);
    printf("# sizes: planner %lu B, plan %lu B, mission %lu B\n", (unsigned long)l.planner_bytes,
           (unsigned long)l.plan_bytes, (unsigned long)l.mission_bytes);
}

// Every test starts from a freshly initialised planner.
void setUp(void)
{
    TEST_ASSERT_EQUAL_INT(SVA_OK, sva_planner_init(&planner));
}
