/// sva_journal.h -- the record layer the nodes' journals share (sva_node's, sva_lcm_journal.h;
/// sva_can_node's, port/can/node/can_journal.h): append-only records with length and CRC,
/// the storage they live on, and a POSIX file storage.
///
/// ## Records, little-endian
///   record = length (u32: payload bytes) | type (u8) | payload | crc (u32)
///   crc    = CRC-32 (IEEE 802.3, zlib's crc32) of length, type and payload
/// A journal is a sequence of records, read from byte 0. sva_journal_read_record()
/// tells a good record from a torn or corrupt one (short, a length over the caller's
/// bound, a bad CRC); what a journal does with either is the journal's (both nodes cut
/// the first bad record and everything after it).
///
/// ## Storage
/// sva_journal_storage_t: function pointers over a caller-owned context, so that a board
/// can keep a journal in flash (append-only pages, two slots for `replace`).
/// sva_journal_file_init() is the POSIX one: a file in a folder, fsync'd, replaced through
/// a temporary file and rename, held with an fcntl lock.
///
/// ## Memory, threads
/// Nothing is allocated; record reads go to a caller's buffer. Not thread-safe: one
/// journal, one thread. zlib is the only dependency (crc32), the core gets none.
#ifndef SVA_JOURNAL_H
#define SVA_JOURNAL_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

#if defined(__GNUC__) || defined(__clang__)
#    define SVA_JOURNAL_NODISCARD __attribute__((warn_unused_result))
#else
#    define SVA_JOURNAL_NODISCARD
#endif

/// length (4) + type (1) + crc (4).
#define SVA_JOURNAL_RECORD_OVERHEAD 9
/// length and type: the bytes before the payload.
#define SVA_JOURNAL_PREFIX_BYTES 5

/// Where a journal lives. Every function returns 0 on success, non-zero on failure
/// (then `error`, when set, says why, e.g. strerror). `ctx` is the caller's.
typedef struct {
    void* ctx;
    /// Opens the journal; *size = its length in bytes (0: there is none yet).
    int (*open)(void* ctx, uint32_t* size);
    /// Reads len bytes at offset (offset + len <= the length).
    int (*read)(void* ctx, uint32_t offset, void* buf, uint32_t len);
    /// Appends len bytes at the end (not yet durable).
    int (*append)(void* ctx, const void* data, uint32_t len);
    /// Makes everything appended durable.
    int (*sync)(void* ctx);
    /// Cuts the journal to size bytes, durably.
    int (*truncate)(void* ctx, uint32_t size);
    /// Replaces the whole journal by data, atomically and durably: after a crash the
    /// journal is the old one or the new one (POSIX: a temporary file, fsync, rename,
    /// fsync of the folder).
    int (*replace)(void* ctx, const void* data, uint32_t len);
    /// Closes it (NULL: nothing to do).
    void (*close)(void* ctx);
    /// Why the last call failed (NULL: no detail).
    const char* (*error)(void* ctx);
} sva_journal_storage_t;

/// What sva_journal_read_record() found.
typedef enum {
    SVA_JOURNAL_RECORD_GOOD = 1,  ///< length within bounds, whole, CRC right
    SVA_JOURNAL_RECORD_BAD = 0,   ///< torn or corrupt (`why` says how)
    SVA_JOURNAL_RECORD_IO = -1,   ///< the storage's read failed
} sva_journal_record_status_t;

/// True iff every storage function but close and error is set.
bool sva_journal_storage_complete(const sva_journal_storage_t* storage);

/// Little-endian fields.
void sva_journal_put_u16(uint8_t* p, uint32_t v);
void sva_journal_put_u32(uint8_t* p, uint32_t v);
void sva_journal_put_u64(uint8_t* p, uint64_t v);
uint32_t sva_journal_get_u16(const uint8_t* p);
uint32_t sva_journal_get_u32(const uint8_t* p);
uint64_t sva_journal_get_u64(const uint8_t* p);

/// zlib's crc32 of n bytes.
uint32_t sva_journal_crc(const uint8_t* p, uint32_t n);

/// Writes one record (length, type, payload, CRC) at out, which must hold
/// len + SVA_JOURNAL_RECORD_OVERHEAD bytes; payload may be NULL when len is 0. Returns
/// the record's size. O(len), allocates nothing.
uint32_t sva_journal_put_record(uint8_t* out, uint8_t type, const void* payload, uint32_t len);

/// Writes "storage CALL failed: WHY" (WHY from storage->error, or "no detail") into
/// message[0..size). Allocates nothing.
void sva_journal_say_failed(const sva_journal_storage_t* storage, const char* call, char* message,
                            size_t size);

/// Appends the n bytes at `bytes` (whole records) to a journal of *size bytes and syncs
/// them: 0 with *size advanced by n and *records by one; -1 with message set when the
/// journal would pass 4 GiB or the storage's append or sync failed (an append that went
/// half-way is cut back to *size). O(n), allocates nothing.
int sva_journal_append(const sva_journal_storage_t* storage, const uint8_t* bytes, uint32_t n,
                       uint32_t* size, uint32_t* records, char* message, size_t message_size);

