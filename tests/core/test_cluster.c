// Clustering (SPEC section 2): sort by (start, end, id); a target joins the current
// cluster iff 100 * |A n B| >= overlap_percent * min(|A|, |B|) with the last member.
#include <stddef.h>
#include <stdint.h>
#include "unity.h"

#include "paper/paper.h"

static sva_planner_t planner;
static sva_mission_t mission;

static sva_target_t window(int32_t id, int32_t start, int32_t end)
{
    return (sva_target_t){
        .id = id, .x = 0, .y = 0, .start_ticks = start, .end_ticks = end, .need = 1};
}

void test_overlap_rule_exact_threshold(void)
{
    const sva_target_t a = window(1, 0, 10);
    const sva_target_t b = window(2, 3, 13);  // overlap 7 of 10: exactly 70 %
    const sva_target_t c = window(3, 4, 14);  // overlap 6 of 10
    TEST_ASSERT_TRUE(sva_windows_overlap(&a, &b, 70));
    TEST_ASSERT_FALSE(sva_windows_overlap(&a, &c, 70));
    TEST_ASSERT_TRUE(sva_windows_overlap(&a, &c, 60));
    // The shorter window decides: [2, 4] lies inside [0, 10].
    const sva_target_t inner = window(4, 2, 4);
    TEST_ASSERT_TRUE(sva_windows_overlap(&a, &inner, 100));
    // Touching windows share nothing; overlap_percent 0 joins everything.
    const sva_target_t after = window(5, 10, 20);
    TEST_ASSERT_FALSE(sva_windows_overlap(&a, &after, 1));
    TEST_ASSERT_TRUE(sva_windows_overlap(&a, &after, 0));
}

// The paper's example (section 4.1): t1 and t2 overlap 70 % -> one cluster; t4 does
// not overlap t2 -> new cluster; t5 overlaps t4 by 40 % -> new cluster.
void test_paper_example(void)
{
    sva_mission_init(&mission);
    mission.target_count = 4;
    mission.targets[0] = window(5, 26, 36);  // listed out of order on purpose
    mission.targets[1] = window(1, 0, 10);
    mission.targets[2] = window(4, 20, 30);
    mission.targets[3] = window(2, 3, 13);
    sva_sort_targets(&planner.priv, &mission);
    sva_cluster_targets(&planner.priv, &mission);
    const uint16_t order[] = {1, 3, 2, 0};
    TEST_ASSERT_EQUAL_MEMORY(order, planner.priv.target_order, sizeof(order));
    TEST_ASSERT_EQUAL_INT(3, planner.priv.cluster_count);
    TEST_ASSERT_EQUAL_INT(2, planner.priv.cluster_end[0]);
    TEST_ASSERT_EQUAL_INT(3, planner.priv.cluster_end[1]);
    TEST_ASSERT_EQUAL_INT(4, planner.priv.cluster_end[2]);
}

void test_sort_ties_by_end_then_id(void)
{
    sva_mission_init(&mission);
    mission.target_count = 3;
    mission.targets[0] = window(9, 5, 9);
    mission.targets[1] = window(3, 5, 9);
    mission.targets[2] = window(1, 5, 12);
    sva_sort_targets(&planner.priv, &mission);
    const uint16_t order[] = {1, 0, 2};
    TEST_ASSERT_EQUAL_MEMORY(order, planner.priv.target_order, sizeof(order));
}

// Chaining compares with the last member only: a, b, c each overlap the previous one
// enough, so all three form one cluster although a and c do not overlap at all.
void test_cluster_chains_through_last_member(void)
{
    sva_mission_init(&mission);
    mission.target_count = 3;
    mission.targets[0] = window(1, 0, 10);
    mission.targets[1] = window(2, 2, 12);
    mission.targets[2] = window(3, 10, 14);  // 2 of 4 with b at 50 %
    mission.overlap_percent = 50;
    sva_sort_targets(&planner.priv, &mission);
    sva_cluster_targets(&planner.priv, &mission);
    TEST_ASSERT_EQUAL_INT(1, planner.priv.cluster_count);
    mission.overlap_percent = 51;
    sva_cluster_targets(&planner.priv, &mission);
    TEST_ASSERT_EQUAL_INT(2, planner.priv.cluster_count);
}
