// Codec tests: CRC check values, exact byte packing, round trips of every frame type
// at their boundaries, and every decode rejection.
#include <stddef.h>
#include <stdint.h>
#include <string.h>

#include "unity.h"

#include "sva/sva_can.h"
#include "sva/sva_can_mission_frame.h"

static sva_can_frame_t enc(const sva_can_msg_t* m)
{
    sva_can_frame_t f;
    memset(&f, 0xEE, sizeof f);
    TEST_ASSERT_EQUAL_INT(SVA_CAN_OK, sva_can_encode(m, &f));
    TEST_ASSERT_EQUAL_INT(8, f.dlc);
    TEST_ASSERT_EQUAL_INT(0, f.flags);
    return f;
}

static sva_can_msg_t dec(const sva_can_frame_t* f)
{
    sva_can_msg_t m;
    memset(&m, 0, sizeof m);
    TEST_ASSERT_EQUAL_INT(SVA_CAN_OK, sva_can_decode(f, &m));
    return m;
}

static void fix_crc(sva_can_frame_t* f)
{
    f->data[7] = sva_can_frame_crc8(f->id, f->data);
}

void test_crc_check_values(void)
{
    const uint8_t check[] = "123456789";
    TEST_ASSERT_EQUAL_INT(0x4B, sva_can_crc8(check, 9));  // CRC-8/SAE-J1850 catalogue value
    TEST_ASSERT_EQUAL_INT(0xCBF43926u, sva_can_crc32(0u, check, 9));  // CRC-32/ISO-HDLC
    TEST_ASSERT_EQUAL_INT(0xCBF43926u, sva_can_crc32(sva_can_crc32(0u, check, 4), check + 4, 5));
    TEST_ASSERT_EQUAL_INT(0, sva_can_crc8(NULL, 3));
}

// Expected bytes worked out by hand from sva.dbc's start bits (little-endian signals).
void test_item_packing_by_bytes(void)
{
    sva_can_msg_t m;
    sva_can_frame_t f;
    const uint8_t want[7] = {0xB5, 0x3A, 0x12, 0xFE, 0xFF, 0x34, 0x12};
    m.kind = SVA_CAN_MSG_PLAN_ITEM;
    m.counter = 5;
    m.u.item.uav_id = 0xAB;
    m.u.item.target_id = 0x123;
    m.u.item.x = -2;
    m.u.item.y = 0x1234;
    f = enc(&m);
    TEST_ASSERT_EQUAL_INT(0x102, f.id);
    TEST_ASSERT_EQUAL_MEMORY(want, f.data, 7);
    {
        const uint8_t crcin[9] = {0x02, 0x01, 0xB5, 0x3A, 0x12, 0xFE, 0xFF, 0x34, 0x12};
        TEST_ASSERT_EQUAL_INT(sva_can_crc8(crcin, 9),
                              f.data[7]);  // id low byte, id high byte, data 0..6
    }
}

void test_commit_and_time_packing_by_bytes(void)
{
    sva_can_msg_t m;
    sva_can_frame_t f;
    m.kind = SVA_CAN_MSG_PLAN_COMMIT;
    m.counter = 15;
    m.u.commit.plan_id = 0xBEEF;
    m.u.commit.plan_crc = 0x11223344u;
    f = enc(&m);
    {
        const uint8_t want[7] = {0x0F, 0xEF, 0xBE, 0x44, 0x33, 0x22, 0x11};
        TEST_ASSERT_EQUAL_MEMORY(want, f.data, 7);
    }
    m.kind = SVA_CAN_MSG_PLAN_ITEM_TIME;
    m.counter = 1;
    m.u.item_time.item_seq = 0xC;
    m.u.item_time.arrive_by_ticks = 0x0A0B0Cu;
    m.u.item_time.hold_until_ticks = 0xFFFFFFu;
    f = enc(&m);
    {
        const uint8_t want[7] = {0xC1, 0x0C, 0x0B, 0x0A, 0xFF, 0xFF, 0xFF};
        TEST_ASSERT_EQUAL_MEMORY(want, f.data, 7);
    }
    m.kind = SVA_CAN_MSG_VEHICLE_FUEL;
    m.counter = 0;
    m.u.fuel.uav_id = 7;
    m.u.fuel.fuel = 0xDEADBEEFu;
    f = enc(&m);
    {
        const uint8_t want[7] = {0x00, 0x07, 0xEF, 0xBE, 0xAD, 0xDE, 0x00};
        TEST_ASSERT_EQUAL_MEMORY(want, f.data, 7);
    }
}

