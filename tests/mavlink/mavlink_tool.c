// Test harness of sva::mavlink without LCM: reads a frame and routes as text on stdin,
// prints the items the library builds and, for routes given a vehicle, uploads them
// (all vehicles at once) and prints one result line per vehicle; then, with `listen`,
// keeps the links up and prints each vehicle's telemetry and report.
//   frame LAT_E7 LON_E7 ALT_CM CELL_CM TICK_MS T0_MS
//   tpc TICKS_PER_CELL
//   route UAV_ID X Y READY_AT         (then its targets in visit order)
//   target ID X Y START END
//   vehicle UAV_ID=udp:HOST:PORT[:SYSID] or UAV_ID=tcp:HOST:PORT[:SYSID]
//                                     (a vehicle without a route only listens)
//   timeout MS RETRIES                (for the vehicles given after it)
//   ardupilot                         (a home item 0 first: sva_mavlink_prepend_home)
//   cruise M_S                        (the speed commanded, for the routes given after it)
//   listen MS [EVERY_MS]              (after the uploads: MS more, printing every EVERY_MS)
//   reportcfg HB_TIMEOUT_MS FUEL_CAPACITY
// Output: `item UAV SEQ COMMAND FRAME P1 P2 P3 P4 X Y Z`, `result UAV ok N` or
// `result UAV error MESSAGE`; listening: `link UAV connected|lost|failed TEXT`,
// `telemetry UAV key=value...`, `report UAV STATUS key=value...`. Exit 0 when every
// upload succeeded, 1 otherwise, 2 on bad input.
// With `parse` as the first line it tests the parser alone: then every line is
// `stream HEX` (bytes of a TCP stream) or `datagram HEX` (one UDP datagram), and it
// prints `msg SYSID COMPID MSGID SEQ` per frame parsed and `parser FRAMES DROPPED` at
// the end; `cell METRES CELL_CM` prints `cell N` (sva_mavlink_cell_of) or `cell none`.
#include <poll.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "sva/sva_mavlink.h"

#define MAX_ROUTES 8
#define LINE_SIZE  4096
#define WAIT_MS    50

static sva_mavlink_target_t targets[MAX_ROUTES][SVA_MAVLINK_MAX_ROUTE_TARGETS + 8];
static sva_mavlink_route_t routes[MAX_ROUTES];
static sva_mavlink_vehicle_t vehicles[MAX_ROUTES];
static sva_mavlink_item_t items[MAX_ROUTES][SVA_MAVLINK_MAX_ITEMS];
static size_t item_counts[MAX_ROUTES];
static bool has_vehicle[MAX_ROUTES];
static bool has_route[MAX_ROUTES];
static bool built[MAX_ROUTES];
static size_t nroutes;  // slots in use: routes, and vehicles without a route after them
static uint32_t said_connects[MAX_ROUTES];
static uint32_t said_drops[MAX_ROUTES];
static uint32_t said_failures[MAX_ROUTES];

static int hex_value(char c)
{
    if (c >= '0' && c <= '9') {
        return c - '0';
    }
    if (c >= 'a' && c <= 'f') {
        return c - 'a' + 10;
    }
    if (c >= 'A' && c <= 'F') {
        return c - 'A' + 10;
    }
    return -1;
}

// The parser alone: `stream HEX` and `datagram HEX` lines.
static int parse_mode(void)
{
    static sva_mavlink_parser_t parser;
    static char line[1 << 20];
    static uint8_t bytes[1 << 19];
    sva_mavlink_parser_reset(&parser);
    uint32_t frames = 0;
    uint32_t dropped = 0;
    while (fgets(line, sizeof line, stdin) != NULL) {
        double metres = 0.0;
        long long cell_cm = 0;
        if (sscanf(line, "cell %lf %lld", &metres, &cell_cm) == 2) {
            int32_t cell = 0;
            if (sva_mavlink_cell_of(metres, (int32_t)cell_cm, &cell)) {
                printf("cell %d\n", (int)cell);
            } else {
                printf("cell none\n");
            }
            continue;
        }
        bool datagram = strncmp(line, "datagram ", 9) == 0;
        if (!datagram && strncmp(line, "stream ", 7) != 0) {
            continue;
        }
        const char* h = line + (datagram ? 9 : 7);
        size_t n = 0;
        while (hex_value(h[0]) >= 0 && hex_value(h[1]) >= 0 && n < sizeof bytes) {
            bytes[n++] = (uint8_t)(hex_value(h[0]) * 16 + hex_value(h[1]));
            h += 2;
        }
        if (datagram) {
            frames += parser.packets;
            dropped += parser.dropped;
            sva_mavlink_parser_reset(&parser);
        }
        mavlink_message_t msg;
        size_t used = 0;
        while (used < n) {
            used += sva_mavlink_parser_put(&parser, bytes + used, n - used);
            while (sva_mavlink_parser_next(&parser, &msg)) {
                printf("msg %u %u %u %u\n", (unsigned)msg.sysid, (unsigned)msg.compid,
                       (unsigned)msg.msgid, (unsigned)msg.seq);
            }
        }
        if (datagram) {
            sva_mavlink_parser_end(&parser);
            while (sva_mavlink_parser_next(&parser, &msg)) {
                printf("msg %u %u %u %u\n", (unsigned)msg.sysid, (unsigned)msg.compid,
                       (unsigned)msg.msgid, (unsigned)msg.seq);
            }
        }
    }
    printf("parser %u %u\n", (unsigned)(frames + parser.packets),
           (unsigned)(dropped + parser.dropped));
    return 0;
}

