// Tests of the node's journal (port/lcm/src/lcm_journal.c, sva_lcm_journal.h): power
// loss and corruption, versions and options, compaction, a failing storage, and the
// POSIX file storage.
//
// The oracle is an uninterrupted node: a sequence of inputs (fleet, mission, events,
// reports, and inputs that change nothing) is fed to a node whose journal lives in
// memory, and its state and its answers are kept after every input. The journal is then
// cut at every byte offset, and bits are flipped in it; each time a fresh node resumes
// from it and must hold the state the uninterrupted node had after the last complete
// record (its sva_live_t byte for byte, its inputs, plan id and revisions), or refuse the
// journal. For the last records, the resumed node is also fed the rest of the inputs: it
// must publish the same answers (times aside) and regrow the same journal, byte for byte.
// Records are parsed here with the test's own reader (zlib's crc32), not the journal's.
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/types.h>
#include <sys/wait.h>
#include <unistd.h>

#include "sva_unity.h"
#include <zlib.h>

#include "sva/sva_lcm.h"
#include "sva/sva_lcm_journal.h"

#define MAX_INPUTS  40
#define MEM_CAP     65536
#define MAX_RECORDS 64

// --- a storage in memory, which can be told to fail -------------------------------------
typedef struct {
    uint8_t data[MEM_CAP];
    uint32_t size;
    long fail_append_after;  ///< -1: never; else the next append writes this many bytes and fails
    bool fail_replace;
    int replaces;
    int appends;
} mem_t;

static int mem_open(void* ctx, uint32_t* size)
{
    *size = ((mem_t*)ctx)->size;
    return 0;
}
static int mem_read(void* ctx, uint32_t offset, void* buf, uint32_t len)
{
    const mem_t* m = (const mem_t*)ctx;
    if ((offset > m->size) || (len > m->size - offset)) {
        return -1;
    }
    memcpy(buf, m->data + offset, len);
    return 0;
}
static int mem_append(void* ctx, const void* data, uint32_t len)
{
    mem_t* m = (mem_t*)ctx;
    uint32_t n = len;
    int rc = 0;
    if (m->fail_append_after >= 0) {
        n = ((uint32_t)m->fail_append_after < len) ? (uint32_t)m->fail_append_after : len;
        m->fail_append_after = -1;
        rc = -1;
    }
    if (n > MEM_CAP - m->size) {
        return -1;
    }
    memcpy(m->data + m->size, data, n);
    m->size += n;
    m->appends++;
    return rc;
}
static int mem_sync(void* ctx)
{
    (void)ctx;
    return 0;
}
static int mem_truncate(void* ctx, uint32_t size)
{
    mem_t* m = (mem_t*)ctx;
    if (size > m->size) {
        return -1;
    }
    m->size = size;
    return 0;
}
static int mem_replace(void* ctx, const void* data, uint32_t len)
{
    mem_t* m = (mem_t*)ctx;
    if ((len > MEM_CAP) || m->fail_replace) {
        return -1;
    }
    memcpy(m->data, data, len);
    m->size = len;
    m->replaces++;
    return 0;
}
static const char* mem_error(void* ctx)
{
    (void)ctx;
    return "the test's storage failed";
}

static void mem_storage(mem_t* m, sva_lcm_storage_t* s)
{
    memset(s, 0, sizeof(*s));
    s->ctx = m;
    s->open = mem_open;
    s->read = mem_read;
    s->append = mem_append;
    s->sync = mem_sync;
    s->truncate = mem_truncate;
    s->replace = mem_replace;
    s->error = mem_error;
}

// --- answers: every plan_t and replan_t, times zeroed, hashed ------------------------------
typedef struct {
    int count;
    uint32_t crc;
} answers_t;

static sva_lcm_replan_t replan_norm;
static sva_lcm_plan_t plan_norm;
static uint8_t norm_buf[SVA_LCM_REPLAN_BYTES];

static bool ends_with(const char* s, const char* tail)
{
    const size_t a = strlen(s);
    const size_t b = strlen(tail);
    return (a >= b) && (strcmp(s + a - b, tail) == 0);
}

static int capture(void* user, const char* channel, const void* data, unsigned int size)
{
    answers_t* a = (answers_t*)user;
    int n = 0;
    if (ends_with(channel, "REPLAN")) {
        memset(&replan_norm, 0, sizeof replan_norm);
        TEST_ASSERT_EQUAL_INT((int)size, sva_lcm_replan_t_decode(data, 0, (int)size, &replan_norm));
        replan_norm.plan.utime = 0;
        replan_norm.plan.solve_us = 0;
        n = sva_lcm_replan_t_encode(norm_buf, 0, (int)sizeof norm_buf, &replan_norm);
    } else if (ends_with(channel, "PLAN")) {
        memset(&plan_norm, 0, sizeof plan_norm);
        TEST_ASSERT_EQUAL_INT((int)size, sva_lcm_plan_t_decode(data, 0, (int)size, &plan_norm));
        plan_norm.utime = 0;
        plan_norm.solve_us = 0;
        n = sva_lcm_plan_t_encode(norm_buf, 0, (int)sizeof norm_buf, &plan_norm);
    } else {
        return 0;  // statuses carry counters: not compared
    }
    TEST_ASSERT_EQUAL_INT((int)size, n);
    a->count++;
    a->crc = (uint32_t)crc32(a->crc, (const Bytef*)channel, (uInt)strlen(channel));
    a->crc = (uint32_t)crc32(a->crc, norm_buf, (uInt)n);
    return 0;
}

// --- inputs -------------------------------------------------------------------------------
typedef struct {
    sva_lcm_input_t kind;
    uint32_t size;
    uint8_t bytes[SVA_LCM_MISSION_BYTES];
} input_t;

static input_t inputs[MAX_INPUTS];
static int n_inputs;

static void add_input(sva_lcm_input_t kind, const void* bytes, uint32_t size)
{
    TEST_ASSERT_TRUE(n_inputs < MAX_INPUTS);
    inputs[n_inputs].kind = kind;
    inputs[n_inputs].size = size;
    memcpy(inputs[n_inputs].bytes, bytes, size);
    n_inputs++;
}

static sva_lcm_fleet_state_t fleet;
static sva_lcm_mission_t mission;

// 5 UAVs, 6 targets (two need 2 UAVs): as in test_lcm_adapter.c.
static void make_fleet_and_mission(int64_t revision)
{
    memset(&fleet, 0, sizeof fleet);
    memset(&mission, 0, sizeof mission);
    fleet.version = SVA_LCM_FLEET_STATE_T_VERSION;
    fleet.revision = revision;
    fleet.uav_count = 5;
    for (int i = 0; i < 5; ++i) {
        fleet.uavs[i].id = 10 + i;
        fleet.uavs[i].fuel = 200;
        fleet.uavs[i].health = SVA_LCM_UAV_STATE_T_HEALTH_OK;
    }
    fleet.uavs[4].x = 3;
    fleet.uavs[4].ready_at_ticks = 4;
    mission.version = SVA_LCM_MISSION_T_VERSION;
    mission.revision = revision;
    mission.ticks_per_cell = 1;
    mission.hover_fuel = 2;
    mission.overlap_percent = 70;
    mission.target_count = 6;
    const int32_t t[6][6] = {{1, 5, 7, 12, 20, 2},   {2, -4, 3, 10, 18, 1},  {3, 6, -2, 14, 22, 1},
                             {4, 10, 10, 40, 50, 2}, {5, -8, -6, 35, 45, 1}, {6, 9, 1, 28, 34, 1}};
    for (int i = 0; i < 6; ++i) {
        sva_lcm_target_t* g = &mission.targets[i];
        g->id = t[i][0];
        g->x = t[i][1];
        g->y = t[i][2];
        g->start_ticks = t[i][3];
        g->end_ticks = t[i][4];
        g->need = t[i][5];
    }
}

