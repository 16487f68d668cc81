// Reachable edges of the core that the other unit tests do not reach (found by
// scripts/coverage.sh): diagnostics of "no error", the range check, out-of-range enums,
// algorithm names out of range, a cluster larger than SVA_MAX_TP_SINKS (solved in chunks), and
// (max profile) needs whose least common multiple is too large for the tableau's
// per-unit cost scaling, which then falls back to unscaled costs.
#include <stddef.h>
#include <stdint.h>
#include <string.h>
#include "unity.h"

#include "spec_checker.h"
#include "sva/sva.h"

static sva_planner_t planner;
static sva_mission_t mission;
static sva_plan_t plan;

void test_cleared_diag_formats_as_ok(void)
{
    sva_diag_t d;
    memset(&d, 0x5a, sizeof d);
    sva_diag_clear(&d);
    TEST_ASSERT_EQUAL_INT(SVA_FIELD_NONE, d.field);
    TEST_ASSERT_EQUAL_INT(SVA_RULE_NONE, d.rule);
    TEST_ASSERT_EQUAL_INT(-1, d.index);
    TEST_ASSERT_NULL(d.limit_name);
    char buf[64];
    const size_t n = sva_diag_format(&d, buf, sizeof buf);
    TEST_ASSERT_EQUAL_STRING("mission: ok", buf);
    TEST_ASSERT_EQUAL_INT(strlen("mission: ok"), n);
}

// sva_in_range, the range check ports share with the core: the bound broken is named.
void test_in_range_names_the_bound(void)
{
    sva_diag_t d;
    sva_diag_clear(&d);
    TEST_ASSERT_TRUE(sva_in_range(&d, SVA_FIELD_UAV_FUEL, 2, 5, 0, 10, "LIMIT"));
    TEST_ASSERT_EQUAL_INT(SVA_RULE_NONE, d.rule);
    TEST_ASSERT_FALSE(sva_in_range(&d, SVA_FIELD_UAV_FUEL, 2, -1, 0, 10, "LIMIT"));
    TEST_ASSERT_EQUAL_INT(SVA_RULE_MIN, d.rule);
    TEST_ASSERT_EQUAL_INT(0, d.limit);
    TEST_ASSERT_NULL(d.limit_name);
    TEST_ASSERT_FALSE(sva_in_range(&d, SVA_FIELD_UAV_FUEL, 2, 11, 0, 10, "LIMIT"));
    TEST_ASSERT_EQUAL_INT(SVA_RULE_MAX, d.rule);
    TEST_ASSERT_EQUAL_INT(10, d.limit);
    TEST_ASSERT_EQUAL_INT(2, d.index);
    TEST_ASSERT_EQUAL_STRING("LIMIT", d.limit_name);
    TEST_ASSERT_FALSE(sva_in_range(NULL, SVA_FIELD_UAV_FUEL, 2, 11, 0, 10, NULL));
}

void test_out_of_range_enums(void)
{
    TEST_ASSERT_EQUAL_STRING("", sva_field_name(SVA_FIELD_COUNT_));
    TEST_ASSERT_EQUAL_STRING("", sva_field_name((sva_field_t)-1));
    TEST_ASSERT_EQUAL_STRING("", sva_algorithm_name(SVA_ALGO_COUNT_));
    sva_diag_t d;
    sva_diag_set(&d, SVA_FIELD_TARGET_NEED, SVA_RULE_COUNT_, 2, 0, 0, NULL);
    char buf[64];
    (void)sva_diag_format(&d, buf, sizeof buf);
    TEST_ASSERT_EQUAL_STRING("targets[2].need: unknown rule", buf);
    sva_algorithm_t algo = SVA_ALGO_GA;
    TEST_ASSERT_EQUAL_INT(SVA_ERR_ARGUMENT, sva_algorithm_from_name("nope", &algo));
    TEST_ASSERT_EQUAL_INT(SVA_ALGO_GA, algo);  // untouched on error
}

