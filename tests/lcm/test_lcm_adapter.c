// Unit tests of the LCM adapter over memq:// and direct calls: codec round trip, every
// rejection reason, change detection, and zero heap allocations per message.
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>

#include <cmocka.h>

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
        assert_int_equal(size, SVA_LCM_REPLAN_BYTES);
        assert_int_equal(sva_lcm_replan_t_decode(data, 0, (int)size, &got_replan), (int)size);
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
    assert_int_equal(sva_lcm_node_init(&node, NULL, "T_", algo), SVA_OK);
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
    assert_int_equal(sva_planner_init(&planner), SVA_OK);
    assert_int_equal(sva_plan(&planner, &direct_mission, algo, &direct_plan, NULL), SVA_OK);
    assert_int_equal(p->algorithm, (int)algo);
    assert_int_equal(p->status, direct_plan.status == SVA_PLAN_COMPLETE
                                    ? SVA_LCM_PLAN_T_STATUS_COMPLETE
                                    : SVA_LCM_PLAN_T_STATUS_PARTIAL);
    assert_int_equal(p->covered, direct_plan.covered);
    assert_int_equal(p->cost, direct_plan.cost);
    assert_int_equal(p->uncovered_count, direct_plan.uncovered_count);
    for (int i = 0; i < p->uncovered_count; ++i) {
        assert_int_equal(p->uncovered[i], direct_mission.targets[direct_plan.uncovered[i]].id);
    }
    assert_int_equal(p->route_count, direct_plan.route_count);
    int k = 0;
    for (int r = 0; r < p->route_count; ++r) {
        const sva_route_t* d = &direct_plan.routes[r];
        assert_int_equal(p->routes[r].uav_id, d->uav_id);
        assert_int_equal(p->routes[r].target_count, d->target_count);
        assert_int_equal(p->routes[r].distance_cells, d->distance_cells);
        assert_int_equal(p->routes[r].fuel_used, d->fuel_used);
        assert_int_equal(p->routes[r].stranded, d->stranded ? 1 : 0);
        for (int j = 0; j < d->target_count; ++j) {
            assert_int_equal(p->route_targets[k++], direct_mission.targets[d->targets[j]].id);
        }
    }
    assert_int_equal(p->item_count, k);
    for (; k < SVA_LCM_PLAN_T_MAX_ROUTE_ITEMS; ++k) {
        assert_int_equal(p->route_targets[k], 0);
    }
    // flow's certificate travels as the core made it; the other algorithms send zeros.
    const sva_stats_t* st = &direct_plan.stats;
    assert_int_equal(st->has_bound, algo == SVA_ALGO_FLOW);
    assert_int_equal(p->has_bound, st->has_bound ? 1 : 0);
    assert_int_equal(p->lower_bound, st->has_bound ? st->lower_bound : 0);
    assert_int_equal(p->optimal, (st->has_bound && st->optimal) ? 1 : 0);
    assert_int_equal(p->flow_incomplete, st->has_bound ? st->flow_incomplete : 0);
    if (p->has_bound == 1) {
        assert_true(p->lower_bound >= 0);
        assert_true(p->lower_bound <= p->cost);
        if (p->optimal == 1) {
            assert_int_equal(p->lower_bound, p->cost);
            assert_int_equal(p->flow_incomplete, 0);
        }
    }
}

static void decode_last_plan(void)
{
    assert_int_equal(last_plan_size, SVA_LCM_PLAN_BYTES);
    assert_int_equal(sva_lcm_plan_t_decode(last_plan_bytes, 0, (int)last_plan_size, &got_plan),
                     SVA_LCM_PLAN_BYTES);
}

// --- tests ------------------------------------------------------------------------------

static void test_encoded_sizes(void** state)
{
    (void)state;
    make_inputs(1);
    static sva_lcm_plan_t p;
    static sva_lcm_node_status_t s;
    assert_int_equal(sva_lcm_fleet_state_t_encoded_size(&fleet), SVA_LCM_FLEET_BYTES);
    assert_int_equal(sva_lcm_mission_t_encoded_size(&mission), SVA_LCM_MISSION_BYTES);
    assert_int_equal(sva_lcm_plan_t_encoded_size(&p), SVA_LCM_PLAN_BYTES);
    assert_int_equal(sva_lcm_node_status_t_encoded_size(&s), SVA_LCM_STATUS_BYTES);
    static sva_lcm_event_t e;
    static sva_lcm_replan_t r;
    assert_int_equal(sva_lcm_event_t_encoded_size(&e), SVA_LCM_EVENT_BYTES);
    assert_int_equal(sva_lcm_replan_t_encoded_size(&r), SVA_LCM_REPLAN_BYTES);
    static sva_lcm_report_t rp;
    assert_int_equal(sva_lcm_report_t_encoded_size(&rp), SVA_LCM_REPORT_BYTES);
    assert_true(SVA_LCM_REPLAN_BYTES + 64 <= 65499);
    // one udpm datagram (LCM_SHORT_MESSAGE_MAX_SIZE) with the longest channel name
    assert_true(SVA_LCM_PLAN_BYTES + 64 <= 65499);
}

static void test_channel_escape(void** state)
{
    (void)state;
    char out[16];
    assert_int_equal(sva_lcm_channel_escape("A_b9", out, sizeof out), SVA_OK);
    assert_string_equal(out, "A_b9");
    assert_int_equal(sva_lcm_channel_escape("a.b*[c]", out, sizeof out), SVA_OK);
    assert_string_equal(out, "a\\.b\\*\\[c\\]");
    assert_int_equal(sva_lcm_channel_escape("x.y", out, 4), SVA_ERR_ARGUMENT);
    assert_string_equal(out, "");
    assert_int_equal(sva_lcm_channel_escape("xy", out, 3), SVA_OK);
    assert_int_equal(sva_lcm_channel_escape(NULL, out, sizeof out), SVA_ERR_ARGUMENT);
}

