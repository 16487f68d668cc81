// sva_can_node: the planner on a CAN bus, running a live mission. Plans the mission of
// a SPEC section 3 mission file, sends the plan with the protocol of port/can/sva.dbc,
// and keeps the live mission (can_live.c) from the flight stack's frames on a SocketCAN
// interface: SVA_MISSION_CLOCK (the clock), SVA_VEHICLE_STATUS (loss, return, position)
// and SVA_VEHICLE_FUEL (fuel), each change a core event; once the bus has been quiet
// for --settle-ms after an event it replans and sends the new plan when it changed.
// Heartbeat every second. SIGINT/SIGTERM: aborts an in-flight transfer, exits 0.
// With --state-dir DIR the live mission's inputs are journaled (can_journal.h) and a
// restart resumes it (docs/can.md, "Crash safety").
//
// Usage: sva_can_node --mission FILE [--iface vcan0] [--algo sva]
//                     [--settle-ms 200] [--track-tolerance 2] [--exit-after-acks N]
//                     [--max-runtime-ms N] [--print-plans] [--state-dir DIR [--state-reset]]
//        sva_can_node --help | --version
#define _POSIX_C_SOURCE 200809L

#include <errno.h>
#include <poll.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "can_live.h"
#include "can_state.h"
#include "mission_file.h"
#include "plan_print.h"
#include "sva/sva.h"
#include "sva/sva_can.h"
#include "sva/sva_can_transport.h"
#include "sva/sva_text.h"

// Room for a user-supplied string (option, file or mission name) as logs show it:
// escaped with sva_text_escape(), cut if longer.
#define SHOWN_SIZE 256

static volatile sig_atomic_t g_stop = 0;

static void on_signal(int sig)
{
    (void)sig;
    g_stop = 1;
}

static uint32_t now_ms(void)
{
    struct timespec ts;
    if (clock_gettime(CLOCK_MONOTONIC, &ts) != 0) {
        return 0U;
    }
    return (uint32_t)((uint64_t)ts.tv_sec * 1000U + (uint64_t)ts.tv_nsec / 1000000U);
}

// Everything the node owns: static, no heap (the live mission and planner are large).
static sva_mission_t g_mission;  // the mission file: the live mission's start
static sva_can_live_t g_live;
static sva_can_state_t g_state;  // --state-dir: the journal
static sva_can_sender_t g_sender;
// The mission's frame, sent (SVA_MISSION_FRAME_A..D) before each plan when it has one.
static sva_can_mission_frame_t g_frame;
static bool g_has_frame;
static uint8_t g_frame_counter;
static sva_can_transport_t* g_tp;

// Sends the mission frame's four CAN frames. Returns the fault bits.
static uint8_t send_frame(void)
{
    sva_can_frame_t out[SVA_CAN_MISSION_FRAME_PARTS];
    unsigned p;
    if (!g_has_frame) {
        return 0U;
    }
    if (sva_can_mission_frame_encode(&g_frame, g_frame_counter, out) != SVA_CAN_OK) {
        return SVA_CAN_FAULT_TX_ERRORS;
    }
    g_frame_counter = (uint8_t)((g_frame_counter + SVA_CAN_MISSION_FRAME_PARTS) & 15U);
    for (p = 0; p < SVA_CAN_MISSION_FRAME_PARTS; ++p) {
        const sva_can_status_t st = g_tp->send(g_tp->ctx, &out[p]);
        if (st != SVA_CAN_OK) {
            fprintf(stderr, "sva_can_node: sending the mission frame: %s\n",
                    sva_can_status_name(st));
            return SVA_CAN_FAULT_TX_ERRORS;
        }
    }
    return 0U;
}

static uint32_t elapsed(uint32_t now, uint32_t then)
{
    return (uint32_t)(now - then);  // modulo 2^32: right across the wrap-around
}

static void usage(FILE* out)
{
    fprintf(out, "usage: sva_can_node --mission FILE [--iface NAME] [--algo sva|ga|hga|bfa|flow]\n"
                 "                    [--settle-ms N] [--track-tolerance N] [--exit-after-acks N]\n"
                 "                    [--max-runtime-ms N] [--print-plans] [--state-dir DIR "
                 "[--state-reset]]\n"
                 "       sva_can_node --help | --version\n"
                 "  --algo NAME  the planner (default sva); --algorithm is the same option\n"
                 "  --state-dir DIR  journal the live mission in DIR (created if missing) and, on\n"
                 "               start, resume it from there\n"
                 "  --state-reset    with --state-dir: discard the journal and start afresh\n"
                 "  --version    print \"sva_can_node VERSION\" (the sva library's)\n");
}

