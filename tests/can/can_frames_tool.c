// Test helper for the cantools cross-check (test_cantools.py) and the VM test.
//
//   can_frames_tool codec      reads lines from stdin, answers one line each:
//       encode NAME sig=value ...   -> "ID#HEX" (16 hex digits) or "error STATUS"
//       decode ID#HEX               -> "NAME sig=value ... crc=N" or "error STATUS"
//       check ID#HEX COUNTER        -> sva_can_frame_check()'s status name ("ok", ...)
//     NAME and signal names are those of port/can/sva.dbc.
//   can_frames_tool plan MISSION ALGORITHM PLAN_ID
//       plans the mission with the core and prints the wire plan as JSON, with
//       its CRC-32 and the transfer frames (as sent on the first attempt, counter from 0).
//   can_frames_tool live MISSION ALGORITHM TICK LOST_UAV
//       the CAN node's live mission (can_live.c): the plan it sends after a clock frame
//       of TICK and a loss of LOST_UAV, printed as for `plan`.
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "can_live.h"
#include "mission_file.h"
#include "sva/sva.h"
#include "sva/sva_can.h"
#include "sva/sva_can_mission_frame.h"
#include "sva/sva_can_transport.h"

typedef struct {
    char key[32];
    long long value;
} kv_t;

static kv_t kvs[32];
static int nkv;
static int missing;

static long long get(const char* key)
{
    int i;
    for (i = 0; i < nkv; ++i) {
        if (strcmp(kvs[i].key, key) == 0) {
            return kvs[i].value;
        }
    }
    fprintf(stderr, "missing signal %s\n", key);
    missing = 1;
    return 0;
}

static const char* const names[SVA_CAN_MSG_COUNT_] = {"",
                                                      "SVA_HEARTBEAT",
                                                      "SVA_PLAN_BEGIN",
                                                      "SVA_PLAN_ITEM",
                                                      "SVA_PLAN_ITEM_TIME",
                                                      "SVA_PLAN_COMMIT",
                                                      "SVA_PLAN_ABORT",
                                                      "SVA_PLAN_ACK",
                                                      "SVA_VEHICLE_STATUS",
                                                      "SVA_VEHICLE_FUEL",
                                                      "SVA_MISSION_CLOCK"};