static void roundtrip(const sva_can_msg_t* m)
{
    const sva_can_frame_t f = enc(m);
    const sva_can_msg_t back = dec(&f);
    TEST_ASSERT_EQUAL_INT(m->kind, back.kind);
    TEST_ASSERT_EQUAL_INT(m->counter, back.counter);
    switch (m->kind) {
    case SVA_CAN_MSG_HEARTBEAT:
        TEST_ASSERT_EQUAL_INT(m->u.heartbeat.state, back.u.heartbeat.state);
        TEST_ASSERT_EQUAL_INT(m->u.heartbeat.active_plan_id, back.u.heartbeat.active_plan_id);
        TEST_ASSERT_EQUAL_INT(m->u.heartbeat.uav_count, back.u.heartbeat.uav_count);
        TEST_ASSERT_EQUAL_INT(m->u.heartbeat.target_count, back.u.heartbeat.target_count);
        TEST_ASSERT_EQUAL_INT(m->u.heartbeat.covered_count, back.u.heartbeat.covered_count);
        TEST_ASSERT_EQUAL_INT(m->u.heartbeat.faults, back.u.heartbeat.faults);
        break;
    case SVA_CAN_MSG_PLAN_BEGIN:
        TEST_ASSERT_EQUAL_INT(m->u.begin.version, back.u.begin.version);
        TEST_ASSERT_EQUAL_INT(m->u.begin.plan_id, back.u.begin.plan_id);
        TEST_ASSERT_EQUAL_INT(m->u.begin.item_count, back.u.begin.item_count);
        TEST_ASSERT_EQUAL_INT(m->u.begin.algorithm, back.u.begin.algorithm);
        TEST_ASSERT_EQUAL_INT(m->u.begin.plan_status, back.u.begin.plan_status);
        TEST_ASSERT_EQUAL_INT(m->u.begin.route_count, back.u.begin.route_count);
        break;
    case SVA_CAN_MSG_PLAN_ITEM:
        TEST_ASSERT_EQUAL_INT(m->u.item.uav_id, back.u.item.uav_id);
        TEST_ASSERT_EQUAL_INT(m->u.item.target_id, back.u.item.target_id);
        TEST_ASSERT_EQUAL_INT(m->u.item.x, back.u.item.x);
        TEST_ASSERT_EQUAL_INT(m->u.item.y, back.u.item.y);
        break;
    case SVA_CAN_MSG_PLAN_ITEM_TIME:
        TEST_ASSERT_EQUAL_INT(m->u.item_time.item_seq, back.u.item_time.item_seq);
        TEST_ASSERT_EQUAL_INT(m->u.item_time.arrive_by_ticks, back.u.item_time.arrive_by_ticks);
        TEST_ASSERT_EQUAL_INT(m->u.item_time.hold_until_ticks, back.u.item_time.hold_until_ticks);
        break;
    case SVA_CAN_MSG_PLAN_COMMIT:
        TEST_ASSERT_EQUAL_INT(m->u.commit.plan_id, back.u.commit.plan_id);
        TEST_ASSERT_EQUAL_INT(m->u.commit.plan_crc, back.u.commit.plan_crc);
        break;
    case SVA_CAN_MSG_PLAN_ABORT:
        TEST_ASSERT_EQUAL_INT(m->u.abort_.reason, back.u.abort_.reason);
        TEST_ASSERT_EQUAL_INT(m->u.abort_.plan_id, back.u.abort_.plan_id);
        break;
    case SVA_CAN_MSG_PLAN_ACK:
        TEST_ASSERT_EQUAL_INT(m->u.ack.result, back.u.ack.result);
        TEST_ASSERT_EQUAL_INT(m->u.ack.plan_id, back.u.ack.plan_id);
        TEST_ASSERT_EQUAL_INT(m->u.ack.items_received, back.u.ack.items_received);
        break;
    case SVA_CAN_MSG_VEHICLE_STATUS:
        TEST_ASSERT_EQUAL_INT(m->u.vehicle.state, back.u.vehicle.state);
        TEST_ASSERT_EQUAL_INT(m->u.vehicle.uav_id, back.u.vehicle.uav_id);
        TEST_ASSERT_EQUAL_INT(m->u.vehicle.x, back.u.vehicle.x);
        TEST_ASSERT_EQUAL_INT(m->u.vehicle.y, back.u.vehicle.y);
        break;
    case SVA_CAN_MSG_VEHICLE_FUEL:
        TEST_ASSERT_EQUAL_INT(m->u.fuel.uav_id, back.u.fuel.uav_id);
        TEST_ASSERT_EQUAL_INT(m->u.fuel.fuel, back.u.fuel.fuel);
        break;
    case SVA_CAN_MSG_MISSION_CLOCK:
        TEST_ASSERT_EQUAL_INT(m->u.clock.tick, back.u.clock.tick);
        break;
    case SVA_CAN_MSG_NONE:
    case SVA_CAN_MSG_COUNT_:
    default:
        TEST_FAIL();
    }
}