static int parse_u32(const char* s, const char* opt, uint32_t* out)
{
    char err[SHOWN_SIZE];
    long v = 0;
    if (sva_text_to_long(opt, s, 0, 0x7FFFFFFFL, &v, err, sizeof err) != SVA_OK) {
        fprintf(stderr, "sva_can_node: error: %s\n", err);
        return -1;
    }
    *out = (uint32_t)v;
    return 0;
}

// Hands the last wire plan the live mission made (g_live.sent: after a resume, the plan in
// force under its id) to the sender. Returns the fault bits.
static uint8_t send_plan(uint32_t t, int print)
{
    sva_can_status_t cst;
    const sva_can_plan_t* plan = &g_live.sent;
    fprintf(stderr, "sva_can_node: plan %u: %s %s, covered %u of %u, %u items, %u frames\n",
            plan->plan_id, sva_algorithm_name((sva_algorithm_t)plan->algorithm),
            (plan->plan_status == SVA_CAN_PLAN_COMPLETE) ? "complete" : "partial", g_live.covered,
            g_live.live.mission.target_count, plan->item_count, 2U * plan->item_count + 2U);
    if (print) {
        sva_can_plan_print(plan);
    }
    if (send_frame() != 0U) {
        return SVA_CAN_FAULT_TX_ERRORS;
    }
    cst = sva_can_sender_start(&g_sender, plan, t);
    if ((cst != SVA_CAN_OK) && (cst != SVA_CAN_AGAIN)) {
        fprintf(stderr, "sva_can_node: sending plan %u: %s\n", plan->plan_id,
                sva_can_status_name(cst));
        return SVA_CAN_FAULT_TX_ERRORS;
    }
    return 0U;
}

// The options that take a value (every option but --help, --version and --state-reset).
static bool takes_value(const char* a)
{
    static const char* const names[] = {
        "--iface",           "--mission",         "--algo",
        "--algorithm",       "--state-dir",       "--settle-ms",
        "--track-tolerance", "--exit-after-acks", "--max-runtime-ms"};
    for (size_t k = 0; k < sizeof names / sizeof names[0]; ++k) {
        if (strcmp(a, names[k]) == 0) {
            return true;
        }
    }
    return false;
}

// What the command line asks for.
typedef struct {
    const char* iface;
    const char* mission_path;
    const char* algo_name;
    const char* algo_option;  // as the user spelled it, for its error line
    sva_algorithm_t algo;
    uint32_t settle_ms;
    uint32_t exit_after_acks;
    uint32_t max_runtime_ms;
    uint32_t track_tolerance;
    int print;
    const char* state_dir;
    bool state_reset;
} node_options_t;

// What the run loop keeps from one round to the next.
typedef struct {
    uint32_t t0;
    uint32_t last_hb;
    uint16_t active_plan_id;
    uint8_t hb_counter;
    uint8_t faults;
    uint8_t covered_active;
    uint32_t acks;
    uint32_t rx_rejected;
    int has_last_counter[3];
    uint8_t last_counter[3];
    sva_can_tx_state_t prev_state;
    bool halted;
} node_run_t;

