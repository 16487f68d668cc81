// State machine tests over the loopback transport: a clean transfer, every kind of
// corrupted traffic (rejected, counted, active plan unchanged), timeouts, retries,
// aborts, transport back-pressure, clock wrap-around and core plan conversion.
#include <stddef.h>
#include <stdint.h>
#include <string.h>

#include "unity.h"

#include "sva/sva.h"
#include "sva/sva_can.h"
#include "sva/sva_can_transport.h"

// Large structs live in static storage, as on firmware.
static sva_can_loopback_t bus;
static sva_can_transport_t tp_tx;  // endpoint 0: the planner
static sva_can_transport_t tp_rx;  // endpoint 1: the bridge
static sva_can_sender_t sender;
static sva_can_receiver_t receiver;
static sva_can_plan_t plan_a;
static sva_can_plan_t plan_b;
static sva_can_plan_t snapshot;

static void make_plan(sva_can_plan_t* p, uint16_t id, uint16_t n, int salt)
{
    uint16_t i;
    memset(p, 0, sizeof *p);
    p->plan_id = id;
    p->algorithm = 0;
    p->plan_status = SVA_CAN_PLAN_COMPLETE;
    p->route_count = 5;
    p->item_count = n;
    for (i = 0; i < n; ++i) {
        p->items[i].uav_id = (uint8_t)(1 + (i % 5));
        p->items[i].target_id = (uint16_t)(100 + i);
        p->items[i].x = (int16_t)(i * 37 - 500 + salt);
        p->items[i].y = (int16_t)(-(i * 11) + salt);
        p->items[i].arrive_by_ticks = (uint32_t)(10 * i + 5);
        p->items[i].hold_until_ticks = (uint32_t)(10 * i + 9 + salt);
    }
}

void setUp(void)
{
    sva_can_loopback_init(&bus);
    TEST_ASSERT_EQUAL_INT(SVA_CAN_OK, sva_can_loopback_transport(&bus, 0, &tp_tx));
    TEST_ASSERT_EQUAL_INT(SVA_CAN_OK, sva_can_loopback_transport(&bus, 1, &tp_rx));
    TEST_ASSERT_EQUAL_INT(SVA_CAN_OK, sva_can_sender_init(&sender, &tp_tx, NULL));
    TEST_ASSERT_EQUAL_INT(SVA_CAN_OK, sva_can_receiver_init(&receiver, &tp_rx, 1000));
    make_plan(&plan_a, 1, 25, 0);
    make_plan(&plan_b, 2, 40, 3);
}

static void assert_plans_equal(const sva_can_plan_t* a, const sva_can_plan_t* b)
{
    uint16_t i;
    TEST_ASSERT_EQUAL_INT(b->plan_id, a->plan_id);
    TEST_ASSERT_EQUAL_INT(b->algorithm, a->algorithm);
    TEST_ASSERT_EQUAL_INT(b->plan_status, a->plan_status);
    TEST_ASSERT_EQUAL_INT(b->route_count, a->route_count);
    TEST_ASSERT_EQUAL_INT(b->item_count, a->item_count);
    for (i = 0; i < a->item_count; ++i) {
        TEST_ASSERT_EQUAL_INT(b->items[i].uav_id, a->items[i].uav_id);
        TEST_ASSERT_EQUAL_INT(b->items[i].target_id, a->items[i].target_id);
        TEST_ASSERT_EQUAL_INT(b->items[i].x, a->items[i].x);
        TEST_ASSERT_EQUAL_INT(b->items[i].y, a->items[i].y);
        TEST_ASSERT_EQUAL_INT(b->items[i].arrive_by_ticks, a->items[i].arrive_by_ticks);
        TEST_ASSERT_EQUAL_INT(b->items[i].hold_until_ticks, a->items[i].hold_until_ticks);
    }
}

// Delivers the bridge's answers (ACK/NACK) to the sender.
static void deliver_acks(uint32_t now)
{
    sva_can_frame_t f;
    while (sva_can_loopback_take(&bus, 0, &f) == SVA_CAN_OK) {
        sva_can_status_t st = sva_can_sender_on_frame(&sender, &f, now);
        TEST_ASSERT_TRUE(st == SVA_CAN_OK || st == SVA_CAN_IGNORED);
    }
}

