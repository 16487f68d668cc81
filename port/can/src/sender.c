// The plan sender: BEGIN, (ITEM, ITEM_TIME) per item, COMMIT, then wait for the
// bridge's ACK; retry from BEGIN on NACK or ACK timeout; ABORT when the attempts are
// exhausted or the whole transfer is older than its deadline. Time comes from the
// caller; the transport may refuse a frame (AGAIN) and the next poll resumes there.

#include "sva/sva_can.h"

#include "can_internal.h"

sva_can_sender_config_t sva_can_sender_default_config(void)
{
    sva_can_sender_config_t c;
    c.ack_timeout_ms = 250U;
    c.transfer_timeout_ms = 3000U;
    c.max_attempts = 3U;
    return c;
}

sva_can_status_t sva_can_sender_init(sva_can_sender_t* self, const sva_can_transport_t* transport,
                                     const sva_can_sender_config_t* config)
{
    sva_can_sender_config_t c = (config != NULL) ? *config : sva_can_sender_default_config();
    if ((self == NULL) || (transport == NULL) || (transport->send == NULL) ||
        (c.ack_timeout_ms == 0U) || (c.transfer_timeout_ms == 0U) || (c.max_attempts == 0U) ||
        (c.transfer_timeout_ms >= 0x80000000U) || (c.ack_timeout_ms >= 0x80000000U)) {
        return SVA_CAN_ERR_ARGUMENT;
    }
    self->transport = transport;
    self->config = c;
    self->state = SVA_CAN_TX_IDLE;
    self->last_abort_reason = 0U;
    self->last_nack = 0U;
    self->stats = (sva_can_sender_stats_t){0U, 0U, 0U, 0U, 0U, 0U, 0U, 0U};
    self->priv.plan.plan_id = 0U;
    self->priv.plan.item_count = 0U;
    self->priv.next_frame = 0U;
    self->priv.started_ms = 0U;
    self->priv.commit_sent_ms = 0U;
    self->priv.counter = 0U;
    self->priv.pending_abort = 0U;
    self->priv.abort_plan_id = 0U;
    self->priv.attempt = 0U;
    self->priv.crc = 0U;
    return SVA_CAN_OK;
}

static bool in_flight(const sva_can_sender_t* self)
{
    return (self->state == SVA_CAN_TX_SENDING) || (self->state == SVA_CAN_TX_WAIT_ACK);
}

static void fail_transfer(sva_can_sender_t* self, uint8_t reason)
{
    self->state = SVA_CAN_TX_FAILED;
    self->last_abort_reason = reason;
    self->priv.pending_abort = reason;
    self->priv.abort_plan_id = self->priv.plan.plan_id;
}

static void next_attempt(sva_can_sender_t* self)
{
    if (self->priv.attempt >= self->config.max_attempts) {
        fail_transfer(self, SVA_CAN_ABORT_RETRIES);
        return;
    }
    ++self->priv.attempt;
    ++self->stats.attempts;
    self->priv.next_frame = 0U;
    self->state = SVA_CAN_TX_SENDING;
}

// One frame to the transport; the counter advances only when the frame left.
static sva_can_status_t push(sva_can_sender_t* self, const sva_can_frame_t* f)
{
    const sva_can_status_t st = self->transport->send(self->transport->ctx, f);
    if (st == SVA_CAN_OK) {
        self->priv.counter = (uint8_t)((self->priv.counter + 1U) & 0x0FU);
        ++self->stats.frames_sent;
    } else if (st != SVA_CAN_AGAIN) {
        ++self->stats.tx_errors;
    }
    return st;
}

sva_can_status_t sva_can_sender_poll(sva_can_sender_t* self, uint32_t now_ms)
{
    sva_can_status_t st;
    if (self == NULL) {
        return SVA_CAN_ERR_ARGUMENT;
    }
    // Timers first, so a stalled transport cannot keep a transfer alive forever.
    if (in_flight(self) &&
        (sva_can_elapsed(now_ms, self->priv.started_ms) >= self->config.transfer_timeout_ms)) {
        fail_transfer(self, SVA_CAN_ABORT_TIMEOUT);
    } else if ((self->state == SVA_CAN_TX_WAIT_ACK) &&
               (sva_can_elapsed(now_ms, self->priv.commit_sent_ms) >=
                self->config.ack_timeout_ms)) {
        ++self->stats.ack_timeouts;
        next_attempt(self);
    }
    if (self->priv.pending_abort != 0U) {
        sva_can_msg_t m;
        sva_can_frame_t f;
        m.kind = SVA_CAN_MSG_PLAN_ABORT;
        m.counter = self->priv.counter;
        m.u.abort_.reason = self->priv.pending_abort;
        m.u.abort_.plan_id = self->priv.abort_plan_id;
        st = sva_can_encode(&m, &f);
        if (st != SVA_CAN_OK) {
            return st;
        }
        st = push(self, &f);
        if (st == SVA_CAN_AGAIN) {
            return SVA_CAN_OK;
        }
        if (st != SVA_CAN_OK) {
            return st;
        }
        self->priv.pending_abort = 0U;
        ++self->stats.aborts_sent;
    }
    while (self->state == SVA_CAN_TX_SENDING) {
        const uint32_t last = (2U * (uint32_t)self->priv.plan.item_count) + 1U;
        sva_can_frame_t f;
        st = sva_can_transfer_frame(&self->priv.plan, self->priv.next_frame, self->priv.counter,
                                    self->priv.crc, &f);
        if (st != SVA_CAN_OK) {
            return st;
        }
        st = push(self, &f);
        if (st == SVA_CAN_AGAIN) {
            return SVA_CAN_OK;
        }
        if (st != SVA_CAN_OK) {
            return st;
        }
        if (self->priv.next_frame == last) {
            self->state = SVA_CAN_TX_WAIT_ACK;
            self->priv.commit_sent_ms = now_ms;
        } else {
            ++self->priv.next_frame;
        }
    }
    return SVA_CAN_OK;
}