static void add_fleet(void)
{
    static uint8_t buf[SVA_LCM_FLEET_BYTES];
    TEST_ASSERT_EQUAL_INT(SVA_LCM_FLEET_BYTES,
                          sva_lcm_fleet_state_t_encode(buf, 0, (int)sizeof buf, &fleet));
    add_input(SVA_LCM_INPUT_FLEET, buf, SVA_LCM_FLEET_BYTES);
}

static void add_mission(void)
{
    static uint8_t buf[SVA_LCM_MISSION_BYTES];
    TEST_ASSERT_EQUAL_INT(SVA_LCM_MISSION_BYTES,
                          sva_lcm_mission_t_encode(buf, 0, (int)sizeof buf, &mission));
    add_input(SVA_LCM_INPUT_MISSION, buf, SVA_LCM_MISSION_BYTES);
}

static void add_event_target(int8_t type, int32_t at, int32_t uav, int32_t x, int32_t y,
                             int32_t fuel, const int32_t* target)
{
    static uint8_t buf[SVA_LCM_EVENT_BYTES];
    sva_lcm_event_t e;
    memset(&e, 0, sizeof e);
    e.version = SVA_LCM_EVENT_T_VERSION;
    e.seq = n_inputs;
    e.type = type;
    e.at_ticks = at;
    e.uav_id = uav;
    e.x = x;
    e.y = y;
    e.fuel = fuel;
    if (target != NULL) {
        e.target.id = target[0];
        e.target.x = target[1];
        e.target.y = target[2];
        e.target.start_ticks = target[3];
        e.target.end_ticks = target[4];
        e.target.need = target[5];
    }
    TEST_ASSERT_EQUAL_INT(SVA_LCM_EVENT_BYTES, sva_lcm_event_t_encode(buf, 0, (int)sizeof buf, &e));
    add_input(SVA_LCM_INPUT_EVENT, buf, SVA_LCM_EVENT_BYTES);
}

static void add_event(int8_t type, int32_t at, int32_t uav, int32_t x, int32_t y, int32_t fuel)
{
    add_event_target(type, at, uav, x, y, fuel, NULL);
}

static void add_report(int32_t uav, int32_t at, int8_t health, int32_t x, int32_t y, int32_t fuel)
{
    static uint8_t buf[SVA_LCM_REPORT_BYTES];
    sva_lcm_report_t r;
    memset(&r, 0, sizeof r);
    r.version = SVA_LCM_REPORT_T_VERSION;
    r.uav_id = uav;
    r.at_ticks = at;
    r.health = health;
    r.x = x;
    r.y = y;
    r.fuel = fuel;
    r.mission_seq = -1;
    r.reached_seq = -1;
    TEST_ASSERT_EQUAL_INT(SVA_LCM_REPORT_BYTES,
                          sva_lcm_report_t_encode(buf, 0, (int)sizeof buf, &r));
    add_input(SVA_LCM_INPUT_REPORT, buf, SVA_LCM_REPORT_BYTES);
}

static sva_lcm_status_t feed(sva_lcm_node_t* n, const input_t* in, uint32_t size)
{
    switch (in->kind) {
    case SVA_LCM_INPUT_FLEET:
        return sva_lcm_on_fleet(n, in->bytes, size);
    case SVA_LCM_INPUT_MISSION:
        return sva_lcm_on_mission(n, in->bytes, size);
    case SVA_LCM_INPUT_EVENT:
        return sva_lcm_on_event(n, in->bytes, size);
    case SVA_LCM_INPUT_REPORT:
    default:
        return sva_lcm_on_report(n, in->bytes, size);
    }
}

// --- the two nodes, their journals and the uninterrupted run's record -------------------
typedef struct {
    sva_algorithm_t algorithm;
    int32_t change_penalty;
    bool fleet_reports;
    int32_t track_tolerance;
    int32_t takeoff_ticks;
} options_t;

static options_t opts;
static sva_lcm_node_t ref_node;
static sva_lcm_node_t node;
static sva_lcm_journal_t ref_journal;
static sva_lcm_journal_t journal;
static mem_t ref_mem;
static mem_t mem;
static answers_t ref_answers[MAX_INPUTS];
static answers_t answers;
static sva_lcm_status_t ref_verdicts[MAX_INPUTS];
/// The input that made the journal's last compaction: inputs before it are not in it.
static int search_from;
static uint32_t records_after[MAX_INPUTS];  ///< the journal's records after input i

typedef struct {
    bool live_active;
    bool have_fleet;
    bool have_mission;
    int64_t plan_id;
    int64_t fleet_revision;
    int64_t mission_revision;
    uint8_t fleet_raw[SVA_LCM_FLEET_BYTES];
    uint8_t mission_raw[SVA_LCM_MISSION_BYTES];
    sva_lcm_frame_t frame;
    sva_mission_t mission;
    sva_live_t live;
} snap_t;

static snap_t snap_initial;
static snap_t snaps[MAX_INPUTS];

static void take_snap(const sva_lcm_node_t* n, snap_t* s)
{
    memset(s, 0, sizeof(*s));
    s->live_active = n->priv.live_active;
    s->have_fleet = n->priv.have_fleet;
    s->have_mission = n->priv.have_mission;
    s->plan_id = n->priv.plan_id;
    s->fleet_revision = n->priv.fleet_revision;
    s->mission_revision = n->priv.mission_revision;
    if (s->have_fleet) {
        memcpy(s->fleet_raw, n->priv.fleet_raw, sizeof s->fleet_raw);
    }
    if (s->have_mission) {
        memcpy(s->mission_raw, n->priv.mission_raw, sizeof s->mission_raw);
        s->frame = n->priv.frame;
    }
    s->mission = n->priv.mission;
    if (s->live_active) {
        s->live = n->priv.live;
    }
}

static void assert_state(const sva_lcm_node_t* n, const snap_t* want)
{
    static snap_t got;
    take_snap(n, &got);
    TEST_ASSERT_EQUAL_INT(want->live_active, got.live_active);
    TEST_ASSERT_EQUAL_INT(want->have_fleet, got.have_fleet);
    TEST_ASSERT_EQUAL_INT(want->have_mission, got.have_mission);
    TEST_ASSERT_EQUAL_INT(want->plan_id, got.plan_id);
    TEST_ASSERT_EQUAL_INT(want->fleet_revision, got.fleet_revision);
    TEST_ASSERT_EQUAL_INT(want->mission_revision, got.mission_revision);
    TEST_ASSERT_EQUAL_MEMORY(want->fleet_raw, got.fleet_raw, sizeof got.fleet_raw);
    TEST_ASSERT_EQUAL_MEMORY(want->mission_raw, got.mission_raw, sizeof got.mission_raw);
    TEST_ASSERT_EQUAL_MEMORY(&want->frame, &got.frame, sizeof got.frame);
    TEST_ASSERT_EQUAL_MEMORY(&want->mission, &got.mission, sizeof got.mission);
    // The live mission, byte for byte: clock, revision, target states, routes in force,
    // the last replan's residual mission and plans.
    TEST_ASSERT_EQUAL_MEMORY(&want->live, &got.live, sizeof got.live);
}

