// Fuzz target: the CAN frame and plan reassembly path of port/can (sva_can_decode,
// the receiver's reassembly of BEGIN, ITEM, ITEM_TIME, COMMIT, its ACKs, and the
// sender's ACK handling). The input is a sequence of 11-byte frame records:
//   byte 0  bits 0..3: id (0..8 this protocol's ids in order ABORT, BEGIN, ITEM,
//           ITEM_TIME, COMMIT, ACK, HEARTBEAT, VEHICLE_STATUS, VEHICLE_FUEL; 9..15
//           other ids); bit 4: set the rolling counter to the harness's next value;
//           bit 5: set the CRC-8; bit 6: set COMMIT's CRC-32 to the one the harness
//           computed over the transfer (SPEC of sva_can.h); bit 7: take DLC and flags
//           from byte 1 (else DLC 8, no flags).
//   byte 1  bits 0..3 DLC, bits 4..6 flags (extended, RTR, FD).
//   byte 2  milliseconds to advance the clock, times 16 (so timeouts happen).
//   bytes 3..10  the data bytes.
// The fix-up bits let the fuzzer past the CRC and counter checks; without them the
// bytes are delivered as they are. Properties: no crash or out-of-bounds access (ASan,
// UBSan); decode -> encode -> decode is stable; the active plan changes only when the
// receiver reports SVA_CAN_APPLIED, and then its CRC-32 is the COMMIT's and every item
// is within the wire's ranges.
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "sva/sva_can.h"
#include "sva/sva_can_transport.h"

int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size);

static sva_can_loopback_t bus;
static sva_can_receiver_t rx;
static sva_can_sender_t tx;
static sva_can_plan_t small_plan;

static const uint32_t ids[9] = {
    SVA_CAN_ID_PLAN_ABORT,     SVA_CAN_ID_PLAN_BEGIN,     SVA_CAN_ID_PLAN_ITEM,
    SVA_CAN_ID_PLAN_ITEM_TIME, SVA_CAN_ID_PLAN_COMMIT,    SVA_CAN_ID_PLAN_ACK,
    SVA_CAN_ID_HEARTBEAT,      SVA_CAN_ID_VEHICLE_STATUS, SVA_CAN_ID_VEHICLE_FUEL,
};

static void fail(const char* what)
{
    fprintf(stderr, "fuzz_can: %s\n", what);
    abort();
}

// decode -> encode -> decode gives the same message (compared through its encoding).
static void check_round_trip(const sva_can_frame_t* f)
{
    sva_can_msg_t m1;
    sva_can_msg_t m2;
    sva_can_frame_t e1;
    sva_can_frame_t e2;
    if (sva_can_decode(f, &m1) != SVA_CAN_OK) {
        return;
    }
    if (sva_can_encode(&m1, &e1) != SVA_CAN_OK || sva_can_decode(&e1, &m2) != SVA_CAN_OK ||
        sva_can_encode(&m2, &e2) != SVA_CAN_OK || memcmp(e1.data, e2.data, 8) != 0 ||
        e1.id != f->id) {
        fail("decode/encode round trip is not stable");
    }
}

static void check_active(uint32_t commit_crc)
{
    if (!rx.has_active || rx.active.item_count > SVA_CAN_MAX_ITEMS) {
        fail("applied plan missing or too large");
    }
    if (sva_can_plan_crc(&rx.active) != commit_crc) {
        fail("applied plan's CRC-32 is not the COMMIT's");
    }
    for (uint16_t i = 0; i < rx.active.item_count; i++) {
        const sva_can_item_t* it = &rx.active.items[i];
        if (it->uav_id == 0U || it->target_id == 0U || it->target_id > SVA_CAN_MAX_TARGET_ID ||
            it->arrive_by_ticks >= it->hold_until_ticks ||
            it->hold_until_ticks > SVA_CAN_MAX_TICK) {
            fail("applied plan holds an item outside the wire's ranges");
        }
    }
}

