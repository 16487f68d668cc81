// The pure codec: CRCs, bit packing, encode and decode of every frame of sva.dbc.
// Signals are little-endian (DBC "@1"): bit k of a signal starting at bit s sits at
// absolute bit s + k, i.e. byte (s + k) / 8, bit (s + k) % 8. Packing is done bit by
// bit on uint64_t values, never by casting the byte array, so host byte order plays no
// part.

#include "sva/sva_can.h"

#include "can_internal.h"

const char* sva_can_status_name(sva_can_status_t status)
{
    switch (status) {
    case SVA_CAN_OK:
        return "ok";
    case SVA_CAN_AGAIN:
        return "again";
    case SVA_CAN_IGNORED:
        return "ignored";
    case SVA_CAN_APPLIED:
        return "applied";
    case SVA_CAN_ERR_ARGUMENT:
        return "argument";
    case SVA_CAN_ERR_DLC:
        return "dlc";
    case SVA_CAN_ERR_CRC:
        return "crc";
    case SVA_CAN_ERR_VALUE:
        return "value";
    case SVA_CAN_ERR_COUNTER:
        return "counter";
    case SVA_CAN_ERR_SEQUENCE:
        return "sequence";
    case SVA_CAN_ERR_PLAN_CRC:
        return "plan_crc";
    case SVA_CAN_ERR_TIMEOUT:
        return "timeout";
    case SVA_CAN_ERR_LIMIT:
        return "limit";
    case SVA_CAN_ERR_IO:
        return "io";
    case SVA_CAN_ERR_NAME:
        return "name";
    case SVA_CAN_ERR_UNSUPPORTED:
        return "unsupported";
    case SVA_CAN_ERR_STATE:
        return "state";
    case SVA_CAN_ERR_VERSION:
        return "version";
    default:
        return "unknown";
    }
}

uint8_t sva_can_crc8(const uint8_t* data, size_t size)
{
    uint8_t crc = 0xFFU;
    size_t i;
    if (data == NULL) {
        return 0U;
    }
    for (i = 0; i < size; ++i) {
        unsigned bit;
        crc = (uint8_t)(crc ^ data[i]);
        for (bit = 0; bit < 8U; ++bit) {
            crc = ((crc & 0x80U) != 0U) ? (uint8_t)((uint8_t)(crc << 1) ^ 0x1DU)
                                        : (uint8_t)(crc << 1);
        }
    }
    return (uint8_t)(crc ^ 0xFFU);
}

uint32_t sva_can_crc32(uint32_t crc, const uint8_t* data, size_t size)
{
    size_t i;
    if (data == NULL) {
        return crc;
    }
    crc = ~crc;
    for (i = 0; i < size; ++i) {
        unsigned bit;
        crc ^= data[i];
        for (bit = 0; bit < 8U; ++bit) {
            crc = ((crc & 1U) != 0U) ? ((crc >> 1) ^ 0xEDB88320U) : (crc >> 1);
        }
    }
    return ~crc;
}

uint8_t sva_can_frame_crc8(uint32_t id, const uint8_t data[8])
{
    // SPEC of the protocol (sva.h top, docs/can.md): id as two little-endian bytes,
    // then data bytes 0..6.
    uint8_t buf[9];
    unsigned i;
    buf[0] = (uint8_t)(id & 0xFFU);
    buf[1] = (uint8_t)((id >> 8) & 0x07U);
    for (i = 0; i < 7U; ++i) {
        buf[2U + i] = data[i];
    }
    return sva_can_crc8(buf, sizeof buf);
}

void sva_can_put_bits(uint8_t data[8], unsigned start, unsigned len, uint64_t value)
{
    unsigned k;
    for (k = 0; k < len; ++k) {
        const unsigned bit = start + k;
        const uint8_t mask = (uint8_t)(1U << (bit % 8U));
        if (((value >> k) & 1U) != 0U) {
            data[bit / 8U] = (uint8_t)(data[bit / 8U] | mask);
        } else {
            data[bit / 8U] = (uint8_t)(data[bit / 8U] & (uint8_t)~mask);
        }
    }
}

uint64_t sva_can_get_bits(const uint8_t data[8], unsigned start, unsigned len)
{
    uint64_t value = 0U;
    unsigned k;
    for (k = 0; k < len; ++k) {
        const unsigned bit = start + k;
        if (((data[bit / 8U] >> (bit % 8U)) & 1U) != 0U) {
            value |= (uint64_t)1U << k;
        }
    }
    return value;
}