void test_roundtrip_every_kind_at_bounds(void)
{
    sva_can_msg_t m;
    int lo;
    for (lo = 0; lo < 2; ++lo) {
        memset(&m, 0, sizeof m);
        m.counter = lo ? 0 : 15;
        m.kind = SVA_CAN_MSG_HEARTBEAT;
        m.u.heartbeat.state = lo ? 0 : SVA_CAN_NODE_STATE_MAX;
        m.u.heartbeat.active_plan_id = lo ? 0 : 65535;
        m.u.heartbeat.uav_count = lo ? 0 : 255;
        m.u.heartbeat.target_count = lo ? 0 : 255;
        m.u.heartbeat.covered_count = lo ? 0 : 255;
        m.u.heartbeat.faults = lo ? 0 : SVA_CAN_FAULT_MASK;
        roundtrip(&m);
        memset(&m, 0, sizeof m);
        m.counter = lo ? 0 : 15;
        m.kind = SVA_CAN_MSG_PLAN_BEGIN;
        m.u.begin.version = SVA_CAN_PROTOCOL_VERSION;
        m.u.begin.plan_id = lo ? 1 : 65535;
        m.u.begin.item_count = lo ? 0 : 65535;
        m.u.begin.algorithm = lo ? 0 : 3;
        m.u.begin.plan_status = lo ? SVA_CAN_PLAN_COMPLETE : SVA_CAN_PLAN_PARTIAL;
        m.u.begin.route_count = lo ? 0 : 255;
        roundtrip(&m);
        memset(&m, 0, sizeof m);
        m.kind = SVA_CAN_MSG_PLAN_ITEM;
        m.u.item.uav_id = lo ? 1 : 255;
        m.u.item.target_id = lo ? 1 : 4095;
        m.u.item.x = lo ? -32768 : 32767;
        m.u.item.y = lo ? 32767 : -32768;
        roundtrip(&m);
        memset(&m, 0, sizeof m);
        m.kind = SVA_CAN_MSG_MISSION_CLOCK;
        m.counter = lo ? 0 : 15;
        m.u.clock.tick = lo ? 0 : (uint32_t)SVA_CAN_MAX_TICK;
        roundtrip(&m);
        {
            sva_can_frame_t too_late;
            m.u.clock.tick = (uint32_t)SVA_CAN_MAX_TICK + 1u;  // does not fit 24 bits
            TEST_ASSERT_EQUAL_INT(SVA_CAN_ERR_ARGUMENT, sva_can_encode(&m, &too_late));
        }
        memset(&m, 0, sizeof m);
        m.kind = SVA_CAN_MSG_PLAN_ITEM_TIME;
        m.u.item_time.item_seq = lo ? 0 : 15;
        m.u.item_time.arrive_by_ticks = lo ? 0 : SVA_CAN_MAX_TICK - 1;
        m.u.item_time.hold_until_ticks = lo ? 1 : SVA_CAN_MAX_TICK;
        roundtrip(&m);
        memset(&m, 0, sizeof m);
        m.kind = SVA_CAN_MSG_PLAN_COMMIT;
        m.u.commit.plan_id = lo ? 1 : 65535;
        m.u.commit.plan_crc = lo ? 0u : 0xFFFFFFFFu;
        roundtrip(&m);
        memset(&m, 0, sizeof m);
        m.kind = SVA_CAN_MSG_PLAN_ABORT;
        m.u.abort_.reason = lo ? 1 : SVA_CAN_ABORT_REASON_MAX;
        m.u.abort_.plan_id = lo ? 0 : 65535;
        roundtrip(&m);
        memset(&m, 0, sizeof m);
        m.kind = SVA_CAN_MSG_PLAN_ACK;
        m.u.ack.result = lo ? 0 : SVA_CAN_ACK_RESULT_MAX;
        m.u.ack.plan_id = lo ? 0 : 65535;
        m.u.ack.items_received = lo ? 0 : 65535;
        roundtrip(&m);
        memset(&m, 0, sizeof m);
        m.kind = SVA_CAN_MSG_VEHICLE_STATUS;
        m.u.vehicle.state = lo ? 0 : SVA_CAN_VEHICLE_STATE_MAX;
        m.u.vehicle.uav_id = lo ? 1 : 255;
        m.u.vehicle.x = lo ? -32768 : 32767;
        m.u.vehicle.y = lo ? -1 : 1;
        roundtrip(&m);
        memset(&m, 0, sizeof m);
        m.kind = SVA_CAN_MSG_VEHICLE_FUEL;
        m.u.fuel.uav_id = lo ? 1 : 255;
        m.u.fuel.fuel = lo ? 0u : 0xFFFFFFFFu;
        roundtrip(&m);
    }
}

