// Unit tests of the LCM adapter over memq:// and direct calls: codec round trip, every
// rejection reason, change detection, and zero heap allocations per message.
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>

#include "unity.h"

#include "sva/sva_lcm.h"

// --- allocation counter: this binary's malloc family wraps glibc's -------------------
extern void* __libc_malloc(size_t size);
extern void* __libc_calloc(size_t n, size_t size);
extern void* __libc_realloc(void* p, size_t size);
extern void __libc_free(void* p);

static volatile int alloc_armed = 0;
static volatile long alloc_count = 0;

void* malloc(size_t size);
void* calloc(size_t n, size_t size);
void* realloc(void* p, size_t size);
void free(void* p);

void* malloc(size_t size)
{
    if (alloc_armed) {
        alloc_count++;
    }
    return __libc_malloc(size);
}
void* calloc(size_t n, size_t size)
{
    if (alloc_armed) {
        alloc_count++;
    }
    return __libc_calloc(n, size);
}
void* realloc(void* p, size_t size)
{
    if (alloc_armed) {
        alloc_count++;
    }
    return __libc_realloc(p, size);
}
void free(void* p)
{
    __libc_free(p);
}

// --- fixtures ------------------------------------------------------------------------
static sva_lcm_node_t node;
static sva_planner_t planner;
static sva_plan_t direct_plan;
static sva_mission_t direct_mission;
static sva_lcm_fleet_state_t fleet;
static sva_lcm_mission_t mission;
static sva_lcm_plan_t got_plan;
static uint8_t fleet_buf[SVA_LCM_FLEET_BYTES + 8];
static uint8_t mission_buf[SVA_LCM_MISSION_BYTES + 8];

// Captured publications (the publish hook).
static uint8_t last_plan_bytes[SVA_LCM_PLAN_BYTES];
static unsigned int last_plan_size;
static int plans_seen;
static int replans_seen;
static sva_lcm_replan_t got_replan;
static int status_seen;
static int log_lines[SVA_LCM_REJECT_COUNT_ + 1];
static char last_log[400];

static int capture(void* user, const char* channel, const void* data, unsigned int size)
{
    (void)user;
    if (strstr(channel, "REPLAN") != NULL) {
        TEST_ASSERT_EQUAL_INT(SVA_LCM_REPLAN_BYTES, size);
        TEST_ASSERT_EQUAL_INT((int)size, sva_lcm_replan_t_decode(data, 0, (int)size, &got_replan));
        replans_seen++;
    } else if (strstr(channel, "PLAN") != NULL) {
        if (size <= sizeof last_plan_bytes) {
            memcpy(last_plan_bytes, data, size);
        }
        last_plan_size = size;
        plans_seen++;
    } else {
        status_seen++;
    }
    return 0;
}

static void count_log(void* user, const char* line)
{
    (void)user;
    (void)snprintf(last_log, sizeof last_log, "%s", line);
    for (int r = 0; r < (int)SVA_LCM_REJECT_COUNT_; ++r) {
        char key[32];
        (void)snprintf(key, sizeof key, "(%s;", sva_lcm_reject_name((sva_lcm_reject_t)r));
        if (strstr(line, key) != NULL) {
            log_lines[r]++;
            return;
        }
    }
    log_lines[SVA_LCM_REJECT_COUNT_]++;
}

// 5 UAVs at the depot, 6 targets (two need 2 UAVs, one is out of reach in time).
static void make_inputs(int64_t revision)
{
    memset(&fleet, 0, sizeof fleet);
    memset(&mission, 0, sizeof mission);
    fleet.version = SVA_LCM_FLEET_STATE_T_VERSION;
    fleet.revision = revision;
    fleet.uav_count = 5;
    for (int i = 0; i < 5; ++i) {
        fleet.uavs[i].id = 10 + i;
        fleet.uavs[i].fuel = 200;
        fleet.uavs[i].health = SVA_LCM_UAV_STATE_T_HEALTH_OK;
    }
    fleet.uavs[4].x = 3;
    fleet.uavs[4].ready_at_ticks = 4;
    mission.version = SVA_LCM_MISSION_T_VERSION;
    mission.revision = revision;
    mission.ticks_per_cell = 1;
    mission.hover_fuel = 2;
    mission.overlap_percent = 70;
    mission.target_count = 6;
    const int32_t t[6][6] = {{1, 5, 7, 12, 20, 2},   {2, -4, 3, 10, 18, 1},  {3, 6, -2, 14, 22, 1},
                             {4, 10, 10, 40, 50, 2}, {5, -8, -6, 35, 45, 1}, {6, 90, 90, 5, 9, 1}};
    for (int i = 0; i < 6; ++i) {
        sva_lcm_target_t* g = &mission.targets[i];
        g->id = t[i][0];
        g->x = t[i][1];
        g->y = t[i][2];
        g->start_ticks = t[i][3];
        g->end_ticks = t[i][4];
        g->need = t[i][5];
    }
}

// The fleet: SVA_MAX_UAVS UAVs at the depot, fuel 1000, ready at once.
static void full_fleet_at_depot(void)
{
    fleet.uav_count = SVA_MAX_UAVS;
    for (int i = 0; i < SVA_MAX_UAVS; ++i) {
        fleet.uavs[i] = (sva_lcm_uav_state_t){i + 1, 0, 0, 1000, 0, 0};
    }
}

static int enc_fleet(void)
{
    return sva_lcm_fleet_state_t_encode(fleet_buf, 0, (int)sizeof fleet_buf, &fleet);
}

static int enc_mission(void)
{
    return sva_lcm_mission_t_encode(mission_buf, 0, (int)sizeof mission_buf, &mission);
}

static void node_setup(sva_algorithm_t algo)
{
    TEST_ASSERT_EQUAL_INT(SVA_OK, sva_lcm_node_init(&node, NULL, "T_", algo));
    node.publish = capture;
    node.log = count_log;
    plans_seen = 0;
    replans_seen = 0;
    status_seen = 0;
    memset(log_lines, 0, sizeof log_lines);
}

// The same mission built by hand for the core, for comparison with what the node did.
static void direct_from_wire(void)
{
    sva_mission_init(&direct_mission);
    direct_mission.ticks_per_cell = mission.ticks_per_cell;
    direct_mission.hover_fuel = mission.hover_fuel;
    direct_mission.overlap_percent = mission.overlap_percent;
    direct_mission.depot_x = mission.depot_x;
    direct_mission.depot_y = mission.depot_y;
    direct_mission.uav_count = (uint16_t)fleet.uav_count;
    for (int i = 0; i < fleet.uav_count; ++i) {
        sva_uav_t* u = &direct_mission.uavs[i];
        u->id = fleet.uavs[i].id;
        u->x = fleet.uavs[i].x;
        u->y = fleet.uavs[i].y;
        u->fuel = fleet.uavs[i].fuel;
        u->ready_at_ticks = fleet.uavs[i].ready_at_ticks;
    }
    direct_mission.target_count = (uint16_t)mission.target_count;
    for (int i = 0; i < mission.target_count; ++i) {
        sva_target_t* t = &direct_mission.targets[i];
        t->id = mission.targets[i].id;
        t->x = mission.targets[i].x;
        t->y = mission.targets[i].y;
        t->start_ticks = mission.targets[i].start_ticks;
        t->end_ticks = mission.targets[i].end_ticks;
        t->need = mission.targets[i].need;
    }
}

static void assert_plan_matches_core(const sva_lcm_plan_t* p, sva_algorithm_t algo)
{
    direct_from_wire();
    TEST_ASSERT_EQUAL_INT(SVA_OK, sva_planner_init(&planner));
    TEST_ASSERT_EQUAL_INT(SVA_OK, sva_plan(&planner, &direct_mission, algo, &direct_plan, NULL));
    TEST_ASSERT_EQUAL_INT((int)algo, p->algorithm);
    TEST_ASSERT_EQUAL_INT(direct_plan.status == SVA_PLAN_COMPLETE ? SVA_LCM_PLAN_T_STATUS_COMPLETE
                                                                  : SVA_LCM_PLAN_T_STATUS_PARTIAL,
                          p->status);
    TEST_ASSERT_EQUAL_INT(direct_plan.covered, p->covered);
    TEST_ASSERT_EQUAL_INT(direct_plan.cost, p->cost);
    TEST_ASSERT_EQUAL_INT(direct_plan.uncovered_count, p->uncovered_count);
    for (int i = 0; i < p->uncovered_count; ++i) {
        TEST_ASSERT_EQUAL_INT(direct_mission.targets[direct_plan.uncovered[i]].id, p->uncovered[i]);
    }
    TEST_ASSERT_EQUAL_INT(direct_plan.route_count, p->route_count);
    int k = 0;
    for (int r = 0; r < p->route_count; ++r) {
        const sva_route_t* d = &direct_plan.routes[r];
        TEST_ASSERT_EQUAL_INT(d->uav_id, p->routes[r].uav_id);
        TEST_ASSERT_EQUAL_INT(d->target_count, p->routes[r].target_count);
        TEST_ASSERT_EQUAL_INT(d->distance_cells, p->routes[r].distance_cells);
        TEST_ASSERT_EQUAL_INT(d->fuel_used, p->routes[r].fuel_used);
        TEST_ASSERT_EQUAL_INT(d->stranded ? 1 : 0, p->routes[r].stranded);
        for (int j = 0; j < d->target_count; ++j) {
            TEST_ASSERT_EQUAL_INT(direct_mission.targets[d->targets[j]].id, p->route_targets[k++]);
        }
    }
    TEST_ASSERT_EQUAL_INT(k, p->item_count);
    for (; k < SVA_LCM_PLAN_T_MAX_ROUTE_ITEMS; ++k) {
        TEST_ASSERT_EQUAL_INT(0, p->route_targets[k]);
    }
    // flow's certificate travels as the core made it; the other algorithms send zeros.
    const sva_stats_t* st = &direct_plan.stats;
    TEST_ASSERT_EQUAL_INT(algo == SVA_ALGO_FLOW, st->has_bound);
    TEST_ASSERT_EQUAL_INT(st->has_bound ? 1 : 0, p->has_bound);
    TEST_ASSERT_EQUAL_INT(st->has_bound ? st->lower_bound : 0, p->lower_bound);
    TEST_ASSERT_EQUAL_INT((st->has_bound && st->optimal) ? 1 : 0, p->optimal);
    TEST_ASSERT_EQUAL_INT(st->has_bound ? st->flow_incomplete : 0, p->flow_incomplete);
    if (p->has_bound == 1) {
        TEST_ASSERT_TRUE(p->lower_bound >= 0);
        TEST_ASSERT_TRUE(p->lower_bound <= p->cost);
        if (p->optimal == 1) {
            TEST_ASSERT_EQUAL_INT(p->cost, p->lower_bound);
            TEST_ASSERT_EQUAL_INT(0, p->flow_incomplete);
        }
    }
}

