// The in-memory loopback bus: two bounded FIFO queues, one per direction.

#include "sva/sva_can.h"
#include "sva/sva_can_transport.h"

void sva_can_loopback_init(sva_can_loopback_t* self)
{
    unsigned e;
    if (self == NULL) {
        return;
    }
    for (e = 0; e < 2U; ++e) {
        self->to[e].head = 0U;
        self->to[e].count = 0U;
        self->sent[e] = 0U;
        self->dropped[e] = 0U;
        self->priv_ends[e].bus = self;
        self->priv_ends[e].endpoint = e;
    }
}

static sva_can_status_t queue_push(sva_can_queue_t* q, const sva_can_frame_t* f)
{
    if (q->count >= SVA_CAN_LOOPBACK_CAPACITY) {
        return SVA_CAN_AGAIN;
    }
    q->frames[((uint32_t)q->head + q->count) % SVA_CAN_LOOPBACK_CAPACITY] = *f;
    ++q->count;
    return SVA_CAN_OK;
}

static sva_can_status_t queue_pop(sva_can_queue_t* q, sva_can_frame_t* f)
{
    if (q->count == 0U) {
        return SVA_CAN_AGAIN;
    }
    *f = q->frames[q->head];
    q->head = (uint16_t)(((uint32_t)q->head + 1U) % SVA_CAN_LOOPBACK_CAPACITY);
    --q->count;
    return SVA_CAN_OK;
}

sva_can_status_t sva_can_loopback_inject(sva_can_loopback_t* self, unsigned endpoint,
                                         const sva_can_frame_t* frame)
{
    if ((self == NULL) || (endpoint > 1U) || (frame == NULL)) {
        return SVA_CAN_ERR_ARGUMENT;
    }
    return queue_push(&self->to[endpoint], frame);
}

sva_can_status_t sva_can_loopback_take(sva_can_loopback_t* self, unsigned endpoint,
                                       sva_can_frame_t* out)
{
    if ((self == NULL) || (endpoint > 1U) || (out == NULL)) {
        return SVA_CAN_ERR_ARGUMENT;
    }
    return queue_pop(&self->to[endpoint], out);
}

static sva_can_status_t loop_send(void* ctx, const sva_can_frame_t* frame)
{
    sva_can_loopback_end_t* end = (sva_can_loopback_end_t*)ctx;
    sva_can_status_t st;
    if ((end == NULL) || (frame == NULL)) {
        return SVA_CAN_ERR_ARGUMENT;
    }
    st = queue_push(&end->bus->to[1U - end->endpoint], frame);
    if (st == SVA_CAN_OK) {
        ++end->bus->sent[end->endpoint];
    } else {
        ++end->bus->dropped[end->endpoint];
    }
    return st;
}

static sva_can_status_t loop_recv(void* ctx, sva_can_frame_t* frame)
{
    sva_can_loopback_end_t* end = (sva_can_loopback_end_t*)ctx;
    if ((end == NULL) || (frame == NULL)) {
        return SVA_CAN_ERR_ARGUMENT;
    }
    return queue_pop(&end->bus->to[end->endpoint], frame);
}

sva_can_status_t sva_can_loopback_transport(sva_can_loopback_t* self, unsigned endpoint,
                                            sva_can_transport_t* out)
{
    if ((self == NULL) || (endpoint > 1U) || (out == NULL)) {
        return SVA_CAN_ERR_ARGUMENT;
    }
    out->send = loop_send;
    out->recv = loop_recv;
    out->ctx = &self->priv_ends[endpoint];
    return SVA_CAN_OK;
}
