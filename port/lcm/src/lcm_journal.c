// lcm_journal.c -- the node's journal of inputs: records, the header, replay, cut and
// compaction (contract in sva_lcm_journal.h). Storage belongs to the caller
// (lcm_journal_file.c is the POSIX one); records, CRC-32 and the storage interface are
// the shared record layer's (sva_journal.h).
#include "sva/sva_lcm_journal.h"

#include <stdio.h>
#include <string.h>

#define MAGIC_BYTES  4
#define NAMED_BYTES  12  // magic, format, sva version: where every format keeps them
#define BASE_BYTES   8
#define PREFIX_BYTES 5  // length and type

static const uint8_t magic[MAGIC_BYTES] = {'S', 'V', 'A', 'J'};

static const char* const status_names[] = {"ok",      "argument", "io",    "format",
                                           "version", "options",  "replay"};

const char* sva_lcm_journal_status_name(sva_lcm_journal_status_t status)
{
    const int i = -(int)status;
    if ((i < 0) || (i >= (int)(sizeof status_names / sizeof status_names[0]))) {
        return "";
    }
    return status_names[i];
}

// --- little-endian fields and records: the shared record layer (sva_journal.h) ---------

typedef char overhead_check[(SVA_LCM_JOURNAL_RECORD_OVERHEAD == SVA_JOURNAL_RECORD_OVERHEAD) &&
                                    (PREFIX_BYTES == SVA_JOURNAL_PREFIX_BYTES) &&
                                    (SVA_LCM_JOURNAL_DIR_MAX == SVA_JOURNAL_DIR_MAX)
                                ? 1
                                : -1];

// Writes one record (length, type, payload, CRC) at out; returns its size.
static uint32_t put_record(uint8_t* out, sva_lcm_record_t type, const void* payload, uint32_t len)
{
    return sva_journal_put_record(out, (uint8_t)type, payload, len);
}

// The payload size each input record must have (0: not an input record).
static uint32_t input_bytes(uint32_t type)
{
    switch (type) {
    case SVA_LCM_RECORD_FLEET:
        return SVA_LCM_FLEET_BYTES;
    case SVA_LCM_RECORD_MISSION:
        return SVA_LCM_MISSION_BYTES;
    case SVA_LCM_RECORD_EVENT:
        return SVA_LCM_EVENT_BYTES;
    case SVA_LCM_RECORD_REPORT:
        return SVA_LCM_REPORT_BYTES;
    default:
        return 0U;
    }
}

// Input kinds and their record types are in the same order.
typedef char record_order_check[((int)SVA_LCM_INPUT_REPORT + (int)SVA_LCM_RECORD_FLEET ==
                                 (int)SVA_LCM_RECORD_REPORT)
                                    ? 1
                                    : -1];

static sva_lcm_record_t record_of(sva_lcm_input_t kind)
{
    return (sva_lcm_record_t)((int)kind + (int)SVA_LCM_RECORD_FLEET);
}

static const char* const record_names[] = {"unknown", "header", "base",  "fleet",
                                           "mission", "event",  "report"};

static const char* record_name(uint32_t type)
{
    return record_names[(type < 7U) ? type : 0U];
}

// --- the header ---------------------------------------------------------------------

// The wire types whose bytes the journal keeps: a header names their fingerprints.
static int64_t (*const hashes[4])(void) = {__sva_lcm_fleet_state_t_get_hash,
                                           __sva_lcm_mission_t_get_hash, __sva_lcm_event_t_get_hash,
                                           __sva_lcm_report_t_get_hash};

static uint64_t fingerprint(int which)
{
    return (uint64_t)hashes[which]();
}

static const char* const fingerprint_names[4] = {"fleet_state_t", "mission_t", "event_t",
                                                 "report_t"};

static void header_payload(const sva_lcm_node_t* node, uint8_t* p)
{
    memcpy(p, magic, MAGIC_BYTES);
    sva_journal_put_u16(p + 4, SVA_LCM_JOURNAL_FORMAT);
    sva_journal_put_u16(p + 6, SVA_VERSION_MAJOR);
    sva_journal_put_u16(p + 8, SVA_VERSION_MINOR);
    sva_journal_put_u16(p + 10, SVA_VERSION_PATCH);
    for (int i = 0; i < 4; ++i) {
        sva_journal_put_u64(p + NAMED_BYTES + (8U * (size_t)i), fingerprint(i));
    }
    p[44] = (uint8_t)node->algorithm;
    p[45] = node->fleet_reports ? 1U : 0U;
    sva_journal_put_u32(p + 46, (uint32_t)node->change_penalty);
    sva_journal_put_u32(p + 50, (uint32_t)node->track_tolerance_cells);
    sva_journal_put_u32(p + 54, (uint32_t)node->takeoff_ticks);
}