// Moves every queued planner frame to the receiver, collecting their statuses.
static int deliver_frames(uint32_t now, sva_can_status_t* last)
{
    sva_can_frame_t f;
    int n = 0;
    while (sva_can_loopback_take(&bus, 1, &f) == SVA_CAN_OK) {
        *last = sva_can_receiver_on_frame(&receiver, &f, now);
        ++n;
    }
    return n;
}

// Applies plan_a cleanly: the baseline that corrupt traffic must not disturb.
static void apply_plan_a(void)
{
    sva_can_status_t last = SVA_CAN_OK;
    TEST_ASSERT_EQUAL_INT(SVA_CAN_OK, sva_can_sender_start(&sender, &plan_a, 0));
    TEST_ASSERT_EQUAL_INT(SVA_CAN_TX_WAIT_ACK, sender.state);
    TEST_ASSERT_EQUAL_INT(2 * 25 + 2, deliver_frames(1, &last));
    TEST_ASSERT_EQUAL_INT(SVA_CAN_APPLIED, last);
    deliver_acks(2);
    TEST_ASSERT_EQUAL_INT(SVA_CAN_TX_DONE, sender.state);
    TEST_ASSERT_TRUE(receiver.has_active);
    assert_plans_equal(&receiver.active, &plan_a);
    snapshot = receiver.active;
}

void test_clean_transfer(void)
{
    apply_plan_a();
    TEST_ASSERT_EQUAL_INT(1, receiver.stats.plans_applied);
    TEST_ASSERT_EQUAL_INT(1, receiver.stats.acks_sent);
    TEST_ASSERT_EQUAL_INT(52, sender.stats.frames_sent);
    TEST_ASSERT_EQUAL_INT(1, sender.stats.attempts);
    // A second plan replaces the first.
    {
        sva_can_status_t last = SVA_CAN_OK;
        TEST_ASSERT_EQUAL_INT(SVA_CAN_OK, sva_can_sender_start(&sender, &plan_b, 10));
        deliver_frames(11, &last);
        TEST_ASSERT_EQUAL_INT(SVA_CAN_APPLIED, last);
        assert_plans_equal(&receiver.active, &plan_b);
    }
}

typedef enum {
    CORRUPT_CRC,        // one bit flipped in an ITEM
    CORRUPT_DROP,       // one ITEM lost: counter jump
    CORRUPT_SHORT_DLC,  // an ITEM_TIME with DLC 5
    CORRUPT_SWAP,       // ITEM_TIME before its ITEM (counters re-stamped: order is the only fault)
    CORRUPT_MISSING,    // a whole item pair left out (counters re-stamped): COMMIT too early
    CORRUPT_TAMPER,     // a coordinate changed with a valid CRC-8 and counter: CRC-32 catches it
    CORRUPT_DUP_ITEM,   // an ITEM repeated (re-stamped)
    CORRUPT_BAD_VALUE,  // arrive_by >= hold_until with valid CRC-8
} corruption_t;

static void restamp(sva_can_frame_t* f, uint8_t counter)
{
    f->data[0] = (uint8_t)((f->data[0] & 0xF0u) | (counter & 0x0Fu));
    f->data[7] = sva_can_frame_crc8(f->id, f->data);
}

