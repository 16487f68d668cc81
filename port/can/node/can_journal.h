// can_journal.h -- the crash-safe live mission of sva_can_node (docs/can.md, "Crash
// safety"): a journal of the inputs that changed its live mission (can_live.h), replayed
// after a restart.
//
// ## What it does
// The live mission is deterministic: the same mission, frames, times and replan points
// through can_live.c give the same sva_can_live_t, byte for byte. So the journal keeps
// inputs, not state: the mission the live mission started from, every flight-stack
// frame that changed it (an event applied, or a fuel reading kept for a UAV's return)
// with the node's time, and every replan attempt with its time and outcome, each
// appended as one record and synced before the node answers (sends a plan). After a
// crash or a power loss, sva_can_journal_resume() replays them through can_live.c with
// its log and hook switched off: the node resumes with the same clock, revision, target
// states, lost UAVs, fuel readings, plan in force and plan id sequence.
//
// ## Format (version SVA_CAN_JOURNAL_FORMAT), little-endian; records are sva_journal.h's
//   record  = length (u32) | type (u8) | payload | crc (u32: zlib crc32 of the rest)
//   journal = HEADER, MISSION, then MSG / REPLAN records in the order they happened
//   HEADER  = "SVAC" | format (u16) | sva version major, minor, patch (u16 each)
//             | CAN protocol version (u16) | SVA_MAX_UAVS (u16) | SVA_MAX_TARGETS (u16)
//             | algorithm (u8) | track_tolerance_cells (i32)                  (23 bytes)
//   MISSION = depot_x, depot_y, ticks_per_cell, hover_fuel, overlap_percent,
//             change_penalty, takeoff_ticks (i32 each) | uav_count, target_count (u16)
//             | per UAV id, x, y, fuel, ready_at_ticks (i32) | per target id, x, y,
//             start_ticks, end_ticks, need (i32)          (32 + 20 U + 24 T bytes)
//   MSG     = now_ms (u32) | CAN id (u16) | the frame's 8 data bytes        (14 bytes)
//   REPLAN  = now_ms (u32) | outcome (i8: 1 new plan sent, 0 none, -1 failed) (5 bytes)
// The first 12 HEADER bytes (magic, format, sva version) keep their place in every
// format, so a journal of any version can be named in a refusal.
//
// ## Resume
// The header must parse (else _ERR_FORMAT) and match this build (format, sva version,
// protocol version and bounds, else _ERR_VERSION naming both) and the node's options
// (--algo, --track-tolerance, else _ERR_OPTIONS naming both); the MISSION record must be
// the node's --mission (else _ERR_MISSION). A refused journal is left as it is, unless
// `reset` discards it. Records are read in order; each is applied only once its length
// and CRC check out. The first that does not (short, a length over
// SVA_CAN_JOURNAL_MAX_PAYLOAD, a bad CRC) ends the journal: it and everything after it
// are cut (the storage is truncated there) and the message names the byte offset. A
// record with a good CRC that the live mission does not take again the same way (an
// unknown type, a size not its type's, a frame that no longer changes anything, a
// replan with another outcome) stops the resume (_ERR_FORMAT, _ERR_REPLAY).
//
// ## Memory
// sva_can_journal_t holds one record buffer (SVA_CAN_JOURNAL_BUF_BYTES, ~7.5 KiB with the
// default bounds); nothing is allocated. There is no compaction: the node runs one
// mission, and its journal grows by 23 bytes per frame that changed the live mission and
// 14 per replan.
#ifndef SVA_CAN_JOURNAL_H
#define SVA_CAN_JOURNAL_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "can_live.h"
#include "sva/sva_journal.h"

/// The journal format this build writes and reads.
#define SVA_CAN_JOURNAL_FORMAT       1
#define SVA_CAN_JOURNAL_HEADER_BYTES 23
#define SVA_CAN_JOURNAL_MSG_BYTES    14
#define SVA_CAN_JOURNAL_REPLAN_BYTES 5
/// The largest payload: a MISSION of SVA_MAX_UAVS UAVs and SVA_MAX_TARGETS targets.
#define SVA_CAN_JOURNAL_MAX_PAYLOAD (32 + (20 * SVA_MAX_UAVS) + (24 * SVA_MAX_TARGETS))
/// A new journal (HEADER and MISSION) fits, and so does any one record.
#define SVA_CAN_JOURNAL_BUF_BYTES \
    ((2 * SVA_JOURNAL_RECORD_OVERHEAD) + SVA_CAN_JOURNAL_HEADER_BYTES + SVA_CAN_JOURNAL_MAX_PAYLOAD)
#define SVA_CAN_JOURNAL_MESSAGE_SIZE 384

