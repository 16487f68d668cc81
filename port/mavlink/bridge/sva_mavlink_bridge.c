// sva_mavlink_bridge: sva_node's plans as MAVLink missions, and the vehicles' telemetry
// as reports (docs/mavlink.md). Reads the options, opens a link per vehicle
// (--vehicle UAV_ID=udp:HOST:PORT[:SYSID] or tcp:...), subscribes to the plans, then
// loops: LCM messages, each vehicle's link, upload results and link events printed,
// reports published.
#include <poll.h>
#include <signal.h>
#include <stdio.h>
#include <string.h>

#include "bridge.h"

/// The loop wakes at least this often (sva_mavlink_vehicle_service wants <= 100 ms).
#define LOOP_WAIT_MS 50

static volatile sig_atomic_t stop_requested;
static void on_signal(int sig)
{
    (void)sig;
    stop_requested = 1;
}

static void run(lcm_t* lcm)
{
    int wait_ms = LOOP_WAIT_MS;
    while (!stop_requested) {
        struct pollfd fds[BRIDGE_MAX_VEHICLES + 1];
        fds[0].fd = lcm_get_fileno(lcm);
        fds[0].events = POLLIN;
        for (size_t k = 0; k < bridge_slot_count; k++) {
            fds[k + 1].fd = bridge_slots[k].link.fd;  // -1 (ignored) while a TCP link is down
            fds[k + 1].events = POLLIN;
        }
        int rc = poll(fds, (nfds_t)(bridge_slot_count + 1), wait_ms);
        if (rc > 0 && (fds[0].revents & POLLIN) != 0) {
            if (lcm_handle(lcm) != 0) {
                fprintf(stderr, "sva_mavlink_bridge: lcm_handle failed\n");
                break;
            }
        }
        int64_t now = sva_mavlink_now_ms();
        bridge_vehicles_service(now);
        int64_t until_report = bridge_reports_service(lcm, now);
        wait_ms =
            (until_report >= 0 && until_report < LOOP_WAIT_MS) ? (int)until_report : LOOP_WAIT_MS;
    }
}

int main(int argc, char** argv)
{
    static bridge_options_t options;
    bridge_parse_t parsed = bridge_options_parse(argc, argv, &options);
    if (parsed != BRIDGE_RUN) {
        return parsed == BRIDGE_HELP ? 0 : 2;
    }
    if (!bridge_vehicles_open(&options)) {
        return 2;
    }
    lcm_t* lcm = lcm_create(options.url);
    if (lcm == NULL) {
        fprintf(stderr, "sva_mavlink_bridge: error: lcm_create(\"%.200s\") failed\n", options.url);
        return 1;
    }
    if (!bridge_plans_subscribe(lcm, &options)) {
        lcm_destroy(lcm);
        return 1;
    }
    bridge_reports_configure(&options);
    if ((signal(SIGINT, on_signal) == SIG_ERR) || (signal(SIGTERM, on_signal) == SIG_ERR)) {
        fprintf(stderr, "sva_mavlink_bridge: error: cannot catch SIGINT and SIGTERM\n");
        bridge_vehicles_close();
        lcm_destroy(lcm);
        return 1;
    }
    printf("sva_mavlink_bridge: %zu vehicles, listening on %sFLEET, MISSION, PLAN, REPLAN; "
           "reports on %sREPORT every %ld ms while a plan is held\n",
           bridge_slot_count, options.prefix, options.prefix, options.report_ms);
    fflush(stdout);
    run(lcm);
    bridge_vehicles_close();
    bridge_reports_release();
    lcm_destroy(lcm);
    printf("sva_mavlink_bridge: stopped\n");
    return 0;
}
