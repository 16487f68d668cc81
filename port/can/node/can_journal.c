// can_journal.c -- sva_can_node's journal of live-mission inputs: header, mission,
// replay, cut (contract in can_journal.h). Records, CRC-32 and storage are the shared
// record layer's (sva_journal.h).
#include "can_journal.h"

#include <stdio.h>
#include <string.h>

#define MAGIC_BYTES 4
#define NAMED_BYTES 12  // magic, format, sva version: where every format keeps them
#define OPTIONS_AT  18  // algorithm, track tolerance

static const uint8_t magic[MAGIC_BYTES] = {'S', 'V', 'A', 'C'};

static const char* const status_names[] = {"ok",      "argument", "io",      "format",
                                           "version", "options",  "mission", "replay"};

const char* sva_can_journal_status_name(sva_can_journal_status_t status)
{
    const int i = -(int)status;
    if ((i < 0) || (i >= (int)(sizeof status_names / sizeof status_names[0]))) {
        return "";
    }
    return status_names[i];
}

static const char* record_name(uint32_t type)
{
    static const char* const names[] = {"unknown", "header", "mission", "msg", "replan"};
    return names[(type < 5U) ? type : 0U];
}

static sva_can_journal_status_t io_failed(sva_can_journal_t* self, const char* call)
{
    sva_journal_say_failed(&self->storage, call, self->message, sizeof self->message);
    return SVA_CAN_JOURNAL_ERR_IO;
}

// --- payloads ---------------------------------------------------------------------------

static void header_payload(const sva_can_live_t* live, uint8_t* p)
{
    memcpy(p, magic, MAGIC_BYTES);
    sva_journal_put_u16(p + 4, SVA_CAN_JOURNAL_FORMAT);
    sva_journal_put_u16(p + 6, SVA_VERSION_MAJOR);
    sva_journal_put_u16(p + 8, SVA_VERSION_MINOR);
    sva_journal_put_u16(p + 10, SVA_VERSION_PATCH);
    sva_journal_put_u16(p + 12, SVA_CAN_PROTOCOL_VERSION);
    sva_journal_put_u16(p + 14, SVA_MAX_UAVS);
    sva_journal_put_u16(p + 16, SVA_MAX_TARGETS);
    p[OPTIONS_AT] = (uint8_t)live->algorithm;
    sva_journal_put_u32(p + OPTIONS_AT + 1, (uint32_t)live->track_tolerance_cells);
}

// The MISSION payload, field by field: written to out, or compared with cmp, or both.
typedef struct {
    uint8_t* out;
    const uint8_t* cmp;
    uint32_t cmp_len;
    uint32_t n;
    bool same;
} emit_t;

static void emit(emit_t* e, uint32_t v, uint32_t bytes)
{
    uint8_t b[4];
    if (bytes == 2U) {
        sva_journal_put_u16(b, v);
    } else {
        sva_journal_put_u32(b, v);
    }
    if (e->out != NULL) {
        memcpy(e->out + e->n, b, bytes);
    }
    if (e->cmp != NULL) {
        e->same = e->same && (e->n + bytes <= e->cmp_len) && (memcmp(e->cmp + e->n, b, bytes) == 0);
    }
    e->n += bytes;
}

static void mission_emit(const sva_mission_t* m, emit_t* e)
{
    const int32_t head[7] = {m->depot_x,      m->depot_y,         m->ticks_per_cell,
                             m->hover_fuel,   m->overlap_percent, m->change_penalty,
                             m->takeoff_ticks};
    for (unsigned i = 0U; i < 7U; ++i) {
        emit(e, (uint32_t)head[i], 4U);
    }
    emit(e, m->uav_count, 2U);
    emit(e, m->target_count, 2U);
    for (uint16_t u = 0U; u < m->uav_count; ++u) {
        const sva_uav_t* v = &m->uavs[u];
        const int32_t f[5] = {v->id, v->x, v->y, v->fuel, v->ready_at_ticks};
        for (unsigned i = 0U; i < 5U; ++i) {
            emit(e, (uint32_t)f[i], 4U);
        }
    }
    for (uint16_t t = 0U; t < m->target_count; ++t) {
        const sva_target_t* v = &m->targets[t];
        const int32_t f[6] = {v->id, v->x, v->y, v->start_ticks, v->end_ticks, v->need};
        for (unsigned i = 0U; i < 6U; ++i) {
            emit(e, (uint32_t)f[i], 4U);
        }
    }
}