static void decode_last_plan(void)
{
    TEST_ASSERT_EQUAL_INT(SVA_LCM_PLAN_BYTES, last_plan_size);
    TEST_ASSERT_EQUAL_INT(
        SVA_LCM_PLAN_BYTES,
        sva_lcm_plan_t_decode(last_plan_bytes, 0, (int)last_plan_size, &got_plan));
}

// --- tests ------------------------------------------------------------------------------

void test_encoded_sizes(void)
{
    make_inputs(1);
    static sva_lcm_plan_t p;
    static sva_lcm_node_status_t s;
    TEST_ASSERT_EQUAL_INT(SVA_LCM_FLEET_BYTES, sva_lcm_fleet_state_t_encoded_size(&fleet));
    TEST_ASSERT_EQUAL_INT(SVA_LCM_MISSION_BYTES, sva_lcm_mission_t_encoded_size(&mission));
    TEST_ASSERT_EQUAL_INT(SVA_LCM_PLAN_BYTES, sva_lcm_plan_t_encoded_size(&p));
    TEST_ASSERT_EQUAL_INT(SVA_LCM_STATUS_BYTES, sva_lcm_node_status_t_encoded_size(&s));
    static sva_lcm_event_t e;
    static sva_lcm_replan_t r;
    TEST_ASSERT_EQUAL_INT(SVA_LCM_EVENT_BYTES, sva_lcm_event_t_encoded_size(&e));
    TEST_ASSERT_EQUAL_INT(SVA_LCM_REPLAN_BYTES, sva_lcm_replan_t_encoded_size(&r));
    static sva_lcm_report_t rp;
    TEST_ASSERT_EQUAL_INT(SVA_LCM_REPORT_BYTES, sva_lcm_report_t_encoded_size(&rp));
    TEST_ASSERT_TRUE(SVA_LCM_REPLAN_BYTES + 64 <= 65499);
    // one udpm datagram (LCM_SHORT_MESSAGE_MAX_SIZE) with the longest channel name
    TEST_ASSERT_TRUE(SVA_LCM_PLAN_BYTES + 64 <= 65499);
}

void test_channel_escape(void)
{
    char out[16];
    TEST_ASSERT_EQUAL_INT(SVA_OK, sva_lcm_channel_escape("A_b9", out, sizeof out));
    TEST_ASSERT_EQUAL_STRING("A_b9", out);
    TEST_ASSERT_EQUAL_INT(SVA_OK, sva_lcm_channel_escape("a.b*[c]", out, sizeof out));
    TEST_ASSERT_EQUAL_STRING("a\\.b\\*\\[c\\]", out);
    TEST_ASSERT_EQUAL_INT(SVA_ERR_ARGUMENT, sva_lcm_channel_escape("x.y", out, 4));
    TEST_ASSERT_EQUAL_STRING("", out);
    TEST_ASSERT_EQUAL_INT(SVA_OK, sva_lcm_channel_escape("xy", out, 3));
    TEST_ASSERT_EQUAL_INT(SVA_ERR_ARGUMENT, sva_lcm_channel_escape(NULL, out, sizeof out));
}

void test_init_arguments(void)
{
    char prefix[80];
    memset(prefix, 'P', sizeof prefix);
    prefix[SVA_LCM_PREFIX_MAX + 1] = '\0';
    TEST_ASSERT_EQUAL_INT(SVA_ERR_ARGUMENT, sva_lcm_node_init(&node, NULL, prefix, SVA_ALGO_SVA));
    prefix[SVA_LCM_PREFIX_MAX] = '\0';
    TEST_ASSERT_EQUAL_INT(SVA_OK, sva_lcm_node_init(&node, NULL, prefix, SVA_ALGO_SVA));
    TEST_ASSERT_EQUAL_INT(63, strlen(node.channel_mission));
    TEST_ASSERT_EQUAL_INT(SVA_ERR_ARGUMENT, sva_lcm_node_init(&node, NULL, "X", SVA_ALGO_COUNT_));
    TEST_ASSERT_EQUAL_INT(SVA_OK, sva_lcm_node_init(&node, NULL, "X", SVA_ALGO_GA));
    TEST_ASSERT_EQUAL_STRING("XPLAN", node.channel_plan);
    TEST_ASSERT_EQUAL_INT(SVA_ERR_ARGUMENT, sva_lcm_node_subscribe(&node));  // no lcm
}

// The real path: lcm_publish -> memq -> lcm_handle -> raw handler -> plan -> lcm_publish.
static lcm_recv_buf_t memq_plan;
static int memq_plans;
static uint8_t memq_plan_bytes[SVA_LCM_PLAN_BYTES];
static void on_memq_plan(const lcm_recv_buf_t* rbuf, const char* channel, void* user)
{
    (void)channel;
    (void)user;
    memq_plan = *rbuf;
    if (rbuf->data_size == SVA_LCM_PLAN_BYTES) {
        memcpy(memq_plan_bytes, rbuf->data, rbuf->data_size);
    }
    memq_plans++;
}

static void drain(lcm_t* lcm)
{
    for (int i = 0; i < 20; ++i) {
        if (lcm_handle_timeout(lcm, 0) <= 0) {
            break;
        }
    }
}

void test_memq_round_trip(void)
{
    lcm_t* lcm = lcm_create("memq://");
    TEST_ASSERT_NOT_NULL(lcm);
    // a prefix with regex metacharacters: subscriptions must match it exactly
    TEST_ASSERT_EQUAL_INT(SVA_OK, sva_lcm_node_init(&node, lcm, "a.b+", SVA_ALGO_SVA));
    TEST_ASSERT_EQUAL_INT(SVA_OK, sva_lcm_node_subscribe(&node));
    lcm_subscription_t* sub = lcm_subscribe(lcm, "a\\.b\\+PLAN", on_memq_plan, NULL);
    TEST_ASSERT_NOT_NULL(sub);
    memq_plans = 0;
    make_inputs(7);
    const int nf = enc_fleet();
    const int nm = enc_mission();
    TEST_ASSERT_EQUAL_INT(SVA_LCM_FLEET_BYTES, nf);
    TEST_ASSERT_EQUAL_INT(SVA_LCM_MISSION_BYTES, nm);
    // "aXb+FLEET" matches the unescaped regex a.b+FLEET: the node must ignore it
    TEST_ASSERT_EQUAL_INT(0, lcm_publish(lcm, "aXbbFLEET", fleet_buf, (unsigned)nf));
    TEST_ASSERT_EQUAL_INT(0, lcm_publish(lcm, "a.b+FLEET", fleet_buf, (unsigned)nf));
    TEST_ASSERT_EQUAL_INT(0, lcm_publish(lcm, "a.b+MISSION", mission_buf, (unsigned)nm));
    drain(lcm);
    TEST_ASSERT_EQUAL_INT(1, node.counters.fleet_rx);
    TEST_ASSERT_EQUAL_INT(1, node.counters.mission_rx);
    TEST_ASSERT_EQUAL_INT(1, memq_plans);
    TEST_ASSERT_EQUAL_INT(SVA_LCM_PLAN_BYTES,
                          sva_lcm_plan_t_decode(memq_plan_bytes, 0, SVA_LCM_PLAN_BYTES, &got_plan));
    TEST_ASSERT_EQUAL_INT(1, got_plan.plan_id);
    TEST_ASSERT_EQUAL_INT(7, got_plan.fleet_revision);
    TEST_ASSERT_EQUAL_INT(7, got_plan.mission_revision);
    assert_plan_matches_core(&got_plan, SVA_ALGO_SVA);
    TEST_ASSERT_TRUE(got_plan.covered >= 1);
    lcm_unsubscribe(lcm, sub);
    sva_lcm_node_unsubscribe(&node);
    lcm_destroy(lcm);
}

void test_every_algorithm(void)
{
    for (int a = 0; a < (int)SVA_ALGO_COUNT_; ++a) {
        node_setup((sva_algorithm_t)a);
        make_inputs(3);
        TEST_ASSERT_EQUAL_INT(SVA_LCM_ACCEPTED,
                              sva_lcm_on_fleet(&node, fleet_buf, (size_t)enc_fleet()));
        TEST_ASSERT_EQUAL_INT(0, plans_seen);  // no mission yet
        TEST_ASSERT_EQUAL_INT(SVA_LCM_ACCEPTED,
                              sva_lcm_on_mission(&node, mission_buf, (size_t)enc_mission()));
        TEST_ASSERT_EQUAL_INT(1, plans_seen);
        decode_last_plan();
        assert_plan_matches_core(&got_plan, (sva_algorithm_t)a);
    }
}