static void do_encode(char* rest)
{
    sva_can_msg_t m;
    sva_can_frame_t f;
    char* tok = strtok(rest, " \t\n");
    int k;
    sva_can_status_t st;
    memset(&m, 0, sizeof m);
    m.kind = SVA_CAN_MSG_NONE;
    for (k = 1; (tok != NULL) && (k < SVA_CAN_MSG_COUNT_); ++k) {
        if (strcmp(tok, names[k]) == 0) {
            m.kind = (sva_can_msg_kind_t)k;
        }
    }
    nkv = 0;
    missing = 0;
    while ((tok = strtok(NULL, " \t\n")) != NULL && nkv < 32) {
        char* eq = strchr(tok, '=');
        if (eq == NULL) {
            continue;
        }
        *eq = '\0';
        snprintf(kvs[nkv].key, sizeof kvs[nkv].key, "%s", tok);
        kvs[nkv].value = strtoll(eq + 1, NULL, 10);
        ++nkv;
    }
    m.counter = (uint8_t)get("counter");
    switch (m.kind) {
    case SVA_CAN_MSG_HEARTBEAT:
        m.u.heartbeat.state = (uint8_t)get("state");
        m.u.heartbeat.active_plan_id = (uint16_t)get("active_plan_id");
        m.u.heartbeat.uav_count = (uint8_t)get("uav_count");
        m.u.heartbeat.target_count = (uint8_t)get("target_count");
        m.u.heartbeat.covered_count = (uint8_t)get("covered_count");
        m.u.heartbeat.faults =
            (uint8_t)(get("fault_mission_invalid") | (get("fault_plan_failed") << 1) |
                      (get("fault_transfer_failed") << 2) | (get("fault_rx_errors") << 3) |
                      (get("fault_tx_errors") << 4));
        break;
    case SVA_CAN_MSG_PLAN_BEGIN:
        m.u.begin.version = (uint8_t)get("version");
        m.u.begin.plan_id = (uint16_t)get("plan_id");
        m.u.begin.item_count = (uint16_t)get("item_count");
        m.u.begin.algorithm = (uint8_t)get("algorithm");
        m.u.begin.plan_status = (uint8_t)get("plan_status");
        m.u.begin.route_count = (uint8_t)get("route_count");
        break;
    case SVA_CAN_MSG_PLAN_ITEM:
        m.u.item.uav_id = (uint8_t)get("uav_id");
        m.u.item.target_id = (uint16_t)get("target_id");
        m.u.item.x = (int16_t)get("x");
        m.u.item.y = (int16_t)get("y");
        break;
    case SVA_CAN_MSG_PLAN_ITEM_TIME:
        m.u.item_time.item_seq = (uint8_t)get("item_seq");
        m.u.item_time.arrive_by_ticks = (uint32_t)get("arrive_by");
        m.u.item_time.hold_until_ticks = (uint32_t)get("hold_until");
        break;
    case SVA_CAN_MSG_PLAN_COMMIT:
        m.u.commit.plan_id = (uint16_t)get("plan_id");
        m.u.commit.plan_crc = (uint32_t)get("plan_crc");
        break;
    case SVA_CAN_MSG_PLAN_ABORT:
        m.u.abort_.reason = (uint8_t)get("reason");
        m.u.abort_.plan_id = (uint16_t)get("plan_id");
        break;
    case SVA_CAN_MSG_PLAN_ACK:
        m.u.ack.result = (uint8_t)get("result");
        m.u.ack.plan_id = (uint16_t)get("plan_id");
        m.u.ack.items_received = (uint16_t)get("items_received");
        break;
    case SVA_CAN_MSG_VEHICLE_STATUS:
        m.u.vehicle.state = (uint8_t)get("state");
        m.u.vehicle.uav_id = (uint8_t)get("uav_id");
        m.u.vehicle.x = (int16_t)get("x");
        m.u.vehicle.y = (int16_t)get("y");
        break;
    case SVA_CAN_MSG_VEHICLE_FUEL:
        m.u.fuel.uav_id = (uint8_t)get("uav_id");
        m.u.fuel.fuel = (uint32_t)get("fuel");
        break;
    case SVA_CAN_MSG_MISSION_CLOCK:
        m.u.clock.tick = (uint32_t)get("tick");
        break;
    case SVA_CAN_MSG_NONE:
    case SVA_CAN_MSG_COUNT_:
    default:
        printf("error unknown_message\n");
        return;
    }
    if (missing) {
        printf("error missing_signal\n");
        return;
    }
    st = sva_can_encode(&m, &f);
    if (st != SVA_CAN_OK) {
        printf("error %s\n", sva_can_status_name(st));
        return;
    }
    printf("%03lX#", (unsigned long)f.id);
    for (k = 0; k < 8; ++k) {
        printf("%02X", f.data[k]);
    }
    printf("\n");
}

// "ID#HEX" -> *f (dlc = the number of bytes given). Returns the text after the hex
// digits, or NULL on a syntax error.
static const char* parse_frame(const char* text, sva_can_frame_t* f)
{
    const char* hash = strchr(text, '#');
    size_t n;
    size_t i;
    if (hash == NULL) {
        return NULL;
    }
    memset(f, 0, sizeof *f);
    f->id = (uint32_t)strtoul(text, NULL, 16);
    n = strspn(hash + 1, "0123456789abcdefABCDEF") / 2u;
    for (i = 0; i < n && i < 8u; ++i) {
        char b[3] = {hash[1 + 2 * i], hash[2 + 2 * i], '\0'};
        f->data[i] = (uint8_t)strtoul(b, NULL, 16);
    }
    f->dlc = (uint8_t)n;
    return hash + 1 + 2u * n;
}

// "check ID#HEX EXPECTED_COUNTER" -> the status name of sva_can_frame_check().
static void do_check(const char* text)
{
    sva_can_frame_t f;
    const char* rest = parse_frame(text, &f);
    if (rest == NULL) {
        printf("error syntax\n");
        return;
    }
    printf("%s\n", sva_can_status_name(sva_can_frame_check(&f, (int)strtol(rest, NULL, 10))));
}