sva_can_status_t sva_can_sender_start(sva_can_sender_t* self, const sva_can_plan_t* plan,
                                      uint32_t now_ms)
{
    uint32_t i;
    if ((self == NULL) || (plan == NULL) || (plan->plan_id == 0U) ||
        (plan->item_count > SVA_CAN_MAX_ITEMS)) {
        return SVA_CAN_ERR_ARGUMENT;
    }
    // Every field must fit its signal before anything changes (all-or-nothing).
    for (i = 0U; i <= (2U * (uint32_t)plan->item_count) + 1U; ++i) {
        sva_can_frame_t f;
        if (sva_can_transfer_frame(plan, i, 0U, 0U, &f) != SVA_CAN_OK) {
            return SVA_CAN_ERR_ARGUMENT;
        }
    }
    if (in_flight(self)) {
        self->priv.pending_abort = SVA_CAN_ABORT_SUPERSEDED;
        self->priv.abort_plan_id = self->priv.plan.plan_id;
    }
    self->priv.plan.plan_id = plan->plan_id;
    self->priv.plan.algorithm = plan->algorithm;
    self->priv.plan.plan_status = plan->plan_status;
    self->priv.plan.route_count = plan->route_count;
    self->priv.plan.item_count = plan->item_count;
    for (i = 0U; i < plan->item_count; ++i) {
        self->priv.plan.items[i] = plan->items[i];
    }
    self->priv.crc = sva_can_plan_crc(&self->priv.plan);
    self->priv.started_ms = now_ms;
    self->priv.attempt = 0U;
    self->last_nack = 0U;
    self->last_abort_reason = 0U;
    next_attempt(self);
    return sva_can_sender_poll(self, now_ms);
}

sva_can_status_t sva_can_sender_on_frame(sva_can_sender_t* self, const sva_can_frame_t* frame,
                                         uint32_t now_ms)
{
    sva_can_msg_t m;
    sva_can_status_t st;
    if ((self == NULL) || (frame == NULL)) {
        return SVA_CAN_ERR_ARGUMENT;
    }
    if ((frame->id != SVA_CAN_ID_PLAN_ACK) ||
        ((frame->flags & (SVA_CAN_FLAG_EXTENDED | SVA_CAN_FLAG_RTR)) != 0U)) {
        return SVA_CAN_IGNORED;
    }
    st = sva_can_decode(frame, &m);
    if (st != SVA_CAN_OK) {
        ++self->stats.rx_rejected;
        return st;
    }
    if (!in_flight(self) || (m.u.ack.plan_id != self->priv.plan.plan_id)) {
        ++self->stats.acks_ignored;
        return SVA_CAN_IGNORED;
    }
    if (m.u.ack.result == SVA_CAN_ACK_ACCEPTED) {
        // Only the answer to a COMMIT we sent counts; a late ACK of an earlier attempt
        // while we resend is ignored (the resent COMMIT gets its own).
        if ((self->state != SVA_CAN_TX_WAIT_ACK) ||
            (m.u.ack.items_received != self->priv.plan.item_count)) {
            ++self->stats.acks_ignored;
            return SVA_CAN_IGNORED;
        }
        self->state = SVA_CAN_TX_DONE;
        return SVA_CAN_OK;
    }
    ++self->stats.nacks;
    self->last_nack = m.u.ack.result;
    next_attempt(self);
    st = sva_can_sender_poll(self, now_ms);
    return st;
}

sva_can_status_t sva_can_sender_abort(sva_can_sender_t* self, uint8_t reason, uint32_t now_ms)
{
    if ((self == NULL) || (reason == 0U) || (reason > SVA_CAN_ABORT_REASON_MAX)) {
        return SVA_CAN_ERR_ARGUMENT;
    }
    if (!in_flight(self)) {
        return SVA_CAN_OK;
    }
    fail_transfer(self, reason);
    return sva_can_sender_poll(self, now_ms);
}