// Sends plan_b through a mutator and returns the receiver's worst status.
static sva_can_status_t send_corrupted(corruption_t kind, uint32_t now)
{
    static sva_can_frame_t frames[2 * SVA_CAN_MAX_ITEMS + 2];
    size_t n = 0;
    size_t i;
    size_t out = 0;
    uint8_t counter;
    sva_can_frame_t f;
    sva_can_status_t worst = SVA_CAN_OK;
    TEST_ASSERT_EQUAL_INT(SVA_CAN_OK, sva_can_sender_start(&sender, &plan_b, now));
    while (sva_can_loopback_take(&bus, 1, &f) == SVA_CAN_OK) {
        if (f.id != SVA_CAN_ID_PLAN_ABORT) {  // a superseded earlier attempt's ABORT
            frames[n++] = f;
        }
    }
    TEST_ASSERT_EQUAL_INT(2 * 40 + 2, n);
    counter = (uint8_t)(frames[0].data[0] & 0x0Fu);
    switch (kind) {
    case CORRUPT_CRC:
        frames[7].data[3] ^= 0x10u;
        break;
    case CORRUPT_DROP:
        memmove(&frames[5], &frames[6], (n - 6) * sizeof frames[0]);
        --n;
        break;
    case CORRUPT_SHORT_DLC:
        frames[4].dlc = 5;
        break;
    case CORRUPT_SWAP: {
        const sva_can_frame_t t = frames[3];
        frames[3] = frames[4];
        frames[4] = t;
        break;
    }
    case CORRUPT_MISSING:
        memmove(&frames[9], &frames[11], (n - 11) * sizeof frames[0]);
        n -= 2;
        break;
    case CORRUPT_TAMPER:
        frames[9].data[3] ^= 0x01u;  // x of item 4
        break;
    case CORRUPT_DUP_ITEM:
        memmove(&frames[4], &frames[3], (n - 3) * sizeof frames[0]);
        ++n;
        break;
    case CORRUPT_BAD_VALUE:
        frames[6].data[1] = 0xFF;  // arrive_by of item 2 becomes huge
        frames[6].data[2] = 0xFF;
        frames[6].data[3] = 0xFF;
        break;
    default:
        TEST_FAIL();
    }
    if (kind != CORRUPT_CRC && kind != CORRUPT_DROP && kind != CORRUPT_SHORT_DLC) {
        for (i = 0; i < n; ++i) {
            restamp(&frames[i], (uint8_t)(counter + i));
        }
    }
    for (i = 0; i < n; ++i) {
        const sva_can_status_t st = sva_can_receiver_on_frame(&receiver, &frames[i], now + 1);
        TEST_ASSERT_TRUE(st != SVA_CAN_APPLIED);
        if ((st < 0) && (worst == SVA_CAN_OK)) {
            worst = st;
        }
        ++out;
    }
    (void)out;
    return worst;
}

static void check_corruption(corruption_t kind, sva_can_status_t expect, const uint32_t* counter)
{
    const uint32_t before = *counter;
    const uint32_t nacks = receiver.stats.nacks_sent;
    const sva_can_status_t st = send_corrupted(kind, 100);
    TEST_ASSERT_EQUAL_INT(expect, st);
    TEST_ASSERT_TRUE(*counter > before);
    TEST_ASSERT_TRUE(receiver.stats.nacks_sent > nacks);  // the sender hears why
    TEST_ASSERT_EQUAL_INT(1, receiver.stats.plans_applied);
    assert_plans_equal(&receiver.active, &snapshot);  // never changed by corrupt traffic
}

void test_corruption_bad_crc(void)
{
    apply_plan_a();
    check_corruption(CORRUPT_CRC, SVA_CAN_ERR_CRC, &receiver.stats.bad_crc);
}

void test_corruption_counter_jump(void)
{
    apply_plan_a();
    check_corruption(CORRUPT_DROP, SVA_CAN_ERR_COUNTER, &receiver.stats.counter_jumps);
}

void test_corruption_short_dlc(void)
{
    apply_plan_a();
    check_corruption(CORRUPT_SHORT_DLC, SVA_CAN_ERR_DLC, &receiver.stats.bad_dlc);
}

void test_corruption_item_out_of_order(void)
{
    apply_plan_a();
    check_corruption(CORRUPT_SWAP, SVA_CAN_ERR_SEQUENCE, &receiver.stats.out_of_order);
    check_corruption(CORRUPT_DUP_ITEM, SVA_CAN_ERR_SEQUENCE, &receiver.stats.out_of_order);
}

void test_corruption_item_missing(void)
{
    apply_plan_a();
    check_corruption(CORRUPT_MISSING, SVA_CAN_ERR_SEQUENCE, &receiver.stats.out_of_order);
}

void test_corruption_commit_crc_mismatch(void)
{
    apply_plan_a();
    check_corruption(CORRUPT_TAMPER, SVA_CAN_ERR_PLAN_CRC, &receiver.stats.plan_crc_mismatch);
}