static uint32_t put_header(const sva_lcm_node_t* node, uint8_t* out)
{
    uint8_t payload[SVA_LCM_JOURNAL_HEADER_BYTES];
    header_payload(node, payload);
    return put_record(out, SVA_LCM_RECORD_HEADER, payload, SVA_LCM_JOURNAL_HEADER_BYTES);
}

static const char* algo_name(uint32_t a)
{
    return (a < (uint32_t)SVA_ALGO_COUNT_) ? sva_algorithm_name((sva_algorithm_t)a) : "?";
}

// The node options a header names, as the node's command line spells them
// (--takeoff-ticks only when not 0).
static void options_text(char* out, size_t size, uint32_t algo, uint32_t reports, int32_t penalty,
                         int32_t tolerance, int32_t takeoff)
{
    char extra[48] = "";
    if (takeoff != 0) {
        (void)snprintf(extra, sizeof extra, " --takeoff-ticks %ld", (long)takeoff);
    }
    (void)snprintf(out, size, "--algo %s --change-penalty %ld --track-tolerance %ld%s%s",
                   algo_name(algo), (long)penalty, (long)tolerance, extra,
                   (reports != 0U) ? " --fleet-reports" : "");
}

// Judges a header payload p of len bytes against this build and the node.
static sva_lcm_journal_status_t check_header(sva_lcm_journal_t* self, const uint8_t* p,
                                             uint32_t len)
{
    if ((len < NAMED_BYTES) || (memcmp(p, magic, MAGIC_BYTES) != 0)) {
        (void)snprintf(self->message, sizeof self->message,
                       "the header does not parse: not an sva_node journal (no \"SVAJ\")");
        return SVA_LCM_JOURNAL_ERR_FORMAT;
    }
    const uint32_t format = sva_journal_get_u16(p + 4);
    const uint32_t major = sva_journal_get_u16(p + 6);
    const uint32_t minor = sva_journal_get_u16(p + 8);
    const uint32_t patch = sva_journal_get_u16(p + 10);
    char theirs[96];
    char ours[96];
    (void)snprintf(theirs, sizeof theirs, "sva %lu.%lu.%lu (journal format %lu)",
                   (unsigned long)major, (unsigned long)minor, (unsigned long)patch,
                   (unsigned long)format);
    (void)snprintf(ours, sizeof ours, "sva %d.%d.%d (journal format %d)", SVA_VERSION_MAJOR,
                   SVA_VERSION_MINOR, SVA_VERSION_PATCH, SVA_LCM_JOURNAL_FORMAT);
    if ((format != (uint32_t)SVA_LCM_JOURNAL_FORMAT) || (major != (uint32_t)SVA_VERSION_MAJOR) ||
        (minor != (uint32_t)SVA_VERSION_MINOR) || (patch != (uint32_t)SVA_VERSION_PATCH)) {
        (void)snprintf(self->message, sizeof self->message,
                       "the journal was written by %s; this node is %s", theirs, ours);
        return SVA_LCM_JOURNAL_ERR_VERSION;
    }
    if (len != (uint32_t)SVA_LCM_JOURNAL_HEADER_BYTES) {
        (void)snprintf(self->message, sizeof self->message,
                       "the header does not parse: %lu bytes, journal format %d has %d",
                       (unsigned long)len, SVA_LCM_JOURNAL_FORMAT, SVA_LCM_JOURNAL_HEADER_BYTES);
        return SVA_LCM_JOURNAL_ERR_FORMAT;
    }
    for (int i = 0; i < 4; ++i) {
        const uint64_t got = sva_journal_get_u64(p + NAMED_BYTES + (8U * (size_t)i));
        if (got != fingerprint(i)) {
            (void)snprintf(self->message, sizeof self->message,
                           "the journal was written by %s with other wire types (%s "
                           "fingerprint 0x%016llx); this node is %s (0x%016llx)",
                           theirs, fingerprint_names[i], (unsigned long long)got, ours,
                           (unsigned long long)fingerprint(i));
            return SVA_LCM_JOURNAL_ERR_VERSION;
        }
    }
    uint8_t want[SVA_LCM_JOURNAL_HEADER_BYTES];
    header_payload(self->node, want);
    if (memcmp(p + 44, want + 44, SVA_LCM_JOURNAL_HEADER_BYTES - 44) != 0) {
        char a[128];
        char b[128];
        options_text(a, sizeof a, p[44], p[45], (int32_t)sva_journal_get_u32(p + 46),
                     (int32_t)sva_journal_get_u32(p + 50), (int32_t)sva_journal_get_u32(p + 54));
        options_text(b, sizeof b, want[44], want[45], self->node->change_penalty,
                     self->node->track_tolerance_cells, self->node->takeoff_ticks);
        (void)snprintf(self->message, sizeof self->message,
                       "the journal was written by a node run with %s; this node runs with %s", a,
                       b);
        return SVA_LCM_JOURNAL_ERR_OPTIONS;
    }
    return SVA_LCM_JOURNAL_OK;
}