// Two's complement int16 <-> 16-bit field, without implementation-defined casts.
static uint64_t from_i16(int16_t v)
{
    return (v < 0) ? (uint64_t)(65536L + (long)v) : (uint64_t)(long)v;
}

static int16_t to_i16(uint64_t raw)
{
    const long v = (long)(raw & 0xFFFFU);
    return (int16_t)((v >= 32768L) ? (v - 65536L) : v);
}

sva_can_msg_kind_t sva_can_kind_of_id(uint32_t id)
{
    switch (id) {
    case SVA_CAN_ID_HEARTBEAT:
        return SVA_CAN_MSG_HEARTBEAT;
    case SVA_CAN_ID_PLAN_BEGIN:
        return SVA_CAN_MSG_PLAN_BEGIN;
    case SVA_CAN_ID_PLAN_ITEM:
        return SVA_CAN_MSG_PLAN_ITEM;
    case SVA_CAN_ID_PLAN_ITEM_TIME:
        return SVA_CAN_MSG_PLAN_ITEM_TIME;
    case SVA_CAN_ID_PLAN_COMMIT:
        return SVA_CAN_MSG_PLAN_COMMIT;
    case SVA_CAN_ID_PLAN_ABORT:
        return SVA_CAN_MSG_PLAN_ABORT;
    case SVA_CAN_ID_PLAN_ACK:
        return SVA_CAN_MSG_PLAN_ACK;
    case SVA_CAN_ID_VEHICLE_STATUS:
        return SVA_CAN_MSG_VEHICLE_STATUS;
    case SVA_CAN_ID_VEHICLE_FUEL:
        return SVA_CAN_MSG_VEHICLE_FUEL;
    case SVA_CAN_ID_MISSION_CLOCK:
        return SVA_CAN_MSG_MISSION_CLOCK;
    default:
        return SVA_CAN_MSG_NONE;
    }
}

static uint32_t id_of_kind(sva_can_msg_kind_t kind)
{
    switch (kind) {
    case SVA_CAN_MSG_HEARTBEAT:
        return SVA_CAN_ID_HEARTBEAT;
    case SVA_CAN_MSG_PLAN_BEGIN:
        return SVA_CAN_ID_PLAN_BEGIN;
    case SVA_CAN_MSG_PLAN_ITEM:
        return SVA_CAN_ID_PLAN_ITEM;
    case SVA_CAN_MSG_PLAN_ITEM_TIME:
        return SVA_CAN_ID_PLAN_ITEM_TIME;
    case SVA_CAN_MSG_PLAN_COMMIT:
        return SVA_CAN_ID_PLAN_COMMIT;
    case SVA_CAN_MSG_PLAN_ABORT:
        return SVA_CAN_ID_PLAN_ABORT;
    case SVA_CAN_MSG_PLAN_ACK:
        return SVA_CAN_ID_PLAN_ACK;
    case SVA_CAN_MSG_VEHICLE_STATUS:
        return SVA_CAN_ID_VEHICLE_STATUS;
    case SVA_CAN_MSG_VEHICLE_FUEL:
        return SVA_CAN_ID_VEHICLE_FUEL;
    case SVA_CAN_MSG_MISSION_CLOCK:
        return SVA_CAN_ID_MISSION_CLOCK;
    case SVA_CAN_MSG_NONE:
    case SVA_CAN_MSG_COUNT_:
    default:
        return 0U;
    }
}

// Field widths must hold the value: the encoder refuses rather than truncates.
#define FITS(value, bits) ((uint64_t)(value) < ((uint64_t)1U << (bits)))