void test_encode_refuses_wide_values(void)
{
    sva_can_msg_t m;
    sva_can_frame_t f;
    memset(&m, 0, sizeof m);
    memset(&f, 0x5A, sizeof f);
    m.kind = SVA_CAN_MSG_PLAN_ITEM;
    m.u.item.uav_id = 1;
    m.u.item.target_id = 4096;  // SVA_CAN_MAX_TARGET_ID + 1
    TEST_ASSERT_EQUAL_INT(SVA_CAN_ERR_ARGUMENT, sva_can_encode(&m, &f));
    TEST_ASSERT_EQUAL_INT(0x5A, f.data[0]);  // untouched
    m.u.item.target_id = 4095;
    m.counter = 16;
    TEST_ASSERT_EQUAL_INT(SVA_CAN_ERR_ARGUMENT, sva_can_encode(&m, &f));
    memset(&m, 0, sizeof m);
    m.kind = SVA_CAN_MSG_PLAN_ITEM_TIME;
    m.u.item_time.hold_until_ticks = SVA_CAN_MAX_TICK + 1;
    TEST_ASSERT_EQUAL_INT(SVA_CAN_ERR_ARGUMENT, sva_can_encode(&m, &f));
    m.kind = SVA_CAN_MSG_NONE;
    TEST_ASSERT_EQUAL_INT(SVA_CAN_ERR_ARGUMENT, sva_can_encode(&m, &f));
    TEST_ASSERT_EQUAL_INT(SVA_CAN_ERR_ARGUMENT, sva_can_encode(NULL, &f));
}

