// test_can_live.c -- the CAN node's live mission (port/can/node/can_live.c) over the
// in-memory loopback bus, no VM needed: the node side sends its plans with
// sva_can_sender, the bridge side receives them with sva_can_receiver (ACKs) and
// sends the flight stack's frames (SVA_MISSION_CLOCK, SVA_VEHICLE_STATUS,
// SVA_VEHICLE_FUEL). A loss frame makes the node send a plan without that UAV; a clock
// frame past a window start makes the visit under way (and, the plan in force kept,
// sends nothing); a position off the track is a position event; a fuel reading is an
// event only when the route in force cannot be flown on it; a BEGIN of another protocol
// version is refused with NACK BAD_VERSION.
#include <stddef.h>
#include <stdint.h>
#include <string.h>

#include "sva_unity.h"

#include "can_live.h"
#include "sva/sva_live.h"
#include "sva/sva_can.h"
#include "sva/sva_can_transport.h"

static sva_can_loopback_t bus;
static sva_can_transport_t node_tp;
static sva_can_transport_t bridge_tp;
static sva_can_sender_t sender;
static sva_can_receiver_t receiver;
static sva_can_live_t node;
static sva_mission_t mission;
static uint32_t now_ms;
static uint8_t bridge_counter;

#define SETTLE_MS 200u

// UAVs 1 and 2 at the depot; T1 at (5, 0) and T2 at (0, 5) in [10, 20]; T3 at (3, 3) in
// [40, 50]; one UAV each.
void setUp(void)
{
    sva_mission_init(&mission);
    mission.uav_count = 2U;
    mission.uavs[0] = (sva_uav_t){.id = 1, .x = 0, .y = 0, .fuel = 100};
    mission.uavs[1] = (sva_uav_t){.id = 2, .x = 0, .y = 0, .fuel = 100};
    mission.target_count = 3U;
    mission.targets[0] = (sva_target_t){1, 5, 0, 10, 20, 1};
    mission.targets[1] = (sva_target_t){2, 0, 5, 10, 20, 1};
    mission.targets[2] = (sva_target_t){3, 3, 3, 40, 50, 1};
    sva_can_loopback_init(&bus);
    TEST_ASSERT_EQUAL_INT(SVA_CAN_OK, sva_can_loopback_transport(&bus, 0, &node_tp));
    TEST_ASSERT_EQUAL_INT(SVA_CAN_OK, sva_can_loopback_transport(&bus, 1, &bridge_tp));
    TEST_ASSERT_EQUAL_INT(SVA_CAN_OK, sva_can_sender_init(&sender, &node_tp, NULL));
    TEST_ASSERT_EQUAL_INT(SVA_CAN_OK, sva_can_receiver_init(&receiver, &bridge_tp, 0));
    memset(&node, 0, sizeof node);
    node.track_tolerance_cells = SVA_CAN_LIVE_TRACK_TOLERANCE;
    now_ms = 1000u;
    bridge_counter = 0u;
    char err[200];
    TEST_ASSERT_EQUAL_INT(0, sva_can_live_start(&node, &mission, SVA_ALGO_SVA, err, sizeof err));
    TEST_ASSERT_EQUAL_INT(SVA_CAN_OK, sva_can_sender_start(&sender, &node.wire, now_ms));
}

// Moves every frame across until the bus is quiet, as the node's loop does: the
// sender's frames to the receiver; the bridge's frames to the sender (ACKs) or, decoded,
// to the live mission; replans after the settle time, a changed plan sent.
static void pump(void)
{
    for (int round = 0; round < 64; ++round) {
        sva_can_frame_t f;
        int moved = 0;
        TEST_ASSERT_EQUAL_INT(SVA_CAN_OK, sva_can_sender_poll(&sender, now_ms));
        while (sva_can_loopback_take(&bus, 1, &f) == SVA_CAN_OK) {
            const sva_can_status_t st = sva_can_receiver_on_frame(&receiver, &f, now_ms);
            TEST_ASSERT_TRUE((st == SVA_CAN_OK) || (st == SVA_CAN_APPLIED));
            moved = 1;
        }
        while (sva_can_loopback_take(&bus, 0, &f) == SVA_CAN_OK) {
            sva_can_msg_t m;
            moved = 1;
            if (sva_can_sender_on_frame(&sender, &f, now_ms) != SVA_CAN_IGNORED) {
                continue;
            }
            TEST_ASSERT_EQUAL_INT(SVA_CAN_OK, sva_can_decode(&f, &m));
            (void)sva_can_live_on_msg(&node, &m, now_ms);
        }
        now_ms += 50u;
        const int changed = sva_can_live_poll(&node, now_ms, SETTLE_MS);
        TEST_ASSERT_TRUE(changed >= 0);
        if (changed > 0) {
            TEST_ASSERT_EQUAL_INT(SVA_CAN_OK, sva_can_sender_start(&sender, &node.wire, now_ms));
            moved = 1;
        }
        if (!moved && (node.pending == 0u) && (sender.state != SVA_CAN_TX_SENDING) &&
            (sender.state != SVA_CAN_TX_WAIT_ACK)) {
            return;
        }
    }
    SVA_TEST_FAIL("the bus never went quiet");
}