// A flow plan over LCM carries its certificate, and only a plan that delivers
// routes does (the node's wire plan is reused: a rejected or too large plan after a flow
// plan must not inherit its bound).
void test_flow_certificate(void)
{
    node_setup(SVA_ALGO_FLOW);
    make_inputs(50);
    TEST_ASSERT_EQUAL_INT(SVA_LCM_ACCEPTED,
                          sva_lcm_on_fleet(&node, fleet_buf, (size_t)enc_fleet()));
    TEST_ASSERT_EQUAL_INT(SVA_LCM_ACCEPTED,
                          sva_lcm_on_mission(&node, mission_buf, (size_t)enc_mission()));
    decode_last_plan();
    assert_plan_matches_core(&got_plan, SVA_ALGO_FLOW);
    // 6 targets, 5 UAVs: flow's search finishes and proves its plan optimal.
    TEST_ASSERT_EQUAL_INT(1, got_plan.has_bound);
    TEST_ASSERT_EQUAL_INT(1, got_plan.optimal);
    TEST_ASSERT_TRUE(got_plan.lower_bound > 0);
    TEST_ASSERT_EQUAL_INT(got_plan.cost, got_plan.lower_bound);

    // the core rejects the next mission: the REJECTED plan has no certificate
    mission.targets[3].id = mission.targets[1].id;
    TEST_ASSERT_EQUAL_INT(SVA_LCM_ACCEPTED,
                          sva_lcm_on_mission(&node, mission_buf, (size_t)enc_mission()));
    decode_last_plan();
    TEST_ASSERT_EQUAL_INT(SVA_LCM_PLAN_T_STATUS_REJECTED, got_plan.status);
    TEST_ASSERT_EQUAL_INT(0, got_plan.has_bound);
    TEST_ASSERT_EQUAL_INT(0, got_plan.lower_bound);
    TEST_ASSERT_EQUAL_INT(0, got_plan.optimal);
    TEST_ASSERT_EQUAL_INT(0, got_plan.flow_incomplete);

    // 64 UAVs and 40 targets needing 13 each: 520 copies, above SVA_FLOW_MAX_COPIES
    // (512), so flow has no relaxation (flow_incomplete 4, lower_bound 0).
    make_inputs(51);
    full_fleet_at_depot();
    mission.target_count = 40;
    for (int i = 0; i < 40; ++i) {
        mission.targets[i] = (sva_lcm_target_t){i + 1, i % 7, i % 5, 20 * i + 10, 20 * i + 15, 13};
    }
    TEST_ASSERT_TRUE(13 * 40 > SVA_FLOW_MAX_COPIES);
    TEST_ASSERT_EQUAL_INT(SVA_LCM_ACCEPTED,
                          sva_lcm_on_fleet(&node, fleet_buf, (size_t)enc_fleet()));
    TEST_ASSERT_EQUAL_INT(SVA_LCM_ACCEPTED,
                          sva_lcm_on_mission(&node, mission_buf, (size_t)enc_mission()));
    decode_last_plan();
    assert_plan_matches_core(&got_plan, SVA_ALGO_FLOW);
    TEST_ASSERT_EQUAL_INT(1, got_plan.has_bound);
    TEST_ASSERT_EQUAL_INT(4, got_plan.flow_incomplete);
    TEST_ASSERT_EQUAL_INT(0, got_plan.optimal);
    TEST_ASSERT_EQUAL_INT(0, got_plan.lower_bound);

    // 65 back-to-back targets at the depot needing all 64 UAVs: 4160 route items, more
    // than MAX_ROUTE_ITEMS. The core's plan has a bound; the TOO_LARGE plan carries none.
    make_inputs(52);
    full_fleet_at_depot();
    mission.target_count = 65;
    for (int i = 0; i < 65; ++i) {
        mission.targets[i] = (sva_lcm_target_t){i + 1, 0, 0, 10 * i + 1, 10 * i + 5, SVA_MAX_UAVS};
    }
    TEST_ASSERT_EQUAL_INT(SVA_LCM_ACCEPTED,
                          sva_lcm_on_fleet(&node, fleet_buf, (size_t)enc_fleet()));
    TEST_ASSERT_EQUAL_INT(SVA_LCM_ACCEPTED,
                          sva_lcm_on_mission(&node, mission_buf, (size_t)enc_mission()));
    decode_last_plan();
    TEST_ASSERT_EQUAL_INT(SVA_LCM_PLAN_T_STATUS_TOO_LARGE, got_plan.status);
    TEST_ASSERT_TRUE(node.priv.plan.stats.has_bound);
    TEST_ASSERT_EQUAL_INT(0, got_plan.has_bound);
    TEST_ASSERT_EQUAL_INT(0, got_plan.lower_bound);
    TEST_ASSERT_EQUAL_INT(0, got_plan.optimal);
    TEST_ASSERT_EQUAL_INT(0, got_plan.flow_incomplete);
}

void test_unchanged_and_replan(void)
{
    node_setup(SVA_ALGO_SVA);
    make_inputs(1);
    TEST_ASSERT_EQUAL_INT(SVA_LCM_ACCEPTED,
                          sva_lcm_on_mission(&node, mission_buf, (size_t)enc_mission()));
    TEST_ASSERT_EQUAL_INT(SVA_LCM_ACCEPTED,
                          sva_lcm_on_fleet(&node, fleet_buf, (size_t)enc_fleet()));
    TEST_ASSERT_EQUAL_INT(1, plans_seen);
    TEST_ASSERT_EQUAL_INT(SVA_LCM_UNCHANGED,
                          sva_lcm_on_fleet(&node, fleet_buf, (size_t)enc_fleet()));
    TEST_ASSERT_EQUAL_INT(SVA_LCM_UNCHANGED,
                          sva_lcm_on_mission(&node, mission_buf, (size_t)enc_mission()));
    TEST_ASSERT_EQUAL_INT(2, node.counters.unchanged);
    TEST_ASSERT_EQUAL_INT(1, plans_seen);
    // same revision, different content: still a change
    fleet.uavs[0].fuel = 199;
    TEST_ASSERT_EQUAL_INT(SVA_LCM_ACCEPTED,
                          sva_lcm_on_fleet(&node, fleet_buf, (size_t)enc_fleet()));
    TEST_ASSERT_EQUAL_INT(2, plans_seen);
    decode_last_plan();
    TEST_ASSERT_EQUAL_INT(2, got_plan.plan_id);
    assert_plan_matches_core(&got_plan, SVA_ALGO_SVA);
}

void test_unavailable_uav_gets_nothing(void)
{
    node_setup(SVA_ALGO_SVA);
    make_inputs(2);
    for (int i = 1; i < 5; ++i) {
        fleet.uavs[i].health = SVA_LCM_UAV_STATE_T_HEALTH_UNAVAILABLE;
    }
    TEST_ASSERT_EQUAL_INT(SVA_LCM_ACCEPTED,
                          sva_lcm_on_fleet(&node, fleet_buf, (size_t)enc_fleet()));
    TEST_ASSERT_EQUAL_INT(SVA_LCM_ACCEPTED,
                          sva_lcm_on_mission(&node, mission_buf, (size_t)enc_mission()));
    decode_last_plan();
    TEST_ASSERT_EQUAL_INT(5, got_plan.route_count);
    TEST_ASSERT_TRUE(got_plan.routes[0].target_count >= 1);
    for (int i = 1; i < 5; ++i) {
        TEST_ASSERT_EQUAL_INT(10 + i, got_plan.routes[i].uav_id);
        TEST_ASSERT_EQUAL_INT(0, got_plan.routes[i].target_count);
    }
}

// Sends bytes of a kind and checks the verdict, the reason, the counter and that the
// node's inputs and plan count did not move.
static void expect_reject(bool is_fleet, const uint8_t* data, size_t size, sva_lcm_reject_t why)
{
    const uint32_t before = node.counters.rejected[why];
    const int plans = plans_seen;
    const int64_t fr = node.priv.fleet_revision;
    const int64_t mr = node.priv.mission_revision;
    const sva_lcm_status_t v =
        is_fleet ? sva_lcm_on_fleet(&node, data, size) : sva_lcm_on_mission(&node, data, size);
    TEST_ASSERT_EQUAL_INT(SVA_LCM_REJECTED, v);
    TEST_ASSERT_EQUAL_INT(why, node.last_reject);
    TEST_ASSERT_EQUAL_INT(before + 1U, node.counters.rejected[why]);
    TEST_ASSERT_EQUAL_INT(plans, plans_seen);
    TEST_ASSERT_EQUAL_INT(fr, node.priv.fleet_revision);
    TEST_ASSERT_EQUAL_INT(mr, node.priv.mission_revision);
}

void test_rejections_frame(void)
{
    node_setup(SVA_ALGO_SVA);
    make_inputs(5);
    TEST_ASSERT_EQUAL_INT(SVA_LCM_ACCEPTED,
                          sva_lcm_on_fleet(&node, fleet_buf, (size_t)enc_fleet()));
    TEST_ASSERT_EQUAL_INT(SVA_LCM_ACCEPTED,
                          sva_lcm_on_mission(&node, mission_buf, (size_t)enc_mission()));
    fleet.revision = 6;
    mission.revision = 6;
    const size_t nf = (size_t)enc_fleet();
    const size_t nm = (size_t)enc_mission();
    expect_reject(true, fleet_buf, nf - 1U, SVA_LCM_REJECT_TRUNCATED);
    expect_reject(true, fleet_buf, 0, SVA_LCM_REJECT_TRUNCATED);
    expect_reject(true, fleet_buf, 7, SVA_LCM_REJECT_TRUNCATED);
    expect_reject(true, NULL, 0, SVA_LCM_REJECT_TRUNCATED);
    expect_reject(false, mission_buf, nm - 100U, SVA_LCM_REJECT_TRUNCATED);
    expect_reject(true, fleet_buf, nf + 1U, SVA_LCM_REJECT_TRAILING);
    expect_reject(false, mission_buf, nm + 8U, SVA_LCM_REJECT_TRAILING);
    // a mission on the fleet channel: wrong size; a fleet-sized mission: wrong fingerprint
    expect_reject(true, mission_buf, nm, SVA_LCM_REJECT_TRAILING);
    fleet_buf[7] ^= 0x01U;
    expect_reject(true, fleet_buf, nf, SVA_LCM_REJECT_FINGERPRINT);
    fleet_buf[7] ^= 0x01U;
    mission_buf[0] ^= 0x80U;
    expect_reject(false, mission_buf, nm, SVA_LCM_REJECT_FINGERPRINT);
    TEST_ASSERT_EQUAL_INT(1, log_lines[SVA_LCM_REJECT_TRUNCATED]);  // logged once per reason
    TEST_ASSERT_EQUAL_INT(1, log_lines[SVA_LCM_REJECT_TRAILING]);
    TEST_ASSERT_EQUAL_INT(1, log_lines[SVA_LCM_REJECT_FINGERPRINT]);
    TEST_ASSERT_EQUAL_INT(5, node.counters.rejected[SVA_LCM_REJECT_TRUNCATED]);
}

