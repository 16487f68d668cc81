// test_can_journal.c -- sva_can_node's crash-safe live mission (port/can/node/
// can_journal.c over the shared record layer port/journal): a scripted live mission
// (clock frames, a loss, a return with the fuel last heard, a position off the track,
// fuel readings, refused frames, replans) is journaled into a memory storage; the
// journal cut at every byte offset and with every bit of its last records flipped
// resumes exactly the state after the last whole record (sva_can_live_t's state byte
// for byte) or is refused, never applying a damaged record; a resumed live mission fed
// the rest of the inputs equals the uninterrupted one and regrows the same journal;
// another version, other options, another mission and not-a-journal are refused with
// their one-line messages and left as they were; a failing storage halts the live
// mission; the POSIX file storage holds the same bytes and cuts a torn file on disk.
#define _POSIX_C_SOURCE 200809L

#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "sva_unity.h"

#include "can_journal.h"
#include "can_live.h"
#include "sva/sva_live.h"
#include "sva/sva_can.h"
#include "sva/sva_journal.h"

// --- a memory storage that can fail ---------------------------------------------------------

#define MEM_MAX 65536u

typedef struct {
    uint8_t bytes[MEM_MAX];
    uint32_t size;
    int fail_append;  // > 0: the n-th append from now fails after writing half its bytes
    int fail_sync;    // > 0: the n-th sync from now fails
    bool fail_replace;
} mem_t;

static int mem_open(void* ctx, uint32_t* size)
{
    *size = ((mem_t*)ctx)->size;
    return 0;
}
static int mem_read(void* ctx, uint32_t off, void* buf, uint32_t len)
{
    mem_t* m = (mem_t*)ctx;
    TEST_ASSERT_TRUE(off + len <= m->size);  // the journal never reads past its length
    memcpy(buf, m->bytes + off, len);
    return 0;
}
static int mem_append(void* ctx, const void* data, uint32_t len)
{
    mem_t* m = (mem_t*)ctx;
    if ((m->fail_append > 0) && (--m->fail_append == 0)) {
        memcpy(m->bytes + m->size, data, len / 2u);
        m->size += len / 2u;
        return -1;
    }
    TEST_ASSERT_TRUE(m->size + len <= MEM_MAX);
    memcpy(m->bytes + m->size, data, len);
    m->size += len;
    return 0;
}
static int mem_sync(void* ctx)
{
    mem_t* m = (mem_t*)ctx;
    return ((m->fail_sync > 0) && (--m->fail_sync == 0)) ? -1 : 0;
}
static int mem_truncate(void* ctx, uint32_t size)
{
    mem_t* m = (mem_t*)ctx;
    if (size < m->size) {
        m->size = size;
    }
    return 0;
}
static int mem_replace(void* ctx, const void* data, uint32_t len)
{
    mem_t* m = (mem_t*)ctx;
    if (m->fail_replace) {
        return -1;
    }
    memcpy(m->bytes, data, len);
    m->size = len;
    return 0;
}
static const char* mem_error(void* ctx)
{
    (void)ctx;
    return "planted failure";
}

static sva_journal_storage_t mem_storage(mem_t* m)
{
    sva_journal_storage_t s;
    memset(&s, 0, sizeof s);
    s.ctx = m;
    s.open = mem_open;
    s.read = mem_read;
    s.append = mem_append;
    s.sync = mem_sync;
    s.truncate = mem_truncate;
    s.replace = mem_replace;
    s.error = mem_error;
    return s;
}

// --- the scripted live mission ---------------------------------------------------------------

static sva_mission_t mission;

// UAVs 1, 2 and 3 at the depot; T1 (5, 0) and T2 (0, 5) in [10, 20]; T3 (3, 3) in
// [40, 50]; T4 (-4, 2) in [60, 70].
static void make_mission(void)
{
    sva_mission_init(&mission);
    mission.uav_count = 3U;
    mission.uavs[0] = (sva_uav_t){.id = 1, .x = 0, .y = 0, .fuel = 100};
    mission.uavs[1] = (sva_uav_t){.id = 2, .x = 0, .y = 0, .fuel = 100};
    mission.uavs[2] = (sva_uav_t){.id = 3, .x = 0, .y = 0, .fuel = 100};
    mission.target_count = 4U;
    mission.targets[0] = (sva_target_t){1, 5, 0, 10, 20, 1};
    mission.targets[1] = (sva_target_t){2, 0, 5, 10, 20, 1};
    mission.targets[2] = (sva_target_t){3, 3, 3, 40, 50, 1};
    mission.targets[3] = (sva_target_t){4, -4, 2, 60, 70, 1};
}