// Reads the command line into *o. Returns -1 to go on, else the exit status (0 after
// --help or --version, 2 after a usage error, each with its message).
static int parse_options(int argc, char** argv, node_options_t* o)
{
    int i;
    memset(o, 0, sizeof *o);
    o->iface = "vcan0";
    o->algo_name = "sva";
    o->algo_option = "--algo";
    o->settle_ms = 200U;
    o->track_tolerance = SVA_CAN_LIVE_TRACK_TOLERANCE;
    for (i = 1; i < argc; ++i) {
        const char* a = argv[i];
        char shown[SHOWN_SIZE];
        const char* v = (i + 1 < argc) ? argv[i + 1] : NULL;
        if (strcmp(a, "--print-plans") == 0) {
            o->print = 1;
            continue;
        }
        if (strcmp(a, "--state-reset") == 0) {
            o->state_reset = true;
            continue;
        }
        if ((strcmp(a, "--help") == 0) || (strcmp(a, "-h") == 0)) {
            usage(stdout);
            return 0;
        }
        if (strcmp(a, "--version") == 0) {
            printf("sva_can_node %d.%d.%d\n", SVA_VERSION_MAJOR, SVA_VERSION_MINOR,
                   SVA_VERSION_PATCH);
            return 0;
        }
        if (!takes_value(a)) {
            fprintf(stderr, "sva_can_node: error: unknown option %s\n",
                    sva_text_escape(shown, sizeof shown, a));
            usage(stderr);
            return 2;
        }
        if (v == NULL) {
            fprintf(stderr, "sva_can_node: error: %s: missing value\n",
                    sva_text_escape(shown, sizeof shown, a));
            usage(stderr);
            return 2;
        }
        ++i;
        if (strcmp(a, "--iface") == 0) {
            o->iface = v;
        } else if (strcmp(a, "--mission") == 0) {
            o->mission_path = v;
        } else if ((strcmp(a, "--algo") == 0) || (strcmp(a, "--algorithm") == 0)) {
            o->algo_option = a;
            o->algo_name = v;
        } else if (strcmp(a, "--state-dir") == 0) {
            o->state_dir = v;
        } else if (strcmp(a, "--settle-ms") == 0) {
            if (parse_u32(v, a, &o->settle_ms) != 0) {
                return 2;
            }
        } else if (strcmp(a, "--track-tolerance") == 0) {
            if (parse_u32(v, a, &o->track_tolerance) != 0) {
                return 2;
            }
        } else if (strcmp(a, "--exit-after-acks") == 0) {
            if (parse_u32(v, a, &o->exit_after_acks) != 0) {
                return 2;
            }
        } else if (strcmp(a, "--max-runtime-ms") == 0) {
            if (parse_u32(v, a, &o->max_runtime_ms) != 0) {
                return 2;
            }
        } else {
            fprintf(stderr, "sva_can_node: error: unknown option %s\n",
                    sva_text_escape(shown, sizeof shown, a));
            usage(stderr);
            return 2;
        }
    }
    if (o->mission_path == NULL) {
        fprintf(stderr, "sva_can_node: error: --mission: missing required option\n");
        usage(stderr);
        return 2;
    }
    if (o->state_reset && (o->state_dir == NULL)) {
        fprintf(stderr, "sva_can_node: error: --state-reset needs --state-dir\n");
        return 2;
    }
    if (sva_algorithm_from_name(o->algo_name, &o->algo) != SVA_OK) {
        char shown_arg[SHOWN_SIZE];
        fprintf(stderr,
                "sva_can_node: error: %s: unknown algorithm \"%s\" (sva, ga, hga, bfa, flow)\n",
                o->algo_option, sva_text_escape(shown_arg, sizeof shown_arg, o->algo_name));
        return 2;
    }
    return -1;
}

// Loads the mission file (its name into name[]), starts the live mission and, with
// --state-dir, replays the journal: all before the node hears the bus. Returns 0 or the
// exit status (the message printed).
static int open_state(const node_options_t* o, char* name, size_t name_size)
{
    char err[256];
    if (sva_can_mission_load_frame(o->mission_path, &g_mission, name, name_size, &g_frame,
                                   &g_has_frame, err, sizeof err) != SVA_JSON_OK) {
        char shown_arg[SHOWN_SIZE];
        fprintf(stderr, "sva_can_node: error: %s: %s\n",
                sva_text_escape(shown_arg, sizeof shown_arg, o->mission_path), err);
        return 1;
    }
    g_live.log = stderr;
    g_live.track_tolerance_cells = (int32_t)o->track_tolerance;
    if (sva_can_live_start(&g_live, &g_mission, o->algo, err, sizeof err) != 0) {
        fprintf(stderr, "sva_can_node: error: %s\n", err);
        return 1;
    }
    // The journal is replayed before the node hears the bus.
    if (o->state_dir != NULL) {
        const int src =
            sva_can_state_open(&g_state, o->state_dir, o->state_reset, &g_live, &g_mission);
        if (src != 0) {
            sva_can_state_close(&g_state);
            return src;
        }
    }
    return 0;
}

