/// sva_lcm_journal.h -- the crash-safe live mission of the LCM node: a journal of its
/// inputs, replayed after a restart.
///
/// ## What it does
/// The node is deterministic: the same accepted inputs through the same handlers give
/// the same state, byte for byte. So the journal keeps the inputs, not the state: every
/// input the adapter hands to its input hook (sva_lcm.h, "Durable inputs") is appended
/// as one record and synced to storage before the node publishes its answer. After a
/// crash or a power loss, sva_lcm_journal_resume() reads the journal back and replays
/// each record through the adapter's own handlers with publishing switched off: the
/// node resumes with the same live mission (clock, revision, target states, plan in
/// force), the same plan id sequence and the same inputs.
///
/// ## Format (version SVA_LCM_JOURNAL_FORMAT), little-endian
///   record  = length (u32: payload bytes) | type (u8) | payload | crc (u32)
///   crc     = CRC-32 (IEEE 802.3, zlib's crc32) of length, type and payload
///   journal = HEADER record, then BASE / FLEET / MISSION / EVENT / REPORT records
///   HEADER  = "SVAJ" | format (u16) | sva version major, minor, patch (u16 each)
///             | fingerprints of fleet_state_t, mission_t, event_t, report_t (i64 each)
///             | algorithm (u8) | fleet_reports (u8) | change_penalty (i32)
///             | track_tolerance_cells (i32) | takeoff_ticks (i32)       (58 bytes)
///   BASE    = plan id (i64): the plan id sequence before the records that follow
///   FLEET, MISSION, EVENT, REPORT = the LCM message's bytes as received
/// The first 12 payload bytes of a HEADER (magic, format, sva version) keep their
/// place in every format, so a journal of any version can be named in a refusal.
///
/// ## Resume
/// The header must parse (else SVA_LCM_JOURNAL_ERR_FORMAT) and match this build (the
/// format, the sva version and the wire types' fingerprints, else _ERR_VERSION, naming
/// both versions) and the node's options (else _ERR_OPTIONS); a refused journal is
/// left as it is, unless `reset` discards it. Records are then read in order; each is
/// applied only once its length and CRC check out. The first one that does not (a
/// short record, a length over SVA_LCM_JOURNAL_MAX_PAYLOAD or not its type's size, a
/// bad CRC) ends the journal: it and everything after it are cut (the storage is
/// truncated there), and the message names the byte offset. A torn write is never
/// half-applied. A record with a good CRC that the node does not take again (a type
/// this format lacks, or a handler's refusal) stops the resume (_ERR_FORMAT,
/// _ERR_REPLAY): the journal does not describe this node's inputs.
///
/// ## Compaction
/// An input planned from scratch (`restarts` in sva_lcm_input_fn: a new fleet or
/// mission) makes the state depend on the current fleet, mission and plan id alone. The
/// journal is then replaced, atomically, by HEADER, BASE, FLEET, MISSION: it grows with
/// one live mission's events and reports, never across missions.
///
/// ## Storage
/// sva_lcm_storage_t (sva_journal.h's, shared with sva_can_node): function pointers over a
/// caller-owned context, so that a board can keep the journal in flash. sva_lcm_journal_file_init()
/// is the POSIX one (a file in a folder, fsync'd). Every function returns 0 on success.
///
/// ## Memory, threads
/// sva_lcm_journal_t holds one compaction buffer (SVA_LCM_JOURNAL_COMPACT_BYTES, ~7.7
/// KiB); nothing is allocated. The journal is called from the thread that calls the
/// adapter's handlers.
#ifndef SVA_LCM_JOURNAL_H
#define SVA_LCM_JOURNAL_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "sva/sva_journal.h"
#include "sva/sva_lcm.h"