typedef struct {
    char kind;   // 'c' clock, 's' status, 'f' fuel, 'p' poll
    uint32_t a;  // tick, or uav
    uint32_t b;  // state, fuel
    int16_t x;
    int16_t y;
    uint32_t ms;
} step_t;

#define SETTLE 200u

static const step_t steps[] = {
    {'c', 12, 0, 0, 0, 1000},                           // visits under way
    {'s', 1, SVA_CAN_VEHICLE_BUSY, 5, 0, 1010},         // agrees: nothing
    {'f', 1, 95, 0, 0, 1020},                           // agrees: nothing
    {'p', 0, 0, 0, 0, 1100},                            // not settled: nothing
    {'p', 0, 0, 0, 0, 1300},                            // replan (plan in force kept)
    {'s', 2, SVA_CAN_VEHICLE_UNAVAILABLE, 0, 5, 1400},  // uav_lost
    {'p', 0, 0, 0, 0, 1700},                            // replan: plan 2
    {'f', 2, 60, 0, 0, 1800},                           // lost UAV: fuel kept for its return
    {'s', 9, SVA_CAN_VEHICLE_AVAILABLE, 1, 1, 1810},    // unknown UAV: refused
    {'c', 5, 0, 0, 0, 1820},                            // clock back: refused
    {'s', 1, SVA_CAN_VEHICLE_BUSY, 5, 4, 1900},         // off its track: position
    {'p', 0, 0, 0, 0, 2200},
    {'s', 2, SVA_CAN_VEHICLE_AVAILABLE, 1, 1, 2300},  // back with fuel 60
    {'f', 3, 40, 0, 0, 2310},                         // fuel event
    {'p', 0, 0, 0, 0, 2600},
    {'c', 41, 0, 0, 0, 2700},
    {'p', 0, 0, 0, 0, 3000},
    {'s', 3, SVA_CAN_VEHICLE_UNAVAILABLE, 0, 0, 3100},
    {'c', 45, 0, 0, 0, 3110},
    {'p', 0, 0, 0, 0, 3400},
    {'c', 62, 0, 0, 0, 3500},
    {'p', 0, 0, 0, 0, 3800},
};
#define STEPS ((int)(sizeof steps / sizeof steps[0]))

static uint8_t counter;

// One step; returns what the live mission returned.
static int run_step(sva_can_live_t* live, const step_t* s)
{
    sva_can_msg_t m;
    if (s->kind == 'p') {
        return sva_can_live_poll(live, s->ms, SETTLE);
    }
    memset(&m, 0, sizeof m);
    m.counter = counter;
    counter = (uint8_t)((counter + 1u) & 15u);
    if (s->kind == 'c') {
        m.kind = SVA_CAN_MSG_MISSION_CLOCK;
        m.u.clock.tick = s->a;
    } else if (s->kind == 's') {
        m.kind = SVA_CAN_MSG_VEHICLE_STATUS;
        m.u.vehicle.uav_id = (uint8_t)s->a;
        m.u.vehicle.state = (uint8_t)s->b;
        m.u.vehicle.x = s->x;
        m.u.vehicle.y = s->y;
    } else {
        m.kind = SVA_CAN_MSG_VEHICLE_FUEL;
        m.u.fuel.uav_id = (uint8_t)s->a;
        m.u.fuel.fuel = s->b;
    }
    return sva_can_live_on_msg(live, &m, s->ms);
}

// The state a resume must restore: everything of sva_can_live_t but the planner's working
// memory, the last result's pointers, the log, stats (this process's counts) and the hook.
typedef struct {
    sva_live_t live;
    sva_plan_t plan;
    sva_can_plan_t wire;
    sva_can_plan_t sent;
    int32_t fuel_heard[SVA_MAX_UAVS];
    uint32_t pending;
    uint32_t last_event_ms;
    uint16_t plan_id;
    uint8_t covered;
    bool halted;
} snap_t;

