// Golden log replay over file://: the node reads tests/lcm/data/golden.lcmlog (made by
// make_golden_log.py from fixtures/missions/rand_7_2.json) and must answer with exactly
// the plans the core makes from the same JSON (loaded here with jansson, independently
// of the Python encoder), and count exactly the malformed events the log contains.
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>
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
        assert_int_equal(sva_lcm_plan_t_decode(data, 0, (int)size, &got[plan_count]), (int)size);
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
    assert_non_null(doc);
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
    assert_int_equal(sva_planner_init(&planner), SVA_OK);
    assert_int_equal(sva_plan(&planner, &mission, SVA_ALGO_SVA, &want, NULL), SVA_OK);
    assert_int_equal(p->status, want.status == SVA_PLAN_COMPLETE ? 1 : 2);
    assert_int_equal(p->covered, want.covered);
    assert_int_equal(p->cost, want.cost);
    assert_int_equal(p->uncovered_count, want.uncovered_count);
    for (int i = 0; i < want.uncovered_count; ++i) {
        assert_int_equal(p->uncovered[i], mission.targets[want.uncovered[i]].id);
    }
    assert_int_equal(p->route_count, want.route_count);
    int k = 0;
    for (int r = 0; r < want.route_count; ++r) {
        assert_int_equal(p->routes[r].uav_id, want.routes[r].uav_id);
        assert_int_equal(p->routes[r].target_count, want.routes[r].target_count);
        assert_int_equal(p->routes[r].distance_cells, want.routes[r].distance_cells);
        assert_int_equal(p->routes[r].fuel_used, want.routes[r].fuel_used);
        for (int j = 0; j < want.routes[r].target_count; ++j) {
            assert_int_equal(p->route_targets[k++], mission.targets[want.routes[r].targets[j]].id);
        }
    }
    assert_int_equal(p->item_count, k);
    assert_false(want.stats.has_bound);  // sva: no certificate, and none on the wire
    assert_int_equal(p->has_bound, 0);
    assert_int_equal(p->lower_bound, 0);
    assert_int_equal(p->optimal, 0);
}

static void test_golden_replay(void** state)
{
    (void)state;
    const char* log = getenv("SVA_LCM_GOLDEN_LOG");
    const char* json = getenv("SVA_LCM_GOLDEN_MISSION");
    assert_non_null(log);
    assert_non_null(json);
    char url[1024];
    assert_true(snprintf(url, sizeof url, "file://%s?speed=0", log) < (int)sizeof url);
    lcm_t* lcm = lcm_create(url);
    assert_non_null(lcm);
    assert_int_equal(sva_lcm_node_init(&node, lcm, "GOLD_", SVA_ALGO_SVA), SVA_OK);
    assert_int_equal(sva_lcm_node_subscribe(&node), SVA_OK);
    node.publish = capture;  // the file provider is read-only
    int events = 0;
    while ((events < 100) && (lcm_handle_timeout(lcm, 1000) > 0)) {
        events++;
    }
    sva_lcm_node_unsubscribe(&node);
    lcm_destroy(lcm);

    assert_int_equal(events, 9);
    assert_int_equal(node.counters.fleet_rx, 4);
    assert_int_equal(node.counters.mission_rx, 5);
    assert_int_equal(node.counters.unchanged, 1);
    assert_int_equal(node.counters.rejected[SVA_LCM_REJECT_TRUNCATED], 1);
    assert_int_equal(node.counters.rejected[SVA_LCM_REJECT_TRAILING], 0);
    assert_int_equal(node.counters.rejected[SVA_LCM_REJECT_FINGERPRINT], 1);
    assert_int_equal(node.counters.rejected[SVA_LCM_REJECT_COUNT], 1);
    assert_int_equal(node.counters.rejected[SVA_LCM_REJECT_VALUE], 1);
    assert_int_equal(node.counters.rejected[SVA_LCM_REJECT_INVALID], 0);
    assert_int_equal(node.counters.rejected[SVA_LCM_REJECT_VERSION], 1);
    assert_int_equal(plan_count, 2);

    load_mission(json);
    assert_int_equal(got[0].version, SVA_LCM_PLAN_T_VERSION);
    assert_int_equal(got[0].plan_id, 1);
    assert_int_equal(got[0].fleet_revision, 1);
    assert_int_equal(got[0].mission_revision, 1);
    assert_same_plan(&got[0]);
    // rev 2: UAV index 2 unavailable, which the node maps to ready_at = SVA_MAX_TICK
    mission.uavs[2].ready_at_ticks = (int32_t)SVA_MAX_TICK;
    assert_int_equal(got[1].plan_id, 2);
    assert_int_equal(got[1].fleet_revision, 2);
    assert_int_equal(got[1].mission_revision, 1);
    assert_int_equal(got[1].routes[2].target_count, 0);
    assert_same_plan(&got[1]);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_golden_replay),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