sva_can_status_t sva_can_encode(const sva_can_msg_t* msg, sva_can_frame_t* out)
{
    uint8_t d[8] = {0U, 0U, 0U, 0U, 0U, 0U, 0U, 0U};
    uint32_t id;
    unsigned i;
    if ((msg == NULL) || (out == NULL) || (msg->counter > 15U)) {
        return SVA_CAN_ERR_ARGUMENT;
    }
    id = id_of_kind(msg->kind);
    if (id == 0U) {
        return SVA_CAN_ERR_ARGUMENT;
    }
    sva_can_put_bits(d, 0U, 4U, msg->counter);
    switch (msg->kind) {
    case SVA_CAN_MSG_HEARTBEAT: {
        const sva_can_heartbeat_t* m = &msg->u.heartbeat;
        if (!FITS(m->state, 4U)) {
            return SVA_CAN_ERR_ARGUMENT;
        }
        sva_can_put_bits(d, 4U, 4U, m->state);
        sva_can_put_bits(d, 8U, 16U, m->active_plan_id);
        sva_can_put_bits(d, 24U, 8U, m->uav_count);
        sva_can_put_bits(d, 32U, 8U, m->target_count);
        sva_can_put_bits(d, 40U, 8U, m->covered_count);
        sva_can_put_bits(d, 48U, 8U, m->faults);
        break;
    }
    case SVA_CAN_MSG_PLAN_BEGIN: {
        const sva_can_begin_t* m = &msg->u.begin;
        if (!FITS(m->version, 4U) || !FITS(m->algorithm, 4U) || !FITS(m->plan_status, 4U)) {
            return SVA_CAN_ERR_ARGUMENT;
        }
        sva_can_put_bits(d, 4U, 4U, m->version);
        sva_can_put_bits(d, 8U, 16U, m->plan_id);
        sva_can_put_bits(d, 24U, 16U, m->item_count);
        sva_can_put_bits(d, 40U, 4U, m->algorithm);
        sva_can_put_bits(d, 44U, 4U, m->plan_status);
        sva_can_put_bits(d, 48U, 8U, m->route_count);
        break;
    }
    case SVA_CAN_MSG_PLAN_ITEM: {
        const sva_can_item_where_t* m = &msg->u.item;
        if (!FITS(m->target_id, 12U)) {
            return SVA_CAN_ERR_ARGUMENT;
        }
        sva_can_put_bits(d, 4U, 8U, m->uav_id);
        sva_can_put_bits(d, 12U, 12U, m->target_id);
        sva_can_put_bits(d, 24U, 16U, from_i16(m->x));
        sva_can_put_bits(d, 40U, 16U, from_i16(m->y));
        break;
    }
    case SVA_CAN_MSG_PLAN_ITEM_TIME: {
        const sva_can_item_time_t* m = &msg->u.item_time;
        if (!FITS(m->item_seq, 4U) || !FITS(m->arrive_by_ticks, 24U) ||
            !FITS(m->hold_until_ticks, 24U)) {
            return SVA_CAN_ERR_ARGUMENT;
        }
        sva_can_put_bits(d, 4U, 4U, m->item_seq);
        sva_can_put_bits(d, 8U, 24U, m->arrive_by_ticks);
        sva_can_put_bits(d, 32U, 24U, m->hold_until_ticks);
        break;
    }
    case SVA_CAN_MSG_PLAN_COMMIT:
        sva_can_put_bits(d, 8U, 16U, msg->u.commit.plan_id);
        sva_can_put_bits(d, 24U, 32U, msg->u.commit.plan_crc);
        break;
    case SVA_CAN_MSG_PLAN_ABORT:
        if (!FITS(msg->u.abort_.reason, 4U)) {
            return SVA_CAN_ERR_ARGUMENT;
        }
        sva_can_put_bits(d, 4U, 4U, msg->u.abort_.reason);
        sva_can_put_bits(d, 8U, 16U, msg->u.abort_.plan_id);
        break;
    case SVA_CAN_MSG_PLAN_ACK:
        if (!FITS(msg->u.ack.result, 4U)) {
            return SVA_CAN_ERR_ARGUMENT;
        }
        sva_can_put_bits(d, 4U, 4U, msg->u.ack.result);
        sva_can_put_bits(d, 8U, 16U, msg->u.ack.plan_id);
        sva_can_put_bits(d, 24U, 16U, msg->u.ack.items_received);
        break;
    case SVA_CAN_MSG_VEHICLE_STATUS: {
        const sva_can_vehicle_status_t* m = &msg->u.vehicle;
        if (!FITS(m->state, 4U)) {
            return SVA_CAN_ERR_ARGUMENT;
        }
        sva_can_put_bits(d, 4U, 4U, m->state);
        sva_can_put_bits(d, 8U, 8U, m->uav_id);
        sva_can_put_bits(d, 16U, 16U, from_i16(m->x));
        sva_can_put_bits(d, 32U, 16U, from_i16(m->y));
        break;
    }
    case SVA_CAN_MSG_VEHICLE_FUEL:
        sva_can_put_bits(d, 8U, 8U, msg->u.fuel.uav_id);
        sva_can_put_bits(d, 16U, 32U, msg->u.fuel.fuel);
        break;
    case SVA_CAN_MSG_MISSION_CLOCK:
        if (msg->u.clock.tick > (uint32_t)SVA_CAN_MAX_TICK) {
            return SVA_CAN_ERR_ARGUMENT;
        }
        sva_can_put_bits(d, 8U, 24U, msg->u.clock.tick);
        break;
    case SVA_CAN_MSG_NONE:
    case SVA_CAN_MSG_COUNT_:
    default:
        return SVA_CAN_ERR_ARGUMENT;
    }
    d[7] = sva_can_frame_crc8(id, d);
    out->id = id;
    out->flags = 0U;
    out->dlc = 8U;
    for (i = 0; i < 8U; ++i) {
        out->data[i] = d[i];
    }
    return SVA_CAN_OK;
}