static uint32_t mission_payload(const sva_mission_t* m, uint8_t* p)
{
    emit_t e = {p, NULL, 0U, 0U, true};
    mission_emit(m, &e);
    return e.n;
}

static bool mission_is(const sva_mission_t* m, const uint8_t* p, uint32_t len)
{
    emit_t e = {NULL, p, len, 0U, true};
    mission_emit(m, &e);
    return e.same && (e.n == len);
}

// The payload of one input (MSG or REPLAN); returns its type, 0 when it has none.
static uint8_t input_payload(const sva_can_live_input_t* in, uint8_t* p, uint32_t* len)
{
    sva_journal_put_u32(p, in->now_ms);
    if (in->kind == SVA_CAN_LIVE_INPUT_REPLAN) {
        p[4] = (uint8_t)(int8_t)in->outcome;
        *len = SVA_CAN_JOURNAL_REPLAN_BYTES;
        return (uint8_t)SVA_CAN_RECORD_REPLAN;
    }
    sva_can_frame_t f;
    if ((in->msg == NULL) || (sva_can_encode(in->msg, &f) != SVA_CAN_OK)) {
        return 0U;
    }
    sva_journal_put_u16(p + 4, f.id);
    memcpy(p + 6, f.data, 8U);
    *len = SVA_CAN_JOURNAL_MSG_BYTES;
    return (uint8_t)SVA_CAN_RECORD_MSG;
}

// --- the header -------------------------------------------------------------------------

static void version_text(char* out, size_t size, const uint8_t* p)
{
    (void)snprintf(
        out, size, "sva %lu.%lu.%lu (journal format %lu", (unsigned long)sva_journal_get_u16(p + 6),
        (unsigned long)sva_journal_get_u16(p + 8), (unsigned long)sva_journal_get_u16(p + 10),
        (unsigned long)sva_journal_get_u16(p + 4));
}

static void build_text(char* out, size_t size, const uint8_t* p)
{
    char v[64];
    version_text(v, sizeof v, p);
    (void)snprintf(out, size, "%s, CAN protocol %lu, SVA_MAX_UAVS %lu, SVA_MAX_TARGETS %lu)", v,
                   (unsigned long)sva_journal_get_u16(p + 12),
                   (unsigned long)sva_journal_get_u16(p + 14),
                   (unsigned long)sva_journal_get_u16(p + 16));
}

static void options_text(char* out, size_t size, const uint8_t* p)
{
    const uint32_t a = p[OPTIONS_AT];
    (void)snprintf(out, size, "--algo %s --track-tolerance %ld",
                   (a < (uint32_t)SVA_ALGO_COUNT_) ? sva_algorithm_name((sva_algorithm_t)a) : "?",
                   (long)(int32_t)sva_journal_get_u32(p + OPTIONS_AT + 1));
}

static sva_can_journal_status_t check_header(sva_can_journal_t* self, const uint8_t* p,
                                             uint32_t len)
{
    uint8_t want[SVA_CAN_JOURNAL_HEADER_BYTES];
    char theirs[150];
    char ours[150];
    if ((len < NAMED_BYTES) || (memcmp(p, magic, MAGIC_BYTES) != 0)) {
        (void)snprintf(self->message, sizeof self->message,
                       "the header does not parse: not an sva_can_node journal (no \"SVAC\")");
        return SVA_CAN_JOURNAL_ERR_FORMAT;
    }
    header_payload(self->live, want);
    if (memcmp(p + 4, want + 4, NAMED_BYTES - 4) != 0) {
        version_text(theirs, sizeof theirs, p);
        version_text(ours, sizeof ours, want);
        (void)snprintf(self->message, sizeof self->message,
                       "the journal was written by %s); this node is %s)", theirs, ours);
        return SVA_CAN_JOURNAL_ERR_VERSION;
    }
    if (len != (uint32_t)SVA_CAN_JOURNAL_HEADER_BYTES) {
        (void)snprintf(self->message, sizeof self->message,
                       "the header does not parse: %lu bytes, journal format %d has %d",
                       (unsigned long)len, SVA_CAN_JOURNAL_FORMAT, SVA_CAN_JOURNAL_HEADER_BYTES);
        return SVA_CAN_JOURNAL_ERR_FORMAT;
    }
    if (memcmp(p + NAMED_BYTES, want + NAMED_BYTES, OPTIONS_AT - NAMED_BYTES) != 0) {
        build_text(theirs, sizeof theirs, p);
        build_text(ours, sizeof ours, want);
        (void)snprintf(self->message, sizeof self->message,
                       "the journal was written by %s; this node is %s", theirs, ours);
        return SVA_CAN_JOURNAL_ERR_VERSION;
    }
    if (memcmp(p + OPTIONS_AT, want + OPTIONS_AT, SVA_CAN_JOURNAL_HEADER_BYTES - OPTIONS_AT) != 0) {
        options_text(theirs, sizeof theirs, p);
        options_text(ours, sizeof ours, want);
        (void)snprintf(self->message, sizeof self->message,
                       "the journal was written by a node run with %s; this node runs with %s",
                       theirs, ours);
        return SVA_CAN_JOURNAL_ERR_OPTIONS;
    }
    return SVA_CAN_JOURNAL_OK;
}

