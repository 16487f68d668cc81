/// sva_can_mission_frame.h -- the mission frame on the CAN wire (docs/can.md, sva.dbc
/// SVA_MISSION_FRAME_A..D): what a cell and a tick mean to the flight side. The
/// integers of sva_frame_t (port/frame), in four CAN frames since one classic CAN frame
/// carries 52 bits after its counter and CRC-8:
///   A (0x130) lat_e7 (int32) and alt_cm (20 bits)
///   B (0x131) lon_e7 (int32) and cell_cm (20 bits)
///   C (0x132) t0_ms (48 bits)
///   D (0x133) tick_ms (22 bits)
/// Each CAN frame: counter in bits 0..3, CRC-8 in byte 7, as every frame of sva.dbc. The
/// four are sent in order with consecutive counters; a receiver takes a mission frame
/// when it has all four of one group (A's counter + 1, + 2, + 3) with every value in range.
/// "Frame" alone is a CAN frame (sva_can_frame_t); the mission's geographic frame is
/// always the mission frame (sva_can_mission_frame_*).
/// The planner sends its mission's frame before each plan when the mission has one.
/// Depends on nothing but sva_can.h: no PROJ, no floating point, nothing allocated.
#ifndef SVA_CAN_MISSION_FRAME_H
#define SVA_CAN_MISSION_FRAME_H

#include <stdint.h>

#include "sva/sva_can.h"

#ifdef __cplusplus
extern "C" {
#endif

#define SVA_CAN_ID_MISSION_FRAME_A 0x130U
#define SVA_CAN_ID_MISSION_FRAME_B 0x131U
#define SVA_CAN_ID_MISSION_FRAME_C 0x132U
#define SVA_CAN_ID_MISSION_FRAME_D 0x133U
/// CAN frames per mission frame.
#define SVA_CAN_MISSION_FRAME_PARTS 4U

/// Ranges of a mission frame on the wire: sva_frame.h's (static-asserted by the node).
#define SVA_CAN_MISSION_FRAME_MAX_LAT_E7  850000000L
#define SVA_CAN_MISSION_FRAME_MAX_LON_E7  1800000000L
#define SVA_CAN_MISSION_FRAME_MAX_ALT_CM  1000000L
#define SVA_CAN_MISSION_FRAME_MIN_CELL_CM 10L
#define SVA_CAN_MISSION_FRAME_MAX_CELL_CM 1000000L
#define SVA_CAN_MISSION_FRAME_MIN_TICK_MS 1L
#define SVA_CAN_MISSION_FRAME_MAX_TICK_MS 3600000L
#define SVA_CAN_MISSION_FRAME_MAX_T0_MS   253402300799999LL

/// A mission frame in integers (sva_frame_t's fields).
typedef struct {
    int32_t lat_e7;   ///< origin latitude, 1e-7 degree
    int32_t lon_e7;   ///< origin longitude, 1e-7 degree
    int32_t alt_cm;   ///< flight altitude above home, centimetres
    int32_t cell_cm;  ///< cell size, centimetres
    int32_t tick_ms;  ///< tick length, milliseconds
    int64_t t0_ms;    ///< tick 0, UTC milliseconds since 1970-01-01
} sva_can_mission_frame_t;

/// A receiver's state: the parts of the group being gathered.
typedef struct {
    uint8_t have;     ///< bit p set: part p (0 A .. 3 D) of the current group received
    uint8_t counter;  ///< part A's counter of the current group
    sva_can_mission_frame_t parts;
} sva_can_mission_frame_rx_t;

/// Encodes the mission frame *frame as its four CAN frames, counters first_counter .. + 3 (mod 16).
/// Returns SVA_CAN_OK, or SVA_CAN_ERR_ARGUMENT for NULL, a counter above 15 or a value
/// outside its range (then out is untouched). O(1).
SVA_CAN_NODISCARD sva_can_status_t sva_can_mission_frame_encode(
    const sva_can_mission_frame_t* frame, uint8_t first_counter, sva_can_frame_t out[4]);

/// Clears a receiver of mission frames.
void sva_can_mission_frame_rx_init(sva_can_mission_frame_rx_t* rx);

/// Takes one received CAN frame. Returns SVA_CAN_IGNORED for any other id (and
/// extended, RTR or FD frames), SVA_CAN_ERR_DLC, SVA_CAN_ERR_CRC, SVA_CAN_ERR_VALUE (a
/// value out of range; the group is dropped), SVA_CAN_ERR_SEQUENCE (a part that is not
/// the next of the group A started; the group is dropped), SVA_CAN_OK (stored), or
/// SVA_CAN_APPLIED when it completed a group: *out then holds the mission frame. O(1).
SVA_CAN_NODISCARD sva_can_status_t sva_can_mission_frame_rx(sva_can_mission_frame_rx_t* rx,
                                                            const sva_can_frame_t* frame,
                                                            sva_can_mission_frame_t* out);

#ifdef __cplusplus
}
#endif

#endif  // SVA_CAN_MISSION_FRAME_H