sva_can_status_t sva_can_frame_check(const sva_can_frame_t* frame, int expected_counter)
{
    if (frame == NULL) {
        return SVA_CAN_ERR_ARGUMENT;
    }
    if ((frame->dlc != 8U) || ((frame->flags & SVA_CAN_FLAG_FD) != 0U)) {
        return SVA_CAN_ERR_DLC;
    }
    if (sva_can_frame_crc8(frame->id, frame->data) != frame->data[7]) {
        return SVA_CAN_ERR_CRC;
    }
    if ((expected_counter >= 0) && (expected_counter <= 15) &&
        ((unsigned)(frame->data[0] & 0x0FU) != (unsigned)expected_counter)) {
        return SVA_CAN_ERR_COUNTER;
    }
    return SVA_CAN_OK;
}

sva_can_status_t sva_can_decode(const sva_can_frame_t* frame, sva_can_msg_t* out)
{
    sva_can_msg_t m;
    const uint8_t* d;
    if ((frame == NULL) || (out == NULL)) {
        return SVA_CAN_ERR_ARGUMENT;
    }
    if ((frame->flags & (SVA_CAN_FLAG_EXTENDED | SVA_CAN_FLAG_RTR)) != 0U) {
        return SVA_CAN_IGNORED;  // DroneCAN and other 29-bit traffic shares the bus
    }
    m.kind = sva_can_kind_of_id(frame->id);
    if (m.kind == SVA_CAN_MSG_NONE) {
        return SVA_CAN_IGNORED;
    }
    // DLC before any byte is read: classic frames of exactly 8 bytes only.
    if ((frame->dlc != 8U) || ((frame->flags & SVA_CAN_FLAG_FD) != 0U)) {
        return SVA_CAN_ERR_DLC;
    }
    d = frame->data;
    if (sva_can_frame_crc8(frame->id, d) != d[7]) {
        return SVA_CAN_ERR_CRC;
    }
    m.counter = (uint8_t)sva_can_get_bits(d, 0U, 4U);
    switch (m.kind) {
    case SVA_CAN_MSG_HEARTBEAT:
        m.u.heartbeat.state = (uint8_t)sva_can_get_bits(d, 4U, 4U);
        m.u.heartbeat.active_plan_id = (uint16_t)sva_can_get_bits(d, 8U, 16U);
        m.u.heartbeat.uav_count = (uint8_t)sva_can_get_bits(d, 24U, 8U);
        m.u.heartbeat.target_count = (uint8_t)sva_can_get_bits(d, 32U, 8U);
        m.u.heartbeat.covered_count = (uint8_t)sva_can_get_bits(d, 40U, 8U);
        m.u.heartbeat.faults = (uint8_t)sva_can_get_bits(d, 48U, 8U);
        if ((m.u.heartbeat.state > SVA_CAN_NODE_STATE_MAX) ||
            ((m.u.heartbeat.faults & (uint8_t)~SVA_CAN_FAULT_MASK) != 0U)) {
            return SVA_CAN_ERR_VALUE;
        }
        break;
    case SVA_CAN_MSG_PLAN_BEGIN:
        m.u.begin.version = (uint8_t)sva_can_get_bits(d, 4U, 4U);
        m.u.begin.plan_id = (uint16_t)sva_can_get_bits(d, 8U, 16U);
        m.u.begin.item_count = (uint16_t)sva_can_get_bits(d, 24U, 16U);
        m.u.begin.algorithm = (uint8_t)sva_can_get_bits(d, 40U, 4U);
        m.u.begin.plan_status = (uint8_t)sva_can_get_bits(d, 44U, 4U);
        m.u.begin.route_count = (uint8_t)sva_can_get_bits(d, 48U, 8U);
        // The version is checked by the receiver (it NACKs with BAD_VERSION).
        if ((m.u.begin.plan_id == 0U) || (m.u.begin.algorithm >= (uint8_t)SVA_ALGO_COUNT_) ||
            (m.u.begin.plan_status < SVA_CAN_PLAN_COMPLETE) ||
            (m.u.begin.plan_status > SVA_CAN_PLAN_PARTIAL)) {
            return SVA_CAN_ERR_VALUE;
        }
        break;
    case SVA_CAN_MSG_PLAN_ITEM:
        m.u.item.uav_id = (uint8_t)sva_can_get_bits(d, 4U, 8U);
        m.u.item.target_id = (uint16_t)sva_can_get_bits(d, 12U, 12U);
        m.u.item.x = to_i16(sva_can_get_bits(d, 24U, 16U));
        m.u.item.y = to_i16(sva_can_get_bits(d, 40U, 16U));
        if ((m.u.item.uav_id == 0U) || (m.u.item.target_id == 0U)) {
            return SVA_CAN_ERR_VALUE;
        }
        break;
    case SVA_CAN_MSG_PLAN_ITEM_TIME:
        m.u.item_time.item_seq = (uint8_t)sva_can_get_bits(d, 4U, 4U);
        m.u.item_time.arrive_by_ticks = (uint32_t)sva_can_get_bits(d, 8U, 24U);
        m.u.item_time.hold_until_ticks = (uint32_t)sva_can_get_bits(d, 32U, 24U);
        if (m.u.item_time.arrive_by_ticks >= m.u.item_time.hold_until_ticks) {
            return SVA_CAN_ERR_VALUE;  // SPEC section 1: start < end
        }
        break;
    case SVA_CAN_MSG_PLAN_COMMIT:
        m.u.commit.plan_id = (uint16_t)sva_can_get_bits(d, 8U, 16U);
        m.u.commit.plan_crc = (uint32_t)sva_can_get_bits(d, 24U, 32U);
        if (m.u.commit.plan_id == 0U) {
            return SVA_CAN_ERR_VALUE;
        }
        break;
    case SVA_CAN_MSG_PLAN_ABORT:
        m.u.abort_.reason = (uint8_t)sva_can_get_bits(d, 4U, 4U);
        m.u.abort_.plan_id = (uint16_t)sva_can_get_bits(d, 8U, 16U);
        if ((m.u.abort_.reason == 0U) || (m.u.abort_.reason > SVA_CAN_ABORT_REASON_MAX)) {
            return SVA_CAN_ERR_VALUE;
        }
        break;
    case SVA_CAN_MSG_PLAN_ACK:
        m.u.ack.result = (uint8_t)sva_can_get_bits(d, 4U, 4U);
        m.u.ack.plan_id = (uint16_t)sva_can_get_bits(d, 8U, 16U);
        m.u.ack.items_received = (uint16_t)sva_can_get_bits(d, 24U, 16U);
        if (m.u.ack.result > SVA_CAN_ACK_RESULT_MAX) {
            return SVA_CAN_ERR_VALUE;
        }
        break;
    case SVA_CAN_MSG_VEHICLE_STATUS:
        m.u.vehicle.state = (uint8_t)sva_can_get_bits(d, 4U, 4U);
        m.u.vehicle.uav_id = (uint8_t)sva_can_get_bits(d, 8U, 8U);
        m.u.vehicle.x = to_i16(sva_can_get_bits(d, 16U, 16U));
        m.u.vehicle.y = to_i16(sva_can_get_bits(d, 32U, 16U));
        if ((m.u.vehicle.uav_id == 0U) || (m.u.vehicle.state > SVA_CAN_VEHICLE_STATE_MAX)) {
            return SVA_CAN_ERR_VALUE;
        }
        break;
    case SVA_CAN_MSG_VEHICLE_FUEL:
        m.u.fuel.uav_id = (uint8_t)sva_can_get_bits(d, 8U, 8U);
        m.u.fuel.fuel = (uint32_t)sva_can_get_bits(d, 16U, 32U);
        if (m.u.fuel.uav_id == 0U) {
            return SVA_CAN_ERR_VALUE;
        }
        break;
    case SVA_CAN_MSG_MISSION_CLOCK:
        m.u.clock.tick = (uint32_t)sva_can_get_bits(d, 8U, 24U);
        break;
    case SVA_CAN_MSG_NONE:
    case SVA_CAN_MSG_COUNT_:
    default:
        return SVA_CAN_IGNORED;
    }
    *out = m;
    return SVA_CAN_OK;
}