// Opens the SocketCAN interface, the sender over it and the signal handlers. Returns 0
// or the exit status (the message printed, what was opened closed).
static int open_transport(const node_options_t* o, sva_can_socketcan_t* sock,
                          sva_can_transport_t* tp)
{
    struct sigaction sa;
    const sva_can_status_t cst = sva_can_socketcan_open(sock, o->iface);
    if (cst != SVA_CAN_OK) {
        char shown_arg[SHOWN_SIZE];
        fprintf(stderr, "sva_can_node: error: --iface %s: %s%s%s\n",
                sva_text_escape(shown_arg, sizeof shown_arg, o->iface),
                (cst == SVA_CAN_ERR_NAME) ? "interface name empty or longer than IFNAMSIZ - 1 (15)"
                                          : "cannot open",
                (sock->last_errno != 0) ? ": " : "",
                (sock->last_errno != 0) ? strerror(sock->last_errno) : "");
        sva_can_state_close(&g_state);
        return 1;
    }
    if ((sva_can_socketcan_transport(sock, tp) != SVA_CAN_OK) ||
        (sva_can_sender_init(&g_sender, tp, NULL) != SVA_CAN_OK)) {
        fprintf(stderr, "sva_can_node: error: transport setup failed\n");
        sva_can_socketcan_close(sock);
        sva_can_state_close(&g_state);
        return 1;
    }
    memset(&sa, 0, sizeof sa);
    sa.sa_handler = on_signal;
    if ((sigemptyset(&sa.sa_mask) != 0) || (sigaction(SIGINT, &sa, NULL) != 0) ||
        (sigaction(SIGTERM, &sa, NULL) != 0)) {
        fprintf(stderr, "sva_can_node: error: sigaction: %s\n", strerror(errno));
        sva_can_socketcan_close(sock);
        sva_can_state_close(&g_state);
        return 1;
    }
    return 0;
}

// Reads every frame waiting on the bus: ACKs to the sender, the flight stack's frames
// into the live mission.
static void drain_bus(node_run_t* r, const sva_can_transport_t* tp, const sva_can_socketcan_t* sock,
                      uint32_t t)
{
    sva_can_frame_t f;
    for (;;) {
        sva_can_msg_t m;
        sva_can_status_t st = tp->recv(tp->ctx, &f);
        if (st == SVA_CAN_AGAIN) {
            break;
        }
        if (st != SVA_CAN_OK) {
            fprintf(stderr, "sva_can_node: error: read: %s\n", strerror(sock->last_errno));
            r->faults |= SVA_CAN_FAULT_TX_ERRORS;
            break;
        }
        st = sva_can_sender_on_frame(&g_sender, &f, t);
        if (st != SVA_CAN_IGNORED) {
            if (st < 0) {
                r->faults |= SVA_CAN_FAULT_RX_ERRORS;
            }
            continue;
        }
        if ((f.id != SVA_CAN_ID_VEHICLE_STATUS) && (f.id != SVA_CAN_ID_VEHICLE_FUEL) &&
            (f.id != SVA_CAN_ID_MISSION_CLOCK)) {
            continue;
        }
        st = sva_can_decode(&f, &m);
        if (st == SVA_CAN_IGNORED) {
            continue;
        }
        if (st != SVA_CAN_OK) {
            ++r->rx_rejected;
            r->faults |= SVA_CAN_FAULT_RX_ERRORS;
            fprintf(stderr, "sva_can_node: rejected flight-stack frame 0x%03lX: %s\n",
                    (unsigned long)f.id, sva_can_status_name(st));
            continue;
        }
        {
            // A repeated counter is a stale or duplicated frame: rejected. A jump is
            // lost frames: the state still applies (latest state wins).
            const int k = (m.kind == SVA_CAN_MSG_VEHICLE_STATUS) ? 0
                          : (m.kind == SVA_CAN_MSG_VEHICLE_FUEL) ? 1
                                                                 : 2;
            if (r->has_last_counter[k] && (m.counter == r->last_counter[k])) {
                ++r->rx_rejected;
                r->faults |= SVA_CAN_FAULT_RX_ERRORS;
                continue;
            }
            r->has_last_counter[k] = 1;
            r->last_counter[k] = m.counter;
        }
        if (sva_can_live_on_msg(&g_live, &m, t) == SVA_CAN_LIVE_HALTED) {
            break;
        }
    }
}

