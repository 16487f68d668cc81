// sva_can_node: the planner on a CAN bus. Reads the mission's targets and initial fleet
// from a SPEC section 3 mission file, listens for vehicle status (SVA_VEHICLE_STATUS,
// SVA_VEHICLE_FUEL) on a SocketCAN interface, replans with sva_plan() when the fleet
// state changes, sends each plan with the protocol of port/can/sva.dbc and sends the
// heartbeat every second. SIGINT/SIGTERM: aborts an in-flight transfer, exits 0.
//
// Usage: sva_can_node --mission FILE [--iface vcan0] [--algorithm sva]
//                     [--settle-ms 200] [--exit-after-acks N] [--max-runtime-ms N]
//                     [--print-plans]
#define _POSIX_C_SOURCE 200809L

#include <errno.h>
#include <poll.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

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
        return 0u;
    }
    return (uint32_t)((uint64_t)ts.tv_sec * 1000u + (uint64_t)ts.tv_nsec / 1000000u);
}

typedef struct {
    uint8_t state;  // SVA_CAN_VEHICLE_*
} vehicle_extra_t;

// Everything the node owns: static, no heap (the planner state is large).
static sva_mission_t g_mission;  // targets and fleet state as last heard
static vehicle_extra_t g_extra[SVA_MAX_UAVS];
static sva_mission_t g_planning;  // what sva_plan sees (unavailable UAVs left out)
static sva_planner_t g_planner;
static sva_plan_t g_plan;
static sva_can_plan_t g_wire;
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
        return 0u;
    }
    if (sva_can_frame_encode(&g_frame, g_frame_counter, out) != SVA_CAN_OK) {
        return SVA_CAN_FAULT_TX_ERRORS;
    }
    g_frame_counter = (uint8_t)((g_frame_counter + SVA_CAN_MISSION_FRAME_PARTS) & 15u);
    for (p = 0; p < SVA_CAN_MISSION_FRAME_PARTS; ++p) {
        const sva_can_status_t st = g_tp->send(g_tp->ctx, &out[p]);
        if (st != SVA_CAN_OK) {
            fprintf(stderr, "sva_can_node: sending the mission frame: %s\n",
                    sva_can_status_name(st));
            return SVA_CAN_FAULT_TX_ERRORS;
        }
    }
    return 0u;
}

static uint32_t elapsed(uint32_t now, uint32_t then)
{
    return (uint32_t)(now - then);  // modulo 2^32: right across the wrap-around
}

static void usage(void)
{
    fprintf(stderr,
            "usage: sva_can_node --mission FILE [--iface NAME] [--algorithm sva|ga|hga|bfa|flow]\n"
            "                    [--settle-ms N] [--exit-after-acks N] [--max-runtime-ms N] "
            "[--print-plans]\n");
}

static int parse_u32(const char* s, const char* opt, uint32_t* out)
{
    char* end = NULL;
    unsigned long v;
    errno = 0;
    v = strtoul(s, &end, 10);
    if ((errno != 0) || (end == s) || (*end != '\0') || (v > 0x7FFFFFFFul) || (s[0] == '-')) {
        char shown[SHOWN_SIZE];
        fprintf(stderr, "sva_can_node: %s: must be an integer in [0, 2147483647], got \"%s\"\n",
                opt, sva_text_escape(shown, sizeof shown, s));
        return -1;
    }
    *out = (uint32_t)v;
    return 0;
}