static void bridge_send(sva_can_msg_t m)
{
    sva_can_frame_t f;
    m.counter = bridge_counter;
    bridge_counter = (uint8_t)((bridge_counter + 1u) & 0x0Fu);
    TEST_ASSERT_EQUAL_INT(SVA_CAN_OK, sva_can_encode(&m, &f));
    TEST_ASSERT_EQUAL_INT(SVA_CAN_OK, bridge_tp.send(bridge_tp.ctx, &f));
}

static void send_clock(uint32_t tick)
{
    sva_can_msg_t m;
    memset(&m, 0, sizeof m);
    m.kind = SVA_CAN_MSG_MISSION_CLOCK;
    m.u.clock.tick = tick;
    bridge_send(m);
}

static void send_status(uint8_t uav, uint8_t state, int16_t x, int16_t y)
{
    sva_can_msg_t m;
    memset(&m, 0, sizeof m);
    m.kind = SVA_CAN_MSG_VEHICLE_STATUS;
    m.u.vehicle.uav_id = uav;
    m.u.vehicle.state = state;
    m.u.vehicle.x = x;
    m.u.vehicle.y = y;
    bridge_send(m);
}

static void send_fuel(uint8_t uav, uint32_t fuel)
{
    sva_can_msg_t m;
    memset(&m, 0, sizeof m);
    m.kind = SVA_CAN_MSG_VEHICLE_FUEL;
    m.u.fuel.uav_id = uav;
    m.u.fuel.fuel = fuel;
    bridge_send(m);
}

static int items_of(const sva_can_plan_t* p, uint8_t uav, uint16_t target)
{
    int n = 0;
    for (uint16_t i = 0; i < p->item_count; ++i) {
        n += ((p->items[i].uav_id == uav) && ((target == 0u) || (p->items[i].target_id == target)))
                 ? 1
                 : 0;
    }
    return n;
}

static sva_target_state_t state_of(int32_t id)
{
    for (uint16_t i = 0; i < node.live.mission.target_count; ++i) {
        if (node.live.mission.targets[i].id == id) {
            return (sva_target_state_t)node.live.target_state[i];
        }
    }
    SVA_TEST_FAIL("no target %d", (int)id);
    return SVA_TARGET_STATE_COUNT_;
}

void test_live_mission_over_loopback(void)
{
    pump();
    TEST_ASSERT_TRUE(receiver.has_active);
    TEST_ASSERT_EQUAL_INT(1, receiver.stats.plans_applied);
    TEST_ASSERT_EQUAL_INT(1, receiver.active.plan_id);
    TEST_ASSERT_EQUAL_INT(3, items_of(&receiver.active, 1, 0) + items_of(&receiver.active, 2, 0));
    TEST_ASSERT_EQUAL_INT(1, items_of(&receiver.active, 2, 0) > 0);

    // A clock frame past the windows' start: both visits under way. The plan in force
    // stays: nothing is sent.
    send_clock(12u);
    pump();
    TEST_ASSERT_EQUAL_INT(12, node.live.now_ticks);
    TEST_ASSERT_EQUAL_INT(SVA_TARGET_UNDER_WAY, state_of(1));
    TEST_ASSERT_EQUAL_INT(SVA_TARGET_UNDER_WAY, state_of(2));
    TEST_ASSERT_EQUAL_INT(1, node.stats.replans);
    TEST_ASSERT_EQUAL_INT(1, node.stats.unchanged);
    TEST_ASSERT_EQUAL_INT(1, receiver.stats.plans_applied);

    // Frames that agree with the flight model change nothing: UAV 1 on T1's cell, its
    // fuel as the model has it (5 cells flown).
    send_status(1, SVA_CAN_VEHICLE_BUSY, 5, 0);
    send_fuel(1, 95u);
    pump();
    TEST_ASSERT_EQUAL_INT(1, node.stats.events_applied);

    // A loss frame: UAV 2 leaves service during its visit of T2 (lost); the node sends a
    // plan without it.
    send_status(2, SVA_CAN_VEHICLE_UNAVAILABLE, 0, 5);
    pump();
    TEST_ASSERT_EQUAL_INT(SVA_TARGET_LOST, state_of(2));
    TEST_ASSERT_EQUAL_INT(2, receiver.stats.plans_applied);
    TEST_ASSERT_EQUAL_INT(2, receiver.active.plan_id);
    TEST_ASSERT_EQUAL_INT(0, items_of(&receiver.active, 2, 0));
    TEST_ASSERT_EQUAL_INT(1, items_of(&receiver.active, 1, 1));  // its visit under way stays
    TEST_ASSERT_EQUAL_INT(1, items_of(&receiver.active, 1, 3));  // and it takes T3
    TEST_ASSERT_EQUAL_INT(1, receiver.active.route_count);
    TEST_ASSERT_EQUAL_INT(1, sva_can_live_in_service(&node));

    // UAV 1 blown off T1's cell during the visit: a position event; T1 is lost too.
    send_status(1, SVA_CAN_VEHICLE_BUSY, 5, 4);
    pump();
    TEST_ASSERT_EQUAL_INT(SVA_TARGET_LOST, state_of(1));
    TEST_ASSERT_EQUAL_INT(3, receiver.stats.plans_applied);
    TEST_ASSERT_EQUAL_INT(0, items_of(&receiver.active, 1, 1));
    TEST_ASSERT_EQUAL_INT(1, items_of(&receiver.active, 1, 3));
    int32_t x = 0;
    int32_t y = 0;
    int32_t fuel = 0;
    int32_t ready = 0;
    TEST_ASSERT_TRUE(sva_live_uav_at(&node.live, 0U, 12, &x, &y, &fuel, &ready));
    TEST_ASSERT_EQUAL_INT(5, x);
    TEST_ASSERT_EQUAL_INT(4, y);

    // UAV 2 back where it says, with the fuel last heard; frames for unknown UAVs and a
    // clock going back are refused and change nothing.
    send_fuel(2, 60u);
    send_status(2, SVA_CAN_VEHICLE_AVAILABLE, 1, 1);
    send_status(9, SVA_CAN_VEHICLE_AVAILABLE, 1, 1);
    send_clock(5u);
    pump();
    TEST_ASSERT_EQUAL_INT(2, sva_can_live_in_service(&node));
    TEST_ASSERT_TRUE(sva_live_uav_at(&node.live, 1U, 12, &x, &y, &fuel, &ready));
    TEST_ASSERT_EQUAL_INT(60, fuel);
    TEST_ASSERT_EQUAL_INT(2, node.stats.events_refused);
    TEST_ASSERT_EQUAL_INT(12, node.live.now_ticks);
    TEST_ASSERT_EQUAL_INT(0, sender.stats.nacks);
}