// Replans once the bus has settled and sends a changed plan. False when the journal
// could not keep an input: the node then stops without an answer.
static bool replan_settled(node_run_t* r, const node_options_t* o, uint32_t t)
{
    const int changed =
        g_live.halted ? SVA_CAN_LIVE_HALTED : sva_can_live_poll(&g_live, t, o->settle_ms);
    if (changed == SVA_CAN_LIVE_HALTED) {
        // The journal could not keep an input: nothing is answered for it. Exit as
        // a crash would; a restart resumes from the last record kept.
        char said[SHOWN_SIZE];
        fprintf(stderr, "sva_can_node: error: journal: %s: stopping without an answer\n",
                sva_text_escape(said, sizeof said, g_state.journal.message));
        return false;
    }
    if (changed < 0) {
        r->faults |= SVA_CAN_FAULT_PLAN_FAILED;
    } else if (changed > 0) {
        r->faults = (uint8_t)(r->faults & (uint8_t)~SVA_CAN_FAULT_PLAN_FAILED);
        r->faults |= send_plan(t, o->print);
    }
    return true;
}

// Follows the plan transfer: an ACK makes the plan the active one, an abort a fault.
static void watch_transfer(node_run_t* r)
{
    if (g_sender.state == r->prev_state) {
        return;
    }
    if (g_sender.state == SVA_CAN_TX_DONE) {
        r->active_plan_id = g_sender.priv.plan.plan_id;
        r->covered_active = g_live.covered;
        r->faults = (uint8_t)(r->faults & (uint8_t)~SVA_CAN_FAULT_TRANSFER_FAILED);
        ++r->acks;
        fprintf(stderr, "sva_can_node: plan %u acknowledged (%lu frames sent so far)\n",
                r->active_plan_id, (unsigned long)g_sender.stats.frames_sent);
    } else if (g_sender.state == SVA_CAN_TX_FAILED) {
        r->faults |= SVA_CAN_FAULT_TRANSFER_FAILED;
        fprintf(stderr, "sva_can_node: plan %u aborted (reason %u)%s\n", g_sender.priv.plan.plan_id,
                g_sender.last_abort_reason,
                (g_sender.last_nack == SVA_CAN_ACK_BAD_VERSION)
                    ? ": the bridge refused the protocol version (NACK BAD_VERSION)"
                    : "");
    }
    r->prev_state = g_sender.state;
}

// The heartbeat, once per period.
static void heartbeat(node_run_t* r, const sva_can_transport_t* tp, uint32_t t)
{
    sva_can_msg_t hb;
    sva_can_frame_t hf;
    if (elapsed(t, r->last_hb) < SVA_CAN_HEARTBEAT_PERIOD_MS) {
        return;
    }
    hb.kind = SVA_CAN_MSG_HEARTBEAT;
    hb.counter = r->hb_counter;
    hb.u.heartbeat.state =
        (uint8_t)((g_sender.state == SVA_CAN_TX_SENDING || g_sender.state == SVA_CAN_TX_WAIT_ACK)
                      ? SVA_CAN_NODE_SENDING
                  : (r->active_plan_id != 0U) ? SVA_CAN_NODE_ACTIVE
                  : (r->faults != 0U)         ? SVA_CAN_NODE_FAULT
                                              : SVA_CAN_NODE_IDLE);
    hb.u.heartbeat.active_plan_id = r->active_plan_id;
    {
        const uint16_t in_service = sva_can_live_in_service(&g_live);
        hb.u.heartbeat.uav_count = (uint8_t)((in_service > 255U) ? 255U : in_service);
        hb.u.heartbeat.target_count =
            (uint8_t)((g_live.live.mission.target_count > 255U) ? 255U
                                                                : g_live.live.mission.target_count);
    }
    hb.u.heartbeat.covered_count = r->covered_active;
    hb.u.heartbeat.faults = (uint8_t)(r->faults & SVA_CAN_FAULT_MASK);
    if ((sva_can_encode(&hb, &hf) == SVA_CAN_OK) && (tp->send(tp->ctx, &hf) == SVA_CAN_OK)) {
        r->hb_counter = (uint8_t)((r->hb_counter + 1U) & 0x0FU);
    }
    r->faults = (uint8_t)(r->faults & (uint8_t)~SVA_CAN_FAULT_RX_ERRORS);  // per heartbeat period
    r->last_hb = t;
}