static void node_setup(sva_lcm_node_t* n, answers_t* a)
{
    TEST_ASSERT_EQUAL_INT(SVA_OK, sva_lcm_node_init(n, NULL, "J_", opts.algorithm));
    n->publish = capture;
    n->publish_user = a;
    n->change_penalty = opts.change_penalty;
    n->fleet_reports = opts.fleet_reports;
    n->track_tolerance_cells = opts.track_tolerance;
    n->takeoff_ticks = opts.takeoff_ticks;
}

// The uninterrupted run: every input through a node with a journal in ref_mem.
static void run_reference(void)
{
    search_from = 0;
    memset(&ref_mem, 0, sizeof ref_mem);
    ref_mem.fail_append_after = -1;
    sva_lcm_storage_t s;
    mem_storage(&ref_mem, &s);
    node_setup(&ref_node, &answers);
    take_snap(&ref_node, &snap_initial);
    TEST_ASSERT_EQUAL_INT(SVA_LCM_JOURNAL_OK, sva_lcm_journal_init(&ref_journal, &s, &ref_node));
    sva_lcm_journal_resume_t r;
    TEST_ASSERT_EQUAL_INT(SVA_LCM_JOURNAL_OK, sva_lcm_journal_resume(&ref_journal, false, &r));
    TEST_ASSERT_TRUE(r.fresh);
    for (int i = 0; i < n_inputs; ++i) {
        memset(&answers, 0, sizeof answers);
        ref_verdicts[i] = feed(&ref_node, &inputs[i], inputs[i].size);
        ref_answers[i] = answers;
        records_after[i] = ref_journal.records;
        take_snap(&ref_node, &snaps[i]);
    }
    TEST_ASSERT_EQUAL_INT(ref_mem.size, ref_journal.size);
}

// --- the test's own record reader ----------------------------------------------------------
static uint32_t le32(const uint8_t* p)
{
    return (uint32_t)p[0] | ((uint32_t)p[1] << 8) | ((uint32_t)p[2] << 16) | ((uint32_t)p[3] << 24);
}

static uint32_t record_end[MAX_RECORDS];  ///< record_end[k]: where record k ends
static uint8_t record_type[MAX_RECORDS];
static int n_records;

static void parse_records(const uint8_t* j, uint32_t size)
{
    n_records = 0;
    uint32_t off = 0;
    while (off < size) {
        TEST_ASSERT_TRUE(size - off >= 9U);
        const uint32_t len = le32(j + off);
        TEST_ASSERT_TRUE(len + 9U <= size - off);
        const uint32_t crc = (uint32_t)crc32(0UL, j + off, (uInt)(len + 5U));
        TEST_ASSERT_EQUAL_INT(le32(j + off + 5U + len), crc);
        TEST_ASSERT_TRUE(n_records < MAX_RECORDS);
        record_type[n_records] = j[off + 4U];
        off += len + 9U;
        record_end[n_records++] = off;
    }
    TEST_ASSERT_EQUAL_INT(size, off);
}

// The reference state with c complete records in the journal: the first input after
// which the journal held c records (inputs that change nothing leave the same state).
static int input_with_records(uint32_t c)
{
    for (int i = search_from; i < n_inputs; ++i) {
        if (records_after[i] == c) {
            return i;
        }
    }
    return -2;
}

static sva_lcm_journal_status_t resume_from(const uint8_t* bytes, uint32_t size,
                                            sva_lcm_journal_resume_t* r)
{
    memset(&mem, 0, sizeof mem);
    mem.fail_append_after = -1;
    if (size > 0U) {
        memcpy(mem.data, bytes, size);
    }
    mem.size = size;
    sva_lcm_storage_t s;
    mem_storage(&mem, &s);
    node_setup(&node, &answers);
    memset(&answers, 0, sizeof answers);
    TEST_ASSERT_EQUAL_INT(SVA_LCM_JOURNAL_OK, sva_lcm_journal_init(&journal, &s, &node));
    return sva_lcm_journal_resume(&journal, false, r);
}

// After a resume that kept c records: the state of input q, and with `rest`, the
// remaining inputs give the same answers and regrow the same journal.
static void check_resumed(int q, bool rest)
{
    TEST_ASSERT_EQUAL_INT(0, answers.count);  // the replay published nothing
    TEST_ASSERT_EQUAL_INT(0U, node.counters.plans_published + node.counters.replans_published);
    assert_state(&node, (q < 0) ? &snap_initial : &snaps[q]);
    if (!rest) {
        return;
    }
    for (int i = q + 1; i < n_inputs; ++i) {
        memset(&answers, 0, sizeof answers);
        TEST_ASSERT_EQUAL_INT(ref_verdicts[i], feed(&node, &inputs[i], inputs[i].size));
        TEST_ASSERT_EQUAL_INT(ref_answers[i].count, answers.count);
        TEST_ASSERT_EQUAL_INT(ref_answers[i].crc, answers.crc);
    }
    assert_state(&node, &snaps[n_inputs - 1]);
    TEST_ASSERT_EQUAL_INT(ref_mem.size, mem.size);
    SVA_TEST_ASSERT_EQUAL_BYTES(ref_mem.data, mem.data, mem.size);
}

static uint8_t saved[MEM_CAP];

// Cuts the reference journal at every offset from `from` (power loss: a torn append);
// the continuation is checked from `rest_from`.
static void sweep_cuts(uint32_t from, uint32_t rest_from)
{
    const uint32_t size = ref_mem.size;
    memcpy(saved, ref_mem.data, size);
    parse_records(saved, size);
    for (uint32_t o = from; o <= size; ++o) {
        sva_lcm_journal_resume_t r;
        const sva_lcm_journal_status_t st = resume_from(saved, o, &r);
        if (o == 0U) {
            TEST_ASSERT_EQUAL_INT(SVA_LCM_JOURNAL_OK, st);  // no journal at all: a new one
            TEST_ASSERT_TRUE(r.fresh && !r.discarded);
            check_resumed(-1, false);
            continue;
        }
        if (o < record_end[0]) {
            TEST_ASSERT_EQUAL_INT(SVA_LCM_JOURNAL_ERR_FORMAT, st);  // the header is torn
            TEST_ASSERT_NOT_NULL(strstr(journal.message, "the header does not parse"));
            TEST_ASSERT_EQUAL_INT(o, mem.size);  // and left as it was
            continue;
        }
        TEST_ASSERT_EQUAL_INT(SVA_LCM_JOURNAL_OK, st);
        uint32_t c = 0;
        while ((c < (uint32_t)n_records) && (record_end[c] <= o)) {
            c++;
        }
        const uint32_t kept = record_end[c - 1];
        TEST_ASSERT_EQUAL_INT(o != kept, r.cut);
        TEST_ASSERT_EQUAL_INT(kept, mem.size);
        TEST_ASSERT_EQUAL_INT(kept, r.bytes);
        if (r.cut) {
            TEST_ASSERT_EQUAL_INT(kept, r.cut_offset);
            TEST_ASSERT_EQUAL_INT(o - kept, r.cut_bytes);
            char want[64];
            (void)snprintf(want, sizeof want, "record at byte %lu (", (unsigned long)kept);
            TEST_ASSERT_NOT_NULL(strstr(journal.message, want));
        }
        const int q = (c <= 2U) ? -1 : input_with_records(c);
        TEST_ASSERT_TRUE(q >= -1);
        check_resumed(q, o >= rest_from);
    }
}

