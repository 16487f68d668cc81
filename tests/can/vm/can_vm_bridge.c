// The flight-side bridge stand-in for the VM test, on a real SocketCAN interface:
// receives plans with sva_can_receiver (ACKs them; refuses another protocol version),
// prints each applied plan as JSON, then sends the mission clock (TICK, MISSION_CLOCK)
// and reports UAV 1 unavailable (VEHICLE_STATUS) to make the node replan, and exits 0
// after the second applied plan once it has refused one BEGIN of another version.
// Exits 1 on any error or after 20 s.
#define _POSIX_C_SOURCE 200809L

#include <errno.h>
#include <poll.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "plan_print.h"
#include "sva/sva_can.h"
#include "sva/sva_can_transport.h"

static uint32_t now_ms(void)
{
    struct timespec ts;
    if (clock_gettime(CLOCK_MONOTONIC, &ts) != 0) {
        return 0u;
    }
    return (uint32_t)((uint64_t)ts.tv_sec * 1000u + (uint64_t)ts.tv_nsec / 1000000u);
}

static sva_can_receiver_t rx;

int main(int argc, char** argv)
{
    sva_can_socketcan_t sock;
    sva_can_transport_t tp;
    sva_can_status_t st;
    uint32_t t0;
    int applied = 0;
    unsigned heartbeats = 0;
    if (argc != 3) {
        fprintf(stderr, "usage: can_vm_bridge IFACE TICK\n");
        return 2;
    }
    st = sva_can_socketcan_open(&sock, argv[1]);
    if (st != SVA_CAN_OK) {
        fprintf(stderr, "can_vm_bridge: open %s: %s (%s)\n", argv[1], sva_can_status_name(st),
                strerror(sock.last_errno));
        return 1;
    }
    if ((sva_can_socketcan_transport(&sock, &tp) != SVA_CAN_OK) ||
        (sva_can_receiver_init(&rx, &tp, 2000) != SVA_CAN_OK)) {
        return 1;
    }
    t0 = now_ms();
    while ((uint32_t)(now_ms() - t0) < 20000u) {
        struct pollfd p;
        sva_can_frame_t f;
        p.fd = sock.fd;
        p.events = POLLIN;
        p.revents = 0;
        if ((poll(&p, 1, 10) < 0) && (errno != EINTR)) {
            perror("poll");
            return 1;
        }
        while ((st = tp.recv(tp.ctx, &f)) == SVA_CAN_OK) {
            sva_can_msg_t m;
            if ((f.id == SVA_CAN_ID_HEARTBEAT) && (sva_can_decode(&f, &m) == SVA_CAN_OK)) {
                ++heartbeats;
            }
            st = sva_can_receiver_on_frame(&rx, &f, now_ms());
            if (st < 0) {
                fprintf(stderr, "can_vm_bridge: rejected frame 0x%03lX: %s\n", (unsigned long)f.id,
                        sva_can_status_name(st));
            }
            if (st == SVA_CAN_APPLIED) {
                ++applied;
                sva_can_plan_print(&rx.active);
                if (applied == 1) {
                    sva_can_msg_t vs;
                    sva_can_frame_t vf;
                    vs.kind = SVA_CAN_MSG_MISSION_CLOCK;
                    vs.counter = 0;
                    vs.u.clock.tick = (uint32_t)strtoul(argv[2], NULL, 10);
                    if ((sva_can_encode(&vs, &vf) != SVA_CAN_OK) ||
                        (tp.send(tp.ctx, &vf) != SVA_CAN_OK)) {
                        fprintf(stderr, "can_vm_bridge: cannot send the mission clock\n");
                        return 1;
                    }
                    vs.kind = SVA_CAN_MSG_VEHICLE_STATUS;
                    vs.counter = 0;
                    vs.u.vehicle.state = SVA_CAN_VEHICLE_UNAVAILABLE;
                    vs.u.vehicle.uav_id = 1;
                    vs.u.vehicle.x = 0;
                    vs.u.vehicle.y = 0;
                    if ((sva_can_encode(&vs, &vf) != SVA_CAN_OK) ||
                        (tp.send(tp.ctx, &vf) != SVA_CAN_OK)) {
                        fprintf(stderr, "can_vm_bridge: cannot send vehicle status\n");
                        return 1;
                    }
                }
            }
        }
        if (st != SVA_CAN_AGAIN) {
            fprintf(stderr, "can_vm_bridge: read: %s\n", strerror(sock.last_errno));
            return 1;
        }
        if ((applied >= 2) && (rx.stats.bad_version >= 1)) {
            fprintf(stderr,
                    "can_vm_bridge: 2 plans applied, %u heartbeats heard, %lu frames rejected, "
                    "%lu of another protocol version\n",
                    heartbeats,
                    (unsigned long)(rx.stats.bad_crc + rx.stats.bad_dlc + rx.stats.counter_jumps +
                                    rx.stats.out_of_order + rx.stats.plan_crc_mismatch),
                    (unsigned long)rx.stats.bad_version);
            sva_can_socketcan_close(&sock);
            return 0;
        }
    }
    fprintf(stderr, "can_vm_bridge: timed out with %d plans applied\n", applied);
    return 1;
}