// Sends the first plan, then serves the bus until a signal, a halt, --exit-after-acks
// or --max-runtime-ms. Returns the exit status.
static int run_loop(const node_options_t* o, node_run_t* r, sva_can_transport_t* tp,
                    const sva_can_socketcan_t* sock)
{
    memset(r, 0, sizeof *r);
    r->prev_state = SVA_CAN_TX_IDLE;
    g_tp = tp;
    r->t0 = now_ms();
    r->last_hb = r->t0 - SVA_CAN_HEARTBEAT_PERIOD_MS;  // first heartbeat at once
    r->faults |= send_plan(r->t0, o->print);

    while (!g_stop) {
        struct pollfd pfd;
        uint32_t t;
        pfd.fd = sock->fd;
        pfd.events = POLLIN;
        pfd.revents = 0;
        if ((poll(&pfd, 1, 10) < 0) && (errno != EINTR)) {
            fprintf(stderr, "sva_can_node: error: poll: %s\n", strerror(errno));
            return 1;
        }
        t = now_ms();
        drain_bus(r, tp, sock, t);
        if (!replan_settled(r, o, t)) {
            r->halted = true;
            return 1;
        }
        if (sva_can_sender_poll(&g_sender, t) != SVA_CAN_OK) {
            r->faults |= SVA_CAN_FAULT_TX_ERRORS;
        }
        watch_transfer(r);
        heartbeat(r, tp, t);
        if ((o->exit_after_acks != 0U) && (r->acks >= o->exit_after_acks)) {
            break;
        }
        if ((o->max_runtime_ms != 0U) && (elapsed(t, r->t0) >= o->max_runtime_ms)) {
            fprintf(stderr, "sva_can_node: --max-runtime-ms %lu reached\n",
                    (unsigned long)o->max_runtime_ms);
            return (o->exit_after_acks != 0U) ? 1 : 0;  // asked for ACKs that never came
        }
    }
    return 0;
}

// Aborts a transfer in flight (unless halted), prints the exit line, closes the bus
// and the journal.
static void shut_down(const node_run_t* r, sva_can_socketcan_t* sock)
{
    if (!r->halted &&
        (sva_can_sender_abort(&g_sender, SVA_CAN_ABORT_SHUTDOWN, now_ms()) != SVA_CAN_OK)) {
        fprintf(stderr, "sva_can_node: could not send ABORT on shutdown\n");
    }
    fprintf(stderr,
            "sva_can_node: exit: %lu frames sent, %lu acks, %lu nacks, %lu rejected flight-stack "
            "frames, %lu events applied, %lu refused, %lu replans (%lu unchanged)\n",
            (unsigned long)g_sender.stats.frames_sent, (unsigned long)r->acks,
            (unsigned long)g_sender.stats.nacks, (unsigned long)r->rx_rejected,
            (unsigned long)g_live.stats.events_applied, (unsigned long)g_live.stats.events_refused,
            (unsigned long)g_live.stats.replans, (unsigned long)g_live.stats.unchanged);
    sva_can_socketcan_close(sock);
    sva_can_state_close(&g_state);
}

int main(int argc, char** argv)
{
    node_options_t opt;
    node_run_t run;
    sva_can_socketcan_t sock;
    sva_can_transport_t tp;
    char name[128];
    char shown_name[SVA_TEXT_ESCAPED_SIZE(sizeof name)];
    char shown_arg[SHOWN_SIZE];
    int rc = parse_options(argc, argv, &opt);
    if (rc >= 0) {
        return rc;
    }
    rc = open_state(&opt, name, sizeof name);
    if (rc != 0) {
        return rc;
    }
    rc = open_transport(&opt, &sock, &tp);
    if (rc != 0) {
        return rc;
    }
    fprintf(stderr, "sva_can_node: mission \"%s\" (%u UAVs, %u targets) on %s, algorithm %s\n",
            sva_text_escape(shown_name, sizeof shown_name, name), g_mission.uav_count,
            g_mission.target_count, sva_text_escape(shown_arg, sizeof shown_arg, opt.iface),
            sva_algorithm_name(opt.algo));
    rc = run_loop(&opt, &run, &tp, &sock);
    shut_down(&run, &sock);
    return rc;
}