void test_corruption_bad_value(void)
{
    apply_plan_a();
    check_corruption(CORRUPT_BAD_VALUE, SVA_CAN_ERR_VALUE, &receiver.stats.bad_value);
}

void test_frames_without_begin_are_rejected(void)
{
    sva_can_frame_t f;
    sva_can_status_t last = SVA_CAN_OK;
    size_t i = 0;
    apply_plan_a();
    TEST_ASSERT_EQUAL_INT(SVA_CAN_OK, sva_can_sender_start(&sender, &plan_b, 50));
    TEST_ASSERT_EQUAL_INT(SVA_CAN_OK, sva_can_loopback_take(&bus, 1, &f));  // BEGIN lost
    while (sva_can_loopback_take(&bus, 1, &f) == SVA_CAN_OK) {
        last = sva_can_receiver_on_frame(&receiver, &f, 51);
        TEST_ASSERT_EQUAL_INT(SVA_CAN_ERR_SEQUENCE, last);
        ++i;
    }
    TEST_ASSERT_EQUAL_INT(81, i);
    TEST_ASSERT_EQUAL_INT(81, receiver.stats.out_of_order);
    assert_plans_equal(&receiver.active, &snapshot);
}

void test_receiver_timeout(void)
{
    sva_can_frame_t f;
    int i;
    apply_plan_a();
    TEST_ASSERT_EQUAL_INT(SVA_CAN_OK, sva_can_sender_start(&sender, &plan_b, 100));
    for (i = 0; i < 20; ++i) {  // half the transfer arrives
        TEST_ASSERT_EQUAL_INT(SVA_CAN_OK, sva_can_loopback_take(&bus, 1, &f));
        TEST_ASSERT_EQUAL_INT(SVA_CAN_OK, sva_can_receiver_on_frame(&receiver, &f, 100));
    }
    TEST_ASSERT_EQUAL_INT(SVA_CAN_OK, sva_can_receiver_poll(&receiver, 1099));
    TEST_ASSERT_EQUAL_INT(SVA_CAN_ERR_TIMEOUT, sva_can_receiver_poll(&receiver, 1100));
    TEST_ASSERT_EQUAL_INT(1, receiver.stats.timeouts);
    // The rest arrives late: nothing of it applies.
    while (sva_can_loopback_take(&bus, 1, &f) == SVA_CAN_OK) {
        TEST_ASSERT_EQUAL_INT(SVA_CAN_ERR_SEQUENCE, sva_can_receiver_on_frame(&receiver, &f, 1200));
    }
    TEST_ASSERT_EQUAL_INT(1, receiver.stats.plans_applied);
    assert_plans_equal(&receiver.active, &snapshot);
}

void test_sender_ack_timeout_retries_then_aborts(void)
{
    sva_can_frame_t f;
    sva_can_msg_t m;
    uint32_t t;
    TEST_ASSERT_EQUAL_INT(SVA_CAN_OK, sva_can_sender_start(&sender, &plan_a, 0));
    TEST_ASSERT_EQUAL_INT(SVA_CAN_TX_WAIT_ACK, sender.state);
    // No bridge answers. Attempts 2 and 3 go out after each ACK timeout (250 ms).
    for (t = 0; t <= 1000; t += 10) {
        TEST_ASSERT_EQUAL_INT(SVA_CAN_OK, sva_can_sender_poll(&sender, t));
    }
    TEST_ASSERT_EQUAL_INT(3, sender.stats.attempts);
    TEST_ASSERT_EQUAL_INT(3, sender.stats.ack_timeouts);
    TEST_ASSERT_EQUAL_INT(SVA_CAN_TX_FAILED, sender.state);
    TEST_ASSERT_EQUAL_INT(SVA_CAN_ABORT_RETRIES, sender.last_abort_reason);
    TEST_ASSERT_EQUAL_INT(1, sender.stats.aborts_sent);
    TEST_ASSERT_EQUAL_INT(3 * 52 + 1, sender.stats.frames_sent);
    // The last frame on the bus is the ABORT for plan 1, and the receiver drops its
    // transfer on it.
    {
        sva_can_frame_t last;
        int n = 0;
        while (sva_can_loopback_take(&bus, 1, &f) == SVA_CAN_OK) {
            last = f;
            ++n;
        }
        TEST_ASSERT_EQUAL_INT(3 * 52 + 1, n);
        TEST_ASSERT_EQUAL_INT(SVA_CAN_OK, sva_can_decode(&last, &m));
        TEST_ASSERT_EQUAL_INT(SVA_CAN_MSG_PLAN_ABORT, m.kind);
        TEST_ASSERT_EQUAL_INT(SVA_CAN_ABORT_RETRIES, m.u.abort_.reason);
        TEST_ASSERT_EQUAL_INT(1, m.u.abort_.plan_id);
    }
}