// --- storage calls ------------------------------------------------------------------

static sva_lcm_journal_status_t io_failed(sva_lcm_journal_t* self, const char* call)
{
    sva_journal_say_failed(&self->storage, call, self->message, sizeof self->message);
    return SVA_LCM_JOURNAL_ERR_IO;
}

// A new journal: the header alone, replacing whatever was there.
static sva_lcm_journal_status_t start_fresh(sva_lcm_journal_t* self)
{
    const uint32_t n = put_header(self->node, self->buf);
    if (self->storage.replace(self->storage.ctx, self->buf, n) != 0) {
        return io_failed(self, "replace");
    }
    self->size = n;
    self->records = 1U;
    return SVA_LCM_JOURNAL_OK;
}

// Reads the record at off of a journal of self->size bytes into self->buf. Returns 1 for
// a good record (*type, *len), 0 for a torn or corrupt one (why says what), -1 when the
// storage failed.
static int read_record(sva_lcm_journal_t* self, uint32_t off, uint32_t* type, uint32_t* len,
                       char* why, size_t why_size)
{
    return (int)sva_journal_read_record(&self->storage, self->size, off, self->buf,
                                        (uint32_t)SVA_LCM_JOURNAL_MAX_PAYLOAD, type, len, why,
                                        why_size);
}

// --- replay ---------------------------------------------------------------------------

// While replaying: the answers go nowhere, and the input hook checks that the handler
// took the record it was given (the same kind and bytes).
typedef struct {
    sva_lcm_input_t kind;
    const uint8_t* data;
    size_t size;
    bool taken;
} replay_t;

static int publish_nothing(void* user, const char* channel, const void* data, unsigned int size)
{
    (void)user;
    (void)channel;
    (void)data;
    (void)size;
    return 0;
}

static int replay_hook(void* user, sva_lcm_input_t kind, bool restarts, const void* data,
                       size_t size)
{
    (void)restarts;
    replay_t* r = (replay_t*)user;
    r->taken =
        !r->taken && (kind == r->kind) && (size == r->size) && (memcmp(data, r->data, size) == 0);
    return 0;
}

static sva_lcm_journal_status_t replay_record(sva_lcm_journal_t* self, uint32_t off, uint32_t type,
                                              uint32_t len)
{
    sva_lcm_node_t* node = self->node;
    const uint8_t* payload = self->buf + PREFIX_BYTES;
    if ((type == (uint32_t)SVA_LCM_RECORD_BASE) && (len == (uint32_t)BASE_BYTES)) {
        if (sva_lcm_node_set_plan_id(node, (int64_t)sva_journal_get_u64(payload)) != SVA_OK) {
            (void)snprintf(self->message, sizeof self->message,
                           "record at byte %lu (base): a negative plan id", (unsigned long)off);
            return SVA_LCM_JOURNAL_ERR_REPLAY;
        }
        return SVA_LCM_JOURNAL_OK;
    }
    if ((input_bytes(type) == 0U) || (len != input_bytes(type))) {
        (void)snprintf(self->message, sizeof self->message,
                       "record at byte %lu: type %lu (%s) of %lu bytes is not in journal "
                       "format %d",
                       (unsigned long)off, (unsigned long)type, record_name(type),
                       (unsigned long)len, SVA_LCM_JOURNAL_FORMAT);
        return SVA_LCM_JOURNAL_ERR_FORMAT;
    }
    replay_t r = {SVA_LCM_INPUT_FLEET, payload, len, false};
    node->input_hook_user = &r;
    sva_lcm_status_t v;
    if (type == (uint32_t)SVA_LCM_RECORD_FLEET) {
        v = sva_lcm_on_fleet(node, payload, len);
    } else if (type == (uint32_t)SVA_LCM_RECORD_MISSION) {
        r.kind = SVA_LCM_INPUT_MISSION;
        v = sva_lcm_on_mission(node, payload, len);
    } else if (type == (uint32_t)SVA_LCM_RECORD_EVENT) {
        r.kind = SVA_LCM_INPUT_EVENT;
        v = sva_lcm_on_event(node, payload, len);
    } else {
        r.kind = SVA_LCM_INPUT_REPORT;
        v = sva_lcm_on_report(node, payload, len);
    }
    if ((v != SVA_LCM_ACCEPTED) || !r.taken) {
        (void)snprintf(self->message, sizeof self->message,
                       "record at byte %lu (%s): the node did not take it again (%s): the "
                       "journal does not hold this node's inputs",
                       (unsigned long)off, record_name(type),
                       (v == SVA_LCM_REJECTED)    ? sva_lcm_reject_name(node->last_reject)
                       : (v == SVA_LCM_UNCHANGED) ? "unchanged"
                                                  : "no change");
        return SVA_LCM_JOURNAL_ERR_REPLAY;
    }
    return SVA_LCM_JOURNAL_OK;
}

