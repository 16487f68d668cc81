// The mission frame on the CAN wire (sva_can_mission_frame.h): four frames, packed bit by bit
// as every frame of sva.dbc (can_internal.h's helpers), so host byte order plays no part.
#include "sva/sva_can_mission_frame.h"

#include <string.h>

#include "can_internal.h"

static bool in_range(const sva_can_mission_frame_t* f)
{
    return (f->lat_e7 >= -SVA_CAN_MISSION_FRAME_MAX_LAT_E7) &&
           (f->lat_e7 <= SVA_CAN_MISSION_FRAME_MAX_LAT_E7) &&
           (f->lon_e7 >= -SVA_CAN_MISSION_FRAME_MAX_LON_E7) &&
           (f->lon_e7 <= SVA_CAN_MISSION_FRAME_MAX_LON_E7) && (f->alt_cm >= 0) &&
           (f->alt_cm <= SVA_CAN_MISSION_FRAME_MAX_ALT_CM) &&
           (f->cell_cm >= SVA_CAN_MISSION_FRAME_MIN_CELL_CM) &&
           (f->cell_cm <= SVA_CAN_MISSION_FRAME_MAX_CELL_CM) &&
           (f->tick_ms >= SVA_CAN_MISSION_FRAME_MIN_TICK_MS) &&
           (f->tick_ms <= SVA_CAN_MISSION_FRAME_MAX_TICK_MS) && (f->t0_ms >= 0) &&
           (f->t0_ms <= SVA_CAN_MISSION_FRAME_MAX_T0_MS);
}

// A two's complement int32 as its 32 bits, and back.
static uint64_t bits32(int32_t v)
{
    return (uint64_t)(uint32_t)v;
}

static int32_t from_bits32(uint64_t b)
{
    const uint32_t u = (uint32_t)b;
    return (u <= 0x7FFFFFFFu) ? (int32_t)u : (int32_t)(-(int64_t)(0xFFFFFFFFu - u) - 1);
}

static void finish(sva_can_frame_t* out, uint32_t id, uint8_t counter)
{
    out->id = id;
    out->flags = 0u;
    out->dlc = 8u;
    sva_can_put_bits(out->data, 0u, 4u, counter);
    out->data[7] = sva_can_frame_crc8(id, out->data);
}

sva_can_status_t sva_can_mission_frame_encode(const sva_can_mission_frame_t* f,
                                              uint8_t first_counter, sva_can_frame_t out[4])
{
    if ((f == NULL) || (out == NULL) || (first_counter > 15u) || !in_range(f)) {
        return SVA_CAN_ERR_ARGUMENT;
    }
    memset(out, 0, 4u * sizeof out[0]);
    sva_can_put_bits(out[0].data, 4u, 32u, bits32(f->lat_e7));
    sva_can_put_bits(out[0].data, 36u, 20u, (uint64_t)f->alt_cm);
    sva_can_put_bits(out[1].data, 4u, 32u, bits32(f->lon_e7));
    sva_can_put_bits(out[1].data, 36u, 20u, (uint64_t)f->cell_cm);
    sva_can_put_bits(out[2].data, 4u, 48u, (uint64_t)f->t0_ms);
    sva_can_put_bits(out[3].data, 4u, 22u, (uint64_t)f->tick_ms);
    finish(&out[0], SVA_CAN_ID_MISSION_FRAME_A, first_counter);
    finish(&out[1], SVA_CAN_ID_MISSION_FRAME_B, (uint8_t)((first_counter + 1u) & 15u));
    finish(&out[2], SVA_CAN_ID_MISSION_FRAME_C, (uint8_t)((first_counter + 2u) & 15u));
    finish(&out[3], SVA_CAN_ID_MISSION_FRAME_D, (uint8_t)((first_counter + 3u) & 15u));
    return SVA_CAN_OK;
}

void sva_can_mission_frame_rx_init(sva_can_mission_frame_rx_t* rx)
{
    if (rx != NULL) {
        memset(rx, 0, sizeof *rx);
    }
}

sva_can_status_t sva_can_mission_frame_rx(sva_can_mission_frame_rx_t* rx,
                                          const sva_can_frame_t* frame,
                                          sva_can_mission_frame_t* out)
{
    if ((rx == NULL) || (frame == NULL) || (out == NULL)) {
        return SVA_CAN_ERR_ARGUMENT;
    }
    if ((frame->id < SVA_CAN_ID_MISSION_FRAME_A) || (frame->id > SVA_CAN_ID_MISSION_FRAME_D) ||
        ((frame->flags & (SVA_CAN_FLAG_EXTENDED | SVA_CAN_FLAG_RTR)) != 0u)) {
        return SVA_CAN_IGNORED;
    }
    if ((frame->dlc != 8u) || ((frame->flags & SVA_CAN_FLAG_FD) != 0u)) {
        return SVA_CAN_ERR_DLC;
    }
    if (frame->data[7] != sva_can_frame_crc8(frame->id, frame->data)) {
        return SVA_CAN_ERR_CRC;
    }
    const unsigned part = (unsigned)(frame->id - SVA_CAN_ID_MISSION_FRAME_A);
    const uint8_t counter = (uint8_t)sva_can_get_bits(frame->data, 0u, 4u);
    if (part == 0u) {
        rx->have = 0u;
        rx->counter = counter;
    } else if ((rx->have != (uint8_t)((1u << part) - 1u)) ||
               (counter != (uint8_t)((rx->counter + part) & 15u))) {
        rx->have = 0u;
        return SVA_CAN_ERR_SEQUENCE;
    }
    sva_can_mission_frame_t* p = &rx->parts;
    switch (part) {
    case 0u:
        p->lat_e7 = from_bits32(sva_can_get_bits(frame->data, 4u, 32u));
        p->alt_cm = (int32_t)sva_can_get_bits(frame->data, 36u, 20u);
        break;
    case 1u:
        p->lon_e7 = from_bits32(sva_can_get_bits(frame->data, 4u, 32u));
        p->cell_cm = (int32_t)sva_can_get_bits(frame->data, 36u, 20u);
        break;
    case 2u:
        p->t0_ms = (int64_t)sva_can_get_bits(frame->data, 4u, 48u);
        break;
    default:
        p->tick_ms = (int32_t)sva_can_get_bits(frame->data, 4u, 22u);
        break;
    }
    rx->have = (uint8_t)(rx->have | (1u << part));
    if (rx->have != 0x0Fu) {
        return SVA_CAN_OK;
    }
    rx->have = 0u;
    if (!in_range(p)) {
        return SVA_CAN_ERR_VALUE;
    }
    *out = *p;
    return SVA_CAN_APPLIED;
}