static void do_decode(const char* text)
{
    sva_can_frame_t f;
    sva_can_msg_t m;
    sva_can_status_t st;
    if (parse_frame(text, &f) == NULL) {
        printf("error syntax\n");
        return;
    }
    st = sva_can_decode(&f, &m);
    if (st != SVA_CAN_OK) {
        printf("error %s\n", sva_can_status_name(st));
        return;
    }
    printf("%s counter=%u", names[m.kind], m.counter);
    switch (m.kind) {
    case SVA_CAN_MSG_HEARTBEAT:
        printf(
            " state=%u active_plan_id=%u uav_count=%u target_count=%u covered_count=%u "
            "fault_mission_invalid=%u "
            "fault_plan_failed=%u fault_transfer_failed=%u fault_rx_errors=%u fault_tx_errors=%u",
            m.u.heartbeat.state, m.u.heartbeat.active_plan_id, m.u.heartbeat.uav_count,
            m.u.heartbeat.target_count, m.u.heartbeat.covered_count, m.u.heartbeat.faults & 1u,
            (m.u.heartbeat.faults >> 1) & 1u, (m.u.heartbeat.faults >> 2) & 1u,
            (m.u.heartbeat.faults >> 3) & 1u, (m.u.heartbeat.faults >> 4) & 1u);
        break;
    case SVA_CAN_MSG_PLAN_BEGIN:
        printf(" version=%u plan_id=%u item_count=%u algorithm=%u plan_status=%u route_count=%u",
               m.u.begin.version, m.u.begin.plan_id, m.u.begin.item_count, m.u.begin.algorithm,
               m.u.begin.plan_status, m.u.begin.route_count);
        break;
    case SVA_CAN_MSG_PLAN_ITEM:
        printf(" uav_id=%u target_id=%u x=%d y=%d", m.u.item.uav_id, m.u.item.target_id, m.u.item.x,
               m.u.item.y);
        break;
    case SVA_CAN_MSG_PLAN_ITEM_TIME:
        printf(" item_seq=%u arrive_by=%lu hold_until=%lu", m.u.item_time.item_seq,
               (unsigned long)m.u.item_time.arrive_by_ticks,
               (unsigned long)m.u.item_time.hold_until_ticks);
        break;
    case SVA_CAN_MSG_PLAN_COMMIT:
        printf(" plan_id=%u plan_crc=%lu", m.u.commit.plan_id, (unsigned long)m.u.commit.plan_crc);
        break;
    case SVA_CAN_MSG_PLAN_ABORT:
        printf(" reason=%u plan_id=%u", m.u.abort_.reason, m.u.abort_.plan_id);
        break;
    case SVA_CAN_MSG_PLAN_ACK:
        printf(" result=%u plan_id=%u items_received=%u", m.u.ack.result, m.u.ack.plan_id,
               m.u.ack.items_received);
        break;
    case SVA_CAN_MSG_VEHICLE_STATUS:
        printf(" state=%u uav_id=%u x=%d y=%d", m.u.vehicle.state, m.u.vehicle.uav_id,
               m.u.vehicle.x, m.u.vehicle.y);
        break;
    case SVA_CAN_MSG_VEHICLE_FUEL:
        printf(" uav_id=%u fuel=%lu", m.u.fuel.uav_id, (unsigned long)m.u.fuel.fuel);
        break;
    case SVA_CAN_MSG_MISSION_CLOCK:
        printf(" tick=%lu", (unsigned long)m.u.clock.tick);
        break;
    case SVA_CAN_MSG_NONE:
    case SVA_CAN_MSG_COUNT_:
    default:
        break;
    }
    printf(" crc=%u\n", f.data[7]);
}

static void print_frame(const sva_can_frame_t* f, const char* sep)
{
    int k;
    printf("%s%03lX#", sep, (unsigned long)f->id);
    for (k = 0; k < 8; ++k) {
        printf("%02X", f->data[k]);
    }
}

static sva_mission_t mission;
static sva_planner_t planner;
static sva_plan_t plan;
static sva_can_plan_t wire;
static sva_can_loopback_t bus;
static sva_can_sender_t sender;

static int print_wire(uint32_t covered, int64_t cost, const sva_can_mission_frame_t* frame);

static int do_plan(const char* path, const char* algo_name, const char* id_text)
{
    char err[256];
    sva_algorithm_t algo;
    sva_diag_t diag;
    const long plan_id = strtol(id_text, NULL, 10);
    if ((plan_id < 1) || (plan_id > 65535)) {
        fprintf(stderr, "plan_id: must be in [1, 65535]\n");
        return 2;
    }
    sva_can_mission_frame_t mframe;
    bool has_frame = false;
    if (sva_can_mission_load_frame(path, &mission, NULL, 0, &mframe, &has_frame, err, sizeof err) !=
        SVA_JSON_OK) {
        fprintf(stderr, "%s: %s\n", path, err);
        return 1;
    }
    if (sva_algorithm_from_name(algo_name, &algo) != SVA_OK) {
        fprintf(stderr, "unknown algorithm %s\n", algo_name);
        return 2;
    }
    if ((sva_planner_init(&planner) != SVA_OK) ||
        (sva_plan(&planner, &mission, algo, &plan, &diag) != SVA_OK) ||
        (sva_can_plan_from_core(&wire, &mission, &plan, (uint16_t)plan_id) != SVA_CAN_OK)) {
        fprintf(stderr, "planning failed\n");
        return 1;
    }
    return print_wire(plan.covered, plan.cost, has_frame ? &mframe : NULL);
}

