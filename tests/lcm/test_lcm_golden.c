// Golden log replay over file://: the node reads tests/lcm/data/golden.lcmlog (made by
// make_golden_log.py from fixtures/missions/rand_7_2.json) and must answer with exactly
// the plans the core makes from the same JSON (loaded here with jansson, independently
// of the Python encoder), and count exactly the malformed events the log contains.
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "unity.h"
#include <jansson.h>

#include "sva/sva_lcm.h"

static sva_lcm_node_t node;
static sva_planner_t planner;
static sva_plan_t want;
static sva_mission_t mission;
static sva_lcm_plan_t got[4];
static int plan_count;

static int capture(void* user, const char* channel, const void* data, unsigned int size)
{
    (void)user;
    if ((strcmp(channel, "GOLD_PLAN") == 0) && (plan_count < 4)) {
        TEST_ASSERT_EQUAL_INT((int)size,
                              sva_lcm_plan_t_decode(data, 0, (int)size, &got[plan_count]));
        plan_count++;
    }
    return 0;
}

static int32_t geti(json_t* obj, const char* key, int32_t dflt)
{
    json_t* v = json_object_get(obj, key);
    return (v == NULL) ? dflt : (int32_t)json_integer_value(v);
}

static void load_mission(const char* path)
{
    json_error_t err;
    json_t* doc = json_load_file(path, 0, &err);
    TEST_ASSERT_NOT_NULL(doc);
    sva_mission_init(&mission);
    json_t* depot = json_object_get(doc, "depot");
    mission.depot_x = geti(depot, "x", 0);
    mission.depot_y = geti(depot, "y", 0);
    mission.ticks_per_cell = geti(doc, "ticks_per_cell", 1);
    mission.hover_fuel = geti(doc, "hover_fuel", 0);
    mission.overlap_percent = geti(doc, "overlap_percent", 70);
    size_t i;
    json_t* v;
    json_array_foreach(json_object_get(doc, "uavs"), i, v)
    {
        sva_uav_t* u = &mission.uavs[mission.uav_count++];
        u->id = geti(v, "id", 0);
        u->x = geti(v, "x", 0);
        u->y = geti(v, "y", 0);
        u->fuel = geti(v, "fuel", 0);
        u->ready_at_ticks = geti(v, "ready_at", 0);
    }
    json_array_foreach(json_object_get(doc, "targets"), i, v)
    {
        sva_target_t* t = &mission.targets[mission.target_count++];
        t->id = geti(v, "id", 0);
        t->x = geti(v, "x", 0);
        t->y = geti(v, "y", 0);
        t->start_ticks = geti(v, "start", 0);
        t->end_ticks = geti(v, "end", 0);
        t->need = geti(v, "need", 0);
    }
    json_decref(doc);
}

static void assert_same_plan(const sva_lcm_plan_t* p)
{
    TEST_ASSERT_EQUAL_INT(SVA_OK, sva_planner_init(&planner));
    TEST_ASSERT_EQUAL_INT(SVA_OK, sva_plan(&planner, &mission, SVA_ALGO_SVA, &want, NULL));
    TEST_ASSERT_EQUAL_INT(want.status == SVA_PLAN_COMPLETE ? 1 : 2, p->status);
    TEST_ASSERT_EQUAL_INT(want.covered, p->covered);
    TEST_ASSERT_EQUAL_INT(want.cost, p->cost);
    TEST_ASSERT_EQUAL_INT(want.uncovered_count, p->uncovered_count);
    for (int i = 0; i < want.uncovered_count; ++i) {
        TEST_ASSERT_EQUAL_INT(mission.targets[want.uncovered[i]].id, p->uncovered[i]);
    }
    TEST_ASSERT_EQUAL_INT(want.route_count, p->route_count);
    int k = 0;
    for (int r = 0; r < want.route_count; ++r) {
        TEST_ASSERT_EQUAL_INT(want.routes[r].uav_id, p->routes[r].uav_id);
        TEST_ASSERT_EQUAL_INT(want.routes[r].target_count, p->routes[r].target_count);
        TEST_ASSERT_EQUAL_INT(want.routes[r].distance_cells, p->routes[r].distance_cells);
        TEST_ASSERT_EQUAL_INT(want.routes[r].fuel_used, p->routes[r].fuel_used);
        for (int j = 0; j < want.routes[r].target_count; ++j) {
            TEST_ASSERT_EQUAL_INT(mission.targets[want.routes[r].targets[j]].id,
                                  p->route_targets[k++]);
        }
    }
    TEST_ASSERT_EQUAL_INT(k, p->item_count);
    TEST_ASSERT_FALSE(want.stats.has_bound);  // sva: no certificate, and none on the wire
    TEST_ASSERT_EQUAL_INT(0, p->has_bound);
    TEST_ASSERT_EQUAL_INT(0, p->lower_bound);
    TEST_ASSERT_EQUAL_INT(0, p->optimal);
}