void test_rejections_counts_and_values(void)
{
    node_setup(SVA_ALGO_SVA);
    make_inputs(5);
    TEST_ASSERT_EQUAL_INT(SVA_LCM_ACCEPTED,
                          sva_lcm_on_fleet(&node, fleet_buf, (size_t)enc_fleet()));
    TEST_ASSERT_EQUAL_INT(SVA_LCM_ACCEPTED,
                          sva_lcm_on_mission(&node, mission_buf, (size_t)enc_mission()));

    static const int16_t bad_counts[] = {SVA_MAX_UAVS + 1, -1, INT16_MAX, INT16_MIN};
    for (size_t i = 0; i < sizeof bad_counts / sizeof bad_counts[0]; ++i) {
        make_inputs(9);
        fleet.uav_count = bad_counts[i];
        expect_reject(true, fleet_buf, (size_t)enc_fleet(), SVA_LCM_REJECT_COUNT);
        TEST_ASSERT_EQUAL_INT(SVA_FIELD_UAVS, node.last_diag.field);
        TEST_ASSERT_EQUAL_STRING("SVA_MAX_UAVS", node.last_diag.limit_name);
        make_inputs(9);
        mission.target_count =
            (int16_t)(bad_counts[i] == SVA_MAX_UAVS + 1 ? SVA_MAX_TARGETS + 1 : bad_counts[i]);
        expect_reject(false, mission_buf, (size_t)enc_mission(), SVA_LCM_REJECT_COUNT);
        TEST_ASSERT_EQUAL_INT(SVA_FIELD_TARGETS, node.last_diag.field);
    }
    // exactly the bound is accepted
    make_inputs(10);
    fleet.uav_count = SVA_MAX_UAVS;
    for (int i = 0; i < SVA_MAX_UAVS; ++i) {
        fleet.uavs[i].id = i + 1;
        fleet.uavs[i].fuel = 50;
    }
    TEST_ASSERT_EQUAL_INT(SVA_LCM_ACCEPTED,
                          sva_lcm_on_fleet(&node, fleet_buf, (size_t)enc_fleet()));

    struct {
        int which;  // 0 fleet, 1 mission
        int idx;
        sva_field_t field;
        int64_t value;
    } cases[] = {
        {0, 2, SVA_FIELD_UAV_X, 32768},
        {0, 0, SVA_FIELD_UAV_Y, -32769},
        {0, 4, SVA_FIELD_UAV_FUEL, -1},
        {0, 1, SVA_FIELD_UAV_ID, 0},
        {0, 3, SVA_FIELD_UAV_READY_AT, -5},
        {1, -1, SVA_FIELD_TICKS_PER_CELL, 0},
        {1, -1, SVA_FIELD_OVERLAP_PERCENT, 101},
        {1, -1, SVA_FIELD_HOVER_FUEL, -1},
        {1, -1, SVA_FIELD_DEPOT_X, 40000},
        {1, 5, SVA_FIELD_TARGET_NEED, 0},
        {1, 5, SVA_FIELD_TARGET_NEED, SVA_MAX_UAVS + 1},
        {1, 2, SVA_FIELD_TARGET_START, -1},
        {1, 0, SVA_FIELD_TARGET_END, SVA_MAX_TICK + 1},
        {1, 3, SVA_FIELD_TARGET_ID, -7},
    };
    for (size_t c = 0; c < sizeof cases / sizeof cases[0]; ++c) {
        make_inputs(11);
        const int32_t v = (int32_t)cases[c].value;
        const int i = cases[c].idx;
        switch (cases[c].field) {
        case SVA_FIELD_UAV_X:
            fleet.uavs[i].x = v;
            break;
        case SVA_FIELD_UAV_Y:
            fleet.uavs[i].y = v;
            break;
        case SVA_FIELD_UAV_FUEL:
            fleet.uavs[i].fuel = v;
            break;
        case SVA_FIELD_UAV_ID:
            fleet.uavs[i].id = v;
            break;
        case SVA_FIELD_UAV_READY_AT:
            fleet.uavs[i].ready_at_ticks = v;
            break;
        case SVA_FIELD_TICKS_PER_CELL:
            mission.ticks_per_cell = v;
            break;
        case SVA_FIELD_OVERLAP_PERCENT:
            mission.overlap_percent = v;
            break;
        case SVA_FIELD_HOVER_FUEL:
            mission.hover_fuel = v;
            break;
        case SVA_FIELD_DEPOT_X:
            mission.depot_x = v;
            break;
        case SVA_FIELD_TARGET_NEED:
            mission.targets[i].need = v;
            break;
        case SVA_FIELD_TARGET_START:
            mission.targets[i].start_ticks = v;
            break;
        case SVA_FIELD_TARGET_END:
            mission.targets[i].end_ticks = v;
            break;
        case SVA_FIELD_TARGET_ID:
            mission.targets[i].id = v;
            break;
        default:
            TEST_FAIL();
        }
        if (cases[c].which == 0) {
            expect_reject(true, fleet_buf, (size_t)enc_fleet(), SVA_LCM_REJECT_VALUE);
        } else {
            expect_reject(false, mission_buf, (size_t)enc_mission(), SVA_LCM_REJECT_VALUE);
        }
        TEST_ASSERT_EQUAL_INT(cases[c].field, node.last_diag.field);
        TEST_ASSERT_EQUAL_INT(i, node.last_diag.index);
        TEST_ASSERT_EQUAL_INT(cases[c].value, node.last_diag.value);
    }
    make_inputs(12);
    fleet.uavs[2].health = 7;
    expect_reject(true, fleet_buf, (size_t)enc_fleet(), SVA_LCM_REJECT_VALUE);
    TEST_ASSERT_EQUAL_INT(1, log_lines[SVA_LCM_REJECT_COUNT]);
    TEST_ASSERT_EQUAL_INT(1, log_lines[SVA_LCM_REJECT_VALUE]);
}

void test_core_rejection_and_planner_limit(void)
{
    node_setup(SVA_ALGO_SVA);
    make_inputs(20);
    mission.targets[3].id = mission.targets[1].id;  // duplicate: only the core sees it
    TEST_ASSERT_EQUAL_INT(SVA_LCM_ACCEPTED,
                          sva_lcm_on_fleet(&node, fleet_buf, (size_t)enc_fleet()));
    TEST_ASSERT_EQUAL_INT(SVA_LCM_ACCEPTED,
                          sva_lcm_on_mission(&node, mission_buf, (size_t)enc_mission()));
    TEST_ASSERT_EQUAL_INT(1, node.counters.rejected[SVA_LCM_REJECT_INVALID]);
    TEST_ASSERT_EQUAL_INT(1, plans_seen);
    decode_last_plan();
    TEST_ASSERT_EQUAL_INT(SVA_LCM_PLAN_T_STATUS_REJECTED, got_plan.status);
    TEST_ASSERT_EQUAL_INT(SVA_ERR_INVALID, got_plan.error_code);
    TEST_ASSERT_EQUAL_INT(SVA_FIELD_TARGET_ID, got_plan.diag_field);
    TEST_ASSERT_EQUAL_INT(SVA_RULE_DUPLICATE, got_plan.diag_rule);
    TEST_ASSERT_EQUAL_INT(3, got_plan.diag_index);
    TEST_ASSERT_EQUAL_INT(0, got_plan.route_count);
    TEST_ASSERT_EQUAL_INT(1, log_lines[SVA_LCM_REJECT_INVALID]);
    // window end before start: the core's rule too
    make_inputs(21);
    mission.targets[2].end_ticks = mission.targets[2].start_ticks;
    TEST_ASSERT_EQUAL_INT(SVA_LCM_ACCEPTED,
                          sva_lcm_on_mission(&node, mission_buf, (size_t)enc_mission()));
    decode_last_plan();
    TEST_ASSERT_EQUAL_INT(SVA_LCM_PLAN_T_STATUS_REJECTED, got_plan.status);
    TEST_ASSERT_EQUAL_INT(SVA_RULE_AFTER, got_plan.diag_rule);

    // bfa refuses more than SVA_BFA_MAX_TARGETS targets: STATUS_FAILED
    node_setup(SVA_ALGO_BFA);
    make_inputs(22);
    mission.target_count = SVA_BFA_MAX_TARGETS + 1;
    for (int i = 0; i < mission.target_count; ++i) {
        mission.targets[i] = (sva_lcm_target_t){i + 1, i, 1, 100 * i + 10, 100 * i + 20, 1};
    }
    TEST_ASSERT_EQUAL_INT(SVA_LCM_ACCEPTED,
                          sva_lcm_on_fleet(&node, fleet_buf, (size_t)enc_fleet()));
    TEST_ASSERT_EQUAL_INT(SVA_LCM_ACCEPTED,
                          sva_lcm_on_mission(&node, mission_buf, (size_t)enc_mission()));
    decode_last_plan();
    TEST_ASSERT_EQUAL_INT(SVA_LCM_PLAN_T_STATUS_FAILED, got_plan.status);
    TEST_ASSERT_EQUAL_INT(SVA_ERR_LIMIT, got_plan.error_code);
    TEST_ASSERT_EQUAL_INT(1, node.counters.rejected[SVA_LCM_REJECT_PLANNER]);
}