// One record of the replay (sva_journal_replay's callback): its status kept, a failure
// stops the replay.
typedef struct {
    sva_lcm_journal_t* self;
    sva_lcm_journal_resume_t* out;
    sva_lcm_journal_status_t status;
} replaying_t;

static int on_record(void* user, uint32_t off, uint32_t type, const uint8_t* payload, uint32_t len)
{
    replaying_t* r = (replaying_t*)user;
    (void)payload;  // in self->buf, where replay_record reads it
    r->status = replay_record(r->self, off, type, len);
    if (r->status != SVA_LCM_JOURNAL_OK) {
        return 1;
    }
    r->out->records += (type == (uint32_t)SVA_LCM_RECORD_BASE) ? 0U : 1U;
    r->self->records += 1U;
    return 0;
}

// Replays the records after the header; a torn or corrupt one ends the journal there.
static sva_lcm_journal_status_t replay(sva_lcm_journal_t* self, uint32_t off,
                                       sva_lcm_journal_resume_t* out)
{
    replaying_t r = {self, out, SVA_LCM_JOURNAL_OK};
    sva_journal_cut_t cut;
    const sva_journal_replay_status_t st = sva_journal_replay(
        &self->storage, off, &self->size, self->buf, (uint32_t)SVA_LCM_JOURNAL_MAX_PAYLOAD,
        on_record, &r, &cut, self->message, sizeof self->message);
    out->cut = cut.cut;
    out->cut_offset = cut.offset;
    out->cut_bytes = cut.bytes;
    if (st == SVA_JOURNAL_REPLAY_IO) {
        return SVA_LCM_JOURNAL_ERR_IO;
    }
    return r.status;
}

// Reads and judges the header record; *end is where the records after it start.
static sva_lcm_journal_status_t read_header(sva_lcm_journal_t* self, uint32_t* end)
{
    uint32_t type = 0U;
    uint32_t len = 0U;
    char why[96];
    const int got = read_record(self, 0U, &type, &len, why, sizeof why);
    if (got < 0) {
        return io_failed(self, "read");
    }
    if (got == 0) {
        (void)snprintf(self->message, sizeof self->message, "the header does not parse: %s", why);
        return SVA_LCM_JOURNAL_ERR_FORMAT;
    }
    if (type != (uint32_t)SVA_LCM_RECORD_HEADER) {
        (void)snprintf(self->message, sizeof self->message,
                       "the header does not parse: the first record is of type %lu",
                       (unsigned long)type);
        return SVA_LCM_JOURNAL_ERR_FORMAT;
    }
    *end = len + (uint32_t)SVA_LCM_JOURNAL_RECORD_OVERHEAD;
    return check_header(self, self->buf + PREFIX_BYTES, len);
}

sva_lcm_journal_status_t sva_lcm_journal_init(sva_lcm_journal_t* self,
                                              const sva_lcm_storage_t* storage,
                                              sva_lcm_node_t* node)
{
    if ((self == NULL) || (node == NULL) || !sva_journal_storage_complete(storage)) {
        return SVA_LCM_JOURNAL_ERR_ARGUMENT;
    }
    memset(self, 0, sizeof(*self));
    self->storage = *storage;
    self->node = node;
    return SVA_LCM_JOURNAL_OK;
}

