// Fuzz target: the MAVLink side of port/mavlink that reads a vehicle's bytes: the
// byte parser (stream and datagram modes), the vehicle telemetry it feeds, and an
// upload in progress answering the vehicle's requests and ACKs. The input is a
// sequence of records; the first byte's low 2 bits say which:
//   0  raw bytes: byte 1 is the count n, then n bytes put into the parser as they are;
//   1  a good frame built by the harness: byte 1 picks the message (one of `ids`),
//      byte 2 its sender (bit 0: the vehicle's system or another; bit 1: component 1
//      or another), byte 3 the payload length n (cut to the message's largest), then
//      n payload bytes; bits 2..3 of the first byte: 0 whole, 1 cut short by its last
//      byte, 2 one payload byte flipped, 3 whole (a MAVLink 1 frame when the message
//      has a v1 id);
//   2  end of datagram (sva_mavlink_parser_end), then the parser drained;
//   3  the clock moves by byte 1 x 64 ms (upload timeouts and resends happen).
// After each record the parser is drained: every frame out goes to the telemetry and
// the upload. Properties: no crash or out-of-bounds access (ASan, UBSan); every frame
// out has a defined message id and a payload no longer than its message's; the
// parser's counters never go back and it never holds more than its size; a whole good
// frame put into an empty parser comes out next, with its id, sender and payload
// (stray bytes never swallow a good frame); the upload's state and sequence stay in
// range and a DONE upload has sent every item.
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "sva/sva_mavlink.h"

int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size);

#define VEHICLE_SYSTEM 7U
#define OWN_SYSTEM     255U
#define ITEMS          4U

static const uint32_t ids[] = {
    MAVLINK_MSG_ID_HEARTBEAT,
    MAVLINK_MSG_ID_MISSION_REQUEST_INT,
    MAVLINK_MSG_ID_MISSION_REQUEST,
    MAVLINK_MSG_ID_MISSION_ACK,
    MAVLINK_MSG_ID_GLOBAL_POSITION_INT,
    MAVLINK_MSG_ID_SYS_STATUS,
    MAVLINK_MSG_ID_BATTERY_STATUS,
    MAVLINK_MSG_ID_MISSION_CURRENT,
    MAVLINK_MSG_ID_MISSION_ITEM_REACHED,
    MAVLINK_MSG_ID_SYSTEM_TIME,
    MAVLINK_MSG_ID_COMMAND_ACK,
    MAVLINK_MSG_ID_STATUSTEXT,
};
#define ID_COUNT (sizeof ids / sizeof ids[0])

static void fail(const char* what)
{
    fprintf(stderr, "fuzz_mavlink: %s\n", what);
    abort();
}

typedef struct {
    sva_mavlink_parser_t parser;
    sva_mavlink_telemetry_t telemetry;
    sva_mavlink_upload_t upload;
    sva_mavlink_item_t items[ITEMS];
    int64_t now_ms;
    uint32_t dropped;
    uint32_t frames;
    bool expect;  // a whole good frame was put into an empty parser: it comes next
    mavlink_message_t expected;
} harness_t;

static harness_t h;

static void take(const mavlink_message_t* msg)
{
    if (mavlink_get_msg_entry(msg->msgid) == NULL) {
        fail("a frame with an undefined message id came out");
    }
    if (msg->len > mavlink_get_msg_entry(msg->msgid)->max_msg_len) {
        fail("a frame with a payload longer than its message's came out");
    }
    if (h.expect) {
        h.expect = false;
        if (msg->msgid != h.expected.msgid || msg->sysid != h.expected.sysid ||
            msg->compid != h.expected.compid || msg->seq != h.expected.seq ||
            msg->len != h.expected.len ||
            memcmp(_MAV_PAYLOAD(msg), _MAV_PAYLOAD(&h.expected), msg->len) != 0) {
            fail("a whole good frame put into an empty parser did not come out next");
        }
    }
    (void)sva_mavlink_telemetry_on_message(&h.telemetry, msg, h.now_ms);
    sva_mavlink_packet_t out;
    if (sva_mavlink_upload_on_message(&h.upload, msg, h.now_ms, &out) &&
        out.len > sizeof out.bytes) {
        fail("the upload's answer is longer than its buffer");
    }
}

static void check_state(void)
{
    if (h.parser.len > SVA_MAVLINK_PARSER_SIZE) {
        fail("the parser holds more than its size");
    }
    if (h.parser.dropped < h.dropped || h.parser.packets < h.frames) {
        fail("a parser counter went back");
    }
    h.dropped = h.parser.dropped;
    h.frames = h.parser.packets;
    const sva_mavlink_upload_t* up = &h.upload;
    if ((int)up->state < (int)SVA_MAVLINK_UPLOAD_IDLE ||
        (int)up->state > (int)SVA_MAVLINK_UPLOAD_FAILED) {
        fail("the upload's state is out of range");
    }
    if (up->state == SVA_MAVLINK_UPLOAD_ITEMS && up->last_seq >= up->count) {
        fail("the upload sent an item past its count");
    }
    if (up->state == SVA_MAVLINK_UPLOAD_DONE && up->distinct_sent != up->count) {
        fail("the upload is DONE without every item sent");
    }
}