void test_plan_too_large(void)
{
    node_setup(SVA_ALGO_GA);
    make_inputs(30);
    // 64 UAVs at the depot serve 256 back-to-back targets there, 17 each: 4352 items.
    full_fleet_at_depot();
    mission.target_count = SVA_MAX_TARGETS;
    for (int i = 0; i < SVA_MAX_TARGETS; ++i) {
        mission.targets[i] = (sva_lcm_target_t){i + 1, 0, 0, 10 * i + 1, 10 * i + 5, 17};
    }
    TEST_ASSERT_EQUAL_INT(SVA_LCM_ACCEPTED,
                          sva_lcm_on_fleet(&node, fleet_buf, (size_t)enc_fleet()));
    TEST_ASSERT_EQUAL_INT(SVA_LCM_ACCEPTED,
                          sva_lcm_on_mission(&node, mission_buf, (size_t)enc_mission()));
    decode_last_plan();
    TEST_ASSERT_EQUAL_INT(SVA_LCM_PLAN_T_STATUS_TOO_LARGE, got_plan.status);
    TEST_ASSERT_EQUAL_INT(0, got_plan.route_count);
    TEST_ASSERT_EQUAL_INT(0, got_plan.item_count);
    TEST_ASSERT_EQUAL_INT(1, node.counters.rejected[SVA_LCM_REJECT_TOO_LARGE]);
    // 15 each (3840 items) fits
    for (int i = 0; i < SVA_MAX_TARGETS; ++i) {
        mission.targets[i].need = 15;
    }
    TEST_ASSERT_EQUAL_INT(SVA_LCM_ACCEPTED,
                          sva_lcm_on_mission(&node, mission_buf, (size_t)enc_mission()));
    decode_last_plan();
    TEST_ASSERT_EQUAL_INT(SVA_LCM_PLAN_T_STATUS_COMPLETE, got_plan.status);
    TEST_ASSERT_EQUAL_INT(15 * SVA_MAX_TARGETS, got_plan.item_count);
    assert_plan_matches_core(&got_plan, SVA_ALGO_GA);
}

void test_status(void)
{
    node_setup(SVA_ALGO_HGA);
    make_inputs(40);
    static sva_lcm_node_status_t s;
    TEST_ASSERT_EQUAL_INT(SVA_OK, sva_lcm_publish_status(&node, 123));
    TEST_ASSERT_EQUAL_INT(1, status_seen);
    TEST_ASSERT_EQUAL_INT(SVA_LCM_REJECTED, sva_lcm_on_fleet(&node, fleet_buf, 3));
    TEST_ASSERT_EQUAL_INT(SVA_LCM_ACCEPTED,
                          sva_lcm_on_fleet(&node, fleet_buf, (size_t)enc_fleet()));
    TEST_ASSERT_EQUAL_INT(SVA_LCM_ACCEPTED,
                          sva_lcm_on_mission(&node, mission_buf, (size_t)enc_mission()));
    TEST_ASSERT_EQUAL_INT(SVA_OK, sva_lcm_publish_status(&node, 456));
    TEST_ASSERT_EQUAL_INT(
        SVA_LCM_STATUS_BYTES,
        sva_lcm_node_status_t_decode(node.priv.status_buf, 0, SVA_LCM_STATUS_BYTES, &s));
    TEST_ASSERT_EQUAL_INT(456, s.utime);
    TEST_ASSERT_EQUAL_INT(2, s.seq);
    TEST_ASSERT_EQUAL_INT(SVA_LCM_NODE_STATUS_T_STATE_READY, s.state);
    TEST_ASSERT_EQUAL_INT(SVA_ALGO_HGA, s.algorithm);
    TEST_ASSERT_EQUAL_INT(40, s.fleet_revision);
    TEST_ASSERT_EQUAL_INT(1, s.last_plan_id);
    TEST_ASSERT_EQUAL_INT(2, s.fleet_rx);
    TEST_ASSERT_EQUAL_INT(1, s.plans_published);
    TEST_ASSERT_EQUAL_INT(1, s.rejected[SVA_LCM_REJECT_TRUNCATED]);
}

// The port's goal: zero heap allocations per message in steady state, accepted or not,
// planning and publishing included.
static int send_event(const sva_lcm_event_t* e)
{
    static uint8_t buf[SVA_LCM_EVENT_BYTES];
    TEST_ASSERT_EQUAL_INT(SVA_LCM_EVENT_BYTES, sva_lcm_event_t_encode(buf, 0, (int)sizeof buf, e));
    return (int)sva_lcm_on_event(&node, buf, sizeof buf);
}

static const char* replan_text(void)
{
    static char text[SVA_LCM_REPLAN_T_DIAG_TEXT_SIZE + 1];
    for (int i = 0; i < SVA_LCM_REPLAN_T_DIAG_TEXT_SIZE; ++i) {
        text[i] = (char)got_replan.diag_text[i];
    }
    text[SVA_LCM_REPLAN_T_DIAG_TEXT_SIZE] = '\0';
    return text;
}

// Events: refused before a mission; a plan starts the live mission; a version, a type
// and the core's verdict refused with the live state byte for byte unchanged; a loss
// applied and replanned as sva_live_replan does on the same live mission.
void test_live_events(void)
{
    node_setup(SVA_ALGO_SVA);
    static sva_lcm_event_t e;
    memset(&e, 0, sizeof e);
    e.version = SVA_LCM_EVENT_T_VERSION;
    e.seq = 7;
    e.type = SVA_LCM_EVENT_T_TYPE_CLOCK;
    e.at_ticks = 1;
    TEST_ASSERT_EQUAL_INT(SVA_LCM_REJECTED, send_event(&e));
    TEST_ASSERT_EQUAL_INT(1, replans_seen);
    TEST_ASSERT_EQUAL_INT(0, got_replan.accepted);
    TEST_ASSERT_EQUAL_INT(7, got_replan.event_seq);
    TEST_ASSERT_EQUAL_STRING(
        "T_EVENT: no live mission: a fleet and a mission must be planned first", replan_text());

    make_inputs(3);
    TEST_ASSERT_EQUAL_INT(SVA_LCM_ACCEPTED,
                          sva_lcm_on_fleet(&node, fleet_buf, (size_t)enc_fleet()));
    TEST_ASSERT_EQUAL_INT(SVA_LCM_ACCEPTED,
                          sva_lcm_on_mission(&node, mission_buf, (size_t)enc_mission()));
    static sva_live_t before;
    before = node.priv.live;

    e.seq = 8;
    e.version = 2;
    TEST_ASSERT_EQUAL_INT(SVA_LCM_REJECTED, send_event(&e));
    TEST_ASSERT_EQUAL_STRING("T_EVENT: event_t.version is 2, this node speaks version 1",
                             replan_text());
    e.version = SVA_LCM_EVENT_T_VERSION;
    e.type = 9;
    TEST_ASSERT_EQUAL_INT(SVA_LCM_REJECTED, send_event(&e));
    TEST_ASSERT_EQUAL_INT((int)SVA_FIELD_EVENT_TYPE, got_replan.diag_field);
    e.type = SVA_LCM_EVENT_T_TYPE_UAV_LOST;
    e.uav_id = 99;
    TEST_ASSERT_EQUAL_INT(SVA_LCM_REJECTED, send_event(&e));
    TEST_ASSERT_EQUAL_INT(0, got_replan.accepted);
    TEST_ASSERT_EQUAL_INT(SVA_LCM_PLAN_T_STATUS_REJECTED, got_replan.plan.status);
    TEST_ASSERT_EQUAL_INT((int)SVA_FIELD_EVENT_UAV, got_replan.diag_field);
    TEST_ASSERT_EQUAL_INT((int)SVA_RULE_UNKNOWN, got_replan.diag_rule);
    TEST_ASSERT_EQUAL_INT(99, got_replan.diag_value);
    TEST_ASSERT_EQUAL_MEMORY(&before, &node.priv.live, sizeof before);
    TEST_ASSERT_EQUAL_INT(2, node.counters.rejected[SVA_LCM_REJECT_VALUE]);
    TEST_ASSERT_EQUAL_INT(1, node.counters.rejected[SVA_LCM_REJECT_VERSION]);
    TEST_ASSERT_EQUAL_INT(1, node.counters.rejected[SVA_LCM_REJECT_INVALID]);

    // A loss at tick 11: the same event on a copy of the live mission, replanned by
    // the core directly, gives the plan the node published.
    e.seq = 9;
    e.uav_id = 10;
    e.at_ticks = 11;
    static sva_live_t mirror;
    mirror = before;
    const sva_event_t ev = {.type = SVA_EVENT_UAV_LOST, .at_ticks = 11, .uav_id = 10};
    TEST_ASSERT_EQUAL_INT(SVA_OK, sva_live_apply(&mirror, &ev, NULL));
    sva_live_result_t res;
    TEST_ASSERT_EQUAL_INT(SVA_OK, sva_planner_init(&planner));
    TEST_ASSERT_EQUAL_INT(SVA_OK, sva_live_replan(&mirror, &planner, SVA_ALGO_SVA, &res, NULL));
    TEST_ASSERT_EQUAL_INT(SVA_LCM_ACCEPTED, send_event(&e));
    TEST_ASSERT_EQUAL_INT(1, got_replan.accepted);
    TEST_ASSERT_EQUAL_INT(9, got_replan.event_seq);
    TEST_ASSERT_EQUAL_INT(11, got_replan.now_ticks);
    TEST_ASSERT_EQUAL_INT((int64_t)res.revision, got_replan.revision);
    TEST_ASSERT_EQUAL_INT(res.kept ? 1 : 0, got_replan.kept);
    TEST_ASSERT_EQUAL_INT((int32_t)res.dropped, got_replan.dropped);
    TEST_ASSERT_EQUAL_INT((int32_t)res.added, got_replan.added);
    TEST_ASSERT_EQUAL_INT((int16_t)res.dropped, got_replan.dropped_listed);
    TEST_ASSERT_EQUAL_INT((int16_t)res.added, got_replan.added_listed);
    TEST_ASSERT_EQUAL_INT(res.objective, got_replan.objective);
    TEST_ASSERT_EQUAL_INT((int16_t)res.residual->uav_count, got_replan.residual_fleet.uav_count);
    TEST_ASSERT_EQUAL_INT((int16_t)res.residual->target_count,
                          got_replan.residual_mission.target_count);
    for (int u = 0; u < got_replan.residual_fleet.uav_count; ++u) {
        TEST_ASSERT_NOT_EQUAL_INT(10, got_replan.residual_fleet.uavs[u].id);  // lost
    }
    TEST_ASSERT_EQUAL_INT(res.plan->cost, got_replan.plan.cost);
    TEST_ASSERT_EQUAL_INT((int16_t)res.plan->covered, got_replan.plan.covered);
    TEST_ASSERT_EQUAL_INT((int16_t)res.plan->route_count, got_replan.plan.route_count);
    TEST_ASSERT_EQUAL_INT(2, got_replan.plan.plan_id);  // after the mission's plan
    TEST_ASSERT_EQUAL_INT(5, node.counters.replans_published);
    // every message of the replan names its version; the mission had no frame
    TEST_ASSERT_EQUAL_INT(SVA_LCM_REPLAN_T_VERSION, got_replan.version);
    TEST_ASSERT_EQUAL_INT(SVA_LCM_FLEET_STATE_T_VERSION, got_replan.residual_fleet.version);
    TEST_ASSERT_EQUAL_INT(SVA_LCM_MISSION_T_VERSION, got_replan.residual_mission.version);
    TEST_ASSERT_EQUAL_INT(SVA_LCM_PLAN_T_VERSION, got_replan.plan.version);
    TEST_ASSERT_EQUAL_INT(0, got_replan.residual_mission.frame.present);
}