sva_lcm_journal_status_t sva_lcm_journal_resume(sva_lcm_journal_t* self, bool reset,
                                                sva_lcm_journal_resume_t* out)
{
    if ((self == NULL) || (out == NULL) || (self->node == NULL)) {
        return SVA_LCM_JOURNAL_ERR_ARGUMENT;
    }
    memset(out, 0, sizeof(*out));
    self->message[0] = '\0';
    if (!self->open) {
        uint32_t size = 0U;
        if (self->storage.open(self->storage.ctx, &size) != 0) {
            return io_failed(self, "open");
        }
        self->open = true;
        self->size = size;
    }
    sva_lcm_journal_status_t st = SVA_LCM_JOURNAL_OK;
    if ((self->size == 0U) || reset) {
        out->fresh = true;
        out->discarded = (self->size > 0U);
        if (out->discarded) {
            (void)snprintf(self->message, sizeof self->message,
                           "reset: a journal of %lu bytes discarded", (unsigned long)self->size);
        }
        st = start_fresh(self);
    } else {
        uint32_t off = 0U;
        st = read_header(self, &off);
        if (st == SVA_LCM_JOURNAL_OK) {
            sva_lcm_node_t* node = self->node;
            const sva_lcm_publish_fn publish = node->publish;
            void* const publish_user = node->publish_user;
            const sva_lcm_log_fn log = node->log;
            node->publish = publish_nothing;
            node->log = NULL;
            node->input_hook = replay_hook;
            self->records = 1U;
            st = replay(self, off, out);
            node->publish = publish;
            node->publish_user = publish_user;
            node->log = log;
            node->input_hook = NULL;
            node->input_hook_user = NULL;
            // The counters count this process's messages, not the replayed ones.
            memset(&node->counters, 0, sizeof node->counters);
        }
    }
    if (st != SVA_LCM_JOURNAL_OK) {
        return st;
    }
    out->bytes = self->size;
    self->node->input_hook = sva_lcm_journal_input;
    self->node->input_hook_user = self;
    return SVA_LCM_JOURNAL_OK;
}

// --- appending ------------------------------------------------------------------------

// The journal replaced by the current inputs alone (sva_lcm_journal.h, "Compaction").
static int compact(sva_lcm_journal_t* self)
{
    const sva_lcm_node_t* node = self->node;
    uint8_t base[BASE_BYTES];
    sva_journal_put_u64(base, (uint64_t)node->priv.plan_id);
    uint32_t n = put_header(node, self->buf);
    n += put_record(self->buf + n, SVA_LCM_RECORD_BASE, base, BASE_BYTES);
    uint32_t records = 2U;
    if (node->priv.have_fleet) {
        n += put_record(self->buf + n, SVA_LCM_RECORD_FLEET, node->priv.fleet_raw,
                        SVA_LCM_FLEET_BYTES);
        records += 1U;
    }
    if (node->priv.have_mission) {
        n += put_record(self->buf + n, SVA_LCM_RECORD_MISSION, node->priv.mission_raw,
                        SVA_LCM_MISSION_BYTES);
        records += 1U;
    }
    if (self->storage.replace(self->storage.ctx, self->buf, n) != 0) {
        (void)io_failed(self, "replace");
        return -1;
    }
    self->size = n;
    self->records = records;
    self->compactions += 1U;
    return 0;
}

int sva_lcm_journal_input(void* user, sva_lcm_input_t kind, bool restarts, const void* data,
                          size_t size)
{
    sva_lcm_journal_t* self = (sva_lcm_journal_t*)user;
    if ((self == NULL) || !self->open || (data == NULL)) {
        return -1;
    }
    if (restarts) {
        return compact(self);
    }
    const sva_lcm_record_t type = record_of(kind);
    if (size != (size_t)input_bytes((uint32_t)type)) {
        (void)snprintf(self->message, sizeof self->message,
                       "append: a %s of %lu bytes is not an input of journal format %d",
                       record_name((uint32_t)type), (unsigned long)size, SVA_LCM_JOURNAL_FORMAT);
        return -1;
    }
    const uint32_t n = put_record(self->buf, type, data, (uint32_t)size);
    return sva_journal_append(&self->storage, self->buf, n, &self->size, &self->records,
                              self->message, sizeof self->message);
}

void sva_lcm_journal_close(sva_lcm_journal_t* self)
{
    if (self == NULL) {
        return;
    }
    if ((self->node != NULL) && (self->node->input_hook_user == self)) {
        self->node->input_hook = NULL;
        self->node->input_hook_user = NULL;
    }
    if (self->open && (self->storage.close != NULL)) {
        self->storage.close(self->storage.ctx);
    }
    self->open = false;
}
