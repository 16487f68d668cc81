/// sva_can.h -- the CAN port of sva: a project-defined protocol (port/can/sva.dbc),
/// its codec, the plan sender and receiver state machines, and transports.
///
/// Its own protocol (no flight stack has a CAN mission message; a bridge on the flight
/// side turns it into commands): docs/can.md says why and how.
///
/// ## Pipeline
///   sva_plan() -> sva_can_plan_from_core() -> sva_can_plan_t (wire items)
///   -> sva_can_sender_*: BEGIN, (ITEM, ITEM_TIME) per assignment, COMMIT, wait ACK,
///      retry, ABORT on timeout -> sva_can_transport_t (loopback or SocketCAN)
///   -> sva_can_receiver_*: checks CRC-8, counter, DLC, order, CRC-32, timeout;
///      applies a plan only when it is complete and intact, then ACKs.
///
/// ## Frames (all 11-bit ids, classic CAN, DLC 8, little-endian signals; sva.dbc)
/// Every frame: bits 0..3 rolling counter, byte 7 CRC-8 (SAE J1850: poly 0x1D, init
/// 0xFF, xorout 0xFF, not reflected) over the id as two little-endian bytes then data
/// bytes 0..6. COMMIT carries a CRC-32 (ISO-HDLC / zlib) over data bytes 0..6 of BEGIN
/// and every ITEM and ITEM_TIME frame in transfer order, counter nibbles cleared.
///
/// ## Where every byte lives
/// Nothing is allocated. The caller owns every struct (sender, receiver, loopback bus,
/// SocketCAN handle: sva_can_transport.h); the largest is sva_can_plan_t, 12 * SVA_CAN_MAX_ITEMS +
/// 8 bytes, held once by the sender and twice (staging, active) by the receiver. Stack use of every
/// function is O(1) and small (a few frames).
///
/// ## Time
/// No function reads a clock. Callers pass a monotonic time in milliseconds (uint32_t);
/// intervals are computed modulo 2^32, so they are right across the wrap-around as long
/// as each interval is shorter than 2^31 ms.
///
/// ## Trust
/// Every received frame is untrusted: it is checked (id, flags, DLC before any copy,
/// CRC, counter, value ranges, order) and rejected with a counted reason, never
/// asserted on. SVA_CAN_ASSERT-style checks are not used on frames; API misuse (NULL
/// pointers) returns SVA_CAN_ERR_ARGUMENT.
///
/// ## Thread safety
/// Reentrant: functions touch only the structs passed in. One struct, one thread.

#ifndef SVA_CAN_H
#define SVA_CAN_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "sva/sva.h"

