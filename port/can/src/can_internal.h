// Private helpers shared by the CAN port's sources (not installed).
#ifndef SVA_CAN_INTERNAL_H
#define SVA_CAN_INTERNAL_H

#include "sva/sva_can.h"

/// Writes `len` bits of value at little-endian bit position `start` of data.
void sva_can_put_bits(uint8_t data[8], unsigned start, unsigned len, uint64_t value);
/// Reads `len` bits at little-endian bit position `start`.
uint64_t sva_can_get_bits(const uint8_t data[8], unsigned start, unsigned len);

/// Builds transfer frame `index` of *plan: 0 BEGIN, 1 + 2i ITEM i, 2 + 2i ITEM_TIME i,
/// 2n + 1 COMMIT (with plan_crc). Returns SVA_CAN_ERR_ARGUMENT past the end.
sva_can_status_t sva_can_transfer_frame(const sva_can_plan_t* plan, uint32_t index, uint8_t counter,
                                        uint32_t plan_crc, sva_can_frame_t* out);

/// Feeds a transfer frame's bytes 0..6, counter nibble cleared, into a running CRC-32.
uint32_t sva_can_crc32_frame(uint32_t crc, const sva_can_frame_t* frame);

/// now - then modulo 2^32: elapsed milliseconds, right across the wrap-around.
static inline uint32_t sva_can_elapsed(uint32_t now_ms, uint32_t then_ms)
{
    return (uint32_t)(now_ms - then_ms);
}

#endif  // SVA_CAN_INTERNAL_H