static void take(snap_t* s, const sva_can_live_t* l)
{
    memset(s, 0, sizeof *s);
    memcpy(&s->live, &l->live, sizeof s->live);
    memcpy(&s->plan, &l->plan, sizeof s->plan);
    memcpy(&s->wire, &l->wire, sizeof s->wire);
    memcpy(&s->sent, &l->sent, sizeof s->sent);
    memcpy(s->fuel_heard, l->fuel_heard, sizeof s->fuel_heard);
    s->pending = l->pending;
    s->last_event_ms = l->last_event_ms;
    s->plan_id = l->plan_id;
    s->covered = l->covered;
    s->halted = l->halted;
}

static sva_can_live_t live_a;  // uninterrupted
static sva_can_live_t live_b;  // resumed
static sva_can_journal_t journal_a;
static sva_can_journal_t journal_b;
static mem_t mem_a;
static mem_t mem_b;
static snap_t snaps[STEPS + 1];     // the state at each journal length in bounds[]
static uint32_t bounds[STEPS + 1];  // journal lengths after the head and after each record
static int nbounds;
static int wrote[STEPS + 1];  // the step that wrote each record
static snap_t got;
static uint32_t full_size;

static void start(sva_can_live_t* l, sva_algorithm_t algo, int32_t tolerance)
{
    char err[200];
    memset(l, 0, sizeof *l);
    l->track_tolerance_cells = tolerance;
    TEST_ASSERT_EQUAL_INT_MESSAGE(0, sva_can_live_start(l, &mission, algo, err, sizeof err), err);
}

// The uninterrupted run: the journal in mem_a, a snapshot at every record boundary.
static void run_uninterrupted(void)
{
    sva_can_journal_resume_t r;
    sva_journal_storage_t s = mem_storage(&mem_a);
    memset(&mem_a, 0, sizeof mem_a);
    counter = 0u;
    start(&live_a, SVA_ALGO_SVA, 2);
    TEST_ASSERT_EQUAL_INT(SVA_CAN_JOURNAL_OK, sva_can_journal_init(&journal_a, &s, &live_a));
    TEST_ASSERT_EQUAL_INT(SVA_CAN_JOURNAL_OK,
                          sva_can_journal_resume(&journal_a, &mission, false, &r));
    TEST_ASSERT_TRUE(r.fresh);
    nbounds = 0;
    bounds[nbounds] = mem_a.size;
    take(&snaps[nbounds++], &live_a);
    for (int i = 0; i < STEPS; ++i) {
        const uint32_t before = mem_a.size;
        (void)run_step(&live_a, &steps[i]);
        if (mem_a.size != before) {
            wrote[nbounds] = i;
            bounds[nbounds] = mem_a.size;
            take(&snaps[nbounds++], &live_a);
        }
    }
    full_size = mem_a.size;
    sva_can_journal_close(&journal_a);
}

// Resumes live_b from `len` bytes of `bytes`; returns the status.
static sva_can_journal_status_t resume_b(const uint8_t* bytes, uint32_t len,
                                         sva_can_journal_resume_t* r, sva_algorithm_t algo,
                                         int32_t tolerance)
{
    sva_journal_storage_t s = mem_storage(&mem_b);
    memset(&mem_b, 0, sizeof mem_b);
    memcpy(mem_b.bytes, bytes, len);
    mem_b.size = len;
    start(&live_b, algo, tolerance);
    TEST_ASSERT_EQUAL_INT(SVA_CAN_JOURNAL_OK, sva_can_journal_init(&journal_b, &s, &live_b));
    return sva_can_journal_resume(&journal_b, &mission, false, r);
}

static void assert_state(int k, const char* what, uint32_t at)
{
    take(&got, &live_b);
    if (memcmp(&got, &snaps[k], sizeof got) != 0) {
        SVA_TEST_FAIL("%s %lu: the resumed state is not the one after record %d", what,
                      (unsigned long)at, k);
    }
}

void setUp(void)
{
    make_mission();
    run_uninterrupted();
}

void tearDown(void)
{
}