static sva_can_frame_t sample_item(void)
{
    sva_can_msg_t m;
    memset(&m, 0, sizeof m);
    m.kind = SVA_CAN_MSG_PLAN_ITEM;
    m.counter = 3;
    m.u.item.uav_id = 9;
    m.u.item.target_id = 77;
    m.u.item.x = -100;
    m.u.item.y = 250;
    return enc(&m);
}

void test_decode_rejects_dlc_fd_crc(void)
{
    sva_can_msg_t out;
    sva_can_frame_t f;
    unsigned dlc;
    unsigned byte;
    unsigned bit;
    for (dlc = 0; dlc <= 15; ++dlc) {
        if (dlc == 8) {
            continue;
        }
        f = sample_item();
        f.dlc = (uint8_t)dlc;
        TEST_ASSERT_EQUAL_INT(SVA_CAN_ERR_DLC, sva_can_decode(&f, &out));
    }
    f = sample_item();
    f.flags = SVA_CAN_FLAG_FD;
    TEST_ASSERT_EQUAL_INT(SVA_CAN_ERR_DLC, sva_can_decode(&f, &out));
    // Every single-bit error in any byte is caught by the CRC-8.
    for (byte = 0; byte < 8; ++byte) {
        for (bit = 0; bit < 8; ++bit) {
            f = sample_item();
            f.data[byte] = (uint8_t)(f.data[byte] ^ (1u << bit));
            TEST_ASSERT_EQUAL_INT(SVA_CAN_ERR_CRC, sva_can_decode(&f, &out));
        }
    }
    // The CRC covers the id: the same bytes under another id fail.
    f = sample_item();
    f.id = SVA_CAN_ID_VEHICLE_STATUS;
    TEST_ASSERT_EQUAL_INT(SVA_CAN_ERR_CRC, sva_can_decode(&f, &out));
}

void test_decode_ignores_foreign_frames(void)
{
    sva_can_msg_t out;
    sva_can_frame_t f = sample_item();
    f.flags = SVA_CAN_FLAG_EXTENDED;  // DroneCAN-style 29-bit frame with the same low bits
    TEST_ASSERT_EQUAL_INT(SVA_CAN_IGNORED, sva_can_decode(&f, &out));
    f.flags = SVA_CAN_FLAG_RTR;
    TEST_ASSERT_EQUAL_INT(SVA_CAN_IGNORED, sva_can_decode(&f, &out));
    f = sample_item();
    f.id = 0x7FF;
    TEST_ASSERT_EQUAL_INT(SVA_CAN_IGNORED, sva_can_decode(&f, &out));
    f.id = 0x105;
    TEST_ASSERT_EQUAL_INT(SVA_CAN_IGNORED, sva_can_decode(&f, &out));
}