/// The journal rule for a torn or corrupt record (sva_journal_read_record's _BAD, `why`)
/// at `offset` of a journal of *size bytes: it and everything after it are cut. 0 with
/// *size set to offset, *dropped to the bytes cut and message "torn or corrupt record at
/// byte OFFSET (WHY): cut there, N bytes dropped"; -1 with message naming the storage's
/// failed truncate. Allocates nothing.
int sva_journal_cut_torn(const sva_journal_storage_t* storage, uint32_t offset, const char* why,
                         uint32_t* size, uint32_t* dropped, char* message, size_t message_size);

/// Reads the record at `offset` of a journal of `size` bytes into buf, which must hold
/// max_payload + SVA_JOURNAL_RECORD_OVERHEAD bytes (the payload is at
/// buf + SVA_JOURNAL_PREFIX_BYTES). Returns _GOOD (*type, *len set), _BAD for a short
/// record, a length over max_payload or a bad CRC (`why`, one line without a newline,
/// says which), or _IO when storage->read failed. O(record), allocates nothing.
SVA_JOURNAL_NODISCARD sva_journal_record_status_t sva_journal_read_record(
    const sva_journal_storage_t* storage, uint32_t size, uint32_t offset, uint8_t* buf,
    uint32_t max_payload, uint32_t* type, uint32_t* len, char* why, size_t why_size);

/// Hands one good record to the journal that replays it (its payload, len bytes, at the
/// record's offset): 0 goes on, non-zero stops the replay (the journal keeps its reason).
typedef int (*sva_journal_on_record_t)(void* user, uint32_t offset, uint32_t type,
                                       const uint8_t* payload, uint32_t len);

/// How sva_journal_replay() ended.
typedef enum {
    SVA_JOURNAL_REPLAY_DONE = 0,     ///< every record handed on (a torn tail cut, if any)
    SVA_JOURNAL_REPLAY_STOPPED = 1,  ///< on_record returned non-zero
    SVA_JOURNAL_REPLAY_IO = -1,      ///< the storage's read or truncate failed (message)
} sva_journal_replay_status_t;

/// A torn tail a replay cut: where (the bytes kept) and how many bytes it dropped.
typedef struct {
    bool cut;
    uint32_t offset;
    uint32_t bytes;
} sva_journal_cut_t;

/// The replay every journal makes: reads the records from `offset` of a journal of *size
/// bytes into buf (as sva_journal_read_record, max_payload) and hands each good one, in
/// order, to on_record. The first torn or corrupt record ends the journal there
/// (sva_journal_cut_torn: *cut filled, *size cut, message says so; cut->cut false when
/// none was). On _IO, message names the failed storage call. O(journal), allocates
/// nothing.
SVA_JOURNAL_NODISCARD sva_journal_replay_status_t
sva_journal_replay(const sva_journal_storage_t* storage, uint32_t offset, uint32_t* size,
                   uint8_t* buf, uint32_t max_payload, sva_journal_on_record_t on_record,
                   void* user, sva_journal_cut_t* cut, char* message, size_t message_size);

// ---------------------------------------------------------------------------------
// POSIX storage: DIR/file, held with an exclusive fcntl lock on DIR/lock; `replace`
// writes DIR/temp, fsyncs it, renames it over DIR/file and fsyncs DIR. `open` removes
// a leftover DIR/temp (a replace a crash interrupted: never the journal).

/// Longest folder path; longest file name.
#define SVA_JOURNAL_DIR_MAX  200
#define SVA_JOURNAL_NAME_MAX 31

/// The POSIX storage's context. Declare it beside the journal; read-only to users.
typedef struct {
    char path[SVA_JOURNAL_DIR_MAX + 32];
    char temp[SVA_JOURNAL_DIR_MAX + 32];
    char lock[SVA_JOURNAL_DIR_MAX + 32];
    char dir[SVA_JOURNAL_DIR_MAX + 1];
    char lock_name[SVA_JOURNAL_NAME_MAX + 1];
    int fd;
    int lock_fd;
    int err;  ///< errno of the last failure
    char what[SVA_JOURNAL_DIR_MAX + 192];
} sva_journal_file_t;

/// Fills *storage with the POSIX file storage of folder `dir` (which must exist) and
/// the three file names in it. A second process opening the same folder fails naming
/// the folder ("DIR is in use: another process holds its lock (LOCK)"). Returns true,
/// or false iff an argument is NULL, dir is empty or longer than SVA_JOURNAL_DIR_MAX,
/// or a name is empty or longer than SVA_JOURNAL_NAME_MAX. Allocates nothing.
SVA_JOURNAL_NODISCARD bool sva_journal_file_init(sva_journal_file_t* self, const char* dir,
                                                 const char* file, const char* temp,
                                                 const char* lock, sva_journal_storage_t* storage);

#ifdef __cplusplus
}
#endif

#endif  // SVA_JOURNAL_H