void test_golden_replay(void)
{
    const char* log = getenv("SVA_LCM_GOLDEN_LOG");
    const char* json = getenv("SVA_LCM_GOLDEN_MISSION");
    TEST_ASSERT_NOT_NULL(log);
    TEST_ASSERT_NOT_NULL(json);
    char url[1024];
    TEST_ASSERT_TRUE(snprintf(url, sizeof url, "file://%s?speed=0", log) < (int)sizeof url);
    lcm_t* lcm = lcm_create(url);
    TEST_ASSERT_NOT_NULL(lcm);
    TEST_ASSERT_EQUAL_INT(SVA_OK, sva_lcm_node_init(&node, lcm, "GOLD_", SVA_ALGO_SVA));
    TEST_ASSERT_EQUAL_INT(SVA_OK, sva_lcm_node_subscribe(&node));
    node.publish = capture;  // the file provider is read-only
    int events = 0;
    while ((events < 100) && (lcm_handle_timeout(lcm, 1000) > 0)) {
        events++;
    }
    sva_lcm_node_unsubscribe(&node);
    lcm_destroy(lcm);

    TEST_ASSERT_EQUAL_INT(9, events);
    TEST_ASSERT_EQUAL_INT(4, node.counters.fleet_rx);
    TEST_ASSERT_EQUAL_INT(5, node.counters.mission_rx);
    TEST_ASSERT_EQUAL_INT(1, node.counters.unchanged);
    TEST_ASSERT_EQUAL_INT(1, node.counters.rejected[SVA_LCM_REJECT_TRUNCATED]);
    TEST_ASSERT_EQUAL_INT(0, node.counters.rejected[SVA_LCM_REJECT_TRAILING]);
    TEST_ASSERT_EQUAL_INT(1, node.counters.rejected[SVA_LCM_REJECT_FINGERPRINT]);
    TEST_ASSERT_EQUAL_INT(1, node.counters.rejected[SVA_LCM_REJECT_COUNT]);
    TEST_ASSERT_EQUAL_INT(1, node.counters.rejected[SVA_LCM_REJECT_VALUE]);
    TEST_ASSERT_EQUAL_INT(0, node.counters.rejected[SVA_LCM_REJECT_INVALID]);
    TEST_ASSERT_EQUAL_INT(1, node.counters.rejected[SVA_LCM_REJECT_VERSION]);
    TEST_ASSERT_EQUAL_INT(2, plan_count);

    load_mission(json);
    TEST_ASSERT_EQUAL_INT(SVA_LCM_PLAN_T_VERSION, got[0].version);
    TEST_ASSERT_EQUAL_INT(1, got[0].plan_id);
    TEST_ASSERT_EQUAL_INT(1, got[0].fleet_revision);
    TEST_ASSERT_EQUAL_INT(1, got[0].mission_revision);
    assert_same_plan(&got[0]);
    // rev 2: UAV index 2 unavailable, which the node maps to ready_at = SVA_MAX_TICK
    mission.uavs[2].ready_at_ticks = (int32_t)SVA_MAX_TICK;
    TEST_ASSERT_EQUAL_INT(2, got[1].plan_id);
    TEST_ASSERT_EQUAL_INT(2, got[1].fleet_revision);
    TEST_ASSERT_EQUAL_INT(1, got[1].mission_revision);
    TEST_ASSERT_EQUAL_INT(0, got[1].routes[2].target_count);
    assert_same_plan(&got[1]);
}