static void test_init_arguments(void** state)
{
    (void)state;
    char prefix[80];
    memset(prefix, 'P', sizeof prefix);
    prefix[SVA_LCM_PREFIX_MAX + 1] = '\0';
    assert_int_equal(sva_lcm_node_init(&node, NULL, prefix, SVA_ALGO_SVA), SVA_ERR_ARGUMENT);
    prefix[SVA_LCM_PREFIX_MAX] = '\0';
    assert_int_equal(sva_lcm_node_init(&node, NULL, prefix, SVA_ALGO_SVA), SVA_OK);
    assert_int_equal(strlen(node.channel_mission), 63);
    assert_int_equal(sva_lcm_node_init(&node, NULL, "X", SVA_ALGO_COUNT_), SVA_ERR_ARGUMENT);
    assert_int_equal(sva_lcm_node_init(&node, NULL, "X", SVA_ALGO_GA), SVA_OK);
    assert_string_equal(node.channel_plan, "XPLAN");
    assert_int_equal(sva_lcm_node_subscribe(&node), SVA_ERR_ARGUMENT);  // no lcm
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

static void test_memq_round_trip(void** state)
{
    (void)state;
    lcm_t* lcm = lcm_create("memq://");
    assert_non_null(lcm);
    // a prefix with regex metacharacters: subscriptions must match it exactly
    assert_int_equal(sva_lcm_node_init(&node, lcm, "a.b+", SVA_ALGO_SVA), SVA_OK);
    assert_int_equal(sva_lcm_node_subscribe(&node), SVA_OK);
    lcm_subscription_t* sub = lcm_subscribe(lcm, "a\\.b\\+PLAN", on_memq_plan, NULL);
    assert_non_null(sub);
    memq_plans = 0;
    make_inputs(7);
    const int nf = enc_fleet();
    const int nm = enc_mission();
    assert_int_equal(nf, SVA_LCM_FLEET_BYTES);
    assert_int_equal(nm, SVA_LCM_MISSION_BYTES);
    // "aXb+FLEET" matches the unescaped regex a.b+FLEET: the node must ignore it
    assert_int_equal(lcm_publish(lcm, "aXbbFLEET", fleet_buf, (unsigned)nf), 0);
    assert_int_equal(lcm_publish(lcm, "a.b+FLEET", fleet_buf, (unsigned)nf), 0);
    assert_int_equal(lcm_publish(lcm, "a.b+MISSION", mission_buf, (unsigned)nm), 0);
    drain(lcm);
    assert_int_equal(node.counters.fleet_rx, 1);
    assert_int_equal(node.counters.mission_rx, 1);
    assert_int_equal(memq_plans, 1);
    assert_int_equal(sva_lcm_plan_t_decode(memq_plan_bytes, 0, SVA_LCM_PLAN_BYTES, &got_plan),
                     SVA_LCM_PLAN_BYTES);
    assert_int_equal(got_plan.plan_id, 1);
    assert_int_equal(got_plan.fleet_revision, 7);
    assert_int_equal(got_plan.mission_revision, 7);
    assert_plan_matches_core(&got_plan, SVA_ALGO_SVA);
    assert_true(got_plan.covered >= 1);
    lcm_unsubscribe(lcm, sub);
    sva_lcm_node_unsubscribe(&node);
    lcm_destroy(lcm);
}

static void test_every_algorithm(void** state)
{
    (void)state;
    for (int a = 0; a < (int)SVA_ALGO_COUNT_; ++a) {
        node_setup((sva_algorithm_t)a);
        make_inputs(3);
        assert_int_equal(sva_lcm_on_fleet(&node, fleet_buf, (size_t)enc_fleet()), SVA_LCM_ACCEPTED);
        assert_int_equal(plans_seen, 0);  // no mission yet
        assert_int_equal(sva_lcm_on_mission(&node, mission_buf, (size_t)enc_mission()),
                         SVA_LCM_ACCEPTED);
        assert_int_equal(plans_seen, 1);
        decode_last_plan();
        assert_plan_matches_core(&got_plan, (sva_algorithm_t)a);
    }
}

// A flow plan over LCM carries its certificate, and only a plan that delivers
// routes does (the node's wire plan is reused: a rejected or too large plan after a flow
// plan must not inherit its bound).
static void test_flow_certificate(void** state)
{
    (void)state;
    node_setup(SVA_ALGO_FLOW);
    make_inputs(50);
    assert_int_equal(sva_lcm_on_fleet(&node, fleet_buf, (size_t)enc_fleet()), SVA_LCM_ACCEPTED);
    assert_int_equal(sva_lcm_on_mission(&node, mission_buf, (size_t)enc_mission()),
                     SVA_LCM_ACCEPTED);
    decode_last_plan();
    assert_plan_matches_core(&got_plan, SVA_ALGO_FLOW);
    // 6 targets, 5 UAVs: flow's search finishes and proves its plan optimal.
    assert_int_equal(got_plan.has_bound, 1);
    assert_int_equal(got_plan.optimal, 1);
    assert_true(got_plan.lower_bound > 0);
    assert_int_equal(got_plan.lower_bound, got_plan.cost);

    // the core rejects the next mission: the REJECTED plan has no certificate
    mission.targets[3].id = mission.targets[1].id;
    assert_int_equal(sva_lcm_on_mission(&node, mission_buf, (size_t)enc_mission()),
                     SVA_LCM_ACCEPTED);
    decode_last_plan();
    assert_int_equal(got_plan.status, SVA_LCM_PLAN_T_STATUS_REJECTED);
    assert_int_equal(got_plan.has_bound, 0);
    assert_int_equal(got_plan.lower_bound, 0);
    assert_int_equal(got_plan.optimal, 0);
    assert_int_equal(got_plan.flow_incomplete, 0);

    // 64 UAVs and 40 targets needing 13 each: 520 copies, above SVA_FLOW_MAX_COPIES
    // (512), so flow has no relaxation (flow_incomplete 4, lower_bound 0).
    make_inputs(51);
    full_fleet_at_depot();
    mission.target_count = 40;
    for (int i = 0; i < 40; ++i) {
        mission.targets[i] = (sva_lcm_target_t){i + 1, i % 7, i % 5, 20 * i + 10, 20 * i + 15, 13};
    }
    assert_true(13 * 40 > SVA_FLOW_MAX_COPIES);
    assert_int_equal(sva_lcm_on_fleet(&node, fleet_buf, (size_t)enc_fleet()), SVA_LCM_ACCEPTED);
    assert_int_equal(sva_lcm_on_mission(&node, mission_buf, (size_t)enc_mission()),
                     SVA_LCM_ACCEPTED);
    decode_last_plan();
    assert_plan_matches_core(&got_plan, SVA_ALGO_FLOW);
    assert_int_equal(got_plan.has_bound, 1);
    assert_int_equal(got_plan.flow_incomplete, 4);
    assert_int_equal(got_plan.optimal, 0);
    assert_int_equal(got_plan.lower_bound, 0);

    // 65 back-to-back targets at the depot needing all 64 UAVs: 4160 route items, more
    // than MAX_ROUTE_ITEMS. The core's plan has a bound; the TOO_LARGE plan carries none.
    make_inputs(52);
    full_fleet_at_depot();
    mission.target_count = 65;
    for (int i = 0; i < 65; ++i) {
        mission.targets[i] = (sva_lcm_target_t){i + 1, 0, 0, 10 * i + 1, 10 * i + 5, SVA_MAX_UAVS};
    }
    assert_int_equal(sva_lcm_on_fleet(&node, fleet_buf, (size_t)enc_fleet()), SVA_LCM_ACCEPTED);
    assert_int_equal(sva_lcm_on_mission(&node, mission_buf, (size_t)enc_mission()),
                     SVA_LCM_ACCEPTED);
    decode_last_plan();
    assert_int_equal(got_plan.status, SVA_LCM_PLAN_T_STATUS_TOO_LARGE);
    assert_true(node.priv.plan.stats.has_bound);
    assert_int_equal(got_plan.has_bound, 0);
    assert_int_equal(got_plan.lower_bound, 0);
    assert_int_equal(got_plan.optimal, 0);
    assert_int_equal(got_plan.flow_incomplete, 0);
}

static void test_unchanged_and_replan(void** state)
{
    (void)state;
    node_setup(SVA_ALGO_SVA);
    make_inputs(1);
    assert_int_equal(sva_lcm_on_mission(&node, mission_buf, (size_t)enc_mission()),
                     SVA_LCM_ACCEPTED);
    assert_int_equal(sva_lcm_on_fleet(&node, fleet_buf, (size_t)enc_fleet()), SVA_LCM_ACCEPTED);
    assert_int_equal(plans_seen, 1);
    assert_int_equal(sva_lcm_on_fleet(&node, fleet_buf, (size_t)enc_fleet()), SVA_LCM_UNCHANGED);
    assert_int_equal(sva_lcm_on_mission(&node, mission_buf, (size_t)enc_mission()),
                     SVA_LCM_UNCHANGED);
    assert_int_equal(node.counters.unchanged, 2);
    assert_int_equal(plans_seen, 1);
    // same revision, different content: still a change
    fleet.uavs[0].fuel = 199;
    assert_int_equal(sva_lcm_on_fleet(&node, fleet_buf, (size_t)enc_fleet()), SVA_LCM_ACCEPTED);
    assert_int_equal(plans_seen, 2);
    decode_last_plan();
    assert_int_equal(got_plan.plan_id, 2);
    assert_plan_matches_core(&got_plan, SVA_ALGO_SVA);
}

static void test_unavailable_uav_gets_nothing(void** state)
{
    (void)state;
    node_setup(SVA_ALGO_SVA);
    make_inputs(2);
    for (int i = 1; i < 5; ++i) {
        fleet.uavs[i].health = SVA_LCM_UAV_STATE_T_HEALTH_UNAVAILABLE;
    }
    assert_int_equal(sva_lcm_on_fleet(&node, fleet_buf, (size_t)enc_fleet()), SVA_LCM_ACCEPTED);
    assert_int_equal(sva_lcm_on_mission(&node, mission_buf, (size_t)enc_mission()),
                     SVA_LCM_ACCEPTED);
    decode_last_plan();
    assert_int_equal(got_plan.route_count, 5);
    assert_true(got_plan.routes[0].target_count >= 1);
    for (int i = 1; i < 5; ++i) {
        assert_int_equal(got_plan.routes[i].uav_id, 10 + i);
        assert_int_equal(got_plan.routes[i].target_count, 0);
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
    const sva_lcm_verdict_t v =
        is_fleet ? sva_lcm_on_fleet(&node, data, size) : sva_lcm_on_mission(&node, data, size);
    assert_int_equal(v, SVA_LCM_REJECTED);
    assert_int_equal(node.last_reject, why);
    assert_int_equal(node.counters.rejected[why], before + 1U);
    assert_int_equal(plans_seen, plans);
    assert_int_equal(node.priv.fleet_revision, fr);
    assert_int_equal(node.priv.mission_revision, mr);
}

static void test_rejections_frame(void** state)
{
    (void)state;
    node_setup(SVA_ALGO_SVA);
    make_inputs(5);
    assert_int_equal(sva_lcm_on_fleet(&node, fleet_buf, (size_t)enc_fleet()), SVA_LCM_ACCEPTED);
    assert_int_equal(sva_lcm_on_mission(&node, mission_buf, (size_t)enc_mission()),
                     SVA_LCM_ACCEPTED);
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
    assert_int_equal(log_lines[SVA_LCM_REJECT_TRUNCATED], 1);  // logged once per reason
    assert_int_equal(log_lines[SVA_LCM_REJECT_TRAILING], 1);
    assert_int_equal(log_lines[SVA_LCM_REJECT_FINGERPRINT], 1);
    assert_int_equal(node.counters.rejected[SVA_LCM_REJECT_TRUNCATED], 5);
}

static void test_rejections_counts_and_values(void** state)
{
    (void)state;
    node_setup(SVA_ALGO_SVA);
    make_inputs(5);
    assert_int_equal(sva_lcm_on_fleet(&node, fleet_buf, (size_t)enc_fleet()), SVA_LCM_ACCEPTED);
    assert_int_equal(sva_lcm_on_mission(&node, mission_buf, (size_t)enc_mission()),
                     SVA_LCM_ACCEPTED);

    static const int16_t bad_counts[] = {SVA_MAX_UAVS + 1, -1, INT16_MAX, INT16_MIN};
    for (size_t i = 0; i < sizeof bad_counts / sizeof bad_counts[0]; ++i) {
        make_inputs(9);
        fleet.uav_count = bad_counts[i];
        expect_reject(true, fleet_buf, (size_t)enc_fleet(), SVA_LCM_REJECT_COUNT);
        assert_int_equal(node.last_diag.field, SVA_FIELD_UAVS);
        assert_string_equal(node.last_diag.limit_name, "SVA_MAX_UAVS");
        make_inputs(9);
        mission.target_count =
            (int16_t)(bad_counts[i] == SVA_MAX_UAVS + 1 ? SVA_MAX_TARGETS + 1 : bad_counts[i]);
        expect_reject(false, mission_buf, (size_t)enc_mission(), SVA_LCM_REJECT_COUNT);
        assert_int_equal(node.last_diag.field, SVA_FIELD_TARGETS);
    }
    // exactly the bound is accepted
    make_inputs(10);
    fleet.uav_count = SVA_MAX_UAVS;
    for (int i = 0; i < SVA_MAX_UAVS; ++i) {
        fleet.uavs[i].id = i + 1;
        fleet.uavs[i].fuel = 50;
    }
    assert_int_equal(sva_lcm_on_fleet(&node, fleet_buf, (size_t)enc_fleet()), SVA_LCM_ACCEPTED);

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
            fail();
        }
        if (cases[c].which == 0) {
            expect_reject(true, fleet_buf, (size_t)enc_fleet(), SVA_LCM_REJECT_VALUE);
        } else {
            expect_reject(false, mission_buf, (size_t)enc_mission(), SVA_LCM_REJECT_VALUE);
        }
        assert_int_equal(node.last_diag.field, cases[c].field);
        assert_int_equal(node.last_diag.index, i);
        assert_int_equal(node.last_diag.value, cases[c].value);
    }
    make_inputs(12);
    fleet.uavs[2].health = 7;
    expect_reject(true, fleet_buf, (size_t)enc_fleet(), SVA_LCM_REJECT_VALUE);
    assert_int_equal(log_lines[SVA_LCM_REJECT_COUNT], 1);
    assert_int_equal(log_lines[SVA_LCM_REJECT_VALUE], 1);
}