static void say_link(size_t i)
{
    const sva_mavlink_vehicle_t* v = &vehicles[i];
    int uav = (int)v->spec.uav_id;
    if (v->drops != said_drops[i]) {
        said_drops[i] = v->drops;
        printf("link %d lost %s\n", uav, v->link_error);
    }
    if (v->connects != said_connects[i]) {
        said_connects[i] = v->connects;
        printf("link %d connected\n", uav);
    }
    if (v->failed_connects > 0 && v->failed_connects != said_failures[i] && said_failures[i] == 0) {
        printf("link %d failed %s\n", uav, v->link_error);
    }
    said_failures[i] = v->failed_connects;
}

static void print_telemetry(size_t i, const sva_frame_t* frame, sva_frame_geodesy_t* geo,
                            const sva_mavlink_report_config_t* cfg, int64_t now)
{
    const sva_mavlink_vehicle_t* v = &vehicles[i];
    const sva_mavlink_telemetry_t* t = &v->telemetry;
    int64_t gps_ms = -1;
    (void)sva_mavlink_telemetry_gps_ms(t, &gps_ms);
    printf("telemetry %d heard=%d age_ms=%lld armed=%d status=%u position=%d lat_e7=%d "
           "lon_e7=%d alt_mm=%d pos_boot_ms=%u gps_time=%d unix_us=%llu time_boot_ms=%u "
           "gps_ms=%lld battery=%d mission_seq=%d reached_seq=%d requests=%u accepted=%u "
           "refused=%u reboots=%u connects=%u drops=%u dropped_bytes=%u frames=%u\n",
           (int)v->spec.uav_id, t->heard ? 1 : 0,
           (long long)(t->heard ? now - t->heartbeat_host_ms : -1), t->armed ? 1 : 0,
           (unsigned)t->system_status, t->has_position ? 1 : 0, (int)t->lat_e7, (int)t->lon_e7,
           (int)t->relative_alt_mm, (unsigned)t->position_boot_ms, t->has_gps_time ? 1 : 0,
           (unsigned long long)t->time_unix_usec, (unsigned)t->time_boot_ms, (long long)gps_ms,
           (int)t->battery_percent, (int)t->mission_seq, (int)t->reached_seq,
           (unsigned)t->requests_sent, (unsigned)t->requests_accepted,
           (unsigned)t->requests_refused, (unsigned)t->reboots, (unsigned)v->connects,
           (unsigned)v->drops, (unsigned)v->parser.dropped, (unsigned)v->parser.packets);
    if (geo == NULL) {
        return;
    }
    sva_mavlink_report_t r;
    sva_mavlink_report_status_t st =
        sva_mavlink_report_make(t, v->spec.uav_id, frame, geo, cfg, now, &r);
    if (st != SVA_MAVLINK_REPORT_OK) {
        printf("report %d %d %s\n", (int)v->spec.uav_id, (int)st,
               sva_mavlink_report_status_text(st));
        return;
    }
    printf("report %d 0 at_ticks=%d health=%d x=%d y=%d fuel=%d mission_seq=%d reached_seq=%d\n",
           (int)r.uav_id, (int)r.at_ticks, (int)r.health, (int)r.x, (int)r.y, (int)r.fuel,
           (int)r.mission_seq, (int)r.reached_seq);
}