void test_sender_transfer_deadline(void)
{
    sva_can_sender_config_t c = sva_can_sender_default_config();
    sva_can_frame_t f;
    sva_can_msg_t m;
    c.max_attempts = 200;  // only the deadline can stop it
    c.transfer_timeout_ms = 700;
    TEST_ASSERT_EQUAL_INT(SVA_CAN_OK, sva_can_sender_init(&sender, &tp_tx, &c));
    TEST_ASSERT_EQUAL_INT(SVA_CAN_OK, sva_can_sender_start(&sender, &plan_a, 0));
    TEST_ASSERT_EQUAL_INT(SVA_CAN_OK, sva_can_sender_poll(&sender, 699));
    TEST_ASSERT_NOT_EQUAL_INT(SVA_CAN_TX_FAILED, sender.state);
    TEST_ASSERT_EQUAL_INT(SVA_CAN_OK, sva_can_sender_poll(&sender, 700));
    TEST_ASSERT_EQUAL_INT(SVA_CAN_TX_FAILED, sender.state);
    TEST_ASSERT_EQUAL_INT(SVA_CAN_ABORT_TIMEOUT, sender.last_abort_reason);
    while (sva_can_loopback_take(&bus, 1, &f) == SVA_CAN_OK) {
        m.kind = SVA_CAN_MSG_NONE;
        TEST_ASSERT_EQUAL_INT(SVA_CAN_OK, sva_can_decode(&f, &m));
    }
    TEST_ASSERT_EQUAL_INT(SVA_CAN_MSG_PLAN_ABORT, m.kind);
    TEST_ASSERT_EQUAL_INT(SVA_CAN_ABORT_TIMEOUT, m.u.abort_.reason);
}

void test_nack_then_retry_succeeds(void)
{
    sva_can_status_t last = SVA_CAN_OK;
    apply_plan_a();
    // First attempt of plan_b corrupted -> NACK -> the sender resends at once.
    TEST_ASSERT_EQUAL_INT(SVA_CAN_ERR_CRC, send_corrupted(CORRUPT_CRC, 100));
    deliver_acks(101);
    TEST_ASSERT_EQUAL_INT(1, sender.stats.nacks);
    TEST_ASSERT_EQUAL_INT(SVA_CAN_ACK_BAD_SEQUENCE, sender.last_nack);
    TEST_ASSERT_EQUAL_INT(SVA_CAN_TX_WAIT_ACK, sender.state);
    TEST_ASSERT_EQUAL_INT(3, sender.stats.attempts);  // plan_a 1 + plan_b 2
    TEST_ASSERT_EQUAL_INT(82, deliver_frames(102, &last));
    TEST_ASSERT_EQUAL_INT(SVA_CAN_APPLIED, last);
    deliver_acks(103);
    TEST_ASSERT_EQUAL_INT(SVA_CAN_TX_DONE, sender.state);
    assert_plans_equal(&receiver.active, &plan_b);
}