static void test_core_rejection_and_planner_limit(void** state)
{
    (void)state;
    node_setup(SVA_ALGO_SVA);
    make_inputs(20);
    mission.targets[3].id = mission.targets[1].id;  // duplicate: only the core sees it
    assert_int_equal(sva_lcm_on_fleet(&node, fleet_buf, (size_t)enc_fleet()), SVA_LCM_ACCEPTED);
    assert_int_equal(sva_lcm_on_mission(&node, mission_buf, (size_t)enc_mission()),
                     SVA_LCM_ACCEPTED);
    assert_int_equal(node.counters.rejected[SVA_LCM_REJECT_INVALID], 1);
    assert_int_equal(plans_seen, 1);
    decode_last_plan();
    assert_int_equal(got_plan.status, SVA_LCM_PLAN_T_STATUS_REJECTED);
    assert_int_equal(got_plan.error_code, SVA_ERR_INVALID);
    assert_int_equal(got_plan.diag_field, SVA_FIELD_TARGET_ID);
    assert_int_equal(got_plan.diag_rule, SVA_RULE_DUPLICATE);
    assert_int_equal(got_plan.diag_index, 3);
    assert_int_equal(got_plan.route_count, 0);
    assert_int_equal(log_lines[SVA_LCM_REJECT_INVALID], 1);
    // window end before start: the core's rule too
    make_inputs(21);
    mission.targets[2].end_ticks = mission.targets[2].start_ticks;
    assert_int_equal(sva_lcm_on_mission(&node, mission_buf, (size_t)enc_mission()),
                     SVA_LCM_ACCEPTED);
    decode_last_plan();
    assert_int_equal(got_plan.status, SVA_LCM_PLAN_T_STATUS_REJECTED);
    assert_int_equal(got_plan.diag_rule, SVA_RULE_AFTER);

    // bfa refuses more than SVA_BFA_MAX_TARGETS targets: STATUS_FAILED
    node_setup(SVA_ALGO_BFA);
    make_inputs(22);
    mission.target_count = SVA_BFA_MAX_TARGETS + 1;
    for (int i = 0; i < mission.target_count; ++i) {
        mission.targets[i] = (sva_lcm_target_t){i + 1, i, 1, 100 * i + 10, 100 * i + 20, 1};
    }
    assert_int_equal(sva_lcm_on_fleet(&node, fleet_buf, (size_t)enc_fleet()), SVA_LCM_ACCEPTED);
    assert_int_equal(sva_lcm_on_mission(&node, mission_buf, (size_t)enc_mission()),
                     SVA_LCM_ACCEPTED);
    decode_last_plan();
    assert_int_equal(got_plan.status, SVA_LCM_PLAN_T_STATUS_FAILED);
    assert_int_equal(got_plan.error_code, SVA_ERR_LIMIT);
    assert_int_equal(node.counters.rejected[SVA_LCM_REJECT_PLANNER], 1);
}