/// Record types (the byte after the length).
typedef enum {
    SVA_CAN_RECORD_HEADER = 1,
    SVA_CAN_RECORD_MISSION = 2,
    SVA_CAN_RECORD_MSG = 3,
    SVA_CAN_RECORD_REPLAN = 4,
} sva_can_record_t;

typedef enum {
    SVA_CAN_JOURNAL_OK = 0,
    SVA_CAN_JOURNAL_ERR_ARGUMENT = -1,  ///< NULL or an incomplete storage
    SVA_CAN_JOURNAL_ERR_IO = -2,        ///< the storage failed (message: which call, why)
    SVA_CAN_JOURNAL_ERR_FORMAT = -3,    ///< the header does not parse, or an unknown record
    SVA_CAN_JOURNAL_ERR_VERSION = -4,   ///< another format, sva or protocol version, bounds
    SVA_CAN_JOURNAL_ERR_OPTIONS = -5,   ///< written by a node with another --algo/--track-tolerance
    SVA_CAN_JOURNAL_ERR_MISSION = -6,   ///< written for another mission
    SVA_CAN_JOURNAL_ERR_REPLAY = -7,    ///< a record the live mission did not take again
} sva_can_journal_status_t;

/// What sva_can_journal_resume() found.
typedef struct {
    bool fresh;           ///< no journal (or reset): a new one was started
    bool discarded;       ///< reset: a journal that was there was discarded
    uint32_t frames;      ///< MSG records replayed
    uint32_t replans;     ///< REPLAN records replayed
    uint32_t bytes;       ///< the journal's length after the resume
    bool cut;             ///< a torn or corrupt tail was cut
    uint32_t cut_offset;  ///< where: the bytes kept
    uint32_t cut_bytes;   ///< the bytes dropped
} sva_can_journal_resume_t;

/// One journal. Declare it static; fields are read-only to users.
typedef struct {
    sva_journal_storage_t storage;
    sva_can_live_t* live;
    bool open;
    uint32_t size;     ///< the journal's length in bytes
    uint32_t records;  ///< records in it, the header included
    /// The last refusal, failure or cut, one line (no newline).
    char message[SVA_CAN_JOURNAL_MESSAGE_SIZE];
    uint8_t buf[SVA_CAN_JOURNAL_BUF_BYTES];
} sva_can_journal_t;

/// Prepares a journal of `live` on `storage` (copied; its ctx stays the caller's). Opens
/// nothing. Returns _OK, or _ERR_ARGUMENT iff an argument is NULL or a storage function
/// other than close and error is missing. Allocates nothing.
SVA_JOURNAL_NODISCARD sva_can_journal_status_t sva_can_journal_init(
    sva_can_journal_t* self, const sva_journal_storage_t* storage, sva_can_live_t* live);

/// Opens the storage, checks the header and the mission, replays every good record into
/// the live mission (its log and stats untouched: stats count this process's frames),
/// cuts a torn or corrupt tail, and installs the journal as the live mission's input
/// hook. With no journal, or with `reset`, starts a new one (HEADER, MISSION).
/// Precondition: sva_can_live_start(live, mission, ...) succeeded and nothing else was
/// given to the live mission. Returns _OK (*out says what was found; self->message
/// describes a cut or a reset), or an error with self->message one line naming the
/// offset or both versions, option sets or missions; on a refusal the journal is left
/// as it was. After an error found past the MISSION record (_ERR_FORMAT, _ERR_REPLAY,
/// _ERR_IO) the live mission holds part of the journal: it must not be used.
/// Allocates nothing; O(journal length) plus a replan per REPLAN record.
SVA_JOURNAL_NODISCARD sva_can_journal_status_t
sva_can_journal_resume(sva_can_journal_t* self, const sva_mission_t* mission, bool reset,
                       sva_can_journal_resume_t* out);

/// The input hook (sva_can_live_input_fn, user = the journal) that resume installs:
/// appends one record and syncs it. Returns 0, or -1 with self->message set (an append
/// that went half-way is cut back, when the storage allows).
int sva_can_journal_input(void* user, const sva_can_live_input_t* input);

/// Removes the hook from the live mission and closes the storage. Safe to call twice.
void sva_can_journal_close(sva_can_journal_t* self);

/// The status's name ("ok", "argument", "io", "format", "version", "options", "mission",
/// "replay"), or "" when out of range. Never NULL.
const char* sva_can_journal_status_name(sva_can_journal_status_t status);

/// sva_can_node's files in its --state-dir.
#define SVA_CAN_JOURNAL_FILE_NAME "sva_can_node.journal"
#define SVA_CAN_JOURNAL_TEMP_NAME "sva_can_node.journal.tmp"
#define SVA_CAN_JOURNAL_LOCK_NAME "sva_can_node.lock"

#endif