// Flips bits: in record k, the journal resumes with the records before k (the header:
// refused), never with a damaged record applied.
static void sweep_flips(uint32_t from, bool every_bit)
{
    const uint32_t size = ref_mem.size;
    memcpy(saved, ref_mem.data, size);
    parse_records(saved, size);
    static uint8_t flipped[MEM_CAP];
    for (uint32_t p = from; p < size; ++p) {
        for (unsigned b = 0; b < 8U; ++b) {
            if (!every_bit && (b != (p % 8U))) {
                continue;
            }
            memcpy(flipped, saved, size);
            flipped[p] ^= (uint8_t)(1U << b);
            sva_lcm_journal_resume_t r;
            const sva_lcm_journal_status_t st = resume_from(flipped, size, &r);
            if (p < record_end[0]) {
                TEST_ASSERT_EQUAL_INT(SVA_LCM_JOURNAL_ERR_FORMAT, st);
                SVA_TEST_ASSERT_EQUAL_BYTES(flipped, mem.data, size);  // refused: left as it was
                continue;
            }
            TEST_ASSERT_EQUAL_INT(SVA_LCM_JOURNAL_OK, st);
            uint32_t k = 0;
            while (record_end[k] <= p) {
                k++;
            }
            TEST_ASSERT_TRUE(r.cut);
            TEST_ASSERT_EQUAL_INT(record_end[k - 1], r.cut_offset);
            TEST_ASSERT_EQUAL_INT(record_end[k - 1], mem.size);
            const int q = (k <= 2U) ? -1 : input_with_records(k);
            TEST_ASSERT_TRUE(q >= -1);
            check_resumed(q, false);
        }
    }
}

// --- the sequences ------------------------------------------------------------------------

// One live mission: events of every type, vehicle reports, and inputs that change
// nothing (an event in the past, the same fleet again, a report that agrees, a
// truncated event): those are answered or counted but not journaled.
static void sequence_one_mission(void)
{
    n_inputs = 0;
    make_fleet_and_mission(7);
    add_fleet();
    add_mission();
    add_event(SVA_LCM_EVENT_T_TYPE_CLOCK, 2, 0, 0, 0, 0);
    add_event(SVA_LCM_EVENT_T_TYPE_UAV_LOST, 5, 10, 0, 0, 0);
    add_event(SVA_LCM_EVENT_T_TYPE_CLOCK, 1, 0, 0, 0, 0);  // in the past: refused
    add_report(11, 7, SVA_LCM_REPORT_T_HEALTH_OK, 1, 1, -1);
    add_event(SVA_LCM_EVENT_T_TYPE_FUEL, 8, 12, 0, 0, 150);
    const int32_t added[6] = {7, 4, 4, 30, 36, 1};
    add_event_target(SVA_LCM_EVENT_T_TYPE_TARGET_ADDED, 9, 0, 0, 0, 0, added);
    add_fleet();  // the same fleet: unchanged
    add_event(SVA_LCM_EVENT_T_TYPE_UAV_BACK, 12, 10, 0, 0, 180);
    const int32_t cancelled[6] = {5, 0, 0, 0, 0, 0};
    add_event_target(SVA_LCM_EVENT_T_TYPE_TARGET_CANCELLED, 13, 0, 0, 0, 0, cancelled);
    const int32_t changed[6] = {4, 9, 9, 42, 50, 1};
    add_event_target(SVA_LCM_EVENT_T_TYPE_TARGET_CHANGED, 14, 0, 0, 0, 0, changed);
    add_report(13, 16, SVA_LCM_REPORT_T_HEALTH_LOST, 0, 0, -1);
    add_report(13, 16, SVA_LCM_REPORT_T_HEALTH_LOST, 0, 0, -1);  // agrees now: nothing
    add_report(13, 17, SVA_LCM_REPORT_T_HEALTH_LOST, 0, 0, -1);  // agrees: the clock alone
    add_event(SVA_LCM_EVENT_T_TYPE_POSITION, 18, 12, 2, 2, 100);
    add_event(SVA_LCM_EVENT_T_TYPE_CLOCK, 20, 0, 0, 0, 0);
    add_input(SVA_LCM_INPUT_EVENT, inputs[n_inputs - 1].bytes,
              SVA_LCM_EVENT_BYTES - 1);  // truncated
    add_event(SVA_LCM_EVENT_T_TYPE_CLOCK, 25, 0, 0, 0, 0);
}

static const int not_journaled_one[] = {4, 8, 13, 17};

static void check_reference_one_mission(void)
{
    run_reference();
    int skipped = 0;
    for (int i = 0; i < n_inputs; ++i) {
        bool journaled = (i == 0) || (records_after[i] != records_after[i - 1]);
        bool listed = false;
        for (size_t k = 0; k < sizeof not_journaled_one / sizeof not_journaled_one[0]; ++k) {
            listed = listed || (not_journaled_one[k] == i);
        }
        if (journaled == listed) {
            SVA_TEST_FAIL("input %d: journaled %d, verdict %d", i, (int)journaled,
                          (int)ref_verdicts[i]);
        }
        skipped += listed ? 1 : 0;
    }
    TEST_ASSERT_EQUAL_INT(4, skipped);
    TEST_ASSERT_EQUAL_INT(SVA_LCM_REJECTED, ref_verdicts[4]);
    TEST_ASSERT_EQUAL_INT(SVA_LCM_UNCHANGED, ref_verdicts[8]);
    TEST_ASSERT_EQUAL_INT(SVA_LCM_REJECTED, ref_verdicts[17]);
    TEST_ASSERT_EQUAL_INT(0, ref_answers[14].count);  // the clock moved: journaled, not answered
    TEST_ASSERT_EQUAL_INT(17, snaps[14].live.now_ticks);
    TEST_ASSERT_EQUAL_INT(1, ref_answers[4].count);  // a refused event is answered, not journaled
    TEST_ASSERT_TRUE(ref_node.priv.live_active);
    // header, base, fleet, mission, then one record per journaled input
    parse_records(ref_mem.data, ref_mem.size);
    TEST_ASSERT_EQUAL_INT(4 + (n_inputs - 2 - 4), n_records);
    TEST_ASSERT_EQUAL_INT(SVA_LCM_RECORD_HEADER, record_type[0]);
    TEST_ASSERT_EQUAL_INT(SVA_LCM_RECORD_BASE, record_type[1]);
    TEST_ASSERT_EQUAL_INT(SVA_LCM_RECORD_FLEET, record_type[2]);
    TEST_ASSERT_EQUAL_INT(SVA_LCM_RECORD_MISSION, record_type[3]);
    TEST_ASSERT_EQUAL_INT(SVA_LCM_RECORD_EVENT, record_type[4]);
    TEST_ASSERT_EQUAL_INT(SVA_LCM_RECORD_REPORT, record_type[6]);
    TEST_ASSERT_EQUAL_INT((uint32_t)n_records, ref_journal.records);
}