// Versions: a fleet or a mission of another version is refused (REJECT_VERSION, one log
// line naming both versions) and changes nothing; plans and status carry theirs.
void test_versions(void)
{
    node_setup(SVA_ALGO_SVA);
    make_inputs(5);
    TEST_ASSERT_EQUAL_INT(SVA_LCM_ACCEPTED,
                          sva_lcm_on_fleet(&node, fleet_buf, (size_t)enc_fleet()));
    TEST_ASSERT_EQUAL_INT(SVA_LCM_ACCEPTED,
                          sva_lcm_on_mission(&node, mission_buf, (size_t)enc_mission()));
    decode_last_plan();
    TEST_ASSERT_EQUAL_INT(SVA_LCM_PLAN_T_VERSION, got_plan.version);
    make_inputs(6);
    fleet.version = 1;
    expect_reject(true, fleet_buf, (size_t)enc_fleet(), SVA_LCM_REJECT_VERSION);
    TEST_ASSERT_EQUAL_STRING("rejected (version; further ones only counted in T_STATUS): T_FLEET: "
                             "fleet_state_t.version is 1, this node speaks version 2",
                             last_log);
    mission.version = 3;
    expect_reject(false, mission_buf, (size_t)enc_mission(), SVA_LCM_REJECT_VERSION);
    TEST_ASSERT_EQUAL_INT(1, log_lines[SVA_LCM_REJECT_VERSION]);  // logged once
    TEST_ASSERT_EQUAL_INT(2, node.counters.rejected[SVA_LCM_REJECT_VERSION]);
    static sva_lcm_node_status_t s;
    TEST_ASSERT_EQUAL_INT(SVA_OK, sva_lcm_publish_status(&node, 1));
    TEST_ASSERT_EQUAL_INT(
        SVA_LCM_STATUS_BYTES,
        sva_lcm_node_status_t_decode(node.priv.status_buf, 0, SVA_LCM_STATUS_BYTES, &s));
    TEST_ASSERT_EQUAL_INT(SVA_LCM_NODE_STATUS_T_VERSION, s.version);
    TEST_ASSERT_EQUAL_INT(2, s.rejected[SVA_LCM_NODE_STATUS_T_REJECT_VERSION]);
    TEST_ASSERT_EQUAL_STRING("version", sva_lcm_reject_name(SVA_LCM_REJECT_VERSION));
}

static void set_frame(void)
{
    mission.frame.present = 1;
    mission.frame.lat_e7 = 473977419;  // 47.3977419
    mission.frame.lon_e7 = 85455939;   // 8.5455939
    mission.frame.alt_cm = 3000;
    mission.frame.cell_cm = 1000;
    mission.frame.tick_ms = 1000;
    mission.frame.t0_ms = 1780300800000LL;  // 2026-06-01T08:00:00Z
}

// The frame: checked by sva_frame_check (REJECT_VALUE with its message), kept by the
// node and carried by the residual mission of every replan.
void test_frame_round_trip(void)
{
    node_setup(SVA_ALGO_SVA);
    make_inputs(5);
    TEST_ASSERT_EQUAL_INT(SVA_LCM_ACCEPTED,
                          sva_lcm_on_fleet(&node, fleet_buf, (size_t)enc_fleet()));

    make_inputs(6);
    set_frame();
    mission.frame.cell_cm = 5;
    expect_reject(false, mission_buf, (size_t)enc_mission(), SVA_LCM_REJECT_VALUE);
    TEST_ASSERT_EQUAL_STRING("rejected (value; further ones only counted in T_STATUS): T_MISSION: "
                             "frame.cell_m: must be >= 0.1, got 0.05",
                             last_log);
    set_frame();
    mission.frame.lat_e7 = 850000001;
    expect_reject(false, mission_buf, (size_t)enc_mission(), SVA_LCM_REJECT_VALUE);
    set_frame();
    mission.frame.t0_ms = -1;
    expect_reject(false, mission_buf, (size_t)enc_mission(), SVA_LCM_REJECT_VALUE);
    set_frame();
    mission.frame.present = 2;
    expect_reject(false, mission_buf, (size_t)enc_mission(), SVA_LCM_REJECT_VALUE);
    memset(&mission.frame, 0, sizeof mission.frame);
    mission.frame.tick_ms = 1000;  // present 0 with a field set
    expect_reject(false, mission_buf, (size_t)enc_mission(), SVA_LCM_REJECT_VALUE);
    TEST_ASSERT_EQUAL_INT(5, node.counters.rejected[SVA_LCM_REJECT_VALUE]);

    set_frame();
    TEST_ASSERT_EQUAL_INT(SVA_LCM_ACCEPTED,
                          sva_lcm_on_mission(&node, mission_buf, (size_t)enc_mission()));
    TEST_ASSERT_EQUAL_INT(1, plans_seen);
    static sva_lcm_event_t e;
    memset(&e, 0, sizeof e);
    e.version = SVA_LCM_EVENT_T_VERSION;
    e.seq = 1;
    e.type = SVA_LCM_EVENT_T_TYPE_CLOCK;
    e.at_ticks = 2;
    TEST_ASSERT_EQUAL_INT(SVA_LCM_ACCEPTED, send_event(&e));
    TEST_ASSERT_EQUAL_INT(1, got_replan.accepted);
    TEST_ASSERT_EQUAL_MEMORY(&mission.frame, &got_replan.residual_mission.frame,
                             sizeof mission.frame);
    // the same mission without its frame is a change: it replans
    memset(&mission.frame, 0, sizeof mission.frame);
    TEST_ASSERT_EQUAL_INT(SVA_LCM_ACCEPTED,
                          sva_lcm_on_mission(&node, mission_buf, (size_t)enc_mission()));
    TEST_ASSERT_EQUAL_INT(2, plans_seen);
    TEST_ASSERT_EQUAL_INT(SVA_LCM_ACCEPTED, send_event(&e));
    TEST_ASSERT_EQUAL_INT(0, got_replan.residual_mission.frame.present);
}