#ifdef __cplusplus
extern "C" {
#endif

/// The journal format this build writes and reads.
#define SVA_LCM_JOURNAL_FORMAT 2
/// length (4) + type (1) + crc (4).
#define SVA_LCM_JOURNAL_RECORD_OVERHEAD 9
/// The HEADER payload of format 2.
#define SVA_LCM_JOURNAL_HEADER_BYTES 58
/// The largest payload (a mission_t).
#define SVA_LCM_JOURNAL_MAX_PAYLOAD SVA_LCM_MISSION_BYTES
/// A compacted journal: HEADER, BASE, FLEET, MISSION.
#define SVA_LCM_JOURNAL_COMPACT_BYTES                                           \
    ((4 * SVA_LCM_JOURNAL_RECORD_OVERHEAD) + SVA_LCM_JOURNAL_HEADER_BYTES + 8 + \
     SVA_LCM_FLEET_BYTES + SVA_LCM_MISSION_BYTES)
/// Room for sva_lcm_journal_t.message.
#define SVA_LCM_JOURNAL_MESSAGE_SIZE 384

/// Record types (the byte after the length).
typedef enum {
    SVA_LCM_RECORD_HEADER = 1,
    SVA_LCM_RECORD_BASE = 2,
    SVA_LCM_RECORD_FLEET = 3,
    SVA_LCM_RECORD_MISSION = 4,
    SVA_LCM_RECORD_EVENT = 5,
    SVA_LCM_RECORD_REPORT = 6,
} sva_lcm_record_t;

/// What a journal call came to.
typedef enum {
    SVA_LCM_JOURNAL_OK = 0,
    SVA_LCM_JOURNAL_ERR_ARGUMENT = -1,  ///< NULL or an incomplete storage
    SVA_LCM_JOURNAL_ERR_IO = -2,        ///< the storage failed (message: which call, why)
    SVA_LCM_JOURNAL_ERR_FORMAT = -3,    ///< the header does not parse, or an unknown record
    SVA_LCM_JOURNAL_ERR_VERSION = -4,   ///< another format, sva version or wire types
    SVA_LCM_JOURNAL_ERR_OPTIONS = -5,   ///< written by a node with other options
    SVA_LCM_JOURNAL_ERR_REPLAY = -6,    ///< a record the node did not take again
} sva_lcm_journal_status_t;

/// Where the journal lives: the storage interface of the shared record layer
/// (sva_journal.h): open, read, append, sync, truncate, replace, close, error, over a
/// caller-owned ctx. Every function returns 0 on success.
typedef sva_journal_storage_t sva_lcm_storage_t;

/// What sva_lcm_journal_resume() found.
typedef struct {
    bool fresh;           ///< no journal (or reset): a new one was started
    bool discarded;       ///< reset: a journal that was there was discarded
    uint32_t records;     ///< input records replayed (FLEET, MISSION, EVENT, REPORT)
    uint32_t bytes;       ///< the journal's length after the resume
    bool cut;             ///< a torn or corrupt tail was cut
    uint32_t cut_offset;  ///< where: the bytes kept
    uint32_t cut_bytes;   ///< the bytes dropped
} sva_lcm_journal_resume_t;

/// One journal. Declare it static; fields are read-only to users.
typedef struct {
    sva_lcm_storage_t storage;
    sva_lcm_node_t* node;
    bool open;
    uint32_t size;     ///< the journal's length in bytes
    uint32_t records;  ///< records in it, the header included
    uint64_t compactions;
    /// The last refusal, failure or cut, one line (no newline).
    char message[SVA_LCM_JOURNAL_MESSAGE_SIZE];
    uint8_t buf[SVA_LCM_JOURNAL_COMPACT_BYTES];
} sva_lcm_journal_t;

/// Prepares a journal of `node` on `storage` (copied; its ctx stays the caller's).
/// Opens nothing. The node's algorithm, change_penalty, takeoff_ticks, fleet_reports and
/// track_tolerance_cells must be set before sva_lcm_journal_resume(): they are part of
/// the header. Returns SVA_LCM_JOURNAL_OK, or _ERR_ARGUMENT iff an argument is NULL or
/// a storage function other than close and error is missing. Allocates nothing.
SVA_NODISCARD sva_lcm_journal_status_t sva_lcm_journal_init(sva_lcm_journal_t* self,
                                                            const sva_lcm_storage_t* storage,
                                                            sva_lcm_node_t* node);

/// Opens the storage, checks the header, replays every good record into the node (its
/// publish and log switched off meanwhile), cuts a torn or corrupt tail, and installs
/// the journal as the node's input_hook. With no journal, or with `reset`, starts a
/// new one (a header alone). The node must not have taken any input yet.
/// Returns SVA_LCM_JOURNAL_OK (*out says what was found; self->message describes a cut),
/// _ERR_IO, _ERR_FORMAT, _ERR_VERSION, _ERR_OPTIONS or _ERR_REPLAY with self->message
/// one line naming the offset or both versions. On a refusal the journal is left as it
/// was. An error found after the header (_ERR_FORMAT for a record this format lacks,
/// _ERR_REPLAY, _ERR_IO) leaves the node holding part of the journal's inputs: it must
/// not be used.
/// Allocates nothing; O(journal length) plus the handlers' work for every record.
SVA_NODISCARD sva_lcm_journal_status_t sva_lcm_journal_resume(sva_lcm_journal_t* self, bool reset,
                                                              sva_lcm_journal_resume_t* out);

/// The input hook (sva_lcm_input_fn, user = the journal) that sva_lcm_journal_resume()
/// installs: appends one record and syncs it, or compacts (`restarts`). Returns 0, or -1
/// with self->message set (then an append that went half-way is cut back, when the
/// storage allows). Allocates nothing.
int sva_lcm_journal_input(void* user, sva_lcm_input_t kind, bool restarts, const void* data,
                          size_t size);

/// Removes the hook from the node and closes the storage. Safe to call twice.
void sva_lcm_journal_close(sva_lcm_journal_t* self);

/// The status's name ("ok", "argument", "io", "format", "version", "options",
/// "replay"), or "" when out of range. Never NULL.
const char* sva_lcm_journal_status_name(sva_lcm_journal_status_t status);

// ---------------------------------------------------------------------------------
// POSIX storage: DIR/SVA_LCM_JOURNAL_FILE_NAME, held with a lock on DIR/SVA_LCM_JOURNAL_LOCK_NAME.

#define SVA_LCM_JOURNAL_FILE_NAME "sva_node.journal"
#define SVA_LCM_JOURNAL_TEMP_NAME "sva_node.journal.tmp"
#define SVA_LCM_JOURNAL_LOCK_NAME "sva_node.lock"
/// Longest folder path.
#define SVA_LCM_JOURNAL_DIR_MAX 200

/// The POSIX storage's context (sva_journal.h's, with the names above). Declare it
/// beside the journal; read-only to users.
typedef sva_journal_file_t sva_lcm_journal_file_t;

/// Fills *storage with the POSIX file storage of folder `dir` (which must exist). open
/// takes an exclusive lock (fcntl) on the lock file, so that two nodes never share a
/// journal; a second one fails naming the folder. Returns SVA_LCM_JOURNAL_OK, or
/// _ERR_ARGUMENT iff an argument is NULL or dir is empty or longer than
/// SVA_LCM_JOURNAL_DIR_MAX. Allocates nothing.
SVA_NODISCARD sva_lcm_journal_status_t sva_lcm_journal_file_init(sva_lcm_journal_file_t* self,
                                                                 const char* dir,
                                                                 sva_lcm_storage_t* storage);

#ifdef __cplusplus
}
#endif

#endif  // SVA_LCM_JOURNAL_H
