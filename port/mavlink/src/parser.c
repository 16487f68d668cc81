// The MAVLink packet parser (sva_mavlink.h): a window over the bytes of the candidate
// packet. A bad candidate loses its first byte only; the search resumes right after it,
// so whatever good packet its bytes hid is found (the generated parser would have taken
// them as the bad packet's payload).
#include <string.h>

#include "sva/sva_mavlink.h"

// MAVLink 1: STX, len, seq, sysid, compid, msgid; MAVLink 2 adds the incompat and compat
// flags and a 3-byte message id.
#define V1_HEADER_LEN 6U
#define V2_HEADER_LEN MAVLINK_NUM_HEADER_BYTES
#define CRC_LEN       MAVLINK_NUM_CHECKSUM_BYTES

typedef enum verdict { PACKET_GOOD, PACKET_BAD, PACKET_INCOMPLETE } verdict_t;

void sva_mavlink_parser_reset(sva_mavlink_parser_t* self)
{
    memset(self, 0, sizeof *self);
}

size_t sva_mavlink_parser_put(sva_mavlink_parser_t* self, const uint8_t* data, size_t size)
{
    size_t room = sizeof self->bytes - self->len;
    size_t n = size < room ? size : room;
    memcpy(self->bytes + self->len, data, n);
    self->len = (uint16_t)(self->len + n);
    return n;
}

void sva_mavlink_parser_end(sva_mavlink_parser_t* self)
{
    self->flushing = true;
}

static bool is_stx(uint8_t b)
{
    return b == MAVLINK_STX || b == MAVLINK_STX_MAVLINK1;
}

// Drops the first byte and every byte after it up to the next possible start of packet.
static void drop_candidate(sva_mavlink_parser_t* self)
{
    uint16_t n = 1;
    while (n < self->len && !is_stx(self->bytes[n])) {
        n++;
    }
    memmove(self->bytes, self->bytes + n, (size_t)(self->len - n));
    self->len = (uint16_t)(self->len - n);
    self->dropped += n;
}

static void consume(sva_mavlink_parser_t* self, size_t n)
{
    memmove(self->bytes, self->bytes + n, self->len - n);
    self->len = (uint16_t)(self->len - n);
}

// Judges the candidate at bytes[0] (an STX) with what is held so far; on PACKET_GOOD
// fills *msg and sets *packet_len.
static verdict_t judge(const sva_mavlink_parser_t* self, mavlink_message_t* msg, size_t* packet_len)
{
    const uint8_t* b = self->bytes;
    const bool v2 = b[0] == MAVLINK_STX;
    const size_t header = v2 ? V2_HEADER_LEN : V1_HEADER_LEN;
    if (v2 && self->len > 2 && (b[2] & ~MAVLINK_IFLAG_MASK) != 0) {
        return PACKET_BAD;
    }
    if (self->len < header) {
        return PACKET_INCOMPLETE;
    }
    const uint8_t payload_len = b[1];
    const uint32_t msgid =
        v2 ? (uint32_t)b[7] | ((uint32_t)b[8] << 8) | ((uint32_t)b[9] << 16) : (uint32_t)b[5];
    const mavlink_msg_entry_t* entry = mavlink_get_msg_entry(msgid);
    if (entry == NULL || payload_len > entry->max_msg_len) {
        return PACKET_BAD;
    }
    const bool signed_packet = v2 && (b[2] & MAVLINK_IFLAG_SIGNED) != 0;
    const size_t total =
        header + payload_len + CRC_LEN + (signed_packet ? MAVLINK_SIGNATURE_BLOCK_LEN : 0U);
    if (self->len < total) {
        return PACKET_INCOMPLETE;
    }
    uint16_t crc;
    crc_init(&crc);
    crc_accumulate_buffer(&crc, (const char*)(b + 1), (uint16_t)(header - 1 + payload_len));
    crc_accumulate(entry->crc_extra, &crc);
    const uint8_t* ck = b + header + payload_len;
    if (ck[0] != (uint8_t)(crc & 0xFFU) || ck[1] != (uint8_t)(crc >> 8)) {
        return PACKET_BAD;
    }
    // Zeroed first: decoders read a MAVLink 2 payload cut at its trailing zeros as zeros.
    memset(msg, 0, sizeof *msg);
    msg->magic = b[0];
    msg->len = payload_len;
    if (v2) {
        msg->incompat_flags = b[2];
        msg->compat_flags = b[3];
        msg->seq = b[4];
        msg->sysid = b[5];
        msg->compid = b[6];
    } else {
        msg->seq = b[2];
        msg->sysid = b[3];
        msg->compid = b[4];
    }
    msg->msgid = msgid;
    memcpy(_MAV_PAYLOAD_NON_CONST(msg), b + header, payload_len);
    msg->checksum = crc;
    msg->ck[0] = ck[0];
    msg->ck[1] = ck[1];
    if (signed_packet) {
        memcpy(msg->signature, ck + CRC_LEN, MAVLINK_SIGNATURE_BLOCK_LEN);
    }
    *packet_len = total;
    return PACKET_GOOD;
}

bool sva_mavlink_parser_next(sva_mavlink_parser_t* self, mavlink_message_t* msg)
{
    for (;;) {
        if (self->len == 0) {
            self->flushing = false;
            return false;
        }
        if (!is_stx(self->bytes[0])) {
            drop_candidate(self);
            continue;
        }
        size_t packet_len = 0;
        switch (judge(self, msg, &packet_len)) {
        case PACKET_GOOD:
            consume(self, packet_len);
            self->packets++;
            return true;
        case PACKET_BAD:
            drop_candidate(self);
            break;
        case PACKET_INCOMPLETE:
            if (!self->flushing) {
                return false;
            }
            drop_candidate(self);  // its datagram ended: it never will be complete
            break;
        }
    }
}

bool sva_mavlink_parse(sva_mavlink_parser_t* parser, uint8_t byte, mavlink_message_t* msg)
{
    // Room is guaranteed: a held packet still incomplete is shorter than the buffer, and
    // a packet returned freed at least its own length.
    (void)sva_mavlink_parser_put(parser, &byte, 1);
    return sva_mavlink_parser_next(parser, msg);
}