void test_superseded_plan_is_aborted(void)
{
    sva_can_frame_t f;
    sva_can_msg_t m;
    sva_can_status_t last = SVA_CAN_OK;
    int seen_abort = 0;
    TEST_ASSERT_EQUAL_INT(SVA_CAN_OK, sva_can_sender_start(&sender, &plan_a, 0));
    TEST_ASSERT_EQUAL_INT(SVA_CAN_OK, sva_can_sender_start(&sender, &plan_b, 5));
    while (sva_can_loopback_take(&bus, 1, &f) == SVA_CAN_OK) {
        if ((sva_can_decode(&f, &m) == SVA_CAN_OK) && (m.kind == SVA_CAN_MSG_PLAN_ABORT)) {
            TEST_ASSERT_EQUAL_INT(SVA_CAN_ABORT_SUPERSEDED, m.u.abort_.reason);
            TEST_ASSERT_EQUAL_INT(1, m.u.abort_.plan_id);
            seen_abort = 1;
        }
        last = sva_can_receiver_on_frame(&receiver, &f, 6);
    }
    TEST_ASSERT_TRUE(seen_abort);
    TEST_ASSERT_EQUAL_INT(SVA_CAN_APPLIED, last);
    TEST_ASSERT_EQUAL_INT(2, receiver.stats.plans_applied);  // plan_a completed before b began
    assert_plans_equal(&receiver.active, &plan_b);
}

// A transport that accepts one frame per poll: the sender must resume where it stopped.
static int budget;
static sva_can_status_t stingy_send(void* ctx, const sva_can_frame_t* f)
{
    if (budget <= 0) {
        return SVA_CAN_AGAIN;
    }
    --budget;
    return tp_tx.send(ctx, f);
}

void test_back_pressure(void)
{
    sva_can_transport_t stingy;
    sva_can_status_t last = SVA_CAN_OK;
    uint32_t t;
    stingy = tp_tx;
    stingy.send = stingy_send;
    TEST_ASSERT_EQUAL_INT(SVA_CAN_OK, sva_can_sender_init(&sender, &stingy, NULL));
    budget = 1;
    TEST_ASSERT_EQUAL_INT(SVA_CAN_OK, sva_can_sender_start(&sender, &plan_a, 0));
    for (t = 1; (t < 200) && (sender.state == SVA_CAN_TX_SENDING); ++t) {
        budget = 1;
        TEST_ASSERT_EQUAL_INT(SVA_CAN_OK, sva_can_sender_poll(&sender, t));
    }
    TEST_ASSERT_EQUAL_INT(SVA_CAN_TX_WAIT_ACK, sender.state);
    TEST_ASSERT_EQUAL_INT(52, sender.stats.frames_sent);
    deliver_frames(t, &last);
    TEST_ASSERT_EQUAL_INT(SVA_CAN_APPLIED, last);
    assert_plans_equal(&receiver.active, &plan_a);
}

void test_time_wraps_around(void)
{
    sva_can_frame_t f;
    const uint32_t t0 = 0xFFFFFF00u;  // 256 ms before the uint32 wrap
    int i;
    TEST_ASSERT_EQUAL_INT(SVA_CAN_OK, sva_can_sender_start(&sender, &plan_a, t0));
    for (i = 0; i < 10; ++i) {
        TEST_ASSERT_EQUAL_INT(SVA_CAN_OK, sva_can_loopback_take(&bus, 1, &f));
        TEST_ASSERT_EQUAL_INT(SVA_CAN_OK, sva_can_receiver_on_frame(&receiver, &f, t0));
    }
    TEST_ASSERT_EQUAL_INT(SVA_CAN_OK, sva_can_receiver_poll(&receiver, t0 + 999u));  // wrapped
    TEST_ASSERT_EQUAL_INT(SVA_CAN_ERR_TIMEOUT, sva_can_receiver_poll(&receiver, t0 + 1000u));
    TEST_ASSERT_EQUAL_INT(SVA_CAN_OK, sva_can_sender_poll(&sender, t0 + 249u));
    TEST_ASSERT_EQUAL_INT(0, sender.stats.ack_timeouts);
    TEST_ASSERT_EQUAL_INT(SVA_CAN_OK, sva_can_sender_poll(&sender, t0 + 250u));
    TEST_ASSERT_EQUAL_INT(1, sender.stats.ack_timeouts);
}