void test_scenario_journals_what_changed(void)
{
    // The head, then the steps that changed the live mission: the clock, UAV 1's fuel
    // reading (kept for a return even when it agrees with the model), the replan, the
    // loss, its replan, the lost UAV's fuel, the position, ... Frames that agree, a poll
    // before the settle time, the unknown UAV and the clock going back write nothing.
    static const int want[] = {0, 2, 4, 5, 6, 7, 10, 11, 12, 13, 14, 15, 16, 17, 18, 19, 20, 21};
    TEST_ASSERT_EQUAL_INT(19, nbounds);
    for (int k = 1; k < nbounds; ++k) {
        TEST_ASSERT_EQUAL_INT(want[k - 1], wrote[k]);
    }
    TEST_ASSERT_EQUAL_UINT32(32u + 9u + 32u + 60u + 96u, bounds[0]);
    TEST_ASSERT_TRUE(live_a.plan_id >= 3u);
    TEST_ASSERT_TRUE(live_a.live.revision > 3u);
    TEST_ASSERT_EQUAL_INT(62, live_a.live.now_ticks);
    TEST_ASSERT_EQUAL_INT(2, live_a.stats.events_refused);
}

// Power loss at every byte offset: the state after the last whole record, or refused
// inside the head, or a new journal when empty; the file cut where the damage starts.
void test_cut_at_every_offset(void)
{
    for (uint32_t c = 0; c <= full_size; ++c) {
        sva_can_journal_resume_t r;
        const sva_can_journal_status_t st = resume_b(mem_a.bytes, c, &r, SVA_ALGO_SVA, 2);
        if (c == 0u) {
            TEST_ASSERT_EQUAL_INT(SVA_CAN_JOURNAL_OK, st);
            TEST_ASSERT_TRUE(r.fresh);
            TEST_ASSERT_EQUAL_UINT32(bounds[0], mem_b.size);
            continue;
        }
        if (c < bounds[0]) {
            if (st != SVA_CAN_JOURNAL_ERR_FORMAT) {
                SVA_TEST_FAIL("cut at %lu inside the head: status %d", (unsigned long)c, (int)st);
            }
            TEST_ASSERT_EQUAL_UINT32(c, mem_b.size);  // left as it was
            continue;
        }
        int k = 0;
        while ((k + 1 < nbounds) && (bounds[k + 1] <= c)) {
            ++k;
        }
        if (st != SVA_CAN_JOURNAL_OK) {
            SVA_TEST_FAIL("cut at %lu: status %d: %s", (unsigned long)c, (int)st,
                          journal_b.message);
        }
        TEST_ASSERT_EQUAL_INT(c != bounds[k], r.cut);
        TEST_ASSERT_EQUAL_UINT32(bounds[k], mem_b.size);
        if (r.cut) {
            TEST_ASSERT_EQUAL_UINT32(bounds[k], r.cut_offset);
            char want[64];
            (void)snprintf(want, sizeof want, "torn or corrupt record at byte %lu (",
                           (unsigned long)bounds[k]);
            TEST_ASSERT_TRUE(strncmp(journal_b.message, want, strlen(want)) == 0);
        }
        assert_state(k, "cut at", c);
        TEST_ASSERT_EQUAL_INT(0, (int)live_b.stats.events_applied);
        sva_can_journal_close(&journal_b);
    }
}

