// The plan receiver (bridge side): reassembles BEGIN, (ITEM, ITEM_TIME)..., COMMIT into
// a staging plan and copies it to the active plan only when the COMMIT's plan id,
// item count and CRC-32 match. Any rejected frame inside a transfer discards the whole
// transfer and sends a NACK, so a partial or corrupt plan is never applied.

#include "sva/sva_can.h"

#include "can_internal.h"

#define SVA_CAN_RX_DEFAULT_TIMEOUT_MS 2000U

sva_can_status_t sva_can_receiver_init(sva_can_receiver_t* self,
                                       const sva_can_transport_t* transport, uint32_t timeout_ms)
{
    if ((self == NULL) || ((transport != NULL) && (transport->send == NULL)) ||
        (timeout_ms >= 0x80000000U)) {
        return SVA_CAN_ERR_ARGUMENT;
    }
    self->transport = transport;
    self->timeout_ms = (timeout_ms == 0U) ? SVA_CAN_RX_DEFAULT_TIMEOUT_MS : timeout_ms;
    self->stats =
        (sva_can_receiver_stats_t){0U, 0U, 0U, 0U, 0U, 0U, 0U, 0U, 0U, 0U, 0U, 0U, 0U, 0U, 0U, 0U};
    self->has_active = false;
    self->active.plan_id = 0U;
    self->active.item_count = 0U;
    self->priv.staging.plan_id = 0U;
    self->priv.staging.item_count = 0U;
    self->priv.receiving = false;
    self->priv.expect_time = false;
    self->priv.last_counter = 0U;
    self->priv.ack_counter = 0U;
    self->priv.items_done = 0U;
    self->priv.begin_ms = 0U;
    self->priv.crc = 0U;
    return SVA_CAN_OK;
}

static void send_ack(sva_can_receiver_t* self, uint8_t result, uint16_t plan_id, uint16_t items)
{
    sva_can_msg_t m;
    sva_can_frame_t f;
    if (self->transport == NULL) {
        return;
    }
    m.kind = SVA_CAN_MSG_PLAN_ACK;
    m.counter = self->priv.ack_counter;
    m.u.ack.result = result;
    m.u.ack.plan_id = plan_id;
    m.u.ack.items_received = items;
    if (sva_can_encode(&m, &f) != SVA_CAN_OK) {
        return;
    }
    if (self->transport->send(self->transport->ctx, &f) != SVA_CAN_OK) {
        ++self->stats.tx_errors;  // the sender's ACK timeout recovers
        return;
    }
    self->priv.ack_counter = (uint8_t)((self->priv.ack_counter + 1U) & 0x0FU);
    if (result == SVA_CAN_ACK_ACCEPTED) {
        ++self->stats.acks_sent;
    } else {
        ++self->stats.nacks_sent;
    }
}

// Discards the open transfer (if any) and NACKs it; returns `status` for the caller.
static sva_can_status_t reject(sva_can_receiver_t* self, uint8_t nack, sva_can_status_t status)
{
    if (self->priv.receiving) {
        self->priv.receiving = false;
        send_ack(self, nack, self->priv.staging.plan_id, self->priv.items_done);
    }
    return status;
}

sva_can_status_t sva_can_receiver_poll(sva_can_receiver_t* self, uint32_t now_ms)
{
    if (self == NULL) {
        return SVA_CAN_ERR_ARGUMENT;
    }
    if (self->priv.receiving &&
        (sva_can_elapsed(now_ms, self->priv.begin_ms) >= self->timeout_ms)) {
        ++self->stats.timeouts;
        self->priv.receiving = false;  // no NACK: the sender has its own deadline
        return SVA_CAN_ERR_TIMEOUT;
    }
    return SVA_CAN_OK;
}

static bool is_transfer_id(uint32_t id)
{
    return (id >= SVA_CAN_ID_PLAN_ABORT) && (id <= SVA_CAN_ID_PLAN_COMMIT);
}