// Power loss: the journal of one live mission cut at every byte offset. The whole file
// is swept (a cut inside the header refuses it); the continuation is checked for cuts
// within the last four records.
void test_power_loss_every_offset(void)
{
    const sva_algorithm_t algos[2] = {SVA_ALGO_SVA, SVA_ALGO_FLOW};
    for (int a = 0; a < 2; ++a) {
        opts = (options_t){algos[a], 2, false, SVA_LCM_TRACK_TOLERANCE_DEFAULT, 0};
        sequence_one_mission();
        check_reference_one_mission();
        sweep_cuts(0U, record_end[n_records - 5]);
    }
}

// Corruption: one bit flipped at every byte (the bit varies with the byte), and every
// bit of the last four records.
void test_bit_flips(void)
{
    opts = (options_t){SVA_ALGO_SVA, 0, false, SVA_LCM_TRACK_TOLERANCE_DEFAULT, 0};
    sequence_one_mission();
    check_reference_one_mission();
    sweep_flips(0U, false);
    sweep_flips(record_end[n_records - 5], true);
}

// A new live mission replaces the journal by its inputs alone (compaction): header, base,
// fleet, mission. With fleet reports, a fleet message during the live mission is a
// report appended, not a restart. The compacted journal resumes the same state, the
// plan ids go on, and appends after it are cut safely at every offset.
void test_compaction(void)
{
    opts = (options_t){SVA_ALGO_SVA, 3, true, 1, 0};
    n_inputs = 0;
    make_fleet_and_mission(1);
    add_fleet();
    add_mission();
    add_event(SVA_LCM_EVENT_T_TYPE_CLOCK, 3, 0, 0, 0, 0);
    fleet.uavs[1].health = SVA_LCM_UAV_STATE_T_HEALTH_UNAVAILABLE;  // a report: UAV 11 lost
    add_fleet();
    add_event(SVA_LCM_EVENT_T_TYPE_UAV_LOST, 6, 12, 0, 0, 0);
    const int mission2 = n_inputs;
    mission.revision = 2;
    mission.target_count = 4;  // a new mission: fewer targets, one moved
    mission.targets[0].x = 2;
    add_mission();
    add_event(SVA_LCM_EVENT_T_TYPE_CLOCK, 4, 0, 0, 0, 0);
    fleet.uavs[0].fuel = 1;  // a report: UAV 10 short of fuel
    add_fleet();
    add_report(13, 8, SVA_LCM_REPORT_T_HEALTH_LOST, 0, 0, -1);
    add_event(SVA_LCM_EVENT_T_TYPE_CLOCK, 12, 0, 0, 0, 0);
    run_reference();
    search_from = mission2;
    for (int i = 0; i < n_inputs; ++i) {
        TEST_ASSERT_EQUAL_INT(SVA_LCM_ACCEPTED, ref_verdicts[i]);
    }
    TEST_ASSERT_EQUAL_INT(1, ref_answers[3].count);         // the fleet report: one replan
    TEST_ASSERT_EQUAL_INT(1, ref_answers[mission2].count);  // the new mission: its plan
    TEST_ASSERT_EQUAL_INT(3U, ref_journal.compactions);  // the fleet, the mission, the new mission
    parse_records(ref_mem.data, ref_mem.size);
    const uint8_t want[9] = {SVA_LCM_RECORD_HEADER,  SVA_LCM_RECORD_BASE,  SVA_LCM_RECORD_FLEET,
                             SVA_LCM_RECORD_MISSION, SVA_LCM_RECORD_EVENT, SVA_LCM_RECORD_FLEET,
                             SVA_LCM_RECORD_REPORT,  SVA_LCM_RECORD_EVENT, 0};
    TEST_ASSERT_EQUAL_INT(8, n_records);
    TEST_ASSERT_EQUAL_MEMORY(want, record_type, 8);
    // the base record holds the plan id sequence before the new mission's plan
    TEST_ASSERT_EQUAL_INT((uint32_t)snaps[mission2 - 1].plan_id,
                          le32(ref_mem.data + record_end[0] + 5U));
    // resumed whole: the same state; every cut after the compacted head: the state of
    // its last record and the same answers after it
    sva_lcm_journal_resume_t r;
    TEST_ASSERT_EQUAL_INT(SVA_LCM_JOURNAL_OK, resume_from(ref_mem.data, ref_mem.size, &r));
    TEST_ASSERT_EQUAL_INT(6U, r.records);
    TEST_ASSERT_FALSE(r.cut);
    assert_state(&node, &snaps[n_inputs - 1]);
    TEST_ASSERT_TRUE(snaps[n_inputs - 1].plan_id > snaps[mission2].plan_id);
    sweep_cuts(record_end[3], record_end[3]);
    // a flipped bit in the compacted head: cut there, nothing of the damaged record
    // applied (base: no plan id; fleet: no fleet; mission: a fleet and no mission)
    for (int k = 1; k <= 3; ++k) {
        static uint8_t flipped[MEM_CAP];
        memcpy(flipped, ref_mem.data, ref_mem.size);
        flipped[record_end[k - 1] + 6U] ^= 0x10U;
        TEST_ASSERT_EQUAL_INT(SVA_LCM_JOURNAL_OK, resume_from(flipped, ref_mem.size, &r));
        TEST_ASSERT_TRUE(r.cut);
        TEST_ASSERT_EQUAL_INT(record_end[k - 1], r.cut_offset);
        TEST_ASSERT_EQUAL_INT((k == 1) ? 0 : snaps[mission2 - 1].plan_id, node.priv.plan_id);
        TEST_ASSERT_EQUAL_INT(k == 3, node.priv.have_fleet);
        TEST_ASSERT_FALSE(node.priv.have_mission);
        TEST_ASSERT_FALSE(node.priv.live_active);
    }

    // Without fleet reports a new fleet is a new live mission too: one of fewer UAVs
    // compacts the journal and resumes to the same bytes (no slot of the old fleet left).
    opts = (options_t){SVA_ALGO_SVA, 0, false, SVA_LCM_TRACK_TOLERANCE_DEFAULT, 0};
    n_inputs = 0;
    make_fleet_and_mission(3);
    add_fleet();
    add_mission();
    add_event(SVA_LCM_EVENT_T_TYPE_UAV_LOST, 4, 11, 0, 0, 0);
    const int fleet2 = n_inputs;
    fleet.revision = 4;
    fleet.uav_count = 3;
    add_fleet();
    add_event(SVA_LCM_EVENT_T_TYPE_CLOCK, 6, 0, 0, 0, 0);
    run_reference();
    search_from = fleet2;
    TEST_ASSERT_EQUAL_INT(3U, ref_journal.compactions);
    parse_records(ref_mem.data, ref_mem.size);
    TEST_ASSERT_EQUAL_INT(5, n_records);
    TEST_ASSERT_EQUAL_INT(SVA_LCM_JOURNAL_OK, resume_from(ref_mem.data, ref_mem.size, &r));
    check_resumed(n_inputs - 1, false);
    sweep_cuts(record_end[3], record_end[3]);
}

// --- headers of other versions, other options, damaged journals ----------------------------