// From a cut at each boundary, the resumed live mission given the rest of the inputs
// ends in the uninterrupted state and regrows the same journal byte for byte.
void test_resumed_equals_uninterrupted(void)
{
    for (int k = 0; k < nbounds; ++k) {
        sva_can_journal_resume_t r;
        TEST_ASSERT_EQUAL_INT(SVA_CAN_JOURNAL_OK,
                              resume_b(mem_a.bytes, bounds[k], &r, SVA_ALGO_SVA, 2));
        // The steps after the one that wrote bounds[k]: replay the script, skipping steps
        // until the journal (replayed on a scratch live mission) reaches that length.
        static sva_can_live_t scratch;
        static mem_t mem_s;
        static sva_can_journal_t journal_s;
        sva_can_journal_resume_t rs;
        sva_journal_storage_t s = mem_storage(&mem_s);
        memset(&mem_s, 0, sizeof mem_s);
        counter = 0u;
        start(&scratch, SVA_ALGO_SVA, 2);
        TEST_ASSERT_EQUAL_INT(SVA_CAN_JOURNAL_OK, sva_can_journal_init(&journal_s, &s, &scratch));
        TEST_ASSERT_EQUAL_INT(SVA_CAN_JOURNAL_OK,
                              sva_can_journal_resume(&journal_s, &mission, false, &rs));
        int i = 0;
        while ((mem_s.size < bounds[k]) && (i < STEPS)) {
            (void)run_step(&scratch, &steps[i++]);
        }
        TEST_ASSERT_EQUAL_UINT32(bounds[k], mem_s.size);
        // Steps that journal nothing right after the boundary run on the resumed one too.
        for (; i < STEPS; ++i) {
            (void)run_step(&live_b, &steps[i]);
        }
        take(&got, &live_b);
        if (memcmp(&got, &snaps[nbounds - 1], sizeof got) != 0) {
            SVA_TEST_FAIL("resumed after record %d: the final state differs", k);
        }
        TEST_ASSERT_EQUAL_UINT32(full_size, mem_b.size);
        TEST_ASSERT_EQUAL_MEMORY(mem_a.bytes, mem_b.bytes, full_size);
        sva_can_journal_close(&journal_b);
        sva_can_journal_close(&journal_s);
    }
}

// Every bit of the last four records flipped, and every byte of the head: the state
// before the damaged record (cut there), or refused; never a damaged record applied.
void test_bit_flips(void)
{
    static uint8_t damaged[MEM_MAX];
    const uint32_t from = bounds[nbounds - 5];
    for (uint32_t at = 0; at < full_size; ++at) {
        const int bits = (at >= from) ? 8 : 1;
        for (int bit = 0; bit < bits; ++bit) {
            sva_can_journal_resume_t r;
            memcpy(damaged, mem_a.bytes, full_size);
            damaged[at] ^= (uint8_t)(1u << (unsigned)((at >= from) ? bit : (int)(at % 8u)));
            const sva_can_journal_status_t st = resume_b(damaged, full_size, &r, SVA_ALGO_SVA, 2);
            if (at < bounds[0]) {
                if (st == SVA_CAN_JOURNAL_OK) {
                    SVA_TEST_FAIL("a flip at byte %lu of the head was taken", (unsigned long)at);
                }
                TEST_ASSERT_EQUAL_MEMORY(damaged, mem_b.bytes, full_size);  // left as it was
                continue;
            }
            int k = 0;
            while ((k + 1 < nbounds) && (bounds[k + 1] <= at)) {
                ++k;
            }
            if (st != SVA_CAN_JOURNAL_OK) {
                SVA_TEST_FAIL("flip at %lu bit %d: status %d: %s", (unsigned long)at, bit, (int)st,
                              journal_b.message);
            }
            TEST_ASSERT_TRUE(r.cut);
            TEST_ASSERT_EQUAL_UINT32(bounds[k], r.cut_offset);
            TEST_ASSERT_EQUAL_UINT32(bounds[k], mem_b.size);
            assert_state(k, "flip at", at);
            sva_can_journal_close(&journal_b);
        }
    }
}

static void put_header_version(uint8_t* bytes, uint32_t at, uint32_t value)
{
    // The header record's payload starts at byte 5; its CRC follows the 23 bytes.
    sva_journal_put_u16(bytes + 5 + at, value);
    sva_journal_put_u32(bytes + 5 + SVA_CAN_JOURNAL_HEADER_BYTES,
                        sva_journal_crc(bytes, 5 + SVA_CAN_JOURNAL_HEADER_BYTES));
}

static void assert_refused(const uint8_t* bytes, sva_can_journal_status_t want, const char* message,
                           sva_algorithm_t algo, int32_t tolerance)
{
    sva_can_journal_resume_t r;
    const sva_can_journal_status_t st = resume_b(bytes, full_size, &r, algo, tolerance);
    TEST_ASSERT_EQUAL_INT(want, st);
    TEST_ASSERT_EQUAL_STRING(message, journal_b.message);
    TEST_ASSERT_EQUAL_UINT32(full_size, mem_b.size);
    TEST_ASSERT_EQUAL_MEMORY(bytes, mem_b.bytes, full_size);
    TEST_ASSERT_TRUE(strchr(journal_b.message, '\n') == NULL);
}

