// Algorithms on hand-made missions whose plans are worked out by hand in the comments.
#include <stddef.h>
#include <stdint.h>
#include <string.h>
#include "sva_unity.h"

#include "spec_checker.h"
#include "sva/sva.h"

static sva_planner_t planner;
static sva_mission_t mission;
static sva_plan_t plan;

static sva_uav_t uav(int32_t id, int32_t x, int32_t y, int32_t fuel)
{
    return (sva_uav_t){.id = id, .x = x, .y = y, .fuel = fuel, .ready_at_ticks = 0};
}

static sva_target_t target(int32_t id, int32_t x, int32_t y, int32_t start, int32_t end,
                           int32_t need)
{
    return (sva_target_t){
        .id = id, .x = x, .y = y, .start_ticks = start, .end_ticks = end, .need = need};
}

static void run(sva_algorithm_t algorithm)
{
    sva_diag_t diag;
    char why[200] = "";
    TEST_ASSERT_EQUAL_INT(SVA_OK, sva_plan(&planner, &mission, algorithm, &plan, &diag));
    if (spec_check_plan(&mission, &plan, why, sizeof(why)) != 0) {
        SVA_TEST_FAIL("%s: %s", sva_algorithm_name(algorithm), why);
    }
}

// One target at (5,7), need 2, three UAVs at the depot: the two lowest ids go,
// each flying 12 out and 12 back (SPEC section 3 example: distance 24 each).
void test_need_two_lowest_ids_go(void)
{
    sva_mission_init(&mission);
    mission.uav_count = 3;
    mission.uavs[0] = uav(3, 0, 0, 60);
    mission.uavs[1] = uav(1, 0, 0, 60);
    mission.uavs[2] = uav(2, 0, 0, 60);
    mission.target_count = 1;
    mission.targets[0] = target(1, 5, 7, 12, 20, 2);
    for (int a = 0; a < (int)SVA_ALGO_COUNT_; a++) {
        run((sva_algorithm_t)a);
        TEST_ASSERT_EQUAL_INT(SVA_PLAN_COMPLETE, plan.status);
        TEST_ASSERT_EQUAL_INT(48, plan.cost);
        TEST_ASSERT_EQUAL_INT(0, plan.routes[0].target_count);  // id 3 stays
        TEST_ASSERT_EQUAL_INT(24, plan.routes[1].distance_cells);
        TEST_ASSERT_EQUAL_INT(24, plan.routes[2].distance_cells);
    }
}

// Fuel with hover and return (SPEC section 1): the round trip is 24 and hover 3, so
// fuel 27 serves the target and fuel 26 does not; a target that cannot be covered in
// full takes no UAV at all.
void test_fuel_binds_exactly(void)
{
    sva_mission_init(&mission);
    mission.hover_fuel = 3;
    mission.uav_count = 1;
    mission.uavs[0] = uav(1, 0, 0, 27);
    mission.target_count = 1;
    mission.targets[0] = target(1, 5, 7, 12, 20, 1);
    for (int a = 0; a < (int)SVA_ALGO_COUNT_; a++) {
        mission.uavs[0].fuel = 27;
        run((sva_algorithm_t)a);
        TEST_ASSERT_EQUAL_INT(1, plan.covered);
        TEST_ASSERT_EQUAL_INT(27, plan.routes[0].fuel_used);
        mission.uavs[0].fuel = 26;
        run((sva_algorithm_t)a);
        TEST_ASSERT_EQUAL_INT(SVA_PLAN_PARTIAL, plan.status);
        TEST_ASSERT_EQUAL_INT(0, plan.cost);
        TEST_ASSERT_EQUAL_INT(1, plan.uncovered_count);
    }
}

// Time with ticks_per_cell: 12 cells take 12 ticks at 1 tick per cell (arrives at the
// start, 12) but 24 ticks at 2 per cell (too late).
void test_ticks_per_cell_decides_reachability(void)
{
    sva_mission_init(&mission);
    mission.uav_count = 1;
    mission.uavs[0] = uav(1, 0, 0, 100);
    mission.target_count = 1;
    mission.targets[0] = target(1, 5, 7, 12, 20, 1);
    for (int a = 0; a < (int)SVA_ALGO_COUNT_; a++) {
        mission.ticks_per_cell = 1;
        run((sva_algorithm_t)a);
        TEST_ASSERT_EQUAL_INT(1, plan.covered);
        mission.ticks_per_cell = 2;
        run((sva_algorithm_t)a);
        TEST_ASSERT_EQUAL_INT(0, plan.covered);
    }
}