int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size)
{
    sva_can_transport_t to_sender;
    sva_can_transport_t to_receiver;
    sva_can_loopback_init(&bus);
    if (sva_can_loopback_transport(&bus, 0, &to_sender) != SVA_CAN_OK ||
        sva_can_loopback_transport(&bus, 1, &to_receiver) != SVA_CAN_OK ||
        sva_can_receiver_init(&rx, &to_receiver, 0) != SVA_CAN_OK ||
        sva_can_sender_init(&tx, &to_sender, NULL) != SVA_CAN_OK) {
        fail("init");
    }
    // A small plan in flight, so that fuzzed ACKs meet a sender waiting for one.
    small_plan.plan_id = 7;
    small_plan.algorithm = 0;
    small_plan.plan_status = SVA_CAN_PLAN_COMPLETE;
    small_plan.route_count = 1;
    small_plan.item_count = 1;
    small_plan.items[0] = (sva_can_item_t){1, 1, 0, 0, 10, 20};
    uint32_t now = 1000;
    if (sva_can_sender_start(&tx, &small_plan, now) != SVA_CAN_OK) {
        fail("sender start");
    }
    uint8_t counter = 0;
    uint32_t crc = 0;
    sva_can_frame_t f;
    for (size_t at = 0; at + 11U <= size; at += 11U) {
        const uint8_t* r = data + at;
        const unsigned sel = r[0] & 0x0FU;
        f.id = (sel < 9U) ? ids[sel] : (0x0F0U + (sel - 9U) * 0x11U);
        if ((r[0] & 0x80U) != 0U) {
            f.dlc = r[1] & 0x0FU;
            f.flags = (uint8_t)((r[1] >> 4U) & 0x07U);
        } else {
            f.dlc = 8;
            f.flags = 0;
        }
        memcpy(f.data, r + 3, 8);
        now += (uint32_t)r[2] * 16U;
        if ((r[0] & 0x10U) != 0U) {
            counter = (uint8_t)((counter + 1U) & 0x0FU);
            f.data[0] = (uint8_t)((f.data[0] & 0xF0U) | counter);
        }
        // The transfer CRC-32 as sva_can.h defines it: data bytes 0..6 of BEGIN, ITEM
        // and ITEM_TIME with the counter nibble cleared, from BEGIN on.
        uint8_t cleared[7];
        memcpy(cleared, f.data, 7);
        cleared[0] &= 0xF0U;
        if (f.id == SVA_CAN_ID_PLAN_BEGIN) {
            crc = sva_can_crc32(0, cleared, 7);
        } else if (f.id == SVA_CAN_ID_PLAN_ITEM || f.id == SVA_CAN_ID_PLAN_ITEM_TIME) {
            crc = sva_can_crc32(crc, cleared, 7);
        }
        if (f.id == SVA_CAN_ID_PLAN_COMMIT && (r[0] & 0x40U) != 0U) {
            // bits 24..55 little-endian (sva.dbc PLAN_COMMIT.plan_crc)
            f.data[3] = (uint8_t)crc;
            f.data[4] = (uint8_t)(crc >> 8U);
            f.data[5] = (uint8_t)(crc >> 16U);
            f.data[6] = (uint8_t)(crc >> 24U);
        }
        if ((r[0] & 0x20U) != 0U) {
            f.data[7] = sva_can_frame_crc8(f.id, f.data);
        }

        check_round_trip(&f);
        const bool had = rx.has_active;
        const sva_can_plan_t* a = &rx.active;
        const uint16_t old_id = a->plan_id;
        const uint16_t old_count = a->item_count;
        const uint32_t old_crc = had ? sva_can_plan_crc(a) : 0U;
        const sva_can_status_t st = sva_can_receiver_on_frame(&rx, &f, now);
        if (st == SVA_CAN_APPLIED) {
            sva_can_msg_t m;
            if (sva_can_decode(&f, &m) != SVA_CAN_OK || m.kind != SVA_CAN_MSG_PLAN_COMMIT) {
                fail("a plan was applied by a frame that is not a valid COMMIT");
            }
            check_active(m.u.commit.plan_crc);
        } else if (had != rx.has_active || old_id != a->plan_id || old_count != a->item_count ||
                   (had && old_crc != sva_can_plan_crc(a))) {
            fail("the active plan changed without SVA_CAN_APPLIED");
        }
        // The sender's and the poll's statuses are not properties: only the absence of
        // crashes and the receiver's invariants are checked for them.
        sva_can_status_t ignored = sva_can_sender_on_frame(&tx, &f, now);
        ignored = sva_can_sender_poll(&tx, now);
        ignored = sva_can_receiver_poll(&rx, now);
        // ACKs the receiver sent go to the sender; the sender's frames are dropped.
        sva_can_frame_t out;
        while (sva_can_loopback_take(&bus, 0, &out) == SVA_CAN_OK) {
            ignored = sva_can_sender_on_frame(&tx, &out, now);
        }
        (void)ignored;
        while (sva_can_loopback_take(&bus, 1, &out) == SVA_CAN_OK) {
        }
    }
    return 0;
}