static sva_can_status_t on_begin(sva_can_receiver_t* self, const sva_can_msg_t* m,
                                 const sva_can_frame_t* frame, uint32_t now_ms)
{
    // A BEGIN always starts over: it is how the sender retries.
    self->priv.receiving = false;
    if (m->u.begin.version != SVA_CAN_PROTOCOL_VERSION) {
        ++self->stats.bad_version;
        send_ack(self, SVA_CAN_ACK_BAD_VERSION, m->u.begin.plan_id, 0U);
        return SVA_CAN_ERR_VERSION;
    }
    if (m->u.begin.item_count > SVA_CAN_MAX_ITEMS) {
        ++self->stats.too_large;
        send_ack(self, SVA_CAN_ACK_TOO_LARGE, m->u.begin.plan_id, 0U);
        return SVA_CAN_ERR_LIMIT;
    }
    self->priv.staging.plan_id = m->u.begin.plan_id;
    self->priv.staging.algorithm = m->u.begin.algorithm;
    self->priv.staging.plan_status = m->u.begin.plan_status;
    self->priv.staging.route_count = m->u.begin.route_count;
    self->priv.staging.item_count = m->u.begin.item_count;
    self->priv.receiving = true;
    self->priv.expect_time = false;
    self->priv.items_done = 0U;
    self->priv.last_counter = m->counter;
    self->priv.begin_ms = now_ms;
    self->priv.crc = sva_can_crc32_frame(0U, frame);
    return SVA_CAN_OK;
}

static sva_can_status_t on_commit(sva_can_receiver_t* self, const sva_can_msg_t* m)
{
    sva_can_plan_t* s = &self->priv.staging;
    uint32_t i;
    if (self->priv.expect_time || (self->priv.items_done != s->item_count)) {
        ++self->stats.out_of_order;  // items missing
        return reject(self, SVA_CAN_ACK_BAD_SEQUENCE, SVA_CAN_ERR_SEQUENCE);
    }
    if ((m->u.commit.plan_id != s->plan_id) || (m->u.commit.plan_crc != self->priv.crc)) {
        ++self->stats.plan_crc_mismatch;
        return reject(self, SVA_CAN_ACK_BAD_CRC, SVA_CAN_ERR_PLAN_CRC);
    }
    // Intact and complete: only now does the active plan change.
    self->active.plan_id = s->plan_id;
    self->active.algorithm = s->algorithm;
    self->active.plan_status = s->plan_status;
    self->active.route_count = s->route_count;
    self->active.item_count = s->item_count;
    for (i = 0U; i < s->item_count; ++i) {
        self->active.items[i] = s->items[i];
    }
    self->has_active = true;
    self->priv.receiving = false;
    ++self->stats.plans_applied;
    send_ack(self, SVA_CAN_ACK_ACCEPTED, s->plan_id, s->item_count);
    return SVA_CAN_APPLIED;
}