void test_too_large_and_bad_version(void)
{
    sva_can_msg_t m;
    sva_can_frame_t f;
    memset(&m, 0, sizeof m);
    m.kind = SVA_CAN_MSG_PLAN_BEGIN;
    m.u.begin.version = SVA_CAN_PROTOCOL_VERSION;
    m.u.begin.plan_id = 9;
    m.u.begin.item_count = SVA_CAN_MAX_ITEMS + 1;
    m.u.begin.plan_status = SVA_CAN_PLAN_COMPLETE;
    TEST_ASSERT_EQUAL_INT(SVA_CAN_OK, sva_can_encode(&m, &f));
    TEST_ASSERT_EQUAL_INT(SVA_CAN_ERR_LIMIT, sva_can_receiver_on_frame(&receiver, &f, 0));
    TEST_ASSERT_EQUAL_INT(1, receiver.stats.too_large);
    m.u.begin.item_count = 1;
    m.u.begin.version = SVA_CAN_PROTOCOL_VERSION + 1;
    TEST_ASSERT_EQUAL_INT(SVA_CAN_OK, sva_can_encode(&m, &f));
    TEST_ASSERT_EQUAL_INT(SVA_CAN_ERR_VERSION, sva_can_receiver_on_frame(&receiver, &f, 0));
    TEST_ASSERT_EQUAL_INT(1, receiver.stats.bad_version);
    // Version 1 (the protocol before SVA_MISSION_CLOCK) is another version too.
    m.u.begin.version = 1;
    TEST_ASSERT_EQUAL_INT(SVA_CAN_OK, sva_can_encode(&m, &f));
    TEST_ASSERT_EQUAL_INT(SVA_CAN_ERR_VERSION, sva_can_receiver_on_frame(&receiver, &f, 0));
    TEST_ASSERT_EQUAL_INT(2, receiver.stats.bad_version);
    TEST_ASSERT_EQUAL_STRING("version", sva_can_status_name(SVA_CAN_ERR_VERSION));
    TEST_ASSERT_EQUAL_INT(3, receiver.stats.nacks_sent);
    TEST_ASSERT_FALSE(receiver.has_active);
}

void test_api_misuse(void)
{
    sva_can_plan_t* p = &plan_a;
    TEST_ASSERT_EQUAL_INT(SVA_CAN_ERR_ARGUMENT, sva_can_sender_init(NULL, &tp_tx, NULL));
    TEST_ASSERT_EQUAL_INT(SVA_CAN_ERR_ARGUMENT, sva_can_sender_init(&sender, NULL, NULL));
    TEST_ASSERT_EQUAL_INT(SVA_CAN_ERR_ARGUMENT, sva_can_sender_start(&sender, NULL, 0));
    p->plan_id = 0;
    TEST_ASSERT_EQUAL_INT(SVA_CAN_ERR_ARGUMENT, sva_can_sender_start(&sender, p, 0));
    p->plan_id = 1;
    p->items[3].target_id = 5000;  // wider than its signal: refused before any frame
    TEST_ASSERT_EQUAL_INT(SVA_CAN_ERR_ARGUMENT, sva_can_sender_start(&sender, p, 0));
    TEST_ASSERT_EQUAL_INT(0, sender.stats.frames_sent);
    TEST_ASSERT_EQUAL_INT(SVA_CAN_ERR_ARGUMENT, sva_can_loopback_transport(&bus, 2, &tp_tx));
    TEST_ASSERT_EQUAL_INT(SVA_CAN_ERR_ARGUMENT, sva_can_receiver_on_frame(NULL, NULL, 0));
}

// The core's plan becomes wire items route by route, in visit order.
static sva_mission_t mission;
static sva_planner_t planner;
static sva_plan_t core_plan;

