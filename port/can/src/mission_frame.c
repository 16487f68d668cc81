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
    return (u <= 0x7FFFFFFFU) ? (int32_t)u : (int32_t)(-(int64_t)(0xFFFFFFFFU - u) - 1);
}

static void finish(sva_can_frame_t* out, uint32_t id, uint8_t counter)
{
    out->id = id;
    out->flags = 0U;
    out->dlc = 8U;
    sva_can_put_bits(out->data, 0U, 4U, counter);
    out->data[7] = sva_can_frame_crc8(id, out->data);
}

sva_can_status_t sva_can_mission_frame_encode(const sva_can_mission_frame_t* f,
                                              uint8_t first_counter, sva_can_frame_t out[4])
{
    if ((f == NULL) || (out == NULL) || (first_counter > 15U) || !in_range(f)) {
        return SVA_CAN_ERR_ARGUMENT;
    }
    memset(out, 0, 4U * sizeof out[0]);
    sva_can_put_bits(out[0].data, 4U, 32U, bits32(f->lat_e7));
    sva_can_put_bits(out[0].data, 36U, 20U, (uint64_t)f->alt_cm);
    sva_can_put_bits(out[1].data, 4U, 32U, bits32(f->lon_e7));
    sva_can_put_bits(out[1].data, 36U, 20U, (uint64_t)f->cell_cm);
    sva_can_put_bits(out[2].data, 4U, 48U, (uint64_t)f->t0_ms);
    sva_can_put_bits(out[3].data, 4U, 22U, (uint64_t)f->tick_ms);
    finish(&out[0], SVA_CAN_ID_MISSION_FRAME_A, first_counter);
    finish(&out[1], SVA_CAN_ID_MISSION_FRAME_B, (uint8_t)((first_counter + 1U) & 15U));
    finish(&out[2], SVA_CAN_ID_MISSION_FRAME_C, (uint8_t)((first_counter + 2U) & 15U));
    finish(&out[3], SVA_CAN_ID_MISSION_FRAME_D, (uint8_t)((first_counter + 3U) & 15U));
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
        ((frame->flags & (SVA_CAN_FLAG_EXTENDED | SVA_CAN_FLAG_RTR)) != 0U)) {
        return SVA_CAN_IGNORED;
    }
    if ((frame->dlc != 8U) || ((frame->flags & SVA_CAN_FLAG_FD) != 0U)) {
        return SVA_CAN_ERR_DLC;
    }
    if (frame->data[7] != sva_can_frame_crc8(frame->id, frame->data)) {
        return SVA_CAN_ERR_CRC;
    }
    const unsigned part = (unsigned)(frame->id - SVA_CAN_ID_MISSION_FRAME_A);
    const uint8_t counter = (uint8_t)sva_can_get_bits(frame->data, 0U, 4U);
    if (part == 0U) {
        rx->have = 0U;
        rx->counter = counter;
    } else if ((rx->have != (uint8_t)((1U << part) - 1U)) ||
               (counter != (uint8_t)((rx->counter + part) & 15U))) {
        rx->have = 0U;
        return SVA_CAN_ERR_SEQUENCE;
    }
    sva_can_mission_frame_t* p = &rx->parts;
    switch (part) {
    case 0U:
        p->lat_e7 = from_bits32(sva_can_get_bits(frame->data, 4U, 32U));
        p->alt_cm = (int32_t)sva_can_get_bits(frame->data, 36U, 20U);
        break;
    case 1U:
        p->lon_e7 = from_bits32(sva_can_get_bits(frame->data, 4U, 32U));
        p->cell_cm = (int32_t)sva_can_get_bits(frame->data, 36U, 20U);
        break;
    case 2U:
        p->t0_ms = (int64_t)sva_can_get_bits(frame->data, 4U, 48U);
        break;
    default:
        p->tick_ms = (int32_t)sva_can_get_bits(frame->data, 4U, 22U);
        break;
    }
    rx->have = (uint8_t)(rx->have | (1U << part));
    if (rx->have != 0x0FU) {
        return SVA_CAN_OK;
    }
    rx->have = 0U;
    if (!in_range(p)) {
        return SVA_CAN_ERR_VALUE;
    }
    *out = *p;
    return SVA_CAN_APPLIED;
}