// fleet_reports: while a live mission runs, a fleet message is a report through the
// core's rule (sva_live_report). A UAV reported unavailable becomes uav_lost, one whose
// fuel is below its route's need a fuel event, one off its track by more than the
// tolerance a position event, each answered by one replan
// (event_seq -1) and no plan from scratch; a report that contradicts nothing publishes nothing.
void test_fleet_reports(void)
{
    node_setup(SVA_ALGO_SVA);
    node.fleet_reports = true;
    make_inputs(4);
    TEST_ASSERT_EQUAL_INT(SVA_LCM_ACCEPTED,
                          sva_lcm_on_fleet(&node, fleet_buf, (size_t)enc_fleet()));
    TEST_ASSERT_EQUAL_INT(SVA_LCM_ACCEPTED,
                          sva_lcm_on_mission(&node, mission_buf, (size_t)enc_mission()));
    TEST_ASSERT_EQUAL_INT(1, plans_seen);
    decode_last_plan();
    int busy = -1;  // a UAV with a route, other than UAV 11
    for (int r = 0; r < got_plan.route_count; ++r) {
        if ((got_plan.routes[r].target_count > 0) && (got_plan.routes[r].uav_id != 11) &&
            (busy < 0)) {
            busy = r;
        }
    }
    TEST_ASSERT_TRUE(busy >= 0);
    const int32_t busy_id = got_plan.routes[busy].uav_id;

    fleet.uavs[1].health = SVA_LCM_UAV_STATE_T_HEALTH_UNAVAILABLE;  // UAV 11
    TEST_ASSERT_EQUAL_INT(SVA_LCM_ACCEPTED,
                          sva_lcm_on_fleet(&node, fleet_buf, (size_t)enc_fleet()));
    TEST_ASSERT_EQUAL_INT(1, plans_seen);
    TEST_ASSERT_EQUAL_INT(1, replans_seen);
    TEST_ASSERT_EQUAL_INT(-1, got_replan.event_seq);
    TEST_ASSERT_EQUAL_INT(SVA_LCM_EVENT_T_TYPE_UAV_LOST, got_replan.event_type);
    TEST_ASSERT_EQUAL_INT(1, got_replan.accepted);
    TEST_ASSERT_EQUAL_INT(1, got_replan.revision);
    TEST_ASSERT_EQUAL_INT(4, got_replan.residual_fleet.uav_count);
    for (int u = 0; u < got_replan.residual_fleet.uav_count; ++u) {
        TEST_ASSERT_NOT_EQUAL_INT(11, got_replan.residual_fleet.uavs[u].id);
    }

    fleet.uavs[busy_id - 10].fuel = 1;  // ids are 10 + index
    TEST_ASSERT_EQUAL_INT(SVA_LCM_ACCEPTED,
                          sva_lcm_on_fleet(&node, fleet_buf, (size_t)enc_fleet()));
    TEST_ASSERT_EQUAL_INT(2, replans_seen);
    TEST_ASSERT_EQUAL_INT(SVA_LCM_EVENT_T_TYPE_FUEL, got_replan.event_type);
    TEST_ASSERT_EQUAL_INT(2, got_replan.revision);
    int found = 0;
    for (int u = 0; u < got_replan.residual_fleet.uav_count; ++u) {
        if (got_replan.residual_fleet.uavs[u].id == busy_id) {
            TEST_ASSERT_EQUAL_INT(1, got_replan.residual_fleet.uavs[u].fuel);
            found = 1;
        }
    }
    TEST_ASSERT_TRUE(found);
    // the same report again: unchanged; more fuel than any route needs: nothing to do
    TEST_ASSERT_EQUAL_INT(SVA_LCM_UNCHANGED,
                          sva_lcm_on_fleet(&node, fleet_buf, (size_t)enc_fleet()));
    fleet.uavs[busy_id - 10].fuel = 200;
    TEST_ASSERT_EQUAL_INT(SVA_LCM_ACCEPTED,
                          sva_lcm_on_fleet(&node, fleet_buf, (size_t)enc_fleet()));
    TEST_ASSERT_EQUAL_INT(2, replans_seen);
    TEST_ASSERT_EQUAL_INT(1, plans_seen);
    TEST_ASSERT_EQUAL_INT(2, node.priv.live.revision);

    // UAV 10 off its track: within the tolerance (2 cells) nothing; 3 cells off, a
    // position event: it flies on from the reported cell with the reported fuel.
    TEST_ASSERT_EQUAL_INT(SVA_LCM_TRACK_TOLERANCE_DEFAULT, node.track_tolerance_cells);
    const int32_t x0 = fleet.uavs[0].x;
    fleet.uavs[0].x = x0 + 1;
    fleet.uavs[0].y += 1;
    TEST_ASSERT_EQUAL_INT(SVA_LCM_ACCEPTED,
                          sva_lcm_on_fleet(&node, fleet_buf, (size_t)enc_fleet()));
    TEST_ASSERT_EQUAL_INT(2, replans_seen);
    fleet.uavs[0].x = x0 + 2;
    fleet.uavs[0].fuel -= 3;
    TEST_ASSERT_EQUAL_INT(SVA_LCM_ACCEPTED,
                          sva_lcm_on_fleet(&node, fleet_buf, (size_t)enc_fleet()));
    TEST_ASSERT_EQUAL_INT(3, replans_seen);
    TEST_ASSERT_EQUAL_INT(SVA_LCM_EVENT_T_TYPE_POSITION, got_replan.event_type);
    TEST_ASSERT_EQUAL_INT(3, got_replan.revision);
    TEST_ASSERT_EQUAL_INT(10, got_replan.residual_fleet.uavs[0].id);
    TEST_ASSERT_EQUAL_INT(x0 + 2, got_replan.residual_fleet.uavs[0].x);
    TEST_ASSERT_EQUAL_INT(fleet.uavs[0].y, got_replan.residual_fleet.uavs[0].y);
    TEST_ASSERT_EQUAL_INT(fleet.uavs[0].fuel, got_replan.residual_fleet.uavs[0].fuel);
    // A tighter tolerance: one cell off the new track, away from where it flies next
    // (its first target, or the depot), is off it now (a cell towards it would not be).
    node.track_tolerance_cells = 0;
    int32_t next_y = got_replan.residual_mission.depot_y;
    if ((got_replan.plan.route_count > 0) && (got_replan.plan.routes[0].target_count > 0)) {
        for (int i = 0; i < got_replan.residual_mission.target_count; ++i) {
            if (got_replan.residual_mission.targets[i].id == got_replan.plan.route_targets[0]) {
                next_y = got_replan.residual_mission.targets[i].y;
            }
        }
    }
    TEST_ASSERT_EQUAL_INT(10, got_replan.plan.routes[0].uav_id);
    fleet.uavs[0].y += (next_y > fleet.uavs[0].y) ? -1 : 1;
    TEST_ASSERT_EQUAL_INT(SVA_LCM_ACCEPTED,
                          sva_lcm_on_fleet(&node, fleet_buf, (size_t)enc_fleet()));
    TEST_ASSERT_EQUAL_INT(4, replans_seen);
    TEST_ASSERT_EQUAL_INT(SVA_LCM_EVENT_T_TYPE_POSITION, got_replan.event_type);
}

static sva_lcm_status_t send_report(int32_t uav, int32_t at, int8_t health, int32_t x, int32_t y,
                                    int32_t fuel)
{
    static uint8_t buf[SVA_LCM_REPORT_BYTES];
    sva_lcm_report_t r;
    memset(&r, 0, sizeof r);
    r.version = SVA_LCM_REPORT_T_VERSION;
    r.uav_id = uav;
    r.at_ticks = at;
    r.health = health;
    r.x = x;
    r.y = y;
    r.fuel = fuel;
    r.mission_seq = -1;
    r.reached_seq = -1;
    TEST_ASSERT_EQUAL_INT(SVA_LCM_REPORT_BYTES,
                          sva_lcm_report_t_encode(buf, 0, (int)sizeof buf, &r));
    return sva_lcm_on_report(&node, buf, sizeof buf);
}

// Vehicle reports (REPORT): refused before a live mission, with another version, a
// field out of range or a wrong size, each counted and changing nothing; a report moves
// the clock to its tick (an earlier tick is taken as now) and the core's rule turns it
// into at most one event: an agreeing report publishes nothing, a lost vehicle a uav_lost
// replan (event_seq -1), the same vehicle heard again a uav_back at its reported cell.
void test_vehicle_reports(void)
{
    node_setup(SVA_ALGO_SVA);
    make_inputs(6);
    TEST_ASSERT_EQUAL_INT(SVA_LCM_REJECTED, send_report(10, 0, 0, 0, 0, -1));
    TEST_ASSERT_EQUAL_INT(SVA_LCM_REJECT_VALUE, node.last_reject);
    TEST_ASSERT_NOT_NULL(strstr(last_log, "T_REPORT: no live mission"));
    TEST_ASSERT_EQUAL_INT(SVA_LCM_ACCEPTED,
                          sva_lcm_on_fleet(&node, fleet_buf, (size_t)enc_fleet()));
    TEST_ASSERT_EQUAL_INT(SVA_LCM_ACCEPTED,
                          sva_lcm_on_mission(&node, mission_buf, (size_t)enc_mission()));
    TEST_ASSERT_EQUAL_INT(1, plans_seen);
    static sva_live_t before;
    memcpy(&before, &node.priv.live, sizeof before);
    const uint32_t values = node.counters.rejected[SVA_LCM_REJECT_VALUE];
    TEST_ASSERT_EQUAL_INT(SVA_LCM_REJECTED, send_report(10, 0, 2, 0, 0, -1));
    TEST_ASSERT_EQUAL_INT(SVA_LCM_REJECTED, send_report(10, -1, 0, 0, 0, -1));
    TEST_ASSERT_EQUAL_INT(SVA_LCM_REJECTED, send_report(10, 0, 0, 40000, 0, -1));
    TEST_ASSERT_EQUAL_INT(SVA_LCM_REJECTED, send_report(10, 0, 0, 0, 0, -2));
    TEST_ASSERT_EQUAL_INT(values + 4U, node.counters.rejected[SVA_LCM_REJECT_VALUE]);
    static uint8_t short_buf[SVA_LCM_REPORT_BYTES - 1];
    TEST_ASSERT_EQUAL_INT(SVA_LCM_REJECTED, sva_lcm_on_report(&node, short_buf, sizeof short_buf));
    TEST_ASSERT_EQUAL_INT(SVA_LCM_REJECT_TRUNCATED, node.last_reject);
    static uint8_t buf[SVA_LCM_REPORT_BYTES];
    sva_lcm_report_t r;
    memset(&r, 0, sizeof r);
    r.version = SVA_LCM_REPORT_T_VERSION + 1;
    TEST_ASSERT_EQUAL_INT(SVA_LCM_REPORT_BYTES,
                          sva_lcm_report_t_encode(buf, 0, (int)sizeof buf, &r));
    TEST_ASSERT_EQUAL_INT(SVA_LCM_REJECTED, sva_lcm_on_report(&node, buf, sizeof buf));
    TEST_ASSERT_EQUAL_INT(SVA_LCM_REJECT_VERSION, node.last_reject);
    TEST_ASSERT_EQUAL_MEMORY(&node.priv.live, &before, sizeof before);
    TEST_ASSERT_EQUAL_INT(0, replans_seen);

    // Agreeing: UAV 10 where the model has it at tick 1, fuel unknown; the clock moves.
    int32_t x = 0;
    int32_t y = 0;
    int32_t fuel = 0;
    int32_t ready = 0;
    TEST_ASSERT_TRUE(sva_live_uav_at(&node.priv.live, 0, 1, &x, &y, &fuel, &ready));
    TEST_ASSERT_EQUAL_INT(SVA_LCM_ACCEPTED, send_report(10, 1, 0, x, y, -1));
    TEST_ASSERT_EQUAL_INT(1, node.priv.live.now_ticks);
    TEST_ASSERT_EQUAL_INT(0, replans_seen);
    // An earlier tick is now; lost: a replan without UAV 11.
    TEST_ASSERT_EQUAL_INT(SVA_LCM_ACCEPTED,
                          send_report(11, 0, SVA_LCM_REPORT_T_HEALTH_LOST, 0, 0, -1));
    TEST_ASSERT_EQUAL_INT(1, replans_seen);
    TEST_ASSERT_EQUAL_INT(-1, got_replan.event_seq);
    TEST_ASSERT_EQUAL_INT(SVA_LCM_EVENT_T_TYPE_UAV_LOST, got_replan.event_type);
    TEST_ASSERT_EQUAL_INT(1, got_replan.now_ticks);
    for (int u = 0; u < got_replan.residual_fleet.uav_count; ++u) {
        TEST_ASSERT_NOT_EQUAL_INT(11, got_replan.residual_fleet.uavs[u].id);
    }
    // Silent again: nothing; heard again at (2, -3) with fuel 150: back there.
    TEST_ASSERT_EQUAL_INT(SVA_LCM_ACCEPTED,
                          send_report(11, 2, SVA_LCM_REPORT_T_HEALTH_LOST, 0, 0, -1));
    TEST_ASSERT_EQUAL_INT(1, replans_seen);
    TEST_ASSERT_EQUAL_INT(SVA_LCM_ACCEPTED,
                          send_report(11, 3, SVA_LCM_REPORT_T_HEALTH_OK, 2, -3, 150));
    TEST_ASSERT_EQUAL_INT(2, replans_seen);
    TEST_ASSERT_EQUAL_INT(SVA_LCM_EVENT_T_TYPE_UAV_BACK, got_replan.event_type);
    TEST_ASSERT_EQUAL_INT(3, got_replan.now_ticks);
    int found = 0;
    for (int u = 0; u < got_replan.residual_fleet.uav_count; ++u) {
        const sva_lcm_uav_state_t* w = &got_replan.residual_fleet.uavs[u];
        if (w->id == 11) {
            TEST_ASSERT_EQUAL_INT(2, w->x);
            TEST_ASSERT_EQUAL_INT(-3, w->y);
            TEST_ASSERT_EQUAL_INT(150, w->fuel);
            found = 1;
        }
    }
    TEST_ASSERT_TRUE(found);
    TEST_ASSERT_EQUAL_INT(11U, node.counters.report_rx);
    TEST_ASSERT_EQUAL_INT(2U, node.counters.reports_applied);
}

