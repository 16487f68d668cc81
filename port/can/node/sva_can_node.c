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
    if (sva_can_frame_encode(&g_frame, g_frame_counter, out) != SVA_CAN_OK) {
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
    char* end = NULL;
    unsigned long v;
    errno = 0;
    v = strtoul(s, &end, 10);
    if ((errno != 0) || (end == s) || (*end != '\0') || (v > 0x7FFFFFFFUL) || (s[0] == '-')) {
        char shown[SHOWN_SIZE];
        fprintf(stderr,
                "sva_can_node: error: %s: must be an integer in [0, 2147483647], got \"%s\"\n", opt,
                sva_text_escape(shown, sizeof shown, s));
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

int main(int argc, char** argv)
{
    const char* iface = "vcan0";
    const char* mission_path = NULL;
    const char* algo_name = "sva";
    const char* algo_option = "--algo";  // as the user spelled it, for its error line
    sva_algorithm_t algo;
    uint32_t settle_ms = 200U;
    uint32_t exit_after_acks = 0U;
    uint32_t max_runtime_ms = 0U;
    int print = 0;
    const char* state_dir = NULL;
    bool state_reset = false;
    bool halted = false;
    int i;
    char err[256];
    char name[128];
    char shown_name[SVA_TEXT_ESCAPED_SIZE(sizeof name)];
    char shown_arg[SHOWN_SIZE];
    sva_can_socketcan_t sock;
    sva_can_transport_t tp;
    sva_can_status_t cst;
    struct sigaction sa;
    uint32_t t0;
    uint32_t last_hb;
    uint32_t track_tolerance = SVA_CAN_LIVE_TRACK_TOLERANCE;
    uint16_t active_plan_id = 0U;
    uint8_t hb_counter = 0U;
    uint8_t faults = 0U;
    uint8_t covered_active = 0U;
    uint32_t acks = 0U;
    uint32_t rx_rejected = 0U;
    int has_last_counter[3] = {0, 0, 0};
    uint8_t last_counter[3] = {0U, 0U, 0U};
    sva_can_tx_state_t prev_state = SVA_CAN_TX_IDLE;
    int rc = 0;

    for (i = 1; i < argc; ++i) {
        const char* a = argv[i];
        char shown[SHOWN_SIZE];
        const char* v = (i + 1 < argc) ? argv[i + 1] : NULL;
        if (strcmp(a, "--print-plans") == 0) {
            print = 1;
            continue;
        }
        if (strcmp(a, "--state-reset") == 0) {
            state_reset = true;
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
            iface = v;
        } else if (strcmp(a, "--mission") == 0) {
            mission_path = v;
        } else if ((strcmp(a, "--algo") == 0) || (strcmp(a, "--algorithm") == 0)) {
            algo_option = a;
            algo_name = v;
        } else if (strcmp(a, "--state-dir") == 0) {
            state_dir = v;
        } else if (strcmp(a, "--settle-ms") == 0) {
            if (parse_u32(v, a, &settle_ms) != 0) {
                return 2;
            }
        } else if (strcmp(a, "--track-tolerance") == 0) {
            if (parse_u32(v, a, &track_tolerance) != 0) {
                return 2;
            }
        } else if (strcmp(a, "--exit-after-acks") == 0) {
            if (parse_u32(v, a, &exit_after_acks) != 0) {
                return 2;
            }
        } else if (strcmp(a, "--max-runtime-ms") == 0) {
            if (parse_u32(v, a, &max_runtime_ms) != 0) {
                return 2;
            }
        } else {
            fprintf(stderr, "sva_can_node: error: unknown option %s\n",
                    sva_text_escape(shown, sizeof shown, a));
            usage(stderr);
            return 2;
        }
    }
    if (mission_path == NULL) {
        fprintf(stderr, "sva_can_node: error: --mission: missing required option\n");
        usage(stderr);
        return 2;
    }
    if (state_reset && (state_dir == NULL)) {
        fprintf(stderr, "sva_can_node: error: --state-reset needs --state-dir\n");
        return 2;
    }
    if (sva_algorithm_from_name(algo_name, &algo) != SVA_OK) {
        fprintf(stderr,
                "sva_can_node: error: %s: unknown algorithm \"%s\" (sva, ga, hga, bfa, flow)\n",
                algo_option, sva_text_escape(shown_arg, sizeof shown_arg, algo_name));
        return 2;
    }
    if (sva_can_mission_load_frame(mission_path, &g_mission, name, sizeof name, &g_frame,
                                   &g_has_frame, err, sizeof err) != 0) {
        fprintf(stderr, "sva_can_node: error: %s: %s\n",
                sva_text_escape(shown_arg, sizeof shown_arg, mission_path), err);
        return 1;
    }
    g_live.log = stderr;
    g_live.track_tolerance_cells = (int32_t)track_tolerance;
    if (sva_can_live_start(&g_live, &g_mission, algo, err, sizeof err) != 0) {
        fprintf(stderr, "sva_can_node: error: %s\n", err);
        return 1;
    }
    // The journal is replayed before the node hears the bus.
    if (state_dir != NULL) {
        const int src = sva_can_state_open(&g_state, state_dir, state_reset, &g_live, &g_mission);
        if (src != 0) {
            sva_can_state_close(&g_state);
            return src;
        }
    }
    cst = sva_can_socketcan_open(&sock, iface);
    if (cst != SVA_CAN_OK) {
        fprintf(stderr, "sva_can_node: error: --iface %s: %s%s%s\n",
                sva_text_escape(shown_arg, sizeof shown_arg, iface),
                (cst == SVA_CAN_ERR_NAME) ? "interface name empty or longer than IFNAMSIZ - 1 (15)"
                                          : "cannot open",
                (sock.last_errno != 0) ? ": " : "",
                (sock.last_errno != 0) ? strerror(sock.last_errno) : "");
        sva_can_state_close(&g_state);
        return 1;
    }
    if ((sva_can_socketcan_transport(&sock, &tp) != SVA_CAN_OK) ||
        (sva_can_sender_init(&g_sender, &tp, NULL) != SVA_CAN_OK)) {
        fprintf(stderr, "sva_can_node: error: transport setup failed\n");
        sva_can_socketcan_close(&sock);
        sva_can_state_close(&g_state);
        return 1;
    }
    memset(&sa, 0, sizeof sa);
    sa.sa_handler = on_signal;
    if ((sigemptyset(&sa.sa_mask) != 0) || (sigaction(SIGINT, &sa, NULL) != 0) ||
        (sigaction(SIGTERM, &sa, NULL) != 0)) {
        fprintf(stderr, "sva_can_node: error: sigaction: %s\n", strerror(errno));
        sva_can_socketcan_close(&sock);
        sva_can_state_close(&g_state);
        return 1;
    }
    fprintf(stderr, "sva_can_node: mission \"%s\" (%u UAVs, %u targets) on %s, algorithm %s\n",
            sva_text_escape(shown_name, sizeof shown_name, name), g_mission.uav_count,
            g_mission.target_count, sva_text_escape(shown_arg, sizeof shown_arg, iface),
            sva_algorithm_name(algo));

    g_tp = &tp;
    t0 = now_ms();
    last_hb = t0 - SVA_CAN_HEARTBEAT_PERIOD_MS;  // first heartbeat at once
    faults |= send_plan(t0, print);

    while (!g_stop) {
        struct pollfd pfd;
        sva_can_frame_t f;
        uint32_t t;
        pfd.fd = sock.fd;
        pfd.events = POLLIN;
        pfd.revents = 0;
        if ((poll(&pfd, 1, 10) < 0) && (errno != EINTR)) {
            fprintf(stderr, "sva_can_node: error: poll: %s\n", strerror(errno));
            rc = 1;
            break;
        }
        t = now_ms();
        for (;;) {
            sva_can_msg_t m;
            sva_can_status_t st = tp.recv(tp.ctx, &f);
            if (st == SVA_CAN_AGAIN) {
                break;
            }
            if (st != SVA_CAN_OK) {
                fprintf(stderr, "sva_can_node: error: read: %s\n", strerror(sock.last_errno));
                faults |= SVA_CAN_FAULT_TX_ERRORS;
                break;
            }
            st = sva_can_sender_on_frame(&g_sender, &f, t);
            if (st != SVA_CAN_IGNORED) {
                if (st < 0) {
                    faults |= SVA_CAN_FAULT_RX_ERRORS;
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
                ++rx_rejected;
                faults |= SVA_CAN_FAULT_RX_ERRORS;
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
                if (has_last_counter[k] && (m.counter == last_counter[k])) {
                    ++rx_rejected;
                    faults |= SVA_CAN_FAULT_RX_ERRORS;
                    continue;
                }
                has_last_counter[k] = 1;
                last_counter[k] = m.counter;
            }
            if (sva_can_live_on_msg(&g_live, &m, t) == SVA_CAN_LIVE_HALTED) {
                break;
            }
        }
        {
            const int changed =
                g_live.halted ? SVA_CAN_LIVE_HALTED : sva_can_live_poll(&g_live, t, settle_ms);
            if (changed == SVA_CAN_LIVE_HALTED) {
                // The journal could not keep an input: nothing is answered for it. Exit as
                // a crash would; a restart resumes from the last record kept.
                char said[SHOWN_SIZE];
                fprintf(stderr, "sva_can_node: error: journal: %s: stopping without an answer\n",
                        sva_text_escape(said, sizeof said, g_state.journal.message));
                halted = true;
                rc = 1;
                break;
            }
            if (changed < 0) {
                faults |= SVA_CAN_FAULT_PLAN_FAILED;
            } else if (changed > 0) {
                faults = (uint8_t)(faults & (uint8_t)~SVA_CAN_FAULT_PLAN_FAILED);
                faults |= send_plan(t, print);
            }
        }
        if (sva_can_sender_poll(&g_sender, t) != SVA_CAN_OK) {
            faults |= SVA_CAN_FAULT_TX_ERRORS;
        }
        if (g_sender.state != prev_state) {
            if (g_sender.state == SVA_CAN_TX_DONE) {
                active_plan_id = g_sender.priv.plan.plan_id;
                covered_active = g_live.covered;
                faults = (uint8_t)(faults & (uint8_t)~SVA_CAN_FAULT_TRANSFER_FAILED);
                ++acks;
                fprintf(stderr, "sva_can_node: plan %u acknowledged (%lu frames sent so far)\n",
                        active_plan_id, (unsigned long)g_sender.stats.frames_sent);
            } else if (g_sender.state == SVA_CAN_TX_FAILED) {
                faults |= SVA_CAN_FAULT_TRANSFER_FAILED;
                fprintf(stderr, "sva_can_node: plan %u aborted (reason %u)%s\n",
                        g_sender.priv.plan.plan_id, g_sender.last_abort_reason,
                        (g_sender.last_nack == SVA_CAN_ACK_BAD_VERSION)
                            ? ": the bridge refused the protocol version (NACK BAD_VERSION)"
                            : "");
            }
            prev_state = g_sender.state;
        }
        if (elapsed(t, last_hb) >= SVA_CAN_HEARTBEAT_PERIOD_MS) {
            sva_can_msg_t hb;
            sva_can_frame_t hf;
            hb.kind = SVA_CAN_MSG_HEARTBEAT;
            hb.counter = hb_counter;
            hb.u.heartbeat.state = (uint8_t)((g_sender.state == SVA_CAN_TX_SENDING ||
                                              g_sender.state == SVA_CAN_TX_WAIT_ACK)
                                                 ? SVA_CAN_NODE_SENDING
                                             : (active_plan_id != 0U) ? SVA_CAN_NODE_ACTIVE
                                             : (faults != 0U)         ? SVA_CAN_NODE_FAULT
                                                                      : SVA_CAN_NODE_IDLE);
            hb.u.heartbeat.active_plan_id = active_plan_id;
            {
                const uint16_t in_service = sva_can_live_in_service(&g_live);
                hb.u.heartbeat.uav_count = (uint8_t)((in_service > 255U) ? 255U : in_service);
                hb.u.heartbeat.target_count = (uint8_t)((g_live.live.mission.target_count > 255U)
                                                            ? 255U
                                                            : g_live.live.mission.target_count);
            }
            hb.u.heartbeat.covered_count = covered_active;
            hb.u.heartbeat.faults = (uint8_t)(faults & SVA_CAN_FAULT_MASK);
            if ((sva_can_encode(&hb, &hf) == SVA_CAN_OK) && (tp.send(tp.ctx, &hf) == SVA_CAN_OK)) {
                hb_counter = (uint8_t)((hb_counter + 1U) & 0x0FU);
            }
            faults = (uint8_t)(faults & (uint8_t)~SVA_CAN_FAULT_RX_ERRORS);  // per heartbeat period
            last_hb = t;
        }
        if ((exit_after_acks != 0U) && (acks >= exit_after_acks)) {
            break;
        }
        if ((max_runtime_ms != 0U) && (elapsed(t, t0) >= max_runtime_ms)) {
            fprintf(stderr, "sva_can_node: --max-runtime-ms %lu reached\n",
                    (unsigned long)max_runtime_ms);
            rc = (exit_after_acks != 0U) ? 1 : 0;  // asked for ACKs that never came
            break;
        }
    }
    if (!halted &&
        (sva_can_sender_abort(&g_sender, SVA_CAN_ABORT_SHUTDOWN, now_ms()) != SVA_CAN_OK)) {
        fprintf(stderr, "sva_can_node: could not send ABORT on shutdown\n");
    }
    fprintf(stderr,
            "sva_can_node: exit: %lu frames sent, %lu acks, %lu nacks, %lu rejected flight-stack "
            "frames, %lu events applied, %lu refused, %lu replans (%lu unchanged)\n",
            (unsigned long)g_sender.stats.frames_sent, (unsigned long)acks,
            (unsigned long)g_sender.stats.nacks, (unsigned long)rx_rejected,
            (unsigned long)g_live.stats.events_applied, (unsigned long)g_live.stats.events_refused,
            (unsigned long)g_live.stats.replans, (unsigned long)g_live.stats.unchanged);
    sva_can_socketcan_close(&sock);
    sva_can_state_close(&g_state);
    return rc;
}