void test_decode_rejects_values(void)
{
    sva_can_msg_t out;
    sva_can_frame_t f;
    f = sample_item();  // uav_id 0
    f.data[0] = (uint8_t)(f.data[0] & 0x0F);
    f.data[1] = (uint8_t)(f.data[1] & 0xF0);
    fix_crc(&f);
    TEST_ASSERT_EQUAL_INT(SVA_CAN_ERR_VALUE, sva_can_decode(&f, &out));
    f = sample_item();  // target_id 0
    f.data[1] = (uint8_t)(f.data[1] & 0x0F);
    f.data[2] = 0;
    fix_crc(&f);
    TEST_ASSERT_EQUAL_INT(SVA_CAN_ERR_VALUE, sva_can_decode(&f, &out));
    {
        sva_can_msg_t m;
        memset(&m, 0, sizeof m);
        m.kind = SVA_CAN_MSG_PLAN_ITEM_TIME;  // arrive_by == hold_until breaks start < end
        m.u.item_time.arrive_by_ticks = 10;
        m.u.item_time.hold_until_ticks = 10;
        TEST_ASSERT_EQUAL_INT(SVA_CAN_OK, sva_can_encode(&m, &f));
        TEST_ASSERT_EQUAL_INT(SVA_CAN_ERR_VALUE, sva_can_decode(&f, &out));
        memset(&m, 0, sizeof m);
        m.kind = SVA_CAN_MSG_VEHICLE_STATUS;
        m.u.vehicle.uav_id = 1;
        m.u.vehicle.state = SVA_CAN_VEHICLE_STATE_MAX + 1;
        TEST_ASSERT_EQUAL_INT(SVA_CAN_OK, sva_can_encode(&m, &f));
        TEST_ASSERT_EQUAL_INT(SVA_CAN_ERR_VALUE, sva_can_decode(&f, &out));
        memset(&m, 0, sizeof m);
        m.kind = SVA_CAN_MSG_PLAN_BEGIN;
        m.u.begin.version = 1;
        m.u.begin.plan_id = 0;  // 0 means no plan
        m.u.begin.plan_status = SVA_CAN_PLAN_COMPLETE;
        TEST_ASSERT_EQUAL_INT(SVA_CAN_OK, sva_can_encode(&m, &f));
        TEST_ASSERT_EQUAL_INT(SVA_CAN_ERR_VALUE, sva_can_decode(&f, &out));
        m.u.begin.plan_id = 1;
        m.u.begin.plan_status = 3;
        TEST_ASSERT_EQUAL_INT(SVA_CAN_OK, sva_can_encode(&m, &f));
        TEST_ASSERT_EQUAL_INT(SVA_CAN_ERR_VALUE, sva_can_decode(&f, &out));
        memset(&m, 0, sizeof m);
        m.kind = SVA_CAN_MSG_PLAN_ACK;
        m.u.ack.result = SVA_CAN_ACK_RESULT_MAX + 1;
        TEST_ASSERT_EQUAL_INT(SVA_CAN_OK, sva_can_encode(&m, &f));
        TEST_ASSERT_EQUAL_INT(SVA_CAN_ERR_VALUE, sva_can_decode(&f, &out));
    }
}