// --- reading ----------------------------------------------------------------------------

static int read_record(sva_can_journal_t* self, uint32_t off, uint32_t* type, uint32_t* len,
                       char* why, size_t why_size)
{
    return (int)sva_journal_read_record(&self->storage, self->size, off, self->buf,
                                        (uint32_t)SVA_CAN_JOURNAL_MAX_PAYLOAD, type, len, why,
                                        why_size);
}

// Reads and judges the header and the mission; *end is where the inputs start.
static sva_can_journal_status_t read_head(sva_can_journal_t* self, const sva_mission_t* mission,
                                          uint32_t* end)
{
    uint32_t type = 0U;
    uint32_t len = 0U;
    char why[96];
    int got = read_record(self, 0U, &type, &len, why, sizeof why);
    if (got < 0) {
        return io_failed(self, "read");
    }
    if (got == 0) {
        (void)snprintf(self->message, sizeof self->message, "the header does not parse: %s", why);
        return SVA_CAN_JOURNAL_ERR_FORMAT;
    }
    if (type != (uint32_t)SVA_CAN_RECORD_HEADER) {
        (void)snprintf(self->message, sizeof self->message,
                       "the header does not parse: the first record is of type %lu",
                       (unsigned long)type);
        return SVA_CAN_JOURNAL_ERR_FORMAT;
    }
    const sva_can_journal_status_t st =
        check_header(self, self->buf + SVA_JOURNAL_PREFIX_BYTES, len);
    if (st != SVA_CAN_JOURNAL_OK) {
        return st;
    }
    *end = len + (uint32_t)SVA_JOURNAL_RECORD_OVERHEAD;
    // The mission is written with the header, in one replace: a journal without it is
    // not one this node wrote.
    got = read_record(self, *end, &type, &len, why, sizeof why);
    if (got < 0) {
        return io_failed(self, "read");
    }
    if ((got == 0) || (type != (uint32_t)SVA_CAN_RECORD_MISSION)) {
        (void)snprintf(self->message, sizeof self->message,
                       "the record at byte %lu is not the mission (%s)", (unsigned long)*end,
                       (got == 0) ? why : record_name(type));
        return SVA_CAN_JOURNAL_ERR_FORMAT;
    }
    const uint8_t* theirs = self->buf + SVA_JOURNAL_PREFIX_BYTES;
    if (!mission_is(mission, theirs, len)) {
        (void)snprintf(self->message, sizeof self->message,
                       "the journal was written for another mission (%lu UAVs, %lu targets); "
                       "--mission has %u UAVs, %u targets, or other values",
                       (unsigned long)((len >= 32U) ? sva_journal_get_u16(theirs + 28) : 0U),
                       (unsigned long)((len >= 32U) ? sva_journal_get_u16(theirs + 30) : 0U),
                       (unsigned)mission->uav_count, (unsigned)mission->target_count);
        return SVA_CAN_JOURNAL_ERR_MISSION;
    }
    *end += len + (uint32_t)SVA_JOURNAL_RECORD_OVERHEAD;
    return SVA_CAN_JOURNAL_OK;
}

// --- replay -----------------------------------------------------------------------------

// While replaying: the hook checks that the live mission took the record it was given
// (the same kind, time, bytes and outcome).
typedef struct {
    const uint8_t* payload;
    uint32_t len;
    uint8_t type;
    bool taken;
} replay_t;

static int replay_hook(void* user, const sva_can_live_input_t* input)
{
    replay_t* r = (replay_t*)user;
    uint8_t p[SVA_CAN_JOURNAL_MSG_BYTES];
    uint32_t len = 0U;
    const uint8_t type = input_payload(input, p, &len);
    r->taken =
        !r->taken && (type == r->type) && (len == r->len) && (memcmp(p, r->payload, len) == 0);
    return 0;
}

