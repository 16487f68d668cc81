// Clustering (SPEC section 2): sort by (start, end, id); a target joins the current
// cluster iff 100 * |A n B| >= overlap_percent * min(|A|, |B|) with the last member.
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include "paper/paper.h"

static sva_planner_t planner;
static sva_mission_t mission;

static sva_target_t window(int32_t id, int32_t start, int32_t end)
{
    return (sva_target_t){
        .id = id, .x = 0, .y = 0, .start_ticks = start, .end_ticks = end, .need = 1};
}

static void test_overlap_rule_exact_threshold(void** state)
{
    (void)state;
    const sva_target_t a = window(1, 0, 10);
    const sva_target_t b = window(2, 3, 13);  // overlap 7 of 10: exactly 70 %
    const sva_target_t c = window(3, 4, 14);  // overlap 6 of 10
    assert_true(sva_windows_overlap(&a, &b, 70));
    assert_false(sva_windows_overlap(&a, &c, 70));
    assert_true(sva_windows_overlap(&a, &c, 60));
    // The shorter window decides: [2, 4] lies inside [0, 10].
    const sva_target_t inner = window(4, 2, 4);
    assert_true(sva_windows_overlap(&a, &inner, 100));
    // Touching windows share nothing; overlap_percent 0 joins everything.
    const sva_target_t after = window(5, 10, 20);
    assert_false(sva_windows_overlap(&a, &after, 1));
    assert_true(sva_windows_overlap(&a, &after, 0));
}

// The paper's example (section 4.1): t1 and t2 overlap 70 % -> one cluster; t4 does
// not overlap t2 -> new cluster; t5 overlaps t4 by 40 % -> new cluster.
static void test_paper_example(void** state)
{
    (void)state;
    sva_mission_init(&mission);
    mission.target_count = 4;
    mission.targets[0] = window(5, 26, 36);  // listed out of order on purpose
    mission.targets[1] = window(1, 0, 10);
    mission.targets[2] = window(4, 20, 30);
    mission.targets[3] = window(2, 3, 13);
    sva_sort_targets(&planner.priv, &mission);
    sva_cluster_targets(&planner.priv, &mission);
    const uint16_t order[] = {1, 3, 2, 0};
    assert_memory_equal(planner.priv.target_order, order, sizeof(order));
    assert_int_equal(planner.priv.cluster_count, 3);
    assert_int_equal(planner.priv.cluster_end[0], 2);
    assert_int_equal(planner.priv.cluster_end[1], 3);
    assert_int_equal(planner.priv.cluster_end[2], 4);
}

static void test_sort_ties_by_end_then_id(void** state)
{
    (void)state;
    sva_mission_init(&mission);
    mission.target_count = 3;
    mission.targets[0] = window(9, 5, 9);
    mission.targets[1] = window(3, 5, 9);
    mission.targets[2] = window(1, 5, 12);
    sva_sort_targets(&planner.priv, &mission);
    const uint16_t order[] = {1, 0, 2};
    assert_memory_equal(planner.priv.target_order, order, sizeof(order));
}

// Chaining compares with the last member only: a, b, c each overlap the previous one
// enough, so all three form one cluster although a and c do not overlap at all.
static void test_cluster_chains_through_last_member(void** state)
{
    (void)state;
    sva_mission_init(&mission);
    mission.target_count = 3;
    mission.targets[0] = window(1, 0, 10);
    mission.targets[1] = window(2, 2, 12);
    mission.targets[2] = window(3, 10, 14);  // 2 of 4 with b at 50 %
    mission.overlap_percent = 50;
    sva_sort_targets(&planner.priv, &mission);
    sva_cluster_targets(&planner.priv, &mission);
    assert_int_equal(planner.priv.cluster_count, 1);
    mission.overlap_percent = 51;
    sva_cluster_targets(&planner.priv, &mission);
    assert_int_equal(planner.priv.cluster_count, 2);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_overlap_rule_exact_threshold),
        cmocka_unit_test(test_paper_example),
        cmocka_unit_test(test_sort_ties_by_end_then_id),
        cmocka_unit_test(test_cluster_chains_through_last_member),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