// A fuel frame goes through the core's report rule (SPEC 12.3, "Vehicle reports"), as
// every other node's readings do: a reading below the model's but enough for the route in
// force is no event; one below what the route still needs is a fuel event.
void test_fuel_frames_follow_the_report_rule(void)
{
    pump();
    send_clock(12u);
    pump();
    TEST_ASSERT_EQUAL_INT(1, node.stats.events_applied);  // the clock
    int32_t x = 0;
    int32_t y = 0;
    int32_t fuel = 0;
    int32_t ready = 0;
    TEST_ASSERT_TRUE(sva_live_uav_at(&node.live, 0U, 12, &x, &y, &fuel, &ready));
    TEST_ASSERT_EQUAL_INT(95, fuel);  // 5 cells flown to T1
    send_fuel(1, 94u);
    pump();
    TEST_ASSERT_EQUAL_INT(1, node.stats.events_applied);
    TEST_ASSERT_TRUE(sva_live_uav_at(&node.live, 0U, 12, &x, &y, &fuel, &ready));
    TEST_ASSERT_EQUAL_INT(95, fuel);
    // T1 at (5, 0): the way home alone needs 5.
    send_fuel(1, 3u);
    pump();
    TEST_ASSERT_EQUAL_INT(2, node.stats.events_applied);
    TEST_ASSERT_TRUE(sva_live_uav_at(&node.live, 0U, 12, &x, &y, &fuel, &ready));
    TEST_ASSERT_EQUAL_INT(3, fuel);
}

// A receiver refuses a BEGIN of another protocol version: NACK BAD_VERSION back on
// the bus, nothing applied; the node's sender sees the NACK.
void test_other_version_refused(void)
{
    pump();
    sva_can_msg_t m;
    sva_can_frame_t f;
    memset(&m, 0, sizeof m);
    m.kind = SVA_CAN_MSG_PLAN_BEGIN;
    m.u.begin.version = 1;  // the protocol before SVA_MISSION_CLOCK
    m.u.begin.plan_id = 77;
    m.u.begin.item_count = 1;
    m.u.begin.plan_status = SVA_CAN_PLAN_COMPLETE;
    TEST_ASSERT_EQUAL_INT(SVA_CAN_OK, sva_can_encode(&m, &f));
    TEST_ASSERT_EQUAL_INT(SVA_CAN_ERR_VERSION, sva_can_receiver_on_frame(&receiver, &f, now_ms));
    TEST_ASSERT_EQUAL_INT(1, receiver.stats.bad_version);
    TEST_ASSERT_EQUAL_INT(1, receiver.active.plan_id);
    TEST_ASSERT_EQUAL_INT(SVA_CAN_OK, sva_can_loopback_take(&bus, 0, &f));
    sva_can_msg_t ack;
    TEST_ASSERT_EQUAL_INT(SVA_CAN_OK, sva_can_decode(&f, &ack));
    TEST_ASSERT_EQUAL_INT(SVA_CAN_MSG_PLAN_ACK, ack.kind);
    TEST_ASSERT_EQUAL_INT(SVA_CAN_ACK_BAD_VERSION, ack.u.ack.result);
    TEST_ASSERT_EQUAL_INT(77, ack.u.ack.plan_id);
}