static sva_can_journal_status_t replay_record(sva_can_journal_t* self, uint32_t off, uint32_t type,
                                              uint32_t len, sva_can_journal_resume_t* out)
{
    sva_can_live_t* live = self->live;
    const uint8_t* p = self->buf + SVA_JOURNAL_PREFIX_BYTES;
    replay_t r = {p, len, (uint8_t)type, false};
    const uint32_t ms = (len >= 4U) ? sva_journal_get_u32(p) : 0U;
    int got = 0;
    if ((type == (uint32_t)SVA_CAN_RECORD_MSG) && (len == (uint32_t)SVA_CAN_JOURNAL_MSG_BYTES)) {
        sva_can_frame_t f;
        sva_can_msg_t m;
        memset(&f, 0, sizeof f);
        f.id = sva_journal_get_u16(p + 4);
        f.dlc = 8U;
        memcpy(f.data, p + 6, 8U);
        if (sva_can_decode(&f, &m) != SVA_CAN_OK) {
            (void)snprintf(self->message, sizeof self->message,
                           "record at byte %lu (msg): frame 0x%03lX does not decode: the journal "
                           "does not hold this node's inputs",
                           (unsigned long)off, (unsigned long)f.id);
            return SVA_CAN_JOURNAL_ERR_REPLAY;
        }
        live->input_hook_user = &r;
        got = sva_can_live_on_msg(live, &m, ms);
        out->frames += 1U;
    } else if ((type == (uint32_t)SVA_CAN_RECORD_REPLAN) &&
               (len == (uint32_t)SVA_CAN_JOURNAL_REPLAN_BYTES)) {
        live->input_hook_user = &r;
        got = sva_can_live_poll(live, ms, 0U);
        out->replans += 1U;
    } else {
        (void)snprintf(self->message, sizeof self->message,
                       "record at byte %lu: type %lu (%s) of %lu bytes is not in journal format %d",
                       (unsigned long)off, (unsigned long)type, record_name(type),
                       (unsigned long)len, SVA_CAN_JOURNAL_FORMAT);
        return SVA_CAN_JOURNAL_ERR_FORMAT;
    }
    if (!r.taken) {
        (void)snprintf(self->message, sizeof self->message,
                       "record at byte %lu (%s): the live mission did not take it again (result "
                       "%d): the journal does not hold this node's inputs",
                       (unsigned long)off, record_name(type), got);
        return SVA_CAN_JOURNAL_ERR_REPLAY;
    }
    return SVA_CAN_JOURNAL_OK;
}

// One record of the replay (sva_journal_replay's callback): its status kept, a failure
// stops the replay.
typedef struct {
    sva_can_journal_t* self;
    sva_can_journal_resume_t* out;
    sva_can_journal_status_t status;
} replaying_t;

static int on_record(void* user, uint32_t off, uint32_t type, const uint8_t* payload, uint32_t len)
{
    replaying_t* r = (replaying_t*)user;
    (void)payload;  // in self->buf, where replay_record reads it
    r->status = replay_record(r->self, off, type, len, r->out);
    if (r->status != SVA_CAN_JOURNAL_OK) {
        return 1;
    }
    r->self->records += 1U;
    return 0;
}

// Replays the records from off; a torn or corrupt one ends the journal there.
static sva_can_journal_status_t replay(sva_can_journal_t* self, uint32_t off,
                                       sva_can_journal_resume_t* out)
{
    replaying_t r = {self, out, SVA_CAN_JOURNAL_OK};
    sva_journal_cut_t cut;
    const sva_journal_replay_status_t st = sva_journal_replay(
        &self->storage, off, &self->size, self->buf, (uint32_t)SVA_CAN_JOURNAL_MAX_PAYLOAD,
        on_record, &r, &cut, self->message, sizeof self->message);
    out->cut = cut.cut;
    out->cut_offset = cut.offset;
    out->cut_bytes = cut.bytes;
    if (st == SVA_JOURNAL_REPLAY_IO) {
        return SVA_CAN_JOURNAL_ERR_IO;
    }
    return r.status;
}