// A UAV 10 cells from the depot with fuel 9 is stranded: reported, not planned for;
// a need-3 target with only two other UAVs is not half-covered.
void test_stranded_and_never_half_cover(void)
{
    sva_mission_init(&mission);
    mission.uav_count = 3;
    mission.uavs[0] = uav(1, 4, 6, 9);
    mission.uavs[1] = uav(2, 0, 0, 100);
    mission.uavs[2] = uav(3, 0, 0, 100);
    mission.target_count = 2;
    mission.targets[0] = target(1, 2, 2, 10, 20, 3);
    mission.targets[1] = target(2, 1, 1, 30, 40, 1);
    for (int a = 0; a < (int)SVA_ALGO_COUNT_; a++) {
        run((sva_algorithm_t)a);
        TEST_ASSERT_EQUAL_INT(1, plan.stranded_count);
        TEST_ASSERT_TRUE(plan.routes[0].stranded);
        TEST_ASSERT_EQUAL_INT(0, plan.routes[0].distance_cells);
        TEST_ASSERT_EQUAL_INT(1, plan.covered);
        TEST_ASSERT_EQUAL_INT(0, plan.uncovered[0]);  // target 1 (need 3) left whole
        TEST_ASSERT_EQUAL_INT(4, plan.cost);          // UAV 2 to (1,1) and back
    }
}

// Replanning: UAV X at (0,0) and Y at (5,0); A at (1,0) from tick 10, B at (0,1) from
// tick 11, windows overlapping (one cluster). Greedy gives A the nearest UAV (X, 1) and
// B gets Y (6): legs 7. The transportation problem sends X to B (1) and Y to A (4):
// legs 5. Both return one cell each, so ga costs 9 and sva/hga/bfa cost 7.
void test_transport_beats_greedy(void)
{
    sva_mission_init(&mission);
    mission.uav_count = 2;
    mission.uavs[0] = uav(1, 0, 0, 100);
    mission.uavs[1] = uav(2, 5, 0, 100);
    mission.target_count = 2;
    mission.targets[0] = target(1, 1, 0, 10, 20, 1);
    mission.targets[1] = target(2, 0, 1, 11, 21, 1);
    run(SVA_ALGO_GA);
    TEST_ASSERT_EQUAL_INT(9, plan.cost);
    for (int a = 0; a < (int)SVA_ALGO_COUNT_; a++) {
        if (a != SVA_ALGO_GA) {
            run((sva_algorithm_t)a);
            TEST_ASSERT_EQUAL_INT(7, plan.cost);
            TEST_ASSERT_EQUAL_INT(1, plan.routes[0].targets[0]);  // X serves B
        }
    }
}

// Chaining across clusters: one UAV serves A [0,10] at (3,0) then B [20,30] at (3,4)
// (4 cells, 4 ticks <= 10 ticks of slack): distance 3 + 4 + 7 = 14.
void test_one_uav_chains_clusters(void)
{
    sva_mission_init(&mission);
    mission.uav_count = 1;
    mission.uavs[0] = uav(1, 0, 0, 100);
    mission.target_count = 2;
    mission.targets[0] = target(7, 3, 4, 20, 30, 1);
    mission.targets[1] = target(5, 3, 0, 3, 10, 1);
    for (int a = 0; a < (int)SVA_ALGO_COUNT_; a++) {
        run((sva_algorithm_t)a);
        TEST_ASSERT_EQUAL_INT(SVA_PLAN_COMPLETE, plan.status);
        TEST_ASSERT_EQUAL_INT(2, plan.routes[0].target_count);
        TEST_ASSERT_EQUAL_INT(1, plan.routes[0].targets[0]);  // the earlier window first
        TEST_ASSERT_EQUAL_INT(14, plan.cost);
    }
}