// Plans the current fleet state; on success starts sending. Returns the fault bits.
static uint8_t replan(sva_algorithm_t algo, uint16_t plan_id, uint32_t t, int print,
                      uint8_t* covered)
{
    sva_diag_t diag;
    uint16_t i;
    char msg[256];
    sva_status_t st;
    sva_can_status_t cst;
    g_planning = g_mission;
    g_planning.uav_count = 0;
    for (i = 0; i < g_mission.uav_count; ++i) {
        if (g_extra[i].state != SVA_CAN_VEHICLE_UNAVAILABLE) {
            g_planning.uavs[g_planning.uav_count++] = g_mission.uavs[i];
        }
    }
    sva_diag_clear(&diag);
    st = sva_plan(&g_planner, &g_planning, algo, &g_plan, &diag);
    if (st != SVA_OK) {
        (void)sva_diag_format(&diag, msg, sizeof msg);
        fprintf(stderr, "sva_can_node: plan %u failed (status %d): %s\n", plan_id, (int)st, msg);
        return (st == SVA_ERR_INVALID) ? SVA_CAN_FAULT_MISSION_INVALID : SVA_CAN_FAULT_PLAN_FAILED;
    }
    cst = sva_can_plan_from_core(&g_wire, &g_planning, &g_plan, plan_id);
    if (cst != SVA_CAN_OK) {
        fprintf(stderr,
                "sva_can_node: plan %u does not fit the wire (%s): more than SVA_CAN_MAX_ITEMS "
                "(%d) items?\n",
                plan_id, sva_can_status_name(cst), SVA_CAN_MAX_ITEMS);
        return SVA_CAN_FAULT_PLAN_FAILED;
    }
    *covered = (uint8_t)((g_plan.covered > 255u) ? 255u : g_plan.covered);
    fprintf(stderr,
            "sva_can_node: plan %u: %s %s, covered %u of %u, cost %lld, %u items, %u frames\n",
            plan_id, sva_algorithm_name(algo),
            (g_plan.status == SVA_PLAN_COMPLETE) ? "complete" : "partial", g_plan.covered,
            g_planning.target_count, (long long)g_plan.cost, g_wire.item_count,
            2u * g_wire.item_count + 2u);
    if (print) {
        sva_can_plan_print(&g_wire);
    }
    if (send_frame() != 0u) {
        return SVA_CAN_FAULT_TX_ERRORS;
    }
    cst = sva_can_sender_start(&g_sender, &g_wire, t);
    if ((cst != SVA_CAN_OK) && (cst != SVA_CAN_AGAIN)) {
        fprintf(stderr, "sva_can_node: sending plan %u: %s\n", plan_id, sva_can_status_name(cst));
        return SVA_CAN_FAULT_TX_ERRORS;
    }
    return 0u;
}

// Applies a vehicle frame to the fleet state. Returns 1 when something changed.
static int apply_vehicle(const sva_can_msg_t* m)
{
    const uint8_t id =
        (m->kind == SVA_CAN_MSG_VEHICLE_STATUS) ? m->u.vehicle.uav_id : m->u.fuel.uav_id;
    uint16_t i;
    sva_uav_t* u = NULL;
    for (i = 0; i < g_mission.uav_count; ++i) {
        if (g_mission.uavs[i].id == (int32_t)id) {
            u = &g_mission.uavs[i];
            break;
        }
    }
    if (u == NULL) {
        if (g_mission.uav_count >= SVA_MAX_UAVS) {
            fprintf(stderr, "sva_can_node: uav %u ignored: fleet full (SVA_MAX_UAVS %d)\n", id,
                    SVA_MAX_UAVS);
            return 0;
        }
        i = g_mission.uav_count++;
        u = &g_mission.uavs[i];
        u->id = id;
        u->x = g_mission.depot_x;
        u->y = g_mission.depot_y;
        u->fuel = 0;  // until its fuel frame arrives
        u->ready_at_ticks = 0;
        g_extra[i].state = SVA_CAN_VEHICLE_UNKNOWN;
    }
    if (m->kind == SVA_CAN_MSG_VEHICLE_STATUS) {
        if ((u->x == m->u.vehicle.x) && (u->y == m->u.vehicle.y) &&
            (g_extra[i].state == m->u.vehicle.state)) {
            return 0;
        }
        u->x = m->u.vehicle.x;
        u->y = m->u.vehicle.y;
        g_extra[i].state = m->u.vehicle.state;
        return 1;
    }
    {
        // Fuel above the core's bound is clamped to it (SVA_MAX_FUEL), so validation holds.
        const int32_t fuel = (m->u.fuel.fuel > (uint32_t)SVA_MAX_FUEL) ? (int32_t)SVA_MAX_FUEL
                                                                       : (int32_t)m->u.fuel.fuel;
        if (u->fuel == fuel) {
            return 0;
        }
        u->fuel = fuel;
        return 1;
    }
}