// The wire plan as JSON with the mission frame's frames (none when frame is NULL) and the
// transfer's frames (first attempt, counter from 0).
static int print_wire(uint32_t covered, int64_t cost, const sva_can_mission_frame_t* frame)
{
    sva_can_transport_t tp;
    sva_can_frame_t f;
    uint16_t i;
    int first = 1;
    sva_can_loopback_init(&bus);
    if ((sva_can_loopback_transport(&bus, 0, &tp) != SVA_CAN_OK) ||
        (sva_can_sender_init(&sender, &tp, NULL) != SVA_CAN_OK) ||
        (sva_can_sender_start(&sender, &wire, 0) != SVA_CAN_OK)) {
        fprintf(stderr, "sending failed\n");
        return 1;
    }
    printf("{\"plan_id\": %u, \"algorithm\": %u, \"plan_status\": %u, \"route_count\": %u, "
           "\"covered\": %u, "
           "\"cost\": %lld, \"plan_crc\": %lu, \"items\": [",
           wire.plan_id, wire.algorithm, wire.plan_status, wire.route_count, (unsigned)covered,
           (long long)cost, (unsigned long)sva_can_plan_crc(&wire));
    for (i = 0; i < wire.item_count; ++i) {
        const sva_can_item_t* it = &wire.items[i];
        printf("%s{\"uav\": %u, \"target\": %u, \"x\": %d, \"y\": %d, \"arrive_by\": %lu, "
               "\"hold_until\": %lu}",
               (i == 0) ? "" : ", ", it->uav_id, it->target_id, it->x, it->y,
               (unsigned long)it->arrive_by_ticks, (unsigned long)it->hold_until_ticks);
    }
    printf("], \"frame_frames\": [");
    if (frame != NULL) {
        // what sva_can_node sends before the plan (counters from 0)
        sva_can_frame_t parts[4];
        int p;
        if (sva_can_mission_frame_encode(frame, 0u, parts) != SVA_CAN_OK) {
            fprintf(stderr, "frame encoding failed\n");
            return 1;
        }
        for (p = 0; p < 4; ++p) {
            printf("%s\"", (p == 0) ? "" : ", ");
            print_frame(&parts[p], "");
            printf("\"");
        }
    }
    printf("], \"frames\": [");
    while (sva_can_loopback_take(&bus, 1, &f) == SVA_CAN_OK) {
        int k;
        printf("%s\"%03lX#", first ? "" : ", ", (unsigned long)f.id);
        for (k = 0; k < 8; ++k) {
            printf("%02X", f.data[k]);
        }
        printf("\"");
        first = 0;
    }
    printf("]}\n");
    return 0;
}

static sva_can_live_t live;

// The CAN node's live mission (can_live.c) on MISSION: plan 1, then a clock frame of
// TICK and UAV LOST_UAV reported unavailable, one replan; prints the plan it sends.
static int do_live(const char* path, const char* algo_name, const char* tick_text,
                   const char* uav_text)
{
    char err[256];
    sva_algorithm_t algo;
    sva_can_msg_t m;
    if (sva_can_mission_load(path, &mission, NULL, 0, err, sizeof err) != SVA_JSON_OK) {
        fprintf(stderr, "%s: %s\n", path, err);
        return 1;
    }
    if ((sva_algorithm_from_name(algo_name, &algo) != SVA_OK) ||
        (sva_can_live_start(&live, &mission, algo, err, sizeof err) != 0)) {
        fprintf(stderr, "live mission: cannot start (%s)\n", algo_name);
        return 1;
    }
    memset(&m, 0, sizeof m);
    m.kind = SVA_CAN_MSG_MISSION_CLOCK;
    m.u.clock.tick = (uint32_t)strtoul(tick_text, NULL, 10);
    if (sva_can_live_on_msg(&live, &m, 0u) != 1) {
        fprintf(stderr, "clock %s refused\n", tick_text);
        return 1;
    }
    memset(&m, 0, sizeof m);
    m.kind = SVA_CAN_MSG_VEHICLE_STATUS;
    m.u.vehicle.uav_id = (uint8_t)strtoul(uav_text, NULL, 10);
    m.u.vehicle.state = SVA_CAN_VEHICLE_UNAVAILABLE;
    if ((sva_can_live_on_msg(&live, &m, 0u) != 1) || (sva_can_live_poll(&live, 0u, 0u) != 1)) {
        fprintf(stderr, "loss of uav %s: no new plan\n", uav_text);
        return 1;
    }
    wire = live.wire;
    return print_wire(live.result.covered, live.result.plan->cost, NULL);
}