#ifdef __cplusplus
extern "C" {
#endif

#define SVA_CAN_VERSION_MAJOR 0
#define SVA_CAN_VERSION_MINOR 1
#define SVA_CAN_VERSION_PATCH 0
/// Protocol version (the DBC's VERSION "sva-can N") carried in PLAN_BEGIN; a receiver
/// refuses any other (SVA_CAN_ERR_VERSION, NACK BAD_VERSION). 2: SVA_MISSION_CLOCK.
#define SVA_CAN_PROTOCOL_VERSION 2

#if defined(__GNUC__) || defined(__clang__)
#    define SVA_CAN_NODISCARD __attribute__((warn_unused_result))
#else
#    define SVA_CAN_NODISCARD
#endif

// =================================================================================
// Bounds

/// Most assignments (ITEM + ITEM_TIME pairs) in one plan. Cost: 12 B per item in each
/// sva_can_plan_t (sender 1, receiver 2).
#ifndef SVA_CAN_MAX_ITEMS
#    define SVA_CAN_MAX_ITEMS 1024
#endif
#if (SVA_CAN_MAX_ITEMS < 1) || (SVA_CAN_MAX_ITEMS > 65535)
#    error "SVA_CAN_MAX_ITEMS must be in [1, 65535]"
#endif

/// Frames the in-memory loopback queue holds per direction.
#ifndef SVA_CAN_LOOPBACK_CAPACITY
#    define SVA_CAN_LOOPBACK_CAPACITY 4096
#endif
#if (SVA_CAN_LOOPBACK_CAPACITY < 2) || (SVA_CAN_LOOPBACK_CAPACITY > 65535)
#    error "SVA_CAN_LOOPBACK_CAPACITY must be in [2, 65535]"
#endif

/// Wire limits (the field widths of sva.dbc). A mission outside them cannot be sent;
/// sva_can_mission_check() reports the field and the limit.
#define SVA_CAN_MAX_UAV_ID    255L       ///< uav_id: 8 bits, 0 is not an id
#define SVA_CAN_MAX_TARGET_ID 4095L      ///< target_id: 12 bits, 0 is not an id
#define SVA_CAN_MAX_TICK      16777215L  ///< arrive_by / hold_until: 24 bits
#define SVA_CAN_MAX_COORD     32767L     ///< x, y: int16, exactly SPEC's range
#define SVA_CAN_MIN_COORD     (-32768L)

// =================================================================================
// Status

typedef enum {
    SVA_CAN_OK = 0,
    /// Nothing to read, or the transmit queue is full: try again later (not an error).
    SVA_CAN_AGAIN = 1,
    /// The frame is not one of this protocol's (other id, extended id, RTR): ignore it.
    SVA_CAN_IGNORED = 2,
    /// sva_can_receiver_on_frame(): this frame completed a plan, which is now active.
    SVA_CAN_APPLIED = 3,
    SVA_CAN_ERR_ARGUMENT = -1,      ///< NULL pointer or value out of range in an API call
    SVA_CAN_ERR_DLC = -2,           ///< data length code is not 8
    SVA_CAN_ERR_CRC = -3,           ///< CRC-8 of the frame does not match
    SVA_CAN_ERR_VALUE = -4,         ///< a field holds a value the protocol forbids
    SVA_CAN_ERR_COUNTER = -5,       ///< rolling counter not previous + 1 (or repeated)
    SVA_CAN_ERR_SEQUENCE = -6,      ///< frame out of order: ITEM/ITEM_TIME/COMMIT unexpected
    SVA_CAN_ERR_PLAN_CRC = -7,      ///< COMMIT's CRC-32 (or count, or plan id) mismatch
    SVA_CAN_ERR_TIMEOUT = -8,       ///< a transfer did not complete in time
    SVA_CAN_ERR_LIMIT = -9,         ///< more items than SVA_CAN_MAX_ITEMS, or a wire limit
    SVA_CAN_ERR_IO = -10,           ///< a system call failed (errno kept by the transport)
    SVA_CAN_ERR_NAME = -11,         ///< interface name empty or too long for IFNAMSIZ
    SVA_CAN_ERR_UNSUPPORTED = -12,  ///< SocketCAN on a non-Linux build
    SVA_CAN_ERR_STATE = -13,        ///< call not valid in the current state
    SVA_CAN_ERR_VERSION = -14,      ///< PLAN_BEGIN of another protocol version
} sva_can_status_t;

/// A short constant name for a status ("ok", "crc", ...). Never NULL.
const char* sva_can_status_name(sva_can_status_t status);

// =================================================================================
// Frames and messages

/// One classic CAN frame as this port sees it. id holds 11 or 29 bits; flags says
/// which. dlc is the data length code as received (0..8 classic, up to 15 for FD).
typedef struct {
    uint32_t id;
    uint8_t flags;  ///< SVA_CAN_FLAG_*
    uint8_t dlc;
    uint8_t data[8];
} sva_can_frame_t;

#define SVA_CAN_FLAG_EXTENDED 0x01U  ///< 29-bit id (never this protocol's)
#define SVA_CAN_FLAG_RTR      0x02U  ///< remote request (never this protocol's)
#define SVA_CAN_FLAG_FD       0x04U  ///< arrived as a CAN FD frame (rejected by decode)

/// Message ids (11-bit). Lower id wins arbitration.
#define SVA_CAN_ID_PLAN_ABORT     0x100U
#define SVA_CAN_ID_PLAN_BEGIN     0x101U
#define SVA_CAN_ID_PLAN_ITEM      0x102U
#define SVA_CAN_ID_PLAN_ITEM_TIME 0x103U
#define SVA_CAN_ID_PLAN_COMMIT    0x104U
#define SVA_CAN_ID_PLAN_ACK       0x108U
#define SVA_CAN_ID_HEARTBEAT      0x110U
#define SVA_CAN_ID_VEHICLE_STATUS 0x120U
#define SVA_CAN_ID_VEHICLE_FUEL   0x121U
#define SVA_CAN_ID_MISSION_CLOCK  0x122U

/// Heartbeat period and the silence after which peers treat the planner as offline.
#define SVA_CAN_HEARTBEAT_PERIOD_MS 1000U
#define SVA_CAN_OFFLINE_AFTER_MS    3000U

typedef enum {
    SVA_CAN_MSG_NONE = 0,
    SVA_CAN_MSG_HEARTBEAT,
    SVA_CAN_MSG_PLAN_BEGIN,
    SVA_CAN_MSG_PLAN_ITEM,
    SVA_CAN_MSG_PLAN_ITEM_TIME,
    SVA_CAN_MSG_PLAN_COMMIT,
    SVA_CAN_MSG_PLAN_ABORT,
    SVA_CAN_MSG_PLAN_ACK,
    SVA_CAN_MSG_VEHICLE_STATUS,
    SVA_CAN_MSG_VEHICLE_FUEL,
    SVA_CAN_MSG_MISSION_CLOCK,
    SVA_CAN_MSG_COUNT_
} sva_can_msg_kind_t;

/// Planner state in the heartbeat.
typedef enum {
    SVA_CAN_NODE_INIT = 0,
    SVA_CAN_NODE_IDLE = 1,  ///< no plan yet
    SVA_CAN_NODE_PLANNING = 2,
    SVA_CAN_NODE_SENDING = 3,  ///< a transfer is in flight
    SVA_CAN_NODE_ACTIVE = 4,   ///< the bridge acknowledged active_plan_id
    SVA_CAN_NODE_FAULT = 5,
} sva_can_node_state_t;
#define SVA_CAN_NODE_STATE_MAX 5U

/// Heartbeat fault bits.
#define SVA_CAN_FAULT_MISSION_INVALID 0x01U  ///< fleet state makes the mission invalid
#define SVA_CAN_FAULT_PLAN_FAILED     0x02U  ///< sva_plan() returned an error
#define SVA_CAN_FAULT_TRANSFER_FAILED 0x04U  ///< last transfer aborted (timeout, retries)
#define SVA_CAN_FAULT_RX_ERRORS       0x08U  ///< corrupt frames seen since last heartbeat
#define SVA_CAN_FAULT_TX_ERRORS       0x10U  ///< the transport reported an error
#define SVA_CAN_FAULT_MASK            0x1FU

/// ABORT reasons.
#define SVA_CAN_ABORT_TIMEOUT    1U  ///< transfer deadline passed
#define SVA_CAN_ABORT_RETRIES    2U  ///< no positive ACK after every attempt
#define SVA_CAN_ABORT_SUPERSEDED 3U  ///< a newer plan replaces it
#define SVA_CAN_ABORT_SHUTDOWN   4U
#define SVA_CAN_ABORT_REASON_MAX 4U

/// ACK results (0 accepted, the rest are NACKs naming the receiver's reason).
#define SVA_CAN_ACK_ACCEPTED     0U
#define SVA_CAN_ACK_BAD_CRC      1U  ///< COMMIT CRC-32, count or plan id mismatch
#define SVA_CAN_ACK_BAD_SEQUENCE 2U  ///< counter jump, ITEM out of order or missing
#define SVA_CAN_ACK_TOO_LARGE    3U  ///< item_count above the receiver's capacity
#define SVA_CAN_ACK_BAD_VERSION  4U
#define SVA_CAN_ACK_BAD_VALUE    5U  ///< a field out of its range
#define SVA_CAN_ACK_RESULT_MAX   5U

/// Vehicle states in VEHICLE_STATUS.
#define SVA_CAN_VEHICLE_UNKNOWN     0U
#define SVA_CAN_VEHICLE_AVAILABLE   1U  ///< planned for
#define SVA_CAN_VEHICLE_BUSY        2U  ///< flying; still planned for from its position
#define SVA_CAN_VEHICLE_UNAVAILABLE 3U  ///< left out of planning
#define SVA_CAN_VEHICLE_STATE_MAX   3U

/// Plan status in PLAN_BEGIN (SPEC section 1).
#define SVA_CAN_PLAN_COMPLETE 1U
#define SVA_CAN_PLAN_PARTIAL  2U

typedef struct {
    uint8_t state;            ///< sva_can_node_state_t
    uint16_t active_plan_id;  ///< last plan the bridge accepted, 0 for none
    uint8_t uav_count;        ///< UAVs in the fleet state (saturates at 255)
    uint8_t target_count;     ///< targets in the mission (saturates at 255)
    uint8_t covered_count;    ///< targets covered by the active plan (saturates)
    uint8_t faults;           ///< SVA_CAN_FAULT_* bits
} sva_can_heartbeat_t;

typedef struct {
    uint8_t version;      ///< SVA_CAN_PROTOCOL_VERSION
    uint16_t plan_id;     ///< 1..65535, 0 is "no plan"
    uint16_t item_count;  ///< ITEM + ITEM_TIME pairs that follow
    uint8_t algorithm;    ///< sva_algorithm_t (0 sva, 1 ga, 2 hga, 3 bfa, 4 flow)
    uint8_t plan_status;  ///< SVA_CAN_PLAN_COMPLETE or SVA_CAN_PLAN_PARTIAL
    uint8_t route_count;  ///< UAVs in the plan (routes, empty ones included)
} sva_can_begin_t;

/// One assignment: UAV uav_id serves target target_id at (x, y), arriving no later than
/// arrive_by and staying until hold_until (SPEC section 1: the target's window).
/// Items of one UAV appear in visit order.
typedef struct {
    uint8_t uav_id;      ///< 1..255
    uint16_t target_id;  ///< 1..4095
    int16_t x;
    int16_t y;
    uint32_t arrive_by_ticks;   ///< 0..SVA_CAN_MAX_TICK
    uint32_t hold_until_ticks;  ///< arrive_by < hold_until <= SVA_CAN_MAX_TICK
} sva_can_item_t;

typedef struct {
    uint8_t uav_id;
    uint16_t target_id;
    int16_t x;
    int16_t y;
} sva_can_item_where_t;

typedef struct {
    uint8_t item_seq;  ///< item index modulo 16 (pairs it with its ITEM)
    uint32_t arrive_by_ticks;
    uint32_t hold_until_ticks;
} sva_can_item_time_t;

typedef struct {
    uint16_t plan_id;
    uint32_t plan_crc;  ///< CRC-32 as described at the top of this file
} sva_can_commit_t;

typedef struct {
    uint8_t reason;  ///< SVA_CAN_ABORT_*
    uint16_t plan_id;
} sva_can_abort_t;

typedef struct {
    uint8_t result;  ///< SVA_CAN_ACK_*
    uint16_t plan_id;
    uint16_t items_received;
} sva_can_ack_t;

typedef struct {
    uint8_t state;   ///< SVA_CAN_VEHICLE_*
    uint8_t uav_id;  ///< 1..255
    int16_t x;
    int16_t y;
} sva_can_vehicle_status_t;

typedef struct {
    uint8_t uav_id;
    uint32_t fuel;  ///< remaining fuel (SPEC units)
} sva_can_vehicle_fuel_t;

/// The flight stack's mission clock: the live mission's tick (SPEC section 12.1).
typedef struct {
    uint32_t tick;  ///< 0..SVA_CAN_MAX_TICK
} sva_can_mission_clock_t;

/// A decoded message: kind, rolling counter and the fields of that kind.
typedef struct {
    sva_can_msg_kind_t kind;
    uint8_t counter;  ///< 0..15
    union {
        sva_can_heartbeat_t heartbeat;
        sva_can_begin_t begin;
        sva_can_item_where_t item;
        sva_can_item_time_t item_time;
        sva_can_commit_t commit;
        sva_can_abort_t abort_;
        sva_can_ack_t ack;
        sva_can_vehicle_status_t vehicle;
        sva_can_vehicle_fuel_t fuel;
        sva_can_mission_clock_t clock;
    } u;
} sva_can_msg_t;

/// CRC-8/SAE-J1850 of `size` bytes. Check value: "123456789" -> 0x4B. O(size).
uint8_t sva_can_crc8(const uint8_t* data, size_t size);

/// CRC-32/ISO-HDLC, resumable: start with crc = 0, feed chunks, the result after each
/// call is the CRC of everything fed so far. "123456789" -> 0xCBF43926. O(size).
uint32_t sva_can_crc32(uint32_t crc, const uint8_t* data, size_t size);

/// The CRC-8 a frame with this id and these first 7 data bytes must carry.
uint8_t sva_can_frame_crc8(uint32_t id, const uint8_t data[8]);

/// Encodes *msg into *out (id, flags 0, dlc 8, data with counter and CRC-8).
/// Returns SVA_CAN_OK, or SVA_CAN_ERR_ARGUMENT for NULL, an unknown kind, a counter
/// above 15 or a field wider than its signal (then *out is untouched).
/// Allocates nothing; O(1). Byte order is explicit: right on any host endianness.
SVA_CAN_NODISCARD sva_can_status_t sva_can_encode(const sva_can_msg_t* msg, sva_can_frame_t* out);

/// Decodes *frame into *out. Checks, in this order: id and flags (SVA_CAN_IGNORED for
/// frames of other protocols: extended, RTR or unknown ids), DLC == 8 and not FD
/// (SVA_CAN_ERR_DLC, checked before any byte is read), CRC-8 (SVA_CAN_ERR_CRC), value
/// ranges (SVA_CAN_ERR_VALUE: enums, ids 0, version, arrive_by >= hold_until).
/// Reserved bits are ignored. *out is written only on SVA_CAN_OK. Allocates nothing; O(1).
SVA_CAN_NODISCARD sva_can_status_t sva_can_decode(const sva_can_frame_t* frame, sva_can_msg_t* out);

/// The frame checks a receiver makes before it reads a field, for bridges that decode
/// with their own code (e.g. from the DBC): DLC 8 and not FD (SVA_CAN_ERR_DLC), the
/// CRC-8 (SVA_CAN_ERR_CRC), then the rolling counter (SVA_CAN_ERR_COUNTER) when
/// expected_counter is 0..15 (any counter passes for -1). Returns the first check that
/// fails, SVA_CAN_OK when all pass, or SVA_CAN_ERR_ARGUMENT for NULL. Ids are not
/// checked. Allocates nothing; O(1).
SVA_CAN_NODISCARD sva_can_status_t sva_can_frame_check(const sva_can_frame_t* frame,
                                                       int expected_counter);

/// The message kind of an 11-bit id, SVA_CAN_MSG_NONE when it is not ours.
sva_can_msg_kind_t sva_can_kind_of_id(uint32_t id);

// =================================================================================
// Transport

/// A CAN interface as function pointers. send returns SVA_CAN_OK (queued),
/// SVA_CAN_AGAIN (queue full, nothing sent) or an error; recv returns SVA_CAN_OK with
/// *frame filled, SVA_CAN_AGAIN when nothing is waiting, or an error. Neither blocks.
typedef struct {
    sva_can_status_t (*send)(void* ctx, const sva_can_frame_t* frame);
    sva_can_status_t (*recv)(void* ctx, sva_can_frame_t* frame);
    void* ctx;
} sva_can_transport_t;

/// The transports this port ships (the in-memory loopback bus, SocketCAN) are in
/// sva_can_transport.h.

// =================================================================================
// Plans on the wire

/// A plan as it crosses the bus.
typedef struct {
    uint16_t plan_id;
    uint8_t algorithm;
    uint8_t plan_status;
    uint8_t route_count;
    uint16_t item_count;
    sva_can_item_t items[SVA_CAN_MAX_ITEMS];
} sva_can_plan_t;

/// CRC-32 COMMIT carries for *plan (as if sent: BEGIN then each ITEM and ITEM_TIME,
/// counters cleared). Returns 0 for NULL. O(item_count).
uint32_t sva_can_plan_crc(const sva_can_plan_t* plan);

/// Checks that every field sva_can_plan_from_core() will put on the wire fits its
/// signal: UAV ids in [1, SVA_CAN_MAX_UAV_ID], target ids in [1, SVA_CAN_MAX_TARGET_ID],
/// target windows within SVA_CAN_MAX_TICK. Returns SVA_CAN_OK, or SVA_CAN_ERR_LIMIT
/// with *diag (if not NULL) naming field, index, value and limit (rule SVA_RULE_MAX or
/// SVA_RULE_MIN, limit_name "SVA_CAN_MAX_*"), so sva_diag_format() prints it.
/// Run it after sva_mission_validate(). O(U + T); allocates nothing.
SVA_CAN_NODISCARD sva_can_status_t sva_can_mission_check(const sva_mission_t* mission,
                                                         sva_diag_t* diag);

/// Turns a core plan (sva_plan_t) for a mission (sva_mission_t) into wire items: for
/// each route in mission order, its targets in visit order. Returns SVA_CAN_OK, or
/// SVA_CAN_ERR_LIMIT when the plan has more assignments than SVA_CAN_MAX_ITEMS or a
/// value does not fit the wire (check the mission first with sva_can_mission_check),
/// or SVA_CAN_ERR_ARGUMENT (NULL, plan_id 0, plan status SVA_PLAN_NONE).
/// All-or-nothing: *out is untouched on error. O(items).
SVA_CAN_NODISCARD sva_can_status_t sva_can_plan_from_core(sva_can_plan_t* out,
                                                          const sva_mission_t* mission,
                                                          const sva_plan_t* plan, uint16_t plan_id);

// =================================================================================
// Sender (planner side)

typedef enum {
    SVA_CAN_TX_IDLE = 0,
    SVA_CAN_TX_SENDING,   ///< frames left to hand to the transport
    SVA_CAN_TX_WAIT_ACK,  ///< COMMIT sent, waiting for the bridge
    SVA_CAN_TX_DONE,      ///< the bridge accepted the plan
    SVA_CAN_TX_FAILED,    ///< aborted (timeout or attempts exhausted); ABORT was sent
} sva_can_tx_state_t;

typedef struct {
    uint32_t ack_timeout_ms;       ///< wait for ACK after COMMIT before retrying (250)
    uint32_t transfer_timeout_ms;  ///< whole transfer, every attempt included (3000)
    uint8_t max_attempts;          ///< transfers before giving up (3)
} sva_can_sender_config_t;

typedef struct {
    uint32_t frames_sent;
    uint32_t attempts;  ///< transfers started (retries included)
    uint32_t nacks;     ///< negative ACKs received
    uint32_t ack_timeouts;
    uint32_t aborts_sent;
    uint32_t acks_ignored;  ///< ACKs for another plan id, or outside WAIT_ACK
    uint32_t rx_rejected;   ///< ACK frames failing decode (CRC, DLC, value)
    uint32_t tx_errors;     ///< transport send errors
} sva_can_sender_stats_t;

typedef struct {
    const sva_can_transport_t* transport;
    sva_can_sender_config_t config;
    sva_can_tx_state_t state;
    uint8_t last_abort_reason;
    uint8_t last_nack;
    sva_can_sender_stats_t stats;
    struct {
        sva_can_plan_t plan;
        uint32_t next_frame;  ///< 0 BEGIN, 1..2n items, 2n+1 COMMIT
        uint32_t started_ms;  ///< first attempt
        uint32_t commit_sent_ms;
        uint8_t counter;        ///< next transfer-stream counter
        uint8_t pending_abort;  ///< reason of an ABORT still to send, 0 for none
        uint16_t abort_plan_id;
        uint8_t attempt;
        uint32_t crc;  ///< CRC-32 over the frames sent in this attempt
    } priv;
} sva_can_sender_t;

/// Default config: ack 250 ms, transfer 3000 ms, 3 attempts.
sva_can_sender_config_t sva_can_sender_default_config(void);

/// Prepares an idle sender. config may be NULL (defaults). Returns SVA_CAN_OK or
/// SVA_CAN_ERR_ARGUMENT (NULL self/transport, zero timeouts or attempts). O(1).
SVA_CAN_NODISCARD sva_can_status_t sva_can_sender_init(sva_can_sender_t* self,
                                                       const sva_can_transport_t* transport,
                                                       const sva_can_sender_config_t* config);

/// Starts sending *plan (copied). If a transfer is in flight it is superseded: an
/// ABORT(SUPERSEDED) for it goes out first. Sends as many frames as the transport
/// accepts now; call sva_can_sender_poll() to continue. Returns SVA_CAN_OK,
/// SVA_CAN_ERR_ARGUMENT (NULL, plan_id 0, item_count > SVA_CAN_MAX_ITEMS), or the
/// transport's error. O(item_count) for the copy.
SVA_CAN_NODISCARD sva_can_status_t sva_can_sender_start(sva_can_sender_t* self,
                                                        const sva_can_plan_t* plan,
                                                        uint32_t now_ms);

/// Hands pending frames to the transport until it says AGAIN, and runs the timers:
/// no ACK within ack_timeout_ms -> next attempt from BEGIN; attempts exhausted or the
/// transfer older than transfer_timeout_ms -> ABORT sent, state FAILED. Returns
/// SVA_CAN_OK or the transport's error (the state machine stays consistent; poll again).
SVA_CAN_NODISCARD sva_can_status_t sva_can_sender_poll(sva_can_sender_t* self, uint32_t now_ms);

/// Feeds one received frame (ACKs; anything else is SVA_CAN_IGNORED). A positive ACK
/// for the plan in WAIT_ACK -> DONE; a NACK -> next attempt (or FAILED). Returns
/// SVA_CAN_OK, SVA_CAN_IGNORED, or the decode error of a corrupt ACK (counted).
SVA_CAN_NODISCARD sva_can_status_t sva_can_sender_on_frame(sva_can_sender_t* self,
                                                           const sva_can_frame_t* frame,
                                                           uint32_t now_ms);

/// Aborts an in-flight transfer with `reason` (ABORT frame queued), state FAILED.
/// No-op (SVA_CAN_OK) when nothing is in flight.
SVA_CAN_NODISCARD sva_can_status_t sva_can_sender_abort(sva_can_sender_t* self, uint8_t reason,
                                                        uint32_t now_ms);

// =================================================================================
// Receiver (bridge side, and tests)

typedef struct {
    uint32_t frames;   ///< frames fed
    uint32_t ignored;  ///< not this protocol's, or not transfer frames
    uint32_t bad_dlc;
    uint32_t bad_crc;
    uint32_t bad_value;
    uint32_t counter_jumps;
    uint32_t out_of_order;  ///< ITEM/ITEM_TIME/COMMIT not expected now, item missing
    uint32_t plan_crc_mismatch;
    uint32_t too_large;
    uint32_t bad_version;
    uint32_t timeouts;
    uint32_t aborted;  ///< transfers the sender aborted
    uint32_t plans_applied;
    uint32_t acks_sent;
    uint32_t nacks_sent;
    uint32_t tx_errors;
} sva_can_receiver_stats_t;

typedef struct {
    const sva_can_transport_t* transport;  ///< for ACKs; NULL: no ACKs are sent
    uint32_t timeout_ms;                   ///< BEGIN to COMMIT (2000 by default)
    sva_can_receiver_stats_t stats;
    bool has_active;
    sva_can_plan_t active;  ///< the applied plan (read-only)
    struct {
        sva_can_plan_t staging;
        bool receiving;
        bool expect_time;  ///< the next transfer frame must be ITEM_TIME
        uint8_t last_counter;
        uint8_t ack_counter;
        uint16_t items_done;
        uint32_t begin_ms;
        uint32_t crc;
    } priv;
} sva_can_receiver_t;

/// Prepares a receiver with no active plan. transport may be NULL; timeout_ms 0 means
/// the default 2000 ms. Returns SVA_CAN_OK or SVA_CAN_ERR_ARGUMENT. O(1).
SVA_CAN_NODISCARD sva_can_status_t sva_can_receiver_init(sva_can_receiver_t* self,
                                                         const sva_can_transport_t* transport,
                                                         uint32_t timeout_ms);

/// Feeds one received frame. Returns
///   SVA_CAN_OK        a transfer frame accepted (or an ABORT handled);
///   SVA_CAN_APPLIED   a COMMIT completed an intact plan: it is now `active` (ACK sent);
///   SVA_CAN_IGNORED   not a transfer frame (heartbeats, status, other protocols);
///   an error          the frame was rejected and counted: SVA_CAN_ERR_DLC, _CRC,
///                     _VALUE, _COUNTER, _SEQUENCE, _PLAN_CRC, _LIMIT. A rejection
///                     inside a transfer discards the whole transfer (NACK sent).
/// The active plan changes only on SVA_CAN_APPLIED: never from a partial or corrupt
/// transfer. Also runs the timeout check first. O(1) per frame.
SVA_CAN_NODISCARD sva_can_status_t sva_can_receiver_on_frame(sva_can_receiver_t* self,
                                                             const sva_can_frame_t* frame,
                                                             uint32_t now_ms);

/// Runs the timeout: a transfer open longer than timeout_ms is discarded and counted
/// (returns SVA_CAN_ERR_TIMEOUT once for it); otherwise SVA_CAN_OK.
SVA_CAN_NODISCARD sva_can_status_t sva_can_receiver_poll(sva_can_receiver_t* self, uint32_t now_ms);

#ifdef __cplusplus
}
#endif

#endif  // SVA_CAN_H