static uint32_t put_record(uint8_t* out, uint8_t type, const uint8_t* payload, uint32_t len)
{
    out[0] = (uint8_t)(len & 0xFFU);
    out[1] = (uint8_t)((len >> 8) & 0xFFU);
    out[2] = (uint8_t)((len >> 16) & 0xFFU);
    out[3] = (uint8_t)((len >> 24) & 0xFFU);
    out[4] = type;
    memcpy(out + 5, payload, len);
    const uint32_t crc = (uint32_t)crc32(0UL, out, (uInt)(len + 5U));
    for (int i = 0; i < 4; ++i) {
        out[5 + len + (uint32_t)i] = (uint8_t)((crc >> (8 * i)) & 0xFFU);
    }
    return len + 9U;
}

static uint8_t header[SVA_LCM_JOURNAL_HEADER_BYTES + 16];
static uint8_t crafted[MEM_CAP];

// The header this build writes, taken from a fresh journal.
static void own_header(void)
{
    sva_lcm_journal_resume_t r;
    TEST_ASSERT_EQUAL_INT(SVA_LCM_JOURNAL_OK, resume_from(NULL, 0U, &r));
    TEST_ASSERT_TRUE(r.fresh);
    TEST_ASSERT_EQUAL_INT(SVA_LCM_JOURNAL_HEADER_BYTES + 9U, mem.size);
    memcpy(header, mem.data + 5, SVA_LCM_JOURNAL_HEADER_BYTES);
    TEST_ASSERT_EQUAL_MEMORY("SVAJ", header, 4);
}

static sva_lcm_journal_status_t resume_crafted(uint32_t header_len)
{
    const uint32_t n = put_record(crafted, SVA_LCM_RECORD_HEADER, header, header_len);
    sva_lcm_journal_resume_t r;
    const sva_lcm_journal_status_t st = resume_from(crafted, n, &r);
    TEST_ASSERT_EQUAL_INT(n, mem.size);  // a refused journal is left as it was
    SVA_TEST_ASSERT_EQUAL_BYTES(crafted, mem.data, n);
    return st;
}

static void set_u16(uint8_t* p, unsigned v)
{
    p[0] = (uint8_t)(v & 0xFFU);
    p[1] = (uint8_t)(v >> 8);
}

void test_other_versions_and_options_refused(void)
{
    opts = (options_t){SVA_ALGO_SVA, 0, false, SVA_LCM_TRACK_TOLERANCE_DEFAULT, 0};
    own_header();
    char ours[96];
    (void)snprintf(ours, sizeof ours, "this node is sva %d.%d.%d (journal format %d)",
                   SVA_VERSION_MAJOR, SVA_VERSION_MINOR, SVA_VERSION_PATCH, SVA_LCM_JOURNAL_FORMAT);
    TEST_ASSERT_EQUAL_INT(SVA_LCM_JOURNAL_OK, resume_crafted(SVA_LCM_JOURNAL_HEADER_BYTES));

    // another sva version: refused, naming both
    set_u16(header + 8, SVA_VERSION_MINOR + 1U);
    TEST_ASSERT_EQUAL_INT(SVA_LCM_JOURNAL_ERR_VERSION,
                          resume_crafted(SVA_LCM_JOURNAL_HEADER_BYTES));
    char theirs[96];
    (void)snprintf(
        theirs, sizeof theirs, "the journal was written by sva %d.%d.%d (journal format %d); ",
        SVA_VERSION_MAJOR, SVA_VERSION_MINOR + 1, SVA_VERSION_PATCH, SVA_LCM_JOURNAL_FORMAT);
    TEST_ASSERT_NOT_NULL(strstr(journal.message, theirs));
    TEST_ASSERT_NOT_NULL(strstr(journal.message, ours));
    set_u16(header + 8, SVA_VERSION_MINOR);
    // another journal format, with a longer header: named too
    set_u16(header + 4, SVA_LCM_JOURNAL_FORMAT + 1U);
    TEST_ASSERT_EQUAL_INT(SVA_LCM_JOURNAL_ERR_VERSION,
                          resume_crafted(SVA_LCM_JOURNAL_HEADER_BYTES + 10U));
    char other[32];
    (void)snprintf(other, sizeof other, "(journal format %d)", SVA_LCM_JOURNAL_FORMAT + 1);
    TEST_ASSERT_NOT_NULL(strstr(journal.message, other));
    TEST_ASSERT_NOT_NULL(strstr(journal.message, ours));
    set_u16(header + 4, SVA_LCM_JOURNAL_FORMAT);
    // the same version with other wire types (event_t's fingerprint)
    header[12 + 16] ^= 1U;
    TEST_ASSERT_EQUAL_INT(SVA_LCM_JOURNAL_ERR_VERSION,
                          resume_crafted(SVA_LCM_JOURNAL_HEADER_BYTES));
    TEST_ASSERT_NOT_NULL(strstr(journal.message, "other wire types (event_t fingerprint"));
    header[12 + 16] ^= 1U;
    // other node options: refused, both named as options
    opts.change_penalty = 5;
    TEST_ASSERT_EQUAL_INT(SVA_LCM_JOURNAL_ERR_OPTIONS,
                          resume_crafted(SVA_LCM_JOURNAL_HEADER_BYTES));
    TEST_ASSERT_EQUAL_STRING(
        "the journal was written by a node run with --algo sva --change-penalty 0 "
        "--track-tolerance 2; this node runs with --algo sva --change-penalty 5 "
        "--track-tolerance 2",
        journal.message);
    opts.change_penalty = 0;
    opts.algorithm = SVA_ALGO_FLOW;
    opts.fleet_reports = true;
    TEST_ASSERT_EQUAL_INT(SVA_LCM_JOURNAL_ERR_OPTIONS,
                          resume_crafted(SVA_LCM_JOURNAL_HEADER_BYTES));
    TEST_ASSERT_NOT_NULL(strstr(journal.message,
                                "this node runs with --algo flow --change-penalty 0 "
                                "--track-tolerance 2 --fleet-reports"));
    opts = (options_t){SVA_ALGO_SVA, 0, false, SVA_LCM_TRACK_TOLERANCE_DEFAULT, 0};
    opts.takeoff_ticks = 4;
    TEST_ASSERT_EQUAL_INT(SVA_LCM_JOURNAL_ERR_OPTIONS,
                          resume_crafted(SVA_LCM_JOURNAL_HEADER_BYTES));
    TEST_ASSERT_EQUAL_STRING(
        "the journal was written by a node run with --algo sva --change-penalty 0 "
        "--track-tolerance 2; this node runs with --algo sva --change-penalty 0 "
        "--track-tolerance 2 --takeoff-ticks 4",
        journal.message);
    opts.takeoff_ticks = 0;
    // not a journal; a header of the wrong size; a first record that is no header
    memcpy(header, "SVAX", 4);
    TEST_ASSERT_EQUAL_INT(SVA_LCM_JOURNAL_ERR_FORMAT, resume_crafted(SVA_LCM_JOURNAL_HEADER_BYTES));
    TEST_ASSERT_NOT_NULL(strstr(journal.message, "not an sva_node journal"));
    memcpy(header, "SVAJ", 4);
    TEST_ASSERT_EQUAL_INT(SVA_LCM_JOURNAL_ERR_FORMAT,
                          resume_crafted(SVA_LCM_JOURNAL_HEADER_BYTES - 1U));
    sva_lcm_journal_resume_t r;
    uint32_t n = put_record(crafted, SVA_LCM_RECORD_BASE, header, 8U);
    TEST_ASSERT_EQUAL_INT(SVA_LCM_JOURNAL_ERR_FORMAT, resume_from(crafted, n, &r));
    TEST_ASSERT_NOT_NULL(strstr(journal.message, "the first record is of type 2"));
    // with reset, any of them is discarded and a new journal started
    n = put_record(crafted, SVA_LCM_RECORD_HEADER, header, 20U);
    memset(&mem, 0, sizeof mem);
    memcpy(mem.data, crafted, n);
    mem.size = n;
    mem.fail_append_after = -1;
    sva_lcm_storage_t s;
    mem_storage(&mem, &s);
    node_setup(&node, &answers);
    TEST_ASSERT_EQUAL_INT(SVA_LCM_JOURNAL_OK, sva_lcm_journal_init(&journal, &s, &node));
    TEST_ASSERT_EQUAL_INT(SVA_LCM_JOURNAL_OK, sva_lcm_journal_resume(&journal, true, &r));
    TEST_ASSERT_TRUE(r.fresh && r.discarded);
    TEST_ASSERT_EQUAL_INT(SVA_LCM_JOURNAL_HEADER_BYTES + 9U, mem.size);

    // records with a good CRC that this node does not take: an unknown type, an input of
    // the wrong size, an event the live mission refuses (in the past)
    n = put_record(crafted, SVA_LCM_RECORD_HEADER, header, SVA_LCM_JOURNAL_HEADER_BYTES);
    uint32_t m = n + put_record(crafted + n, 9, header, 4U);
    TEST_ASSERT_EQUAL_INT(SVA_LCM_JOURNAL_ERR_FORMAT, resume_from(crafted, m, &r));
    TEST_ASSERT_NOT_NULL(strstr(journal.message, "record at byte 67: type 9 (unknown) of 4 bytes"));
    m = n + put_record(crafted + n, SVA_LCM_RECORD_EVENT, header, 20U);
    TEST_ASSERT_EQUAL_INT(SVA_LCM_JOURNAL_ERR_FORMAT, resume_from(crafted, m, &r));
    opts = (options_t){SVA_ALGO_SVA, 2, false, SVA_LCM_TRACK_TOLERANCE_DEFAULT, 0};
    sequence_one_mission();
    check_reference_one_mission();
    memcpy(crafted, ref_mem.data, ref_mem.size);
    m = ref_mem.size + put_record(crafted + ref_mem.size, SVA_LCM_RECORD_EVENT, inputs[4].bytes,
                                  SVA_LCM_EVENT_BYTES);
    TEST_ASSERT_EQUAL_INT(SVA_LCM_JOURNAL_ERR_REPLAY, resume_from(crafted, m, &r));
    char want[96];
    (void)snprintf(want, sizeof want, "record at byte %lu (event): the node did not take it again",
                   (unsigned long)ref_mem.size);
    TEST_ASSERT_NOT_NULL(strstr(journal.message, want));
    TEST_ASSERT_EQUAL_INT(m, mem.size);
}