// Services every open vehicle for up to `ms` (while any upload runs when `ms` < 0),
// printing link events, and telemetry every `every_ms` when `every_ms` > 0.
static void service(int64_t ms, int64_t every_ms, const sva_frame_t* frame,
                    sva_frame_geodesy_t* geo, const sva_mavlink_report_config_t* cfg)
{
    int64_t start = sva_mavlink_now_ms();
    int64_t next_print = start + every_ms;
    for (;;) {
        struct pollfd fds[MAX_ROUTES];
        nfds_t n = 0;
        bool busy = false;
        for (size_t i = 0; i < nroutes; i++) {
            if (has_vehicle[i]) {
                fds[n].fd = vehicles[i].fd;
                fds[n].events = POLLIN;
                n++;
                busy = busy || sva_mavlink_vehicle_busy(&vehicles[i]);
            }
        }
        int64_t now = sva_mavlink_now_ms();
        if ((ms < 0 && !busy) || (ms >= 0 && now - start >= ms)) {
            break;
        }
        (void)poll(fds, n, WAIT_MS);
        now = sva_mavlink_now_ms();
        for (size_t i = 0; i < nroutes; i++) {
            if (has_vehicle[i]) {
                sva_mavlink_vehicle_service(&vehicles[i], now);
                say_link(i);
            }
        }
        if (every_ms > 0 && now >= next_print) {
            next_print += every_ms;
            for (size_t i = 0; i < nroutes; i++) {
                if (has_vehicle[i]) {
                    print_telemetry(i, frame, geo, cfg, now);
                }
            }
        }
        fflush(stdout);
    }
}