sva_can_status_t sva_can_receiver_on_frame(sva_can_receiver_t* self, const sva_can_frame_t* frame,
                                           uint32_t now_ms)
{
    sva_can_msg_t m;
    sva_can_status_t st;
    if ((self == NULL) || (frame == NULL)) {
        return SVA_CAN_ERR_ARGUMENT;
    }
    ++self->stats.frames;
    if (sva_can_receiver_poll(self, now_ms) != SVA_CAN_OK) {
        // Counted as a timeout; the frame is still handled (a BEGIN may start anew).
    }
    if (((frame->flags & (SVA_CAN_FLAG_EXTENDED | SVA_CAN_FLAG_RTR)) != 0U) ||
        !is_transfer_id(frame->id)) {
        ++self->stats.ignored;
        return SVA_CAN_IGNORED;
    }
    st = sva_can_decode(frame, &m);
    switch (st) {
    case SVA_CAN_OK:
        break;
    case SVA_CAN_ERR_DLC:
        ++self->stats.bad_dlc;
        return reject(self, SVA_CAN_ACK_BAD_SEQUENCE, st);
    case SVA_CAN_ERR_CRC:
        ++self->stats.bad_crc;
        return reject(self, SVA_CAN_ACK_BAD_SEQUENCE, st);
    case SVA_CAN_ERR_VALUE:
        ++self->stats.bad_value;
        return reject(self, SVA_CAN_ACK_BAD_VALUE, st);
    case SVA_CAN_IGNORED:
    case SVA_CAN_AGAIN:
    case SVA_CAN_APPLIED:
    case SVA_CAN_ERR_ARGUMENT:
    case SVA_CAN_ERR_COUNTER:
    case SVA_CAN_ERR_SEQUENCE:
    case SVA_CAN_ERR_PLAN_CRC:
    case SVA_CAN_ERR_TIMEOUT:
    case SVA_CAN_ERR_LIMIT:
    case SVA_CAN_ERR_IO:
    case SVA_CAN_ERR_NAME:
    case SVA_CAN_ERR_UNSUPPORTED:
    case SVA_CAN_ERR_STATE:
    case SVA_CAN_ERR_VERSION:
    default:
        ++self->stats.ignored;
        return SVA_CAN_IGNORED;
    }
    if (m.kind == SVA_CAN_MSG_PLAN_BEGIN) {
        return on_begin(self, &m, frame, now_ms);
    }
    if (m.kind == SVA_CAN_MSG_PLAN_ABORT) {
        if (self->priv.receiving && (m.u.abort_.plan_id == self->priv.staging.plan_id)) {
            self->priv.receiving = false;
            ++self->stats.aborted;
        }
        return SVA_CAN_OK;
    }
    if (!self->priv.receiving) {
        ++self->stats.out_of_order;  // ITEM, ITEM_TIME or COMMIT without a BEGIN
        return SVA_CAN_ERR_SEQUENCE;
    }
    if (m.counter != ((self->priv.last_counter + 1U) & 0x0FU)) {
        ++self->stats.counter_jumps;  // a frame lost, repeated or reordered
        return reject(self, SVA_CAN_ACK_BAD_SEQUENCE, SVA_CAN_ERR_COUNTER);
    }
    self->priv.last_counter = m.counter;
    if (m.kind == SVA_CAN_MSG_PLAN_COMMIT) {
        return on_commit(self, &m);
    }
    if (m.kind == SVA_CAN_MSG_PLAN_ITEM) {
        sva_can_item_t* it;
        if (self->priv.expect_time || (self->priv.items_done >= self->priv.staging.item_count)) {
            ++self->stats.out_of_order;
            return reject(self, SVA_CAN_ACK_BAD_SEQUENCE, SVA_CAN_ERR_SEQUENCE);
        }
        it = &self->priv.staging.items[self->priv.items_done];
        it->uav_id = m.u.item.uav_id;
        it->target_id = m.u.item.target_id;
        it->x = m.u.item.x;
        it->y = m.u.item.y;
        self->priv.expect_time = true;
    } else {  // SVA_CAN_MSG_PLAN_ITEM_TIME
        sva_can_item_t* it;
        if (!self->priv.expect_time ||
            (m.u.item_time.item_seq != (self->priv.items_done & 0x0FU))) {
            ++self->stats.out_of_order;
            return reject(self, SVA_CAN_ACK_BAD_SEQUENCE, SVA_CAN_ERR_SEQUENCE);
        }
        it = &self->priv.staging.items[self->priv.items_done];
        it->arrive_by_ticks = m.u.item_time.arrive_by_ticks;
        it->hold_until_ticks = m.u.item_time.hold_until_ticks;
        self->priv.expect_time = false;
        ++self->priv.items_done;
    }
    self->priv.crc = sva_can_crc32_frame(self->priv.crc, frame);
    return SVA_CAN_OK;
}