// Same input, same plan; UAVs listed in another order get the same targets by id.
void test_deterministic_and_order_independent(void)
{
    sva_mission_init(&mission);
    mission.uav_count = 3;
    mission.uavs[0] = uav(10, 0, 0, 100);
    mission.uavs[1] = uav(20, 0, 0, 100);
    mission.uavs[2] = uav(30, 0, 0, 100);
    mission.target_count = 2;
    mission.targets[0] = target(1, 4, 4, 10, 20, 1);
    mission.targets[1] = target(2, 4, 4, 11, 21, 1);
    for (int a = 0; a < (int)SVA_ALGO_COUNT_; a++) {
        run((sva_algorithm_t)a);
        const int32_t first = plan.routes[0].target_count;
        const int32_t second = plan.routes[1].target_count;
        TEST_ASSERT_EQUAL_INT(2, first + second);  // ids 10 and 20 go, 30 stays
        const sva_uav_t swap = mission.uavs[0];
        mission.uavs[0] = mission.uavs[2];
        mission.uavs[2] = swap;
        run((sva_algorithm_t)a);
        TEST_ASSERT_EQUAL_INT(first, plan.routes[2].target_count);  // id 10, now listed last
        TEST_ASSERT_EQUAL_INT(0, plan.routes[0].target_count);      // id 30
        mission.uavs[2] = mission.uavs[0];
        mission.uavs[0] = swap;
    }
}

// No UAVs, no targets: trivially complete; no UAVs with targets: partial, cost 0.
void test_empty_fleet_and_empty_mission(void)
{
    sva_mission_init(&mission);
    for (int a = 0; a < (int)SVA_ALGO_COUNT_; a++) {
        run((sva_algorithm_t)a);
        TEST_ASSERT_EQUAL_INT(SVA_PLAN_COMPLETE, plan.status);
    }
    mission.target_count = 1;
    mission.targets[0] = target(1, 1, 1, 5, 6, 1);
    for (int a = 0; a < (int)SVA_ALGO_COUNT_; a++) {
        run((sva_algorithm_t)a);
        TEST_ASSERT_EQUAL_INT(SVA_PLAN_PARTIAL, plan.status);
        TEST_ASSERT_EQUAL_INT(0, plan.cost);
    }
}

// A UAV away from the depot that serves nothing still flies home (SPEC section 1).
void test_idle_uav_flies_home(void)
{
    sva_mission_init(&mission);
    mission.uav_count = 1;
    mission.uavs[0] = uav(1, 3, -4, 100);
    for (int a = 0; a < (int)SVA_ALGO_COUNT_; a++) {
        run((sva_algorithm_t)a);
        TEST_ASSERT_EQUAL_INT(7, plan.routes[0].distance_cells);
        TEST_ASSERT_EQUAL_INT(7, plan.cost);
    }
}

// Regression (found on fixtures/missions/hand_5_5.json): two UAVs at the depot, A needs
// 2 at 6 cells, B needs 1 at 8 cells, same window. Either covers one target; B costs 16
// (8 out, 8 back) and A 24 (two UAVs, 12 each). A plain per-unit big M filled A. Now
// unmet demand is priced per whole target: the LP splits 1 + 1, A is short and dropped,
// B is covered.
void test_whole_targets_not_units_decide(void)
{
    sva_mission_init(&mission);
    mission.uav_count = 2;
    mission.uavs[0] = uav(1, 0, 0, 100);
    mission.uavs[1] = uav(2, 0, 0, 100);
    mission.target_count = 2;
    mission.targets[0] = target(1, 6, 0, 10, 20, 2);
    mission.targets[1] = target(2, 0, 8, 10, 20, 1);
    for (int a = 0; a < (int)SVA_ALGO_COUNT_; a++) {
        if (a == SVA_ALGO_GA) {
            continue;  // greedy fills the earliest target first by design (A: 24)
        }
        run((sva_algorithm_t)a);
        TEST_ASSERT_EQUAL_INT(1, plan.covered);
        TEST_ASSERT_EQUAL_INT(0, plan.uncovered[0]);
        TEST_ASSERT_EQUAL_INT(16, plan.cost);
    }
}

// Every test starts from a freshly initialised planner.
void setUp(void)
{
    TEST_ASSERT_EQUAL_INT(SVA_OK, sva_planner_init(&planner));
}