int main(int argc, char** argv)
{
    const char* iface = "vcan0";
    const char* mission_path = NULL;
    const char* algo_name = "sva";
    sva_algorithm_t algo;
    uint32_t settle_ms = 200u;
    uint32_t exit_after_acks = 0u;
    uint32_t max_runtime_ms = 0u;
    int print = 0;
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
    uint32_t last_change = 0u;
    int dirty = 0;
    uint16_t plan_id = 0u;
    uint16_t active_plan_id = 0u;
    uint8_t hb_counter = 0u;
    uint8_t faults = 0u;
    uint8_t covered = 0u;
    uint8_t covered_active = 0u;
    uint32_t acks = 0u;
    uint32_t rx_rejected = 0u;
    int has_last_counter[2] = {0, 0};
    uint8_t last_counter[2] = {0u, 0u};
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
        if (strcmp(a, "--help") == 0) {
            usage();
            return 0;
        }
        if (v == NULL) {
            fprintf(stderr, "sva_can_node: %s: missing value\n",
                    sva_text_escape(shown, sizeof shown, a));
            usage();
            return 2;
        }
        ++i;
        if (strcmp(a, "--iface") == 0) {
            iface = v;
        } else if (strcmp(a, "--mission") == 0) {
            mission_path = v;
        } else if (strcmp(a, "--algorithm") == 0) {
            algo_name = v;
        } else if (strcmp(a, "--settle-ms") == 0) {
            if (parse_u32(v, a, &settle_ms) != 0)
                return 2;
        } else if (strcmp(a, "--exit-after-acks") == 0) {
            if (parse_u32(v, a, &exit_after_acks) != 0)
                return 2;
        } else if (strcmp(a, "--max-runtime-ms") == 0) {
            if (parse_u32(v, a, &max_runtime_ms) != 0)
                return 2;
        } else {
            fprintf(stderr, "sva_can_node: unknown option %s\n",
                    sva_text_escape(shown, sizeof shown, a));
            usage();
            return 2;
        }
    }
    if (mission_path == NULL) {
        fprintf(stderr, "sva_can_node: --mission: missing required option\n");
        usage();
        return 2;
    }
    if (sva_algorithm_from_name(algo_name, &algo) != SVA_OK) {
        fprintf(stderr,
                "sva_can_node: --algorithm: unknown algorithm \"%s\" (sva, ga, hga, bfa, flow)\n",
                sva_text_escape(shown_arg, sizeof shown_arg, algo_name));
        return 2;
    }
    if (sva_can_mission_load_frame(mission_path, &g_mission, name, sizeof name, &g_frame,
                                   &g_has_frame, err, sizeof err) != 0) {
        fprintf(stderr, "sva_can_node: %s: %s\n",
                sva_text_escape(shown_arg, sizeof shown_arg, mission_path), err);
        return 1;
    }
    for (i = 0; i < (int)g_mission.uav_count; ++i) {
        g_extra[i].state = SVA_CAN_VEHICLE_AVAILABLE;
    }
    if (sva_planner_init(&g_planner) != SVA_OK) {
        fprintf(stderr, "sva_can_node: planner init failed\n");
        return 1;
    }
    cst = sva_can_socketcan_open(&sock, iface);
    if (cst != SVA_CAN_OK) {
        fprintf(stderr, "sva_can_node: --iface %s: %s%s%s\n",
                sva_text_escape(shown_arg, sizeof shown_arg, iface),
                (cst == SVA_CAN_ERR_NAME) ? "interface name empty or longer than IFNAMSIZ - 1 (15)"
                                          : "cannot open",
                (sock.last_errno != 0) ? ": " : "",
                (sock.last_errno != 0) ? strerror(sock.last_errno) : "");
        return 1;
    }
    if ((sva_can_socketcan_transport(&sock, &tp) != SVA_CAN_OK) ||
        (sva_can_sender_init(&g_sender, &tp, NULL) != SVA_CAN_OK)) {
        fprintf(stderr, "sva_can_node: transport setup failed\n");
        sva_can_socketcan_close(&sock);
        return 1;
    }
    memset(&sa, 0, sizeof sa);
    sa.sa_handler = on_signal;
    if ((sigemptyset(&sa.sa_mask) != 0) || (sigaction(SIGINT, &sa, NULL) != 0) ||
        (sigaction(SIGTERM, &sa, NULL) != 0)) {
        fprintf(stderr, "sva_can_node: sigaction: %s\n", strerror(errno));
        sva_can_socketcan_close(&sock);
        return 1;
    }
    fprintf(stderr, "sva_can_node: mission \"%s\" (%u UAVs, %u targets) on %s, algorithm %s\n",
            sva_text_escape(shown_name, sizeof shown_name, name), g_mission.uav_count,
            g_mission.target_count, sva_text_escape(shown_arg, sizeof shown_arg, iface),
            sva_algorithm_name(algo));

    g_tp = &tp;
    t0 = now_ms();
    last_hb = t0 - SVA_CAN_HEARTBEAT_PERIOD_MS;  // first heartbeat at once
    plan_id = 1u;
    faults |= replan(algo, plan_id, t0, print, &covered);

    while (!g_stop) {
        struct pollfd pfd;
        sva_can_frame_t f;
        uint32_t t;
        pfd.fd = sock.fd;
        pfd.events = POLLIN;
        pfd.revents = 0;
        if ((poll(&pfd, 1, 10) < 0) && (errno != EINTR)) {
            fprintf(stderr, "sva_can_node: poll: %s\n", strerror(errno));
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
                fprintf(stderr, "sva_can_node: read: %s\n", strerror(sock.last_errno));
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
            if ((f.id != SVA_CAN_ID_VEHICLE_STATUS) && (f.id != SVA_CAN_ID_VEHICLE_FUEL)) {
                continue;
            }
            st = sva_can_decode(&f, &m);
            if (st == SVA_CAN_IGNORED) {
                continue;
            }
            if (st != SVA_CAN_OK) {
                ++rx_rejected;
                faults |= SVA_CAN_FAULT_RX_ERRORS;
                fprintf(stderr, "sva_can_node: rejected vehicle frame 0x%03lX: %s\n",
                        (unsigned long)f.id, sva_can_status_name(st));
                continue;
            }
            {
                // A repeated counter is a stale or duplicated frame: rejected. A jump is
                // lost frames: the state still applies (latest state wins).
                const int k = (m.kind == SVA_CAN_MSG_VEHICLE_STATUS) ? 0 : 1;
                if (has_last_counter[k] && (m.counter == last_counter[k])) {
                    ++rx_rejected;
                    faults |= SVA_CAN_FAULT_RX_ERRORS;
                    continue;
                }
                has_last_counter[k] = 1;
                last_counter[k] = m.counter;
            }
            if (apply_vehicle(&m)) {
                dirty = 1;
                last_change = t;
            }
        }
        if (dirty && (elapsed(t, last_change) >= settle_ms)) {
            dirty = 0;
            plan_id = (uint16_t)((plan_id == 65535u) ? 1u : (plan_id + 1u));
            faults = (uint8_t)(faults & (uint8_t) ~(SVA_CAN_FAULT_MISSION_INVALID |
                                                    SVA_CAN_FAULT_PLAN_FAILED));
            faults |= replan(algo, plan_id, t, print, &covered);
        }
        if (sva_can_sender_poll(&g_sender, t) != SVA_CAN_OK) {
            faults |= SVA_CAN_FAULT_TX_ERRORS;
        }
        if (g_sender.state != prev_state) {
            if (g_sender.state == SVA_CAN_TX_DONE) {
                active_plan_id = g_sender.priv.plan.plan_id;
                covered_active = covered;
                faults = (uint8_t)(faults & (uint8_t)~SVA_CAN_FAULT_TRANSFER_FAILED);
                ++acks;
                fprintf(stderr, "sva_can_node: plan %u acknowledged (%lu frames sent so far)\n",
                        active_plan_id, (unsigned long)g_sender.stats.frames_sent);
            } else if (g_sender.state == SVA_CAN_TX_FAILED) {
                faults |= SVA_CAN_FAULT_TRANSFER_FAILED;
                fprintf(stderr, "sva_can_node: plan %u aborted (reason %u)\n",
                        g_sender.priv.plan.plan_id, g_sender.last_abort_reason);
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
                                             : (active_plan_id != 0u) ? SVA_CAN_NODE_ACTIVE
                                             : (faults != 0u)         ? SVA_CAN_NODE_FAULT
                                                                      : SVA_CAN_NODE_IDLE);
            hb.u.heartbeat.active_plan_id = active_plan_id;
            hb.u.heartbeat.uav_count =
                (uint8_t)((g_mission.uav_count > 255u) ? 255u : g_mission.uav_count);
            hb.u.heartbeat.target_count =
                (uint8_t)((g_mission.target_count > 255u) ? 255u : g_mission.target_count);
            hb.u.heartbeat.covered_count = covered_active;
            hb.u.heartbeat.faults = (uint8_t)(faults & SVA_CAN_FAULT_MASK);
            if ((sva_can_encode(&hb, &hf) == SVA_CAN_OK) && (tp.send(tp.ctx, &hf) == SVA_CAN_OK)) {
                hb_counter = (uint8_t)((hb_counter + 1u) & 0x0Fu);
            }
            faults = (uint8_t)(faults & (uint8_t)~SVA_CAN_FAULT_RX_ERRORS);  // per heartbeat period
            last_hb = t;
        }
        if ((exit_after_acks != 0u) && (acks >= exit_after_acks)) {
            break;
        }
        if ((max_runtime_ms != 0u) && (elapsed(t, t0) >= max_runtime_ms)) {
            fprintf(stderr, "sva_can_node: --max-runtime-ms %lu reached\n",
                    (unsigned long)max_runtime_ms);
            rc = (exit_after_acks != 0u) ? 1 : 0;  // asked for ACKs that never came
            break;
        }
    }
    if (sva_can_sender_abort(&g_sender, SVA_CAN_ABORT_SHUTDOWN, now_ms()) != SVA_CAN_OK) {
        fprintf(stderr, "sva_can_node: could not send ABORT on shutdown\n");
    }
    fprintf(
        stderr,
        "sva_can_node: exit: %lu frames sent, %lu acks, %lu nacks, %lu rejected vehicle frames\n",
        (unsigned long)g_sender.stats.frames_sent, (unsigned long)acks,
        (unsigned long)g_sender.stats.nacks, (unsigned long)rx_rejected);
    sva_can_socketcan_close(&sock);
    return rc;
}