// "frame LAT_E7 LON_E7 ALT_CM CELL_CM TICK_MS T0_MS COUNTER": the four frames of a
// mission frame (sva_can_mission_frame_encode), or "error <status>".
static int do_frame_encode(char** v)
{
    sva_can_mission_frame_t mf;
    sva_can_frame_t out[4];
    int i;
    mf.lat_e7 = (int32_t)strtol(v[0], NULL, 10);
    mf.lon_e7 = (int32_t)strtol(v[1], NULL, 10);
    mf.alt_cm = (int32_t)strtol(v[2], NULL, 10);
    mf.cell_cm = (int32_t)strtol(v[3], NULL, 10);
    mf.tick_ms = (int32_t)strtol(v[4], NULL, 10);
    mf.t0_ms = (int64_t)strtoll(v[5], NULL, 10);
    const sva_can_status_t st =
        sva_can_mission_frame_encode(&mf, (uint8_t)strtoul(v[6], NULL, 10), out);
    if (st != SVA_CAN_OK) {
        printf("error %s\n", sva_can_status_name(st));
        return 1;
    }
    for (i = 0; i < 4; ++i) {
        print_frame(&out[i], (i == 0) ? "" : " ");
    }
    printf("\n");
    return 0;
}

// "frame-rx ID#HEX ...": each frame through one receiver; prints every status and, when
// a group completes, the frame's six integers.
static int do_frame_rx(int n, char** v)
{
    sva_can_mission_frame_rx_t rx;
    sva_can_mission_frame_t mf;
    int i;
    sva_can_mission_frame_rx_init(&rx);
    for (i = 0; i < n; ++i) {
        sva_can_frame_t f;
        const char* hash = strchr(v[i], '#');
        size_t k;
        size_t len;
        if (hash == NULL) {
            printf("error syntax\n");
            return 2;
        }
        memset(&f, 0, sizeof f);
        f.id = (uint32_t)strtoul(v[i], NULL, 16);
        len = strspn(hash + 1, "0123456789abcdefABCDEF") / 2u;
        for (k = 0; k < len && k < 8u; ++k) {
            char b[3] = {hash[1 + 2 * k], hash[2 + 2 * k], '\0'};
            f.data[k] = (uint8_t)strtoul(b, NULL, 16);
        }
        f.dlc = (uint8_t)len;
        const sva_can_status_t st = sva_can_mission_frame_rx(&rx, &f, &mf);
        printf("%s%s", (i == 0) ? "" : " ", sva_can_status_name(st));
        if (st == SVA_CAN_APPLIED) {
            printf(" lat_e7=%ld lon_e7=%ld alt_cm=%ld cell_cm=%ld tick_ms=%ld t0_ms=%lld",
                   (long)mf.lat_e7, (long)mf.lon_e7, (long)mf.alt_cm, (long)mf.cell_cm,
                   (long)mf.tick_ms, (long long)mf.t0_ms);
        }
    }
    printf("\n");
    return 0;
}

int main(int argc, char** argv)
{
    char line[1024];
    if ((argc == 9) && (strcmp(argv[1], "frame") == 0)) {
        return do_frame_encode(argv + 2);
    }
    if ((argc >= 3) && (strcmp(argv[1], "frame-rx") == 0)) {
        return do_frame_rx(argc - 2, argv + 2);
    }
    if ((argc == 5) && (strcmp(argv[1], "plan") == 0)) {
        return do_plan(argv[2], argv[3], argv[4]);
    }
    if ((argc == 6) && (strcmp(argv[1], "live") == 0)) {
        return do_live(argv[2], argv[3], argv[4], argv[5]);
    }
    if ((argc != 2) || (strcmp(argv[1], "codec") != 0)) {
        fprintf(stderr, "usage: can_frames_tool codec | plan MISSION ALGORITHM PLAN_ID | live "
                        "MISSION ALGORITHM TICK LOST_UAV | frame LAT_E7 LON_E7 ALT_CM CELL_CM "
                        "TICK_MS T0_MS COUNTER | frame-rx FRAME...\n");
        return 2;
    }
    while (fgets(line, sizeof line, stdin) != NULL) {
        if (strncmp(line, "encode ", 7) == 0) {
            do_encode(line + 7);
        } else if (strncmp(line, "decode ", 7) == 0) {
            do_decode(line + 7);
        } else if (strncmp(line, "check ", 6) == 0) {
            do_check(line + 6);
        } else {
            printf("error syntax\n");
        }
        fflush(stdout);
    }
    return 0;
}