int main(void)
{
    sva_frame_t frame;
    memset(&frame, 0, sizeof frame);
    int32_t tpc = 1;
    int32_t timeout_ms = SVA_MAVLINK_TIMEOUT_MS;
    int32_t retries = SVA_MAVLINK_RETRIES;
    bool ardupilot = false;
    double cruise = 0.0;
    bool have_frame = false;
    long long listen_ms = 0;
    long long every_ms = 1000;
    sva_mavlink_report_config_t cfg = {3000, 0};
    static char line[LINE_SIZE];
    char err[SVA_MAVLINK_ERROR_SIZE];
    bool first = true;
    while (fgets(line, sizeof line, stdin) != NULL) {
        if (first && strncmp(line, "parse", 5) == 0) {
            return parse_mode();
        }
        first = false;
        long long a[6];
        char spec_text[300];
        if (sscanf(line, "frame %lld %lld %lld %lld %lld %lld", &a[0], &a[1], &a[2], &a[3], &a[4],
                   &a[5]) == 6) {
            frame.lat_e7 = (int32_t)a[0];
            frame.lon_e7 = (int32_t)a[1];
            frame.alt_cm = (int32_t)a[2];
            frame.cell_cm = (int32_t)a[3];
            frame.tick_ms = (int32_t)a[4];
            frame.t0_ms = a[5];
            have_frame = true;
        } else if (strncmp(line, "ardupilot", 9) == 0) {
            ardupilot = true;
        } else if (sscanf(line, "cruise %lf", &cruise) == 1) {
            // the routes that follow command it
        } else if (sscanf(line, "timeout %lld %lld", &a[0], &a[1]) == 2) {
            timeout_ms = (int32_t)a[0];
            retries = (int32_t)a[1];
        } else if (sscanf(line, "listen %lld %lld", &a[0], &a[1]) >= 1) {
            listen_ms = a[0];
            if (sscanf(line, "listen %lld %lld", &a[0], &a[1]) == 2) {
                every_ms = a[1];
            }
        } else if (sscanf(line, "reportcfg %lld %lld", &a[0], &a[1]) == 2) {
            cfg.heartbeat_timeout_ms = (int32_t)a[0];
            cfg.fuel_capacity_cells = (int32_t)a[1];
        } else if (sscanf(line, "tpc %lld", &a[0]) == 1) {
            tpc = (int32_t)a[0];
        } else if (sscanf(line, "route %lld %lld %lld %lld", &a[0], &a[1], &a[2], &a[3]) == 4) {
            if (nroutes == MAX_ROUTES) {
                fprintf(stderr, "mavlink_tool: more than %d routes\n", MAX_ROUTES);
                return 2;
            }
            sva_mavlink_route_t* r = &routes[nroutes];
            r->uav_id = (int32_t)a[0];
            r->x = (int32_t)a[1];
            r->y = (int32_t)a[2];
            r->ready_at = (int32_t)a[3];
            r->targets = targets[nroutes];
            r->target_count = 0;
            r->cruise_m_s = (float)cruise;
            has_route[nroutes] = true;
            nroutes++;
        } else if (sscanf(line, "target %lld %lld %lld %lld %lld", &a[0], &a[1], &a[2], &a[3],
                          &a[4]) == 5) {
            if (nroutes == 0 || !has_route[nroutes - 1] ||
                routes[nroutes - 1].target_count == SVA_MAVLINK_MAX_ROUTE_TARGETS + 8) {
                fprintf(stderr, "mavlink_tool: target outside a route or too many\n");
                return 2;
            }
            sva_mavlink_target_t* t = &targets[nroutes - 1][routes[nroutes - 1].target_count++];
            t->id = (int32_t)a[0];
            t->x = (int32_t)a[1];
            t->y = (int32_t)a[2];
            t->start = (int32_t)a[3];
            t->end = (int32_t)a[4];
        } else if (sscanf(line, "vehicle %299s", spec_text) == 1) {
            sva_mavlink_vehicle_spec_t spec;
            if (sva_mavlink_parse_vehicle(spec_text, &spec, err, sizeof err) != SVA_MAVLINK_OK) {
                fprintf(stderr, "mavlink_tool: %s\n", err);
                return 2;
            }
            size_t i = 0;
            while (i < nroutes && routes[i].uav_id != spec.uav_id) {
                i++;
            }
            if (i == nroutes) {  // no route: it only listens
                if (nroutes == MAX_ROUTES) {
                    fprintf(stderr, "mavlink_tool: more than %d vehicles\n", MAX_ROUTES);
                    return 2;
                }
                routes[nroutes].uav_id = spec.uav_id;
                nroutes++;
            }
            if (sva_mavlink_vehicle_open(&vehicles[i], &spec, 250, err, sizeof err) !=
                SVA_MAVLINK_OK) {
                fprintf(stderr, "mavlink_tool: %s\n", err);
                return 2;
            }
            vehicles[i].upload.timeout_ms = timeout_ms;
            vehicles[i].upload.retries = retries;
            has_vehicle[i] = true;
        }
    }
    sva_frame_geodesy_t* geo = NULL;
    if (have_frame) {
        if (sva_frame_check(&frame, err, sizeof err) != SVA_OK) {
            fprintf(stderr, "mavlink_tool: %s\n", err);
            return 2;
        }
        geo = sva_frame_geodesy_open(&frame, err, sizeof err);
        if (geo == NULL) {
            fprintf(stderr, "mavlink_tool: %s\n", err);
            return 2;
        }
    }
    int status = 0;
    for (size_t i = 0; i < nroutes; i++) {
        if (!has_route[i]) {
            continue;
        }
        if (geo == NULL) {
            fprintf(stderr, "mavlink_tool: routes need a frame\n");
            return 2;
        }
        routes[i].ticks_per_cell = tpc;
        built[i] = sva_mavlink_build(&frame, geo, &routes[i], items[i], SVA_MAVLINK_MAX_ITEMS,
                                     &item_counts[i], err, sizeof err) == SVA_MAVLINK_OK;
        if (!built[i]) {
            printf("result %d error %s\n", (int)routes[i].uav_id, err);
            status = 1;
            continue;
        }
        if (ardupilot && item_counts[i] > 0 &&
            !sva_mavlink_prepend_home(items[i], SVA_MAVLINK_MAX_ITEMS, &item_counts[i])) {
            printf("result %d error no room for the home item\n", (int)routes[i].uav_id);
            status = 1;
            built[i] = false;
            continue;
        }
        for (size_t k = 0; k < item_counts[i]; k++) {
            const sva_mavlink_item_t* it = &items[i][k];
            printf("item %d %zu %u %u %.9g %.9g %.9g %.9g %d %d %.9g\n", (int)routes[i].uav_id, k,
                   (unsigned)it->command, (unsigned)it->frame, (double)it->param1,
                   (double)it->param2, (double)it->param3, (double)it->param4, (int)it->x,
                   (int)it->y, (double)it->z);
        }
    }
    int64_t now = sva_mavlink_now_ms();
    for (size_t i = 0; i < nroutes; i++) {
        if (has_vehicle[i] && has_route[i] && built[i]) {
            memcpy(vehicles[i].items, items[i], item_counts[i] * sizeof items[i][0]);
            vehicles[i].item_count = item_counts[i];
            (void)sva_mavlink_vehicle_start(&vehicles[i], now);
        }
    }
    fflush(stdout);
    service(-1, 0, &frame, geo, &cfg);
    for (size_t i = 0; i < nroutes; i++) {
        if (!has_vehicle[i] || !has_route[i] || !built[i]) {
            continue;
        }
        if (vehicles[i].upload.state == SVA_MAVLINK_UPLOAD_DONE) {
            printf("result %d ok %zu\n", (int)routes[i].uav_id, item_counts[i]);
        } else {
            printf("result %d error %s\n", (int)routes[i].uav_id, vehicles[i].upload.error);
            status = 1;
        }
    }
    fflush(stdout);
    if (listen_ms > 0) {
        service(listen_ms, every_ms, &frame, geo, &cfg);
    }
    for (size_t i = 0; i < nroutes; i++) {
        if (has_vehicle[i]) {
            sva_mavlink_vehicle_close(&vehicles[i]);
        }
    }
    if (geo != NULL) {
        sva_frame_geodesy_close(geo);
    }
    return status;
}