// A storage that fails halts the node: the input it could not keep is not answered,
// nothing after it is taken, a half-written record is cut back; the journal resumes
// the state before that input, and the input sent again gets the reference's answer.
void test_failing_storage_halts(void)
{
    opts = (options_t){SVA_ALGO_SVA, 2, false, SVA_LCM_TRACK_TOLERANCE_DEFAULT, 0};
    sequence_one_mission();
    check_reference_one_mission();
    const int k = 6;  // the fuel event
    memset(&mem, 0, sizeof mem);
    mem.fail_append_after = -1;
    sva_lcm_storage_t s;
    mem_storage(&mem, &s);
    node_setup(&node, &answers);
    TEST_ASSERT_EQUAL_INT(SVA_LCM_JOURNAL_OK, sva_lcm_journal_init(&journal, &s, &node));
    sva_lcm_journal_resume_t r;
    TEST_ASSERT_EQUAL_INT(SVA_LCM_JOURNAL_OK, sva_lcm_journal_resume(&journal, false, &r));
    for (int i = 0; i < k; ++i) {
        TEST_ASSERT_EQUAL_INT(ref_verdicts[i], feed(&node, &inputs[i], inputs[i].size));
    }
    const uint32_t before = mem.size;
    mem.fail_append_after = 17;
    memset(&answers, 0, sizeof answers);
    TEST_ASSERT_EQUAL_INT(SVA_LCM_HALTED, feed(&node, &inputs[k], inputs[k].size));
    TEST_ASSERT_EQUAL_INT(0, answers.count);
    TEST_ASSERT_TRUE(node.halted);
    TEST_ASSERT_NOT_NULL(strstr(journal.message, "storage append failed"));
    TEST_ASSERT_EQUAL_INT(before, mem.size);
    TEST_ASSERT_EQUAL_INT(SVA_LCM_HALTED, feed(&node, &inputs[k + 1], inputs[k + 1].size));
    TEST_ASSERT_EQUAL_INT(0, answers.count);
    // restart
    static uint8_t kept[MEM_CAP];
    memcpy(kept, mem.data, mem.size);
    TEST_ASSERT_EQUAL_INT(SVA_LCM_JOURNAL_OK, resume_from(kept, before, &r));
    TEST_ASSERT_FALSE(r.cut);
    check_resumed(k - 1, true);

    // a compaction (a new mission) that fails halts too, and leaves the old journal
    TEST_ASSERT_EQUAL_INT(SVA_LCM_JOURNAL_OK, resume_from(kept, before, &r));
    mem.fail_replace = true;
    memset(&answers, 0, sizeof answers);
    make_fleet_and_mission(8);
    add_mission();
    TEST_ASSERT_EQUAL_INT(SVA_LCM_HALTED,
                          feed(&node, &inputs[n_inputs - 1], SVA_LCM_MISSION_BYTES));
    TEST_ASSERT_EQUAL_INT(0, answers.count);
    TEST_ASSERT_NOT_NULL(strstr(journal.message, "storage replace failed"));
    TEST_ASSERT_EQUAL_INT(before, mem.size);
    SVA_TEST_ASSERT_EQUAL_BYTES(kept, mem.data, before);
}

// Random damage (seeded, printed; SVA_JOURNAL_SEED=N replays one): a cut anywhere, then
// garbage appended, or bytes overwritten. The journal resumes with the records before the
// first damaged one (found by the test's own reader) or refuses a damaged header.
static uint32_t good_records(const uint8_t* j, uint32_t size)
{
    uint32_t off = 0;
    uint32_t c = 0;
    while (size - off >= 9U) {
        const uint32_t len = le32(j + off);
        if ((len > (uint32_t)SVA_LCM_JOURNAL_MAX_PAYLOAD) || (len + 9U > size - off) ||
            ((uint32_t)crc32(0UL, j + off, (uInt)(len + 5U)) != le32(j + off + 5U + len))) {
            break;
        }
        off += len + 9U;
        c++;
    }
    return c;
}