void test_plan_from_core(void)
{
    sva_diag_t diag;
    sva_can_plan_t* w = &plan_b;
    uint16_t r;
    uint16_t k;
    uint16_t n = 0;
    int i;
    sva_mission_init(&mission);
    mission.uav_count = 3;
    for (i = 0; i < 3; ++i) {
        mission.uavs[i].id = 10 + i;
        mission.uavs[i].x = 0;
        mission.uavs[i].y = 0;
        mission.uavs[i].fuel = 500;
        mission.uavs[i].ready_at_ticks = 0;
    }
    mission.target_count = 4;
    for (i = 0; i < 4; ++i) {
        mission.targets[i].id = 200 + i;
        mission.targets[i].x = 5 * (i + 1);
        mission.targets[i].y = -3 * i;
        mission.targets[i].start_ticks = 20 + 40 * i;
        mission.targets[i].end_ticks = 40 + 40 * i;
        mission.targets[i].need = 1 + (i % 2);
    }
    TEST_ASSERT_EQUAL_INT(SVA_CAN_OK, sva_can_mission_check(&mission, &diag));
    TEST_ASSERT_EQUAL_INT(SVA_OK, sva_planner_init(&planner));
    TEST_ASSERT_EQUAL_INT(SVA_OK, sva_plan(&planner, &mission, SVA_ALGO_SVA, &core_plan, &diag));
    TEST_ASSERT_EQUAL_INT(SVA_CAN_OK, sva_can_plan_from_core(w, &mission, &core_plan, 42));
    TEST_ASSERT_EQUAL_INT(42, w->plan_id);
    TEST_ASSERT_EQUAL_INT(3, w->route_count);
    for (r = 0; r < core_plan.route_count; ++r) {
        for (k = 0; k < core_plan.routes[r].target_count; ++k) {
            const sva_target_t* t = &mission.targets[core_plan.routes[r].targets[k]];
            TEST_ASSERT_EQUAL_INT(core_plan.routes[r].uav_id, w->items[n].uav_id);
            TEST_ASSERT_EQUAL_INT(t->id, w->items[n].target_id);
            TEST_ASSERT_EQUAL_INT(t->x, w->items[n].x);
            TEST_ASSERT_EQUAL_INT(t->y, w->items[n].y);
            TEST_ASSERT_EQUAL_INT(t->start_ticks, w->items[n].arrive_by_ticks);
            TEST_ASSERT_EQUAL_INT(t->end_ticks, w->items[n].hold_until_ticks);
            ++n;
        }
    }
    TEST_ASSERT_EQUAL_INT(n, w->item_count);
    TEST_ASSERT_TRUE(n >= 4);  // needs 1+2+1+2 when covered
}

void test_mission_check_names_limits(void)
{
    sva_diag_t diag;
    char msg[160];
    sva_mission_init(&mission);
    mission.uav_count = 1;
    mission.uavs[0].id = 256;
    mission.uavs[0].fuel = 10;
    TEST_ASSERT_EQUAL_INT(SVA_CAN_ERR_LIMIT, sva_can_mission_check(&mission, &diag));
    TEST_ASSERT_EQUAL_INT(SVA_FIELD_UAV_ID, diag.field);
    TEST_ASSERT_EQUAL_INT(256, diag.value);
    TEST_ASSERT_EQUAL_STRING("SVA_CAN_MAX_UAV_ID", diag.limit_name);
    (void)sva_diag_format(&diag, msg, sizeof msg);
    TEST_ASSERT_NOT_NULL(strstr(msg, "SVA_CAN_MAX_UAV_ID"));
    mission.uavs[0].id = 255;
    mission.target_count = 1;
    mission.targets[0].id = 4096;
    mission.targets[0].start_ticks = 0;
    mission.targets[0].end_ticks = 5;
    mission.targets[0].need = 1;
    TEST_ASSERT_EQUAL_INT(SVA_CAN_ERR_LIMIT, sva_can_mission_check(&mission, &diag));
    TEST_ASSERT_EQUAL_STRING("SVA_CAN_MAX_TARGET_ID", diag.limit_name);
    mission.targets[0].id = 4095;
    mission.targets[0].end_ticks = SVA_CAN_MAX_TICK + 1;
    TEST_ASSERT_EQUAL_INT(SVA_CAN_ERR_LIMIT, sva_can_mission_check(&mission, &diag));
    TEST_ASSERT_EQUAL_INT(SVA_FIELD_TARGET_END, diag.field);
    TEST_ASSERT_EQUAL_STRING("SVA_CAN_MAX_TICK", diag.limit_name);
    mission.targets[0].end_ticks = SVA_CAN_MAX_TICK;
    TEST_ASSERT_EQUAL_INT(SVA_CAN_OK, sva_can_mission_check(&mission, &diag));
}