// A new journal: HEADER and MISSION, replacing whatever was there.
static sva_can_journal_status_t start_fresh(sva_can_journal_t* self, const sva_mission_t* mission)
{
    uint8_t header[SVA_CAN_JOURNAL_HEADER_BYTES];
    header_payload(self->live, header);
    uint32_t n = sva_journal_put_record(self->buf, (uint8_t)SVA_CAN_RECORD_HEADER, header,
                                        SVA_CAN_JOURNAL_HEADER_BYTES);
    // The mission goes straight into its record's place.
    uint8_t* rec = self->buf + n;
    const uint32_t len = mission_payload(mission, rec + SVA_JOURNAL_PREFIX_BYTES);
    sva_journal_put_u32(rec, len);
    rec[4] = (uint8_t)SVA_CAN_RECORD_MISSION;
    sva_journal_put_u32(rec + SVA_JOURNAL_PREFIX_BYTES + len,
                        sva_journal_crc(rec, SVA_JOURNAL_PREFIX_BYTES + len));
    n += len + (uint32_t)SVA_JOURNAL_RECORD_OVERHEAD;
    if (self->storage.replace(self->storage.ctx, self->buf, n) != 0) {
        return io_failed(self, "replace");
    }
    self->size = n;
    self->records = 2U;
    return SVA_CAN_JOURNAL_OK;
}

sva_can_journal_status_t sva_can_journal_init(sva_can_journal_t* self,
                                              const sva_journal_storage_t* storage,
                                              sva_can_live_t* live)
{
    if ((self == NULL) || (live == NULL) || !sva_journal_storage_complete(storage)) {
        return SVA_CAN_JOURNAL_ERR_ARGUMENT;
    }
    memset(self, 0, sizeof(*self));
    self->storage = *storage;
    self->live = live;
    return SVA_CAN_JOURNAL_OK;
}

sva_can_journal_status_t sva_can_journal_resume(sva_can_journal_t* self,
                                                const sva_mission_t* mission, bool reset,
                                                sva_can_journal_resume_t* out)
{
    if ((self == NULL) || (mission == NULL) || (out == NULL) || (self->live == NULL)) {
        return SVA_CAN_JOURNAL_ERR_ARGUMENT;
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
    sva_can_journal_status_t st = SVA_CAN_JOURNAL_OK;
    sva_can_live_t* live = self->live;
    if ((self->size == 0U) || reset) {
        out->fresh = true;
        out->discarded = (self->size > 0U);
        if (out->discarded) {
            (void)snprintf(self->message, sizeof self->message,
                           "reset: a journal of %lu bytes discarded", (unsigned long)self->size);
        }
        st = start_fresh(self, mission);
    } else {
        uint32_t off = 0U;
        st = read_head(self, mission, &off);
        if (st == SVA_CAN_JOURNAL_OK) {
            FILE* const log = live->log;
            live->log = NULL;
            live->input_hook = replay_hook;
            self->records = 2U;
            st = replay(self, off, out);
            live->log = log;
            live->input_hook = NULL;
            live->input_hook_user = NULL;
            // The counters count this process's frames, not the replayed ones.
            memset(&live->stats, 0, sizeof live->stats);
        }
    }
    if (st != SVA_CAN_JOURNAL_OK) {
        return st;
    }
    out->bytes = self->size;
    live->input_hook = sva_can_journal_input;
    live->input_hook_user = self;
    return SVA_CAN_JOURNAL_OK;
}

// --- appending ----------------------------------------------------------------------------

int sva_can_journal_input(void* user, const sva_can_live_input_t* input)
{
    sva_can_journal_t* self = (sva_can_journal_t*)user;
    uint8_t p[SVA_CAN_JOURNAL_MSG_BYTES];
    uint32_t len = 0U;
    if ((self == NULL) || !self->open || (input == NULL)) {
        return -1;
    }
    const uint8_t type = input_payload(input, p, &len);
    if (type == 0U) {
        (void)snprintf(self->message, sizeof self->message,
                       "append: a frame that does not encode is not an input");
        return -1;
    }
    const uint32_t n = sva_journal_put_record(self->buf, type, p, len);
    return sva_journal_append(&self->storage, self->buf, n, &self->size, &self->records,
                              self->message, sizeof self->message);
}

void sva_can_journal_close(sva_can_journal_t* self)
{
    if (self == NULL) {
        return;
    }
    if ((self->live != NULL) && (self->live->input_hook_user == self)) {
        self->live->input_hook = NULL;
        self->live->input_hook_user = NULL;
    }
    if (self->open && (self->storage.close != NULL)) {
        self->storage.close(self->storage.ctx);
    }
    self->open = false;
}