// The input hook (sva_lcm_input_fn): called once for each input that changes the node,
// with its kind, its bytes and whether it starts over, before its answer is published;
// not for a refused or unchanged input. A hook that fails halts the node: that input's
// answer and every later input are dropped (SVA_LCM_HALTED).
typedef struct {
    int calls;
    sva_lcm_input_t kind;
    bool restarts;
    size_t size;
    int answers_before;  ///< answers published when the hook ran
    int fail;
} hook_seen_t;

static int hook(void* user, sva_lcm_input_t kind, bool restarts, const void* data, size_t size)
{
    hook_seen_t* h = (hook_seen_t*)user;
    (void)data;
    h->calls++;
    h->kind = kind;
    h->restarts = restarts;
    h->size = size;
    h->answers_before = plans_seen + replans_seen;
    return h->fail;
}

void test_input_hook(void)
{
    node_setup(SVA_ALGO_SVA);
    static hook_seen_t h;
    memset(&h, 0, sizeof h);
    node.input_hook = hook;
    node.input_hook_user = &h;
    make_inputs(8);
    TEST_ASSERT_EQUAL_INT(SVA_LCM_ACCEPTED,
                          sva_lcm_on_fleet(&node, fleet_buf, (size_t)enc_fleet()));
    TEST_ASSERT_TRUE((h.calls == 1) && (h.kind == SVA_LCM_INPUT_FLEET) && h.restarts);
    TEST_ASSERT_EQUAL_INT(SVA_LCM_FLEET_BYTES, h.size);
    TEST_ASSERT_EQUAL_INT(SVA_LCM_ACCEPTED,
                          sva_lcm_on_mission(&node, mission_buf, (size_t)enc_mission()));
    TEST_ASSERT_TRUE((h.calls == 2) && (h.kind == SVA_LCM_INPUT_MISSION) && h.restarts);
    TEST_ASSERT_EQUAL_INT(0, h.answers_before);  // before the plan went out
    TEST_ASSERT_EQUAL_INT(1, plans_seen);
    // unchanged and refused: not handed over
    TEST_ASSERT_EQUAL_INT(SVA_LCM_UNCHANGED,
                          sva_lcm_on_mission(&node, mission_buf, (size_t)enc_mission()));
    TEST_ASSERT_EQUAL_INT(SVA_LCM_REJECTED, sva_lcm_on_fleet(&node, fleet_buf, 7));
    static sva_lcm_event_t e;
    memset(&e, 0, sizeof e);
    e.version = SVA_LCM_EVENT_T_VERSION;
    e.type = SVA_LCM_EVENT_T_TYPE_UAV_LOST;
    e.uav_id = 99;  // unknown: refused, answered, not handed over
    e.at_ticks = 2;
    TEST_ASSERT_EQUAL_INT(SVA_LCM_REJECTED, send_event(&e));
    TEST_ASSERT_EQUAL_INT(2, h.calls);
    e.uav_id = 10;
    TEST_ASSERT_EQUAL_INT(SVA_LCM_ACCEPTED, send_event(&e));
    TEST_ASSERT_TRUE((h.calls == 3) && (h.kind == SVA_LCM_INPUT_EVENT) && !h.restarts);
    TEST_ASSERT_EQUAL_INT(2, h.answers_before);  // the plan and the refusal, not this replan
    TEST_ASSERT_EQUAL_INT(2, replans_seen);
    // a report that moves the clock is handed over (no answer: nothing applied)
    TEST_ASSERT_EQUAL_INT(SVA_LCM_ACCEPTED,
                          send_report(10, 5, SVA_LCM_REPORT_T_HEALTH_LOST, 0, 0, -1));
    TEST_ASSERT_TRUE((h.calls == 4) && (h.kind == SVA_LCM_INPUT_REPORT));
    TEST_ASSERT_EQUAL_INT(2, replans_seen);
    // the hook fails: nothing published, the node halted
    h.fail = -1;
    e.type = SVA_LCM_EVENT_T_TYPE_CLOCK;
    e.at_ticks = 6;
    TEST_ASSERT_EQUAL_INT(SVA_LCM_HALTED, send_event(&e));
    TEST_ASSERT_TRUE(node.halted);
    TEST_ASSERT_EQUAL_INT(2, replans_seen);
    h.fail = 0;
    TEST_ASSERT_EQUAL_INT(SVA_LCM_HALTED, sva_lcm_on_fleet(&node, fleet_buf, (size_t)enc_fleet()));
    TEST_ASSERT_EQUAL_INT(5, h.calls);
    TEST_ASSERT_EQUAL_INT(4U, node.counters.inputs_hooked);
}

void test_zero_allocations_per_message(void)
{
    node_setup(SVA_ALGO_SVA);
    make_inputs(100);
    TEST_ASSERT_EQUAL_INT(SVA_LCM_ACCEPTED,
                          sva_lcm_on_fleet(&node, fleet_buf, (size_t)enc_fleet()));
    TEST_ASSERT_EQUAL_INT(SVA_LCM_ACCEPTED,
                          sva_lcm_on_mission(&node, mission_buf, (size_t)enc_mission()));
    // warm every logging path once
    (void)sva_lcm_on_fleet(&node, fleet_buf, 5);
    const int plans_before = plans_seen;

    // prove the counter counts
    alloc_count = 0;
    alloc_armed = 1;
    void* volatile p = malloc(16);
    alloc_armed = 0;
    free(p);
    TEST_ASSERT_EQUAL_INT(1, alloc_count);

    static uint8_t fb[200][SVA_LCM_FLEET_BYTES];
    static uint8_t mb[2][SVA_LCM_MISSION_BYTES];
    for (int i = 0; i < 200; ++i) {
        fleet.revision = 1000 + i;
        fleet.uavs[i % 5].fuel = 150 + i;
        TEST_ASSERT_EQUAL_INT(SVA_LCM_FLEET_BYTES,
                              sva_lcm_fleet_state_t_encode(fb[i], 0, SVA_LCM_FLEET_BYTES, &fleet));
    }
    for (int i = 0; i < 2; ++i) {
        mission.revision = 2000 + i;
        mission.targets[0].need = 1 + i;
        TEST_ASSERT_EQUAL_INT(SVA_LCM_MISSION_BYTES,
                              sva_lcm_mission_t_encode(mb[i], 0, SVA_LCM_MISSION_BYTES, &mission));
    }

    alloc_count = 0;
    alloc_armed = 1;
    for (int i = 0; i < 200; ++i) {
        (void)sva_lcm_on_fleet(&node, fb[i], SVA_LCM_FLEET_BYTES);
        (void)sva_lcm_on_mission(&node, mb[i % 2], SVA_LCM_MISSION_BYTES);
        (void)sva_lcm_on_fleet(&node, fb[i], SVA_LCM_FLEET_BYTES - 3);  // rejected
        TEST_ASSERT_EQUAL_INT(SVA_OK, sva_lcm_publish_status(&node, i));
    }
    alloc_armed = 0;
    TEST_ASSERT_EQUAL_INT(0, alloc_count);
    TEST_ASSERT_EQUAL_INT(400, plans_seen - plans_before);

    // For the record: the whole memq path (memq copies every message: LCM's, not ours).
    lcm_t* lcm = lcm_create("memq://");
    TEST_ASSERT_NOT_NULL(lcm);
    TEST_ASSERT_EQUAL_INT(SVA_OK, sva_lcm_node_init(&node, lcm, "Z_", SVA_ALGO_SVA));
    TEST_ASSERT_EQUAL_INT(SVA_OK, sva_lcm_node_subscribe(&node));
    (void)lcm_publish(lcm, "Z_FLEET", fb[0], SVA_LCM_FLEET_BYTES);
    (void)lcm_publish(lcm, "Z_MISSION", mb[0], SVA_LCM_MISSION_BYTES);
    drain(lcm);
    alloc_count = 0;
    alloc_armed = 1;
    for (int i = 1; i < 101; ++i) {
        (void)lcm_publish(lcm, "Z_FLEET", fb[i], SVA_LCM_FLEET_BYTES);
        drain(lcm);
    }
    alloc_armed = 0;
    printf("memq provider: %.1f heap allocations per fleet message + plan (LCM's copies)\n",
           (double)alloc_count / 100.0);
    TEST_ASSERT_EQUAL_INT(101, node.counters.plans_published);
    sva_lcm_node_unsubscribe(&node);
    lcm_destroy(lcm);
}