// Puts bytes into the parser, draining it whenever it is full.
static void put(const uint8_t* bytes, size_t n)
{
    size_t done = 0;
    mavlink_message_t msg;
    while (done < n) {
        const size_t k = sva_mavlink_parser_put(&h.parser, bytes + done, n - done);
        done += k;
        if (k == 0U) {  // full: the next frame out, or room made (the parser's promise)
            if (sva_mavlink_parser_next(&h.parser, &msg)) {
                take(&msg);
            } else if (h.parser.len >= SVA_MAVLINK_PARSER_SIZE) {
                fail("a full parser returned no frame and made no room");
            }
        }
    }
}

static void drain(void)
{
    mavlink_message_t msg;
    while (sva_mavlink_parser_next(&h.parser, &msg)) {
        take(&msg);
        check_state();
    }
    if (h.expect) {
        fail("a whole good frame put into an empty parser did not come out");
    }
}

// A good frame of message ids[pick] (MAVLink 2, or 1 when asked and possible).
static size_t build(uint8_t pick, uint8_t sender, const uint8_t* payload, size_t n, bool v1,
                    mavlink_message_t* msg, uint8_t* out)
{
    static uint8_t seq;
    const mavlink_msg_entry_t* e = mavlink_get_msg_entry(ids[pick % ID_COUNT]);
    if (e == NULL) {
        fail("a message of the harness's list is not defined");
    }
    const bool mavlink1 = v1 && e->msgid < 256U;
    const size_t most = mavlink1 ? e->min_msg_len : e->max_msg_len;  // v1: no extensions
    if (n > most) {
        n = most;
    }
    memset(msg, 0, sizeof *msg);
    msg->msgid = e->msgid;
    msg->seq = seq++;
    memcpy(_MAV_PAYLOAD_NON_CONST(msg), payload, n);
    mavlink_status_t status;
    memset(&status, 0, sizeof status);
    if (mavlink1) {
        status.flags = MAVLINK_STATUS_FLAG_OUT_MAVLINK1;
    }
    const uint8_t system = (sender & 1U) ? VEHICLE_SYSTEM : 42U;
    const uint8_t component = (sender & 2U) ? MAV_COMP_ID_AUTOPILOT1 : 99U;
    status.current_tx_seq = msg->seq;
    mavlink_finalize_message_buffer(msg, system, component, &status, e->min_msg_len, (uint8_t)n,
                                    e->crc_extra);
    return mavlink_msg_to_send_buffer(out, msg);
}

int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size)
{
    memset(&h, 0, sizeof h);
    sva_mavlink_parser_reset(&h.parser);
    sva_mavlink_telemetry_init(&h.telemetry, VEHICLE_SYSTEM);
    h.upload.own_system = OWN_SYSTEM;
    h.upload.own_component = MAV_COMP_ID_MISSIONPLANNER;
    h.upload.target_system = VEHICLE_SYSTEM;
    h.upload.target_component = MAV_COMP_ID_AUTOPILOT1;
    h.upload.timeout_ms = 1500;
    h.upload.retries = 5;
    h.now_ms = 1000;
    sva_mavlink_packet_t out;
    (void)sva_mavlink_upload_start(&h.upload, h.items, ITEMS, h.now_ms, &out);

    size_t i = 0;
    while (i < size) {
        const uint8_t head = data[i++];
        switch (head & 3U) {
        case 0: {  // raw bytes
            if (i >= size) {
                break;
            }
            size_t n = data[i++];
            if (n > size - i) {
                n = size - i;
            }
            put(data + i, n);
            i += n;
            break;
        }
        case 1: {  // a good frame, whole, cut or flipped
            if (size - i < 3U) {
                i = size;
                break;
            }
            const uint8_t pick = data[i];
            const uint8_t sender = data[i + 1U];
            size_t n = data[i + 2U];
            i += 3U;
            if (n > size - i) {
                n = size - i;
            }
            const unsigned how = (head >> 2) & 3U;
            mavlink_message_t msg;
            uint8_t bytes[MAVLINK_MAX_PACKET_LEN];
            size_t len = build(pick, sender, data + i, n, how == 3U, &msg, bytes);
            i += n;
            if (how == 1U && len > 0U) {
                len--;  // cut short
            } else if (how == 2U) {
                bytes[len / 2U] ^= 0x5AU;  // one byte flipped
            } else if (h.parser.len == 0U) {
                h.expect = true;  // whole into an empty parser: it must come out next
                h.expected = msg;
            }
            put(bytes, len);
            if (h.expect) {
                mavlink_message_t got;
                if (!sva_mavlink_parser_next(&h.parser, &got)) {
                    fail("a whole good frame put into an empty parser did not come out");
                }
                take(&got);
            }
            break;
        }
        case 2:  // end of datagram
            sva_mavlink_parser_end(&h.parser);
            drain();
            if (h.parser.len != 0U) {
                fail("the parser still holds bytes after a datagram's end was drained");
            }
            break;
        default:  // the clock
            if (i < size) {
                h.now_ms += (int64_t)data[i++] * 64;
                (void)sva_mavlink_upload_on_time(&h.upload, h.now_ms, &out);
            }
            break;
        }
        drain();
        check_state();
    }
    return 0;
}