// SVA_MAX_TP_SINKS + 1 targets in one window form one cluster, solved as two chunks.
void test_cluster_larger_than_the_tableau_is_chunked(void)
{
#if SVA_MAX_TP_SINKS + 1 > SVA_MAX_TARGETS || SVA_MAX_TP_SINKS + 1 > SVA_MAX_UAVS
    TEST_IGNORE();  // the profile cannot hold such a mission
#else
    const int n = SVA_MAX_TP_SINKS + 1;
    sva_mission_init(&mission);
    for (int i = 0; i < n; i++) {
        mission.uavs[i] =
            (sva_uav_t){.id = i + 1, .x = 0, .y = 0, .fuel = 1000, .ready_at_ticks = 0};
        mission.targets[i] = (sva_target_t){
            .id = i + 1, .x = i % 7, .y = i / 7, .start_ticks = 50, .end_ticks = 60, .need = 1};
    }
    mission.uav_count = (uint16_t)n;
    mission.target_count = (uint16_t)n;
    TEST_ASSERT_EQUAL_INT(SVA_OK, sva_planner_init(&planner));
    for (int a = 0; a < 2; a++) {
        const sva_algorithm_t algo = (a == 0) ? SVA_ALGO_SVA : SVA_ALGO_HGA;
        sva_diag_t d;
        TEST_ASSERT_EQUAL_INT(SVA_OK, sva_plan(&planner, &mission, algo, &plan, &d));
        TEST_ASSERT_EQUAL_INT(1, plan.stats.clusters);
        TEST_ASSERT_EQUAL_INT(n, plan.stats.largest_cluster);
        TEST_ASSERT_EQUAL_INT(1, plan.stats.chunked_clusters);
        TEST_ASSERT_EQUAL_INT(2, plan.stats.transport_problems);
        TEST_ASSERT_EQUAL_INT(n, plan.covered);
        char msg[256];
        TEST_ASSERT_EQUAL_INT(0, spec_check_plan(&mission, &plan, msg, sizeof msg));
    }
#endif
}

// Nine targets with prime needs 11..41 (221 UAVs, lcm 1.45e12) about 2000 cells from
// the fleet: the lcm times the big M would overflow the reduced costs' headroom, so
// the tableau uses L = 1. The plan must still be complete and pass the checker.
// Regression: with L = 1 the unmet-demand cost big_m * (L / need) was 0 for every
// need above 1, so the simplex left such targets unserved (8 of 9 covered here).
void test_needs_lcm_overflow_falls_back(void)
{
#if SVA_MAX_UAVS < 221 || SVA_MAX_TP_SINKS < 9
    TEST_IGNORE();  // only the max profile holds such a mission
#else
    static const int32_t needs[9] = {11, 13, 17, 19, 23, 29, 31, 37, 41};
    const int uavs = 221;
    sva_mission_init(&mission);
    for (int i = 0; i < uavs; i++) {
        mission.uavs[i] =
            (sva_uav_t){.id = i + 1, .x = (i % 2) * 5, .y = 0, .fuel = 10000, .ready_at_ticks = 0};
    }
    for (int k = 0; k < 9; k++) {
        mission.targets[k] = (sva_target_t){.id = k + 1,
                                            .x = 1000 + k,
                                            .y = 1000,
                                            .start_ticks = 3000,
                                            .end_ticks = 3010,
                                            .need = needs[k]};
    }
    mission.uav_count = (uint16_t)uavs;
    mission.target_count = 9;
    TEST_ASSERT_EQUAL_INT(SVA_OK, sva_planner_init(&planner));
    sva_diag_t d;
    TEST_ASSERT_EQUAL_INT(SVA_OK, sva_plan(&planner, &mission, SVA_ALGO_SVA, &plan, &d));
    TEST_ASSERT_EQUAL_INT(SVA_PLAN_COMPLETE, plan.status);
    TEST_ASSERT_EQUAL_INT(9, plan.covered);
    char msg[256];
    TEST_ASSERT_EQUAL_INT(0, spec_check_plan(&mission, &plan, msg, sizeof msg));
#endif
}