void test_other_version_options_mission_refused(void)
{
    static uint8_t other[MEM_MAX];
    char want[400];
    memcpy(other, mem_a.bytes, full_size);
    put_header_version(other, 10, SVA_VERSION_PATCH + 1);
    (void)snprintf(want, sizeof want,
                   "the journal was written by sva %d.%d.%d (journal format 1); this node is sva "
                   "%d.%d.%d (journal format 1)",
                   SVA_VERSION_MAJOR, SVA_VERSION_MINOR, SVA_VERSION_PATCH + 1, SVA_VERSION_MAJOR,
                   SVA_VERSION_MINOR, SVA_VERSION_PATCH);
    assert_refused(other, SVA_CAN_JOURNAL_ERR_VERSION, want, SVA_ALGO_SVA, 2);

    memcpy(other, mem_a.bytes, full_size);
    put_header_version(other, 4, 2);
    (void)snprintf(want, sizeof want,
                   "the journal was written by sva %d.%d.%d (journal format 2); this node is sva "
                   "%d.%d.%d (journal format 1)",
                   SVA_VERSION_MAJOR, SVA_VERSION_MINOR, SVA_VERSION_PATCH, SVA_VERSION_MAJOR,
                   SVA_VERSION_MINOR, SVA_VERSION_PATCH);
    assert_refused(other, SVA_CAN_JOURNAL_ERR_VERSION, want, SVA_ALGO_SVA, 2);

    memcpy(other, mem_a.bytes, full_size);
    put_header_version(other, 12, 1);  // CAN protocol 1
    (void)snprintf(want, sizeof want,
                   "the journal was written by sva %d.%d.%d (journal format 1, CAN protocol 1, "
                   "SVA_MAX_UAVS %d, SVA_MAX_TARGETS %d); this node is sva %d.%d.%d (journal "
                   "format 1, CAN protocol %d, SVA_MAX_UAVS %d, SVA_MAX_TARGETS %d)",
                   SVA_VERSION_MAJOR, SVA_VERSION_MINOR, SVA_VERSION_PATCH, SVA_MAX_UAVS,
                   SVA_MAX_TARGETS, SVA_VERSION_MAJOR, SVA_VERSION_MINOR, SVA_VERSION_PATCH,
                   SVA_CAN_PROTOCOL_VERSION, SVA_MAX_UAVS, SVA_MAX_TARGETS);
    assert_refused(other, SVA_CAN_JOURNAL_ERR_VERSION, want, SVA_ALGO_SVA, 2);

    assert_refused(mem_a.bytes, SVA_CAN_JOURNAL_ERR_OPTIONS,
                   "the journal was written by a node run with --algo sva --track-tolerance 2; "
                   "this node runs with --algo ga --track-tolerance 2",
                   SVA_ALGO_GA, 2);
    assert_refused(mem_a.bytes, SVA_CAN_JOURNAL_ERR_OPTIONS,
                   "the journal was written by a node run with --algo sva --track-tolerance 2; "
                   "this node runs with --algo sva --track-tolerance 5",
                   SVA_ALGO_SVA, 5);

    // Another mission: one target moved.
    mission.targets[3].x = -5;
    assert_refused(mem_a.bytes, SVA_CAN_JOURNAL_ERR_MISSION,
                   "the journal was written for another mission (3 UAVs, 4 targets); --mission "
                   "has 3 UAVs, 4 targets, or other values",
                   SVA_ALGO_SVA, 2);
    make_mission();

    // Not a journal of this node: sva_node's magic.
    memcpy(other, mem_a.bytes, full_size);
    other[5 + 3] = 'J';
    sva_journal_put_u32(other + 5 + SVA_CAN_JOURNAL_HEADER_BYTES,
                        sva_journal_crc(other, 5 + SVA_CAN_JOURNAL_HEADER_BYTES));
    assert_refused(other, SVA_CAN_JOURNAL_ERR_FORMAT,
                   "the header does not parse: not an sva_can_node journal (no \"SVAC\")",
                   SVA_ALGO_SVA, 2);

    // Reset discards it and starts afresh.
    sva_can_journal_resume_t r;
    sva_journal_storage_t s = mem_storage(&mem_b);
    memcpy(mem_b.bytes, other, full_size);
    mem_b.size = full_size;
    start(&live_b, SVA_ALGO_SVA, 2);
    TEST_ASSERT_EQUAL_INT(SVA_CAN_JOURNAL_OK, sva_can_journal_init(&journal_b, &s, &live_b));
    TEST_ASSERT_EQUAL_INT(SVA_CAN_JOURNAL_OK,
                          sva_can_journal_resume(&journal_b, &mission, true, &r));
    TEST_ASSERT_TRUE(r.fresh && r.discarded);
    TEST_ASSERT_EQUAL_UINT32(bounds[0], mem_b.size);
    TEST_ASSERT_EQUAL_MEMORY(mem_a.bytes, mem_b.bytes, bounds[0]);
}