static void test_plan_too_large(void** state)
{
    (void)state;
    node_setup(SVA_ALGO_GA);
    make_inputs(30);
    // 64 UAVs at the depot serve 256 back-to-back targets there, 17 each: 4352 items.
    full_fleet_at_depot();
    mission.target_count = SVA_MAX_TARGETS;
    for (int i = 0; i < SVA_MAX_TARGETS; ++i) {
        mission.targets[i] = (sva_lcm_target_t){i + 1, 0, 0, 10 * i + 1, 10 * i + 5, 17};
    }
    assert_int_equal(sva_lcm_on_fleet(&node, fleet_buf, (size_t)enc_fleet()), SVA_LCM_ACCEPTED);
    assert_int_equal(sva_lcm_on_mission(&node, mission_buf, (size_t)enc_mission()),
                     SVA_LCM_ACCEPTED);
    decode_last_plan();
    assert_int_equal(got_plan.status, SVA_LCM_PLAN_T_STATUS_TOO_LARGE);
    assert_int_equal(got_plan.route_count, 0);
    assert_int_equal(got_plan.item_count, 0);
    assert_int_equal(node.counters.rejected[SVA_LCM_REJECT_TOO_LARGE], 1);
    // 15 each (3840 items) fits
    for (int i = 0; i < SVA_MAX_TARGETS; ++i) {
        mission.targets[i].need = 15;
    }
    assert_int_equal(sva_lcm_on_mission(&node, mission_buf, (size_t)enc_mission()),
                     SVA_LCM_ACCEPTED);
    decode_last_plan();
    assert_int_equal(got_plan.status, SVA_LCM_PLAN_T_STATUS_COMPLETE);
    assert_int_equal(got_plan.item_count, 15 * SVA_MAX_TARGETS);
    assert_plan_matches_core(&got_plan, SVA_ALGO_GA);
}

static void test_status(void** state)
{
    (void)state;
    node_setup(SVA_ALGO_HGA);
    make_inputs(40);
    static sva_lcm_node_status_t s;
    assert_int_equal(sva_lcm_publish_status(&node, 123), SVA_OK);
    assert_int_equal(status_seen, 1);
    assert_int_equal(sva_lcm_on_fleet(&node, fleet_buf, 3), SVA_LCM_REJECTED);
    assert_int_equal(sva_lcm_on_fleet(&node, fleet_buf, (size_t)enc_fleet()), SVA_LCM_ACCEPTED);
    assert_int_equal(sva_lcm_on_mission(&node, mission_buf, (size_t)enc_mission()),
                     SVA_LCM_ACCEPTED);
    assert_int_equal(sva_lcm_publish_status(&node, 456), SVA_OK);
    assert_int_equal(
        sva_lcm_node_status_t_decode(node.priv.status_buf, 0, SVA_LCM_STATUS_BYTES, &s),
        SVA_LCM_STATUS_BYTES);
    assert_int_equal(s.utime, 456);
    assert_int_equal(s.seq, 2);
    assert_int_equal(s.state, SVA_LCM_NODE_STATUS_T_STATE_READY);
    assert_int_equal(s.algorithm, SVA_ALGO_HGA);
    assert_int_equal(s.fleet_revision, 40);
    assert_int_equal(s.last_plan_id, 1);
    assert_int_equal(s.fleet_rx, 2);
    assert_int_equal(s.plans_published, 1);
    assert_int_equal(s.rejected[SVA_LCM_REJECT_TRUNCATED], 1);
}