void test_random_damage(void)
{
    opts = (options_t){SVA_ALGO_SVA, 2, false, SVA_LCM_TRACK_TOLERANCE_DEFAULT, 0};
    sequence_one_mission();
    check_reference_one_mission();
    const uint32_t size = ref_mem.size;
    memcpy(saved, ref_mem.data, size);
    const char* env = getenv("SVA_JOURNAL_SEED");
    const unsigned long first = (env != NULL) ? strtoul(env, NULL, 10) : 1UL;
    const unsigned long count = (env != NULL) ? 1UL : 1500UL;
    static uint8_t damaged[MEM_CAP];
    for (unsigned long seed = first; seed < first + count; ++seed) {
        srand((unsigned)seed);
        uint32_t n = size;
        memcpy(damaged, saved, size);
        if ((rand() % 2) == 0) {
            n = (uint32_t)rand() % (size + 1U);  // cut, then garbage
            const uint32_t extra = (uint32_t)rand() % 200U;
            for (uint32_t i = 0; i < extra; ++i) {
                damaged[n + i] = (uint8_t)rand();
            }
            n += extra;
        } else {
            const int writes = 1 + (rand() % 4);  // overwritten bytes
            for (int w = 0; w < writes; ++w) {
                damaged[(uint32_t)rand() % size] = (uint8_t)rand();
            }
        }
        const uint32_t c = good_records(damaged, n);
        sva_lcm_journal_resume_t r;
        const sva_lcm_journal_status_t st = resume_from(damaged, n, &r);
        if ((n == 0U) || (c == 0U)) {
            if ((n != 0U) && (st != SVA_LCM_JOURNAL_ERR_FORMAT)) {
                SVA_TEST_FAIL("seed %lu: a damaged header gave status %d", seed, (int)st);
            }
            continue;
        }
        if (st != SVA_LCM_JOURNAL_OK) {
            SVA_TEST_FAIL("seed %lu (SVA_JOURNAL_SEED=%lu replays it): status %d: %s", seed, seed,
                          (int)st, journal.message);
        }
        uint32_t kept = 0;
        for (uint32_t k = 0; k < c; ++k) {
            kept += le32(damaged + kept) + 9U;
        }
        TEST_ASSERT_EQUAL_INT(kept, mem.size);
        SVA_TEST_ASSERT_EQUAL_BYTES(saved, mem.data, kept);
        const int q = (c <= 2U) ? -1 : input_with_records(c);
        TEST_ASSERT_TRUE(q >= -1);
        check_resumed(q, false);
    }
    printf("random damage: seeds %lu..%lu\n", first, first + count - 1UL);
}

// --- the POSIX file storage -------------------------------------------------------------

static char dir[64];

static void write_file(const char* path, const uint8_t* data, uint32_t size)
{
    FILE* f = fopen(path, "wb");
    TEST_ASSERT_NOT_NULL(f);
    TEST_ASSERT_EQUAL_INT(size, fwrite(data, 1, size, f));
    TEST_ASSERT_EQUAL_INT(0, fclose(f));
}

static long file_size(const char* path)
{
    struct stat st;
    return (stat(path, &st) == 0) ? (long)st.st_size : -1L;
}

static sva_lcm_journal_file_t file_ctx;

static sva_lcm_journal_status_t resume_file(sva_lcm_journal_resume_t* r)
{
    sva_lcm_storage_t s;
    TEST_ASSERT_EQUAL_INT(SVA_LCM_JOURNAL_OK, sva_lcm_journal_file_init(&file_ctx, dir, &s));
    node_setup(&node, &answers);
    TEST_ASSERT_EQUAL_INT(SVA_LCM_JOURNAL_OK, sva_lcm_journal_init(&journal, &s, &node));
    return sva_lcm_journal_resume(&journal, false, r);
}

// The same journal through files: the same bytes as in memory; a torn file cut at every
// offset of its last records (truncated on disk, the state of the last complete record);
// a leftover temporary file removed; a second process refused the folder while one
// holds it.
void test_file_storage(void)
{
    opts = (options_t){SVA_ALGO_SVA, 2, false, SVA_LCM_TRACK_TOLERANCE_DEFAULT, 0};
    sequence_one_mission();
    check_reference_one_mission();
    (void)snprintf(dir, sizeof dir, "/tmp/sva-journal-XXXXXX");
    TEST_ASSERT_NOT_NULL(mkdtemp(dir));
    char path[128];
    char temp[128];
    (void)snprintf(path, sizeof path, "%s/%s", dir, SVA_LCM_JOURNAL_FILE_NAME);
    (void)snprintf(temp, sizeof temp, "%s/%s", dir, SVA_LCM_JOURNAL_TEMP_NAME);

    sva_lcm_journal_resume_t r;
    TEST_ASSERT_EQUAL_INT(SVA_LCM_JOURNAL_OK, resume_file(&r));
    TEST_ASSERT_TRUE(r.fresh);
    for (int i = 0; i < n_inputs; ++i) {
        memset(&answers, 0, sizeof answers);
        TEST_ASSERT_EQUAL_INT(ref_verdicts[i], feed(&node, &inputs[i], inputs[i].size));
        TEST_ASSERT_EQUAL_INT(ref_answers[i].crc, answers.crc);
    }
    TEST_ASSERT_EQUAL_INT((long)ref_mem.size, file_size(path));
    TEST_ASSERT_EQUAL_INT(-1L, file_size(temp));  // the compaction's temporary file was renamed

    // a second process may not open the folder while this one holds it
    const pid_t pid = fork();
    TEST_ASSERT_TRUE(pid >= 0);
    if (pid == 0) {
        sva_lcm_journal_file_t other;
        sva_lcm_storage_t s;
        uint32_t size = 0;
        if ((sva_lcm_journal_file_init(&other, dir, &s) != SVA_LCM_JOURNAL_OK) ||
            (s.open(s.ctx, &size) == 0)) {
            _exit(1);
        }
        _exit((strstr(s.error(s.ctx), "is in use") != NULL) ? 0 : 2);
    }
    int status = -1;
    TEST_ASSERT_EQUAL_INT(pid, waitpid(pid, &status, 0));
    TEST_ASSERT_TRUE(WIFEXITED(status) && (WEXITSTATUS(status) == 0));
    sva_lcm_journal_close(&journal);

    FILE* f = fopen(path, "rb");
    TEST_ASSERT_NOT_NULL(f);
    static uint8_t whole[MEM_CAP];
    TEST_ASSERT_EQUAL_INT(ref_mem.size, fread(whole, 1, sizeof whole, f));
    TEST_ASSERT_EQUAL_INT(0, fclose(f));
    SVA_TEST_ASSERT_EQUAL_BYTES(ref_mem.data, whole, ref_mem.size);
    parse_records(whole, ref_mem.size);
    const uint32_t from = record_end[n_records - 4];
    for (uint32_t o = from; o <= ref_mem.size; ++o) {
        write_file(path, whole, o);
        write_file(temp, whole, 7U);  // a compaction a crash interrupted
        TEST_ASSERT_EQUAL_INT(SVA_LCM_JOURNAL_OK, resume_file(&r));
        uint32_t c = 0;
        while ((c < (uint32_t)n_records) && (record_end[c] <= o)) {
            c++;
        }
        TEST_ASSERT_EQUAL_INT((long)record_end[c - 1], file_size(path));
        TEST_ASSERT_EQUAL_INT(-1L, file_size(temp));
        TEST_ASSERT_EQUAL_INT(o != record_end[c - 1], r.cut);
        assert_state(&node, &snaps[input_with_records(c)]);
        sva_lcm_journal_close(&journal);
    }
    (void)unlink(path);
    char lock[128];
    (void)snprintf(lock, sizeof lock, "%s/%s", dir, SVA_LCM_JOURNAL_LOCK_NAME);
    (void)unlink(lock);
    TEST_ASSERT_EQUAL_INT(0, rmdir(dir));
}