// A record the live mission does not take again: refused, never silently skipped.
void test_record_not_taken_again_refused(void)
{
    static uint8_t other[MEM_MAX];
    sva_can_journal_resume_t r;
    // The first input record (the clock to 12) doubled: the second changes nothing.
    const uint32_t len = bounds[1] - bounds[0];
    memcpy(other, mem_a.bytes, bounds[1]);
    memcpy(other + bounds[1], mem_a.bytes + bounds[0], len);
    TEST_ASSERT_EQUAL_INT(SVA_CAN_JOURNAL_ERR_REPLAY,
                          resume_b(other, bounds[1] + len, &r, SVA_ALGO_SVA, 2));
    char want[160];
    (void)snprintf(want, sizeof want,
                   "record at byte %lu (msg): the live mission did not take it again",
                   (unsigned long)bounds[1]);
    TEST_ASSERT_TRUE(strncmp(journal_b.message, want, strlen(want)) == 0);
}

// A storage whose append or sync fails halts the live mission: the input is not
// answered, later ones are refused, a half-written record is cut back, and the journal
// resumes the state before that input.
void test_failing_storage_halts(void)
{
    for (int fail = 0; fail < 2; ++fail) {
        sva_can_journal_resume_t r;
        sva_journal_storage_t s = mem_storage(&mem_b);
        memset(&mem_b, 0, sizeof mem_b);
        counter = 0u;
        start(&live_b, SVA_ALGO_SVA, 2);
        TEST_ASSERT_EQUAL_INT(SVA_CAN_JOURNAL_OK, sva_can_journal_init(&journal_b, &s, &live_b));
        TEST_ASSERT_EQUAL_INT(SVA_CAN_JOURNAL_OK,
                              sva_can_journal_resume(&journal_b, &mission, false, &r));
        if (fail == 0) {
            mem_b.fail_append = 4;  // the loss frame (fourth record)
        } else {
            mem_b.fail_sync = 4;
        }
        int i = 0;
        int ret = 0;
        while ((i < STEPS) && (ret != SVA_CAN_LIVE_HALTED)) {
            ret = run_step(&live_b, &steps[i++]);
        }
        TEST_ASSERT_EQUAL_INT(SVA_CAN_LIVE_HALTED, ret);
        TEST_ASSERT_TRUE(live_b.halted);
        TEST_ASSERT_EQUAL_INT(6, i);  // the loss frame
        TEST_ASSERT_EQUAL_INT(SVA_CAN_LIVE_HALTED, run_step(&live_b, &steps[i]));
        TEST_ASSERT_EQUAL_INT(SVA_CAN_LIVE_HALTED, sva_can_live_poll(&live_b, 99999u, 0u));
        TEST_ASSERT_TRUE(strstr(journal_b.message,
                                (fail == 0) ? "storage append failed: planted failure"
                                            : "storage sync failed: planted failure") != NULL);
        if (fail == 0) {
            TEST_ASSERT_EQUAL_UINT32(bounds[3], mem_b.size);  // the half record cut back
        }
        // Power lost now: what was synced (the records before the loss) resumes the
        // state before the loss.
        static uint8_t kept[MEM_MAX];
        memcpy(kept, mem_b.bytes, bounds[3]);
        sva_can_journal_close(&journal_b);
        TEST_ASSERT_EQUAL_INT(SVA_CAN_JOURNAL_OK, resume_b(kept, bounds[3], &r, SVA_ALGO_SVA, 2));
        assert_state(3, "after a failed append/sync, length", mem_b.size);
    }
    // A replace that fails at the start: ERR_IO naming the call.
    sva_can_journal_resume_t r;
    sva_journal_storage_t s = mem_storage(&mem_b);
    memset(&mem_b, 0, sizeof mem_b);
    mem_b.fail_replace = true;
    start(&live_b, SVA_ALGO_SVA, 2);
    TEST_ASSERT_EQUAL_INT(SVA_CAN_JOURNAL_OK, sva_can_journal_init(&journal_b, &s, &live_b));
    TEST_ASSERT_EQUAL_INT(SVA_CAN_JOURNAL_ERR_IO,
                          sva_can_journal_resume(&journal_b, &mission, false, &r));
    TEST_ASSERT_EQUAL_STRING("storage replace failed: planted failure", journal_b.message);
}