// The port's goal: zero heap allocations per message in steady state, accepted or not,
// planning and publishing included.
static int send_event(const sva_lcm_event_t* e)
{
    static uint8_t buf[SVA_LCM_EVENT_BYTES];
    assert_int_equal(sva_lcm_event_t_encode(buf, 0, (int)sizeof buf, e), SVA_LCM_EVENT_BYTES);
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
static void test_live_events(void** state)
{
    (void)state;
    node_setup(SVA_ALGO_SVA);
    static sva_lcm_event_t e;
    memset(&e, 0, sizeof e);
    e.version = SVA_LCM_EVENT_T_VERSION;
    e.seq = 7;
    e.type = SVA_LCM_EVENT_T_TYPE_CLOCK;
    e.at_ticks = 1;
    assert_int_equal(send_event(&e), SVA_LCM_REJECTED);
    assert_int_equal(replans_seen, 1);
    assert_int_equal(got_replan.accepted, 0);
    assert_int_equal(got_replan.event_seq, 7);
    assert_string_equal(replan_text(),
                        "T_EVENT: no live mission: a fleet and a mission must be planned first");

    make_inputs(3);
    assert_int_equal(sva_lcm_on_fleet(&node, fleet_buf, (size_t)enc_fleet()), SVA_LCM_ACCEPTED);
    assert_int_equal(sva_lcm_on_mission(&node, mission_buf, (size_t)enc_mission()),
                     SVA_LCM_ACCEPTED);
    static sva_live_t before;
    before = node.priv.live;

    e.seq = 8;
    e.version = 2;
    assert_int_equal(send_event(&e), SVA_LCM_REJECTED);
    assert_string_equal(replan_text(), "T_EVENT: event_t.version is 2, this node speaks version 1");
    e.version = SVA_LCM_EVENT_T_VERSION;
    e.type = 9;
    assert_int_equal(send_event(&e), SVA_LCM_REJECTED);
    assert_int_equal(got_replan.diag_field, (int)SVA_FIELD_EVENT_TYPE);
    e.type = SVA_LCM_EVENT_T_TYPE_UAV_LOST;
    e.uav_id = 99;
    assert_int_equal(send_event(&e), SVA_LCM_REJECTED);
    assert_int_equal(got_replan.accepted, 0);
    assert_int_equal(got_replan.plan.status, SVA_LCM_PLAN_T_STATUS_REJECTED);
    assert_int_equal(got_replan.diag_field, (int)SVA_FIELD_EVENT_UAV);
    assert_int_equal(got_replan.diag_rule, (int)SVA_RULE_UNKNOWN);
    assert_int_equal(got_replan.diag_value, 99);
    assert_memory_equal(&node.priv.live, &before, sizeof before);
    assert_int_equal(node.counters.rejected[SVA_LCM_REJECT_VALUE], 2);
    assert_int_equal(node.counters.rejected[SVA_LCM_REJECT_VERSION], 1);
    assert_int_equal(node.counters.rejected[SVA_LCM_REJECT_INVALID], 1);

    // A loss at tick 11: the same event on a copy of the live mission, replanned by
    // the core directly, gives the plan the node published.
    e.seq = 9;
    e.uav_id = 10;
    e.at_ticks = 11;
    static sva_live_t mirror;
    mirror = before;
    const sva_event_t ev = {.type = SVA_EVENT_UAV_LOST, .at_ticks = 11, .uav_id = 10};
    assert_int_equal(sva_live_apply(&mirror, &ev, NULL), SVA_OK);
    sva_live_result_t res;
    assert_int_equal(sva_planner_init(&planner), SVA_OK);
    assert_int_equal(sva_live_replan(&mirror, &planner, SVA_ALGO_SVA, &res, NULL), SVA_OK);
    assert_int_equal(send_event(&e), SVA_LCM_ACCEPTED);
    assert_int_equal(got_replan.accepted, 1);
    assert_int_equal(got_replan.event_seq, 9);
    assert_int_equal(got_replan.now_ticks, 11);
    assert_int_equal(got_replan.revision, (int64_t)res.revision);
    assert_int_equal(got_replan.kept, res.kept ? 1 : 0);
    assert_int_equal(got_replan.dropped, (int32_t)res.dropped);
    assert_int_equal(got_replan.added, (int32_t)res.added);
    assert_int_equal(got_replan.dropped_listed, (int16_t)res.dropped);
    assert_int_equal(got_replan.added_listed, (int16_t)res.added);
    assert_int_equal(got_replan.objective, res.objective);
    assert_int_equal(got_replan.residual_fleet.uav_count, (int16_t)res.residual->uav_count);
    assert_int_equal(got_replan.residual_mission.target_count, (int16_t)res.residual->target_count);
    for (int u = 0; u < got_replan.residual_fleet.uav_count; ++u) {
        assert_int_not_equal(got_replan.residual_fleet.uavs[u].id, 10);  // lost
    }
    assert_int_equal(got_replan.plan.cost, res.plan->cost);
    assert_int_equal(got_replan.plan.covered, (int16_t)res.plan->covered);
    assert_int_equal(got_replan.plan.route_count, (int16_t)res.plan->route_count);
    assert_int_equal(got_replan.plan.plan_id, 2);  // after the mission's plan
    assert_int_equal(node.counters.replans_published, 5);
    // every message of the replan names its version; the mission had no frame
    assert_int_equal(got_replan.version, SVA_LCM_REPLAN_T_VERSION);
    assert_int_equal(got_replan.residual_fleet.version, SVA_LCM_FLEET_STATE_T_VERSION);
    assert_int_equal(got_replan.residual_mission.version, SVA_LCM_MISSION_T_VERSION);
    assert_int_equal(got_replan.plan.version, SVA_LCM_PLAN_T_VERSION);
    assert_int_equal(got_replan.residual_mission.frame.present, 0);
}

// Versions: a fleet or a mission of another version is refused (REJECT_VERSION, one log
// line naming both versions) and changes nothing; plans and status carry theirs.
static void test_versions(void** state)
{
    (void)state;
    node_setup(SVA_ALGO_SVA);
    make_inputs(5);
    assert_int_equal(sva_lcm_on_fleet(&node, fleet_buf, (size_t)enc_fleet()), SVA_LCM_ACCEPTED);
    assert_int_equal(sva_lcm_on_mission(&node, mission_buf, (size_t)enc_mission()),
                     SVA_LCM_ACCEPTED);
    decode_last_plan();
    assert_int_equal(got_plan.version, SVA_LCM_PLAN_T_VERSION);
    make_inputs(6);
    fleet.version = 1;
    expect_reject(true, fleet_buf, (size_t)enc_fleet(), SVA_LCM_REJECT_VERSION);
    assert_string_equal(last_log,
                        "rejected (version; further ones only counted in T_STATUS): T_FLEET: "
                        "fleet_state_t.version is 1, this node speaks version 2");
    mission.version = 3;
    expect_reject(false, mission_buf, (size_t)enc_mission(), SVA_LCM_REJECT_VERSION);
    assert_int_equal(log_lines[SVA_LCM_REJECT_VERSION], 1);  // logged once
    assert_int_equal(node.counters.rejected[SVA_LCM_REJECT_VERSION], 2);
    static sva_lcm_node_status_t s;
    assert_int_equal(sva_lcm_publish_status(&node, 1), SVA_OK);
    assert_int_equal(
        sva_lcm_node_status_t_decode(node.priv.status_buf, 0, SVA_LCM_STATUS_BYTES, &s),
        SVA_LCM_STATUS_BYTES);
    assert_int_equal(s.version, SVA_LCM_NODE_STATUS_T_VERSION);
    assert_int_equal(s.rejected[SVA_LCM_NODE_STATUS_T_REJECT_VERSION], 2);
    assert_string_equal(sva_lcm_reject_name(SVA_LCM_REJECT_VERSION), "version");
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
static void test_frame_round_trip(void** state)
{
    (void)state;
    node_setup(SVA_ALGO_SVA);
    make_inputs(5);
    assert_int_equal(sva_lcm_on_fleet(&node, fleet_buf, (size_t)enc_fleet()), SVA_LCM_ACCEPTED);

    make_inputs(6);
    set_frame();
    mission.frame.cell_cm = 5;
    expect_reject(false, mission_buf, (size_t)enc_mission(), SVA_LCM_REJECT_VALUE);
    assert_string_equal(last_log,
                        "rejected (value; further ones only counted in T_STATUS): T_MISSION: "
                        "frame.cell_m: must be >= 0.1, got 0.05");
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
    assert_int_equal(node.counters.rejected[SVA_LCM_REJECT_VALUE], 5);

    set_frame();
    assert_int_equal(sva_lcm_on_mission(&node, mission_buf, (size_t)enc_mission()),
                     SVA_LCM_ACCEPTED);
    assert_int_equal(plans_seen, 1);
    static sva_lcm_event_t e;
    memset(&e, 0, sizeof e);
    e.version = SVA_LCM_EVENT_T_VERSION;
    e.seq = 1;
    e.type = SVA_LCM_EVENT_T_TYPE_CLOCK;
    e.at_ticks = 2;
    assert_int_equal(send_event(&e), SVA_LCM_ACCEPTED);
    assert_int_equal(got_replan.accepted, 1);
    assert_memory_equal(&got_replan.residual_mission.frame, &mission.frame, sizeof mission.frame);
    // the same mission without its frame is a change: it replans
    memset(&mission.frame, 0, sizeof mission.frame);
    assert_int_equal(sva_lcm_on_mission(&node, mission_buf, (size_t)enc_mission()),
                     SVA_LCM_ACCEPTED);
    assert_int_equal(plans_seen, 2);
    assert_int_equal(send_event(&e), SVA_LCM_ACCEPTED);
    assert_int_equal(got_replan.residual_mission.frame.present, 0);
}

// fleet_reports: while a live mission runs, a fleet message is a report through the
// core's rule (sva_live_report). A UAV reported unavailable becomes uav_lost, one whose
// fuel is below its route's need a fuel event, one off its track by more than the
// tolerance a position event, each answered by one replan
// (event_seq -1) and no plan from scratch; a report that contradicts nothing publishes nothing.
static void test_fleet_reports(void** state)
{
    (void)state;
    node_setup(SVA_ALGO_SVA);
    node.fleet_reports = true;
    make_inputs(4);
    assert_int_equal(sva_lcm_on_fleet(&node, fleet_buf, (size_t)enc_fleet()), SVA_LCM_ACCEPTED);
    assert_int_equal(sva_lcm_on_mission(&node, mission_buf, (size_t)enc_mission()),
                     SVA_LCM_ACCEPTED);
    assert_int_equal(plans_seen, 1);
    decode_last_plan();
    int busy = -1;  // a UAV with a route, other than UAV 11
    for (int r = 0; r < got_plan.route_count; ++r) {
        if ((got_plan.routes[r].target_count > 0) && (got_plan.routes[r].uav_id != 11) &&
            (busy < 0)) {
            busy = r;
        }
    }
    assert_true(busy >= 0);
    const int32_t busy_id = got_plan.routes[busy].uav_id;

    fleet.uavs[1].health = SVA_LCM_UAV_STATE_T_HEALTH_UNAVAILABLE;  // UAV 11
    assert_int_equal(sva_lcm_on_fleet(&node, fleet_buf, (size_t)enc_fleet()), SVA_LCM_ACCEPTED);
    assert_int_equal(plans_seen, 1);
    assert_int_equal(replans_seen, 1);
    assert_int_equal(got_replan.event_seq, -1);
    assert_int_equal(got_replan.event_type, SVA_LCM_EVENT_T_TYPE_UAV_LOST);
    assert_int_equal(got_replan.accepted, 1);
    assert_int_equal(got_replan.revision, 1);
    assert_int_equal(got_replan.residual_fleet.uav_count, 4);
    for (int u = 0; u < got_replan.residual_fleet.uav_count; ++u) {
        assert_int_not_equal(got_replan.residual_fleet.uavs[u].id, 11);
    }

    fleet.uavs[busy_id - 10].fuel = 1;  // ids are 10 + index
    assert_int_equal(sva_lcm_on_fleet(&node, fleet_buf, (size_t)enc_fleet()), SVA_LCM_ACCEPTED);
    assert_int_equal(replans_seen, 2);
    assert_int_equal(got_replan.event_type, SVA_LCM_EVENT_T_TYPE_FUEL);
    assert_int_equal(got_replan.revision, 2);
    int found = 0;
    for (int u = 0; u < got_replan.residual_fleet.uav_count; ++u) {
        if (got_replan.residual_fleet.uavs[u].id == busy_id) {
            assert_int_equal(got_replan.residual_fleet.uavs[u].fuel, 1);
            found = 1;
        }
    }
    assert_true(found);
    // the same report again: unchanged; more fuel than any route needs: nothing to do
    assert_int_equal(sva_lcm_on_fleet(&node, fleet_buf, (size_t)enc_fleet()), SVA_LCM_UNCHANGED);
    fleet.uavs[busy_id - 10].fuel = 200;
    assert_int_equal(sva_lcm_on_fleet(&node, fleet_buf, (size_t)enc_fleet()), SVA_LCM_ACCEPTED);
    assert_int_equal(replans_seen, 2);
    assert_int_equal(plans_seen, 1);
    assert_int_equal(node.priv.live.revision, 2);

    // UAV 10 off its track: within the tolerance (2 cells) nothing; 3 cells off, a
    // position event: it flies on from the reported cell with the reported fuel.
    assert_int_equal(node.track_tolerance_cells, SVA_LCM_TRACK_TOLERANCE_DEFAULT);
    const int32_t x0 = fleet.uavs[0].x;
    fleet.uavs[0].x = x0 + 1;
    fleet.uavs[0].y += 1;
    assert_int_equal(sva_lcm_on_fleet(&node, fleet_buf, (size_t)enc_fleet()), SVA_LCM_ACCEPTED);
    assert_int_equal(replans_seen, 2);
    fleet.uavs[0].x = x0 + 2;
    fleet.uavs[0].fuel -= 3;
    assert_int_equal(sva_lcm_on_fleet(&node, fleet_buf, (size_t)enc_fleet()), SVA_LCM_ACCEPTED);
    assert_int_equal(replans_seen, 3);
    assert_int_equal(got_replan.event_type, SVA_LCM_EVENT_T_TYPE_POSITION);
    assert_int_equal(got_replan.revision, 3);
    assert_int_equal(got_replan.residual_fleet.uavs[0].id, 10);
    assert_int_equal(got_replan.residual_fleet.uavs[0].x, x0 + 2);
    assert_int_equal(got_replan.residual_fleet.uavs[0].y, fleet.uavs[0].y);
    assert_int_equal(got_replan.residual_fleet.uavs[0].fuel, fleet.uavs[0].fuel);
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
    assert_int_equal(got_replan.plan.routes[0].uav_id, 10);
    fleet.uavs[0].y += (next_y > fleet.uavs[0].y) ? -1 : 1;
    assert_int_equal(sva_lcm_on_fleet(&node, fleet_buf, (size_t)enc_fleet()), SVA_LCM_ACCEPTED);
    assert_int_equal(replans_seen, 4);
    assert_int_equal(got_replan.event_type, SVA_LCM_EVENT_T_TYPE_POSITION);
}

static sva_lcm_verdict_t send_report(int32_t uav, int32_t at, int8_t health, int32_t x, int32_t y,
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
    assert_int_equal(sva_lcm_report_t_encode(buf, 0, (int)sizeof buf, &r), SVA_LCM_REPORT_BYTES);
    return sva_lcm_on_report(&node, buf, sizeof buf);
}

// Vehicle reports (REPORT): refused before a live mission, with another version, a
// field out of range or a wrong size, each counted and changing nothing; a report moves
// the clock to its tick (an earlier tick is taken as now) and the core's rule turns it
// into at most one event: an agreeing report publishes nothing, a lost vehicle a uav_lost
// replan (event_seq -1), the same vehicle heard again a uav_back at its reported cell.
static void test_vehicle_reports(void** state)
{
    (void)state;
    node_setup(SVA_ALGO_SVA);
    make_inputs(6);
    assert_int_equal(send_report(10, 0, 0, 0, 0, -1), SVA_LCM_REJECTED);
    assert_int_equal(node.last_reject, SVA_LCM_REJECT_VALUE);
    assert_non_null(strstr(last_log, "T_REPORT: no live mission"));
    assert_int_equal(sva_lcm_on_fleet(&node, fleet_buf, (size_t)enc_fleet()), SVA_LCM_ACCEPTED);
    assert_int_equal(sva_lcm_on_mission(&node, mission_buf, (size_t)enc_mission()),
                     SVA_LCM_ACCEPTED);
    assert_int_equal(plans_seen, 1);
    static sva_live_t before;
    memcpy(&before, &node.priv.live, sizeof before);
    const uint32_t values = node.counters.rejected[SVA_LCM_REJECT_VALUE];
    assert_int_equal(send_report(10, 0, 2, 0, 0, -1), SVA_LCM_REJECTED);
    assert_int_equal(send_report(10, -1, 0, 0, 0, -1), SVA_LCM_REJECTED);
    assert_int_equal(send_report(10, 0, 0, 40000, 0, -1), SVA_LCM_REJECTED);
    assert_int_equal(send_report(10, 0, 0, 0, 0, -2), SVA_LCM_REJECTED);
    assert_int_equal(node.counters.rejected[SVA_LCM_REJECT_VALUE], values + 4U);
    static uint8_t short_buf[SVA_LCM_REPORT_BYTES - 1];
    assert_int_equal(sva_lcm_on_report(&node, short_buf, sizeof short_buf), SVA_LCM_REJECTED);
    assert_int_equal(node.last_reject, SVA_LCM_REJECT_TRUNCATED);
    static uint8_t buf[SVA_LCM_REPORT_BYTES];
    sva_lcm_report_t r;
    memset(&r, 0, sizeof r);
    r.version = SVA_LCM_REPORT_T_VERSION + 1;
    assert_int_equal(sva_lcm_report_t_encode(buf, 0, (int)sizeof buf, &r), SVA_LCM_REPORT_BYTES);
    assert_int_equal(sva_lcm_on_report(&node, buf, sizeof buf), SVA_LCM_REJECTED);
    assert_int_equal(node.last_reject, SVA_LCM_REJECT_VERSION);
    assert_memory_equal(&before, &node.priv.live, sizeof before);
    assert_int_equal(replans_seen, 0);

    // Agreeing: UAV 10 where the model has it at tick 1, fuel unknown; the clock moves.
    int32_t x = 0;
    int32_t y = 0;
    int32_t fuel = 0;
    int32_t ready = 0;
    assert_true(sva_live_uav_at(&node.priv.live, 0, 1, &x, &y, &fuel, &ready));
    assert_int_equal(send_report(10, 1, 0, x, y, -1), SVA_LCM_ACCEPTED);
    assert_int_equal(node.priv.live.now_ticks, 1);
    assert_int_equal(replans_seen, 0);
    // An earlier tick is now; lost: a replan without UAV 11.
    assert_int_equal(send_report(11, 0, SVA_LCM_REPORT_T_HEALTH_LOST, 0, 0, -1), SVA_LCM_ACCEPTED);
    assert_int_equal(replans_seen, 1);
    assert_int_equal(got_replan.event_seq, -1);
    assert_int_equal(got_replan.event_type, SVA_LCM_EVENT_T_TYPE_UAV_LOST);
    assert_int_equal(got_replan.now_ticks, 1);
    for (int u = 0; u < got_replan.residual_fleet.uav_count; ++u) {
        assert_int_not_equal(got_replan.residual_fleet.uavs[u].id, 11);
    }
    // Silent again: nothing; heard again at (2, -3) with fuel 150: back there.
    assert_int_equal(send_report(11, 2, SVA_LCM_REPORT_T_HEALTH_LOST, 0, 0, -1), SVA_LCM_ACCEPTED);
    assert_int_equal(replans_seen, 1);
    assert_int_equal(send_report(11, 3, SVA_LCM_REPORT_T_HEALTH_OK, 2, -3, 150), SVA_LCM_ACCEPTED);
    assert_int_equal(replans_seen, 2);
    assert_int_equal(got_replan.event_type, SVA_LCM_EVENT_T_TYPE_UAV_BACK);
    assert_int_equal(got_replan.now_ticks, 3);
    int found = 0;
    for (int u = 0; u < got_replan.residual_fleet.uav_count; ++u) {
        const sva_lcm_uav_state_t* w = &got_replan.residual_fleet.uavs[u];
        if (w->id == 11) {
            assert_int_equal(w->x, 2);
            assert_int_equal(w->y, -3);
            assert_int_equal(w->fuel, 150);
            found = 1;
        }
    }
    assert_true(found);
    assert_int_equal(node.counters.report_rx, 11U);
    assert_int_equal(node.counters.reports_applied, 2U);
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

static void test_input_hook(void** state)
{
    (void)state;
    node_setup(SVA_ALGO_SVA);
    static hook_seen_t h;
    memset(&h, 0, sizeof h);
    node.input_hook = hook;
    node.input_hook_user = &h;
    make_inputs(8);
    assert_int_equal(sva_lcm_on_fleet(&node, fleet_buf, (size_t)enc_fleet()), SVA_LCM_ACCEPTED);
    assert_true((h.calls == 1) && (h.kind == SVA_LCM_INPUT_FLEET) && h.restarts);
    assert_int_equal(h.size, SVA_LCM_FLEET_BYTES);
    assert_int_equal(sva_lcm_on_mission(&node, mission_buf, (size_t)enc_mission()),
                     SVA_LCM_ACCEPTED);
    assert_true((h.calls == 2) && (h.kind == SVA_LCM_INPUT_MISSION) && h.restarts);
    assert_int_equal(h.answers_before, 0);  // before the plan went out
    assert_int_equal(plans_seen, 1);
    // unchanged and refused: not handed over
    assert_int_equal(sva_lcm_on_mission(&node, mission_buf, (size_t)enc_mission()),
                     SVA_LCM_UNCHANGED);
    assert_int_equal(sva_lcm_on_fleet(&node, fleet_buf, 7), SVA_LCM_REJECTED);
    static sva_lcm_event_t e;
    memset(&e, 0, sizeof e);
    e.version = SVA_LCM_EVENT_T_VERSION;
    e.type = SVA_LCM_EVENT_T_TYPE_UAV_LOST;
    e.uav_id = 99;  // unknown: refused, answered, not handed over
    e.at_ticks = 2;
    assert_int_equal(send_event(&e), SVA_LCM_REJECTED);
    assert_int_equal(h.calls, 2);
    e.uav_id = 10;
    assert_int_equal(send_event(&e), SVA_LCM_ACCEPTED);
    assert_true((h.calls == 3) && (h.kind == SVA_LCM_INPUT_EVENT) && !h.restarts);
    assert_int_equal(h.answers_before, 2);  // the plan and the refusal, not this replan
    assert_int_equal(replans_seen, 2);
    // a report that moves the clock is handed over (no answer: nothing applied)
    assert_int_equal(send_report(10, 5, SVA_LCM_REPORT_T_HEALTH_LOST, 0, 0, -1), SVA_LCM_ACCEPTED);
    assert_true((h.calls == 4) && (h.kind == SVA_LCM_INPUT_REPORT));
    assert_int_equal(replans_seen, 2);
    // the hook fails: nothing published, the node halted
    h.fail = -1;
    e.type = SVA_LCM_EVENT_T_TYPE_CLOCK;
    e.at_ticks = 6;
    assert_int_equal(send_event(&e), SVA_LCM_HALTED);
    assert_true(node.halted);
    assert_int_equal(replans_seen, 2);
    h.fail = 0;
    assert_int_equal(sva_lcm_on_fleet(&node, fleet_buf, (size_t)enc_fleet()), SVA_LCM_HALTED);
    assert_int_equal(h.calls, 5);
    assert_int_equal(node.counters.inputs_hooked, 4U);
}

static void test_zero_allocations_per_message(void** state)
{
    (void)state;
    node_setup(SVA_ALGO_SVA);
    make_inputs(100);
    assert_int_equal(sva_lcm_on_fleet(&node, fleet_buf, (size_t)enc_fleet()), SVA_LCM_ACCEPTED);
    assert_int_equal(sva_lcm_on_mission(&node, mission_buf, (size_t)enc_mission()),
                     SVA_LCM_ACCEPTED);
    // warm every logging path once
    (void)sva_lcm_on_fleet(&node, fleet_buf, 5);
    const int plans_before = plans_seen;

    // prove the counter counts
    alloc_count = 0;
    alloc_armed = 1;
    void* volatile p = malloc(16);
    alloc_armed = 0;
    free(p);
    assert_int_equal(alloc_count, 1);

    static uint8_t fb[200][SVA_LCM_FLEET_BYTES];
    static uint8_t mb[2][SVA_LCM_MISSION_BYTES];
    for (int i = 0; i < 200; ++i) {
        fleet.revision = 1000 + i;
        fleet.uavs[i % 5].fuel = 150 + i;
        assert_int_equal(sva_lcm_fleet_state_t_encode(fb[i], 0, SVA_LCM_FLEET_BYTES, &fleet),
                         SVA_LCM_FLEET_BYTES);
    }
    for (int i = 0; i < 2; ++i) {
        mission.revision = 2000 + i;
        mission.targets[0].need = 1 + i;
        assert_int_equal(sva_lcm_mission_t_encode(mb[i], 0, SVA_LCM_MISSION_BYTES, &mission),
                         SVA_LCM_MISSION_BYTES);
    }

    alloc_count = 0;
    alloc_armed = 1;
    for (int i = 0; i < 200; ++i) {
        (void)sva_lcm_on_fleet(&node, fb[i], SVA_LCM_FLEET_BYTES);
        (void)sva_lcm_on_mission(&node, mb[i % 2], SVA_LCM_MISSION_BYTES);
        (void)sva_lcm_on_fleet(&node, fb[i], SVA_LCM_FLEET_BYTES - 3);  // rejected
        assert_int_equal(sva_lcm_publish_status(&node, i), SVA_OK);
    }
    alloc_armed = 0;
    assert_int_equal(alloc_count, 0);
    assert_int_equal(plans_seen - plans_before, 400);

    // For the record: the whole memq path (memq copies every message: LCM's, not ours).
    lcm_t* lcm = lcm_create("memq://");
    assert_non_null(lcm);
    assert_int_equal(sva_lcm_node_init(&node, lcm, "Z_", SVA_ALGO_SVA), SVA_OK);
    assert_int_equal(sva_lcm_node_subscribe(&node), SVA_OK);
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
    assert_int_equal(node.counters.plans_published, 101);
    sva_lcm_node_unsubscribe(&node);
    lcm_destroy(lcm);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_encoded_sizes),
        cmocka_unit_test(test_channel_escape),
        cmocka_unit_test(test_init_arguments),
        cmocka_unit_test(test_memq_round_trip),
        cmocka_unit_test(test_every_algorithm),
        cmocka_unit_test(test_flow_certificate),
        cmocka_unit_test(test_unchanged_and_replan),
        cmocka_unit_test(test_unavailable_uav_gets_nothing),
        cmocka_unit_test(test_rejections_frame),
        cmocka_unit_test(test_rejections_counts_and_values),
        cmocka_unit_test(test_core_rejection_and_planner_limit),
        cmocka_unit_test(test_plan_too_large),
        cmocka_unit_test(test_status),
        cmocka_unit_test(test_live_events),
        cmocka_unit_test(test_versions),
        cmocka_unit_test(test_frame_round_trip),
        cmocka_unit_test(test_fleet_reports),
        cmocka_unit_test(test_vehicle_reports),
        cmocka_unit_test(test_input_hook),
        cmocka_unit_test(test_zero_allocations_per_message),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