// The mission frame: four frames with consecutive counters; a group decodes to the same
// integers at every range bound; a break in the group, a bad CRC or DLC, an out-of-range
// value and a foreign id are each refused as their status says.
void test_mission_frame_round_trip(void)
{
    static const sva_can_mission_frame_t cases[] = {
        {473977419, 85455939, 3000, 1000, 1000, 1780300800125LL},
        {-850000000, -1800000000, 0, 10, 1, 0},
        {850000000, 1800000000, 1000000, 1000000, 3600000, 253402300799999LL},
    };
    for (size_t c = 0; c < sizeof cases / sizeof cases[0]; ++c) {
        sva_can_frame_t out[4];
        const uint8_t first = (uint8_t)(13u + c) & 15u;  // wraps past 15
        TEST_ASSERT_EQUAL_INT(SVA_CAN_OK, sva_can_mission_frame_encode(&cases[c], first, out));
        sva_can_mission_frame_rx_t rx;
        sva_can_mission_frame_t got;
        sva_can_mission_frame_rx_init(&rx);
        for (unsigned p = 0; p < 4u; ++p) {
            TEST_ASSERT_EQUAL_INT(SVA_CAN_ID_MISSION_FRAME_A + p, out[p].id);
            TEST_ASSERT_EQUAL_INT(8, out[p].dlc);
            TEST_ASSERT_EQUAL_INT((first + p) & 15u, out[p].data[0] & 15u);
            TEST_ASSERT_EQUAL_INT(SVA_CAN_MSG_NONE,
                                  sva_can_kind_of_id(out[p].id));  // plan path ignores it
            TEST_ASSERT_EQUAL_INT(p < 3u ? SVA_CAN_OK : SVA_CAN_APPLIED,
                                  sva_can_mission_frame_rx(&rx, &out[p], &got));
        }
        TEST_ASSERT_EQUAL_MEMORY(&cases[c], &got, sizeof got);
    }
    sva_can_mission_frame_t bad = cases[0];
    sva_can_frame_t out[4];
    bad.cell_cm = 9;
    TEST_ASSERT_EQUAL_INT(SVA_CAN_ERR_ARGUMENT, sva_can_mission_frame_encode(&bad, 0, out));
    bad = cases[0];
    bad.t0_ms = -1;
    TEST_ASSERT_EQUAL_INT(SVA_CAN_ERR_ARGUMENT, sva_can_mission_frame_encode(&bad, 0, out));
    TEST_ASSERT_EQUAL_INT(SVA_CAN_ERR_ARGUMENT, sva_can_mission_frame_encode(&cases[0], 16, out));

    sva_can_mission_frame_rx_t rx;
    sva_can_mission_frame_t got;
    TEST_ASSERT_EQUAL_INT(SVA_CAN_OK, sva_can_mission_frame_encode(&cases[0], 5, out));
    sva_can_mission_frame_rx_init(&rx);
    // B without A, then A and C (B missing): sequence errors, nothing taken
    TEST_ASSERT_EQUAL_INT(SVA_CAN_ERR_SEQUENCE, sva_can_mission_frame_rx(&rx, &out[1], &got));
    TEST_ASSERT_EQUAL_INT(SVA_CAN_OK, sva_can_mission_frame_rx(&rx, &out[0], &got));
    TEST_ASSERT_EQUAL_INT(SVA_CAN_ERR_SEQUENCE, sva_can_mission_frame_rx(&rx, &out[2], &got));
    // a part of another group (its counter does not follow A's)
    sva_can_frame_t other[4];
    TEST_ASSERT_EQUAL_INT(SVA_CAN_OK, sva_can_mission_frame_encode(&cases[1], 9, other));
    TEST_ASSERT_EQUAL_INT(SVA_CAN_OK, sva_can_mission_frame_rx(&rx, &out[0], &got));
    TEST_ASSERT_EQUAL_INT(SVA_CAN_ERR_SEQUENCE, sva_can_mission_frame_rx(&rx, &other[1], &got));
    // CRC, DLC, foreign ids
    sva_can_frame_t f = out[0];
    f.data[3] ^= 0x10u;
    TEST_ASSERT_EQUAL_INT(SVA_CAN_ERR_CRC, sva_can_mission_frame_rx(&rx, &f, &got));
    f = out[0];
    f.dlc = 7;
    TEST_ASSERT_EQUAL_INT(SVA_CAN_ERR_DLC, sva_can_mission_frame_rx(&rx, &f, &got));
    f = out[0];
    f.id = SVA_CAN_ID_PLAN_BEGIN;
    TEST_ASSERT_EQUAL_INT(SVA_CAN_IGNORED, sva_can_mission_frame_rx(&rx, &f, &got));
    f = out[0];
    f.flags = SVA_CAN_FLAG_EXTENDED;
    TEST_ASSERT_EQUAL_INT(SVA_CAN_IGNORED, sva_can_mission_frame_rx(&rx, &f, &got));
    // a tick of 0 on the wire (22 bits hold it): out of range when the group completes
    f = out[3];
    f.data[0] = (uint8_t)(f.data[0] & 0x0Fu);
    f.data[1] = 0u;
    f.data[2] = 0u;
    f.data[3] = (uint8_t)(f.data[3] & 0xFCu);
    f.data[7] = sva_can_frame_crc8(f.id, f.data);
    TEST_ASSERT_EQUAL_INT(SVA_CAN_OK, sva_can_mission_frame_rx(&rx, &out[0], &got));
    TEST_ASSERT_EQUAL_INT(SVA_CAN_OK, sva_can_mission_frame_rx(&rx, &out[1], &got));
    TEST_ASSERT_EQUAL_INT(SVA_CAN_OK, sva_can_mission_frame_rx(&rx, &out[2], &got));
    TEST_ASSERT_EQUAL_INT(SVA_CAN_ERR_VALUE, sva_can_mission_frame_rx(&rx, &f, &got));
}