// The POSIX storage: the same bytes as the memory one; a torn file cut on disk.
void test_posix_file_storage(void)
{
    static sva_journal_file_t file;
    char dir[] = "/tmp/sva_can_journal_XXXXXX";
    char path[300];
    sva_journal_storage_t s;
    sva_can_journal_resume_t r;
    TEST_ASSERT_NOT_NULL(mkdtemp(dir));
    TEST_ASSERT_TRUE(sva_journal_file_init(&file, dir, SVA_CAN_JOURNAL_FILE_NAME,
                                           SVA_CAN_JOURNAL_TEMP_NAME, SVA_CAN_JOURNAL_LOCK_NAME,
                                           &s));
    counter = 0u;
    start(&live_b, SVA_ALGO_SVA, 2);
    TEST_ASSERT_EQUAL_INT(SVA_CAN_JOURNAL_OK, sva_can_journal_init(&journal_b, &s, &live_b));
    TEST_ASSERT_EQUAL_INT(SVA_CAN_JOURNAL_OK,
                          sva_can_journal_resume(&journal_b, &mission, false, &r));
    for (int i = 0; i < STEPS; ++i) {
        (void)run_step(&live_b, &steps[i]);
    }
    sva_can_journal_close(&journal_b);
    (void)snprintf(path, sizeof path, "%s/%s", dir, SVA_CAN_JOURNAL_FILE_NAME);
    static uint8_t disk[MEM_MAX];
    FILE* f = fopen(path, "rb");
    TEST_ASSERT_NOT_NULL(f);
    const size_t n = fread(disk, 1, sizeof disk, f);
    (void)fclose(f);
    TEST_ASSERT_EQUAL_UINT32(full_size, (uint32_t)n);
    TEST_ASSERT_EQUAL_MEMORY(mem_a.bytes, disk, full_size);
    // Torn: half of a record appended; the resume cuts the file back on disk.
    f = fopen(path, "ab");
    TEST_ASSERT_NOT_NULL(f);
    TEST_ASSERT_EQUAL_INT(11, (int)fwrite(mem_a.bytes + bounds[1] - 12u, 1, 11, f));
    (void)fclose(f);
    start(&live_b, SVA_ALGO_SVA, 2);
    TEST_ASSERT_EQUAL_INT(SVA_CAN_JOURNAL_OK, sva_can_journal_init(&journal_b, &s, &live_b));
    TEST_ASSERT_EQUAL_INT(SVA_CAN_JOURNAL_OK,
                          sva_can_journal_resume(&journal_b, &mission, false, &r));
    TEST_ASSERT_TRUE(r.cut);
    TEST_ASSERT_EQUAL_UINT32(full_size, r.cut_offset);
    assert_state(nbounds - 1, "file of", full_size);
    sva_can_journal_close(&journal_b);
    f = fopen(path, "rb");
    TEST_ASSERT_NOT_NULL(f);
    TEST_ASSERT_EQUAL_UINT32(full_size, (uint32_t)fread(disk, 1, sizeof disk, f));
    (void)fclose(f);
    (void)unlink(path);
    (void)snprintf(path, sizeof path, "%s/%s", dir, SVA_CAN_JOURNAL_LOCK_NAME);
    (void)unlink(path);
    (void)rmdir(dir);
}
