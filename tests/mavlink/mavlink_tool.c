// Test harness of sva::mavlink without LCM: reads a frame and routes as text on stdin,
// prints the items the library builds and, for routes given a vehicle, uploads them
// (all vehicles at once) and prints one result line per vehicle.
//   frame LAT_E7 LON_E7 ALT_CM CELL_CM TICK_MS T0_MS
//   tpc TICKS_PER_CELL
//   route UAV_ID X Y READY_AT         (then its targets in visit order)
//   target ID X Y START END
//   vehicle UAV_ID=udp:HOST:PORT[:SYSID]
//   timeout MS RETRIES                (for the vehicles given after it)
//   ardupilot                         (a home item 0 first: sva_mavlink_prepend_home)
// Output: `item UAV SEQ COMMAND FRAME P1 P2 P3 P4 X Y Z`, `result UAV ok N` or
// `result UAV error MESSAGE`. Exit 0 when every upload succeeded, 1 otherwise, 2 on bad
// input.
#include <poll.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "sva/sva_mavlink.h"

#define MAX_ROUTES 8

static sva_mavlink_target_t targets[MAX_ROUTES][SVA_MAVLINK_MAX_ROUTE_TARGETS + 8];
static sva_mavlink_route_t routes[MAX_ROUTES];
static sva_mavlink_vehicle_t vehicles[MAX_ROUTES];
static sva_mavlink_item_t items[MAX_ROUTES][SVA_MAVLINK_MAX_ITEMS];
static size_t item_counts[MAX_ROUTES];
static bool has_vehicle[MAX_ROUTES];
static bool built[MAX_ROUTES];

int main(void)
{
    sva_frame_t frame;
    memset(&frame, 0, sizeof frame);
    int32_t tpc = 1;
    int32_t timeout_ms = SVA_MAVLINK_TIMEOUT_MS;
    int32_t retries = SVA_MAVLINK_RETRIES;
    bool ardupilot = false;
    size_t nroutes = 0;
    char line[512];
    char err[SVA_MAVLINK_ERROR_SIZE];
    while (fgets(line, sizeof line, stdin) != NULL) {
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
        } else if (strncmp(line, "ardupilot", 9) == 0) {
            ardupilot = true;
        } else if (sscanf(line, "timeout %lld %lld", &a[0], &a[1]) == 2) {
            timeout_ms = (int32_t)a[0];
            retries = (int32_t)a[1];
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
            nroutes++;
        } else if (sscanf(line, "target %lld %lld %lld %lld %lld", &a[0], &a[1], &a[2], &a[3],
                          &a[4]) == 5) {
            if (nroutes == 0 ||
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
            if (!sva_mavlink_parse_vehicle(spec_text, &spec, err, sizeof err)) {
                fprintf(stderr, "mavlink_tool: %s\n", err);
                return 2;
            }
            size_t i = 0;
            while (i < nroutes && routes[i].uav_id != spec.uav_id) {
                i++;
            }
            if (i == nroutes) {
                fprintf(stderr, "mavlink_tool: vehicle for unknown uav %d\n", (int)spec.uav_id);
                return 2;
            }
            if (!sva_mavlink_vehicle_open(&vehicles[i], &spec, 250, err, sizeof err)) {
                fprintf(stderr, "mavlink_tool: %s\n", err);
                return 2;
            }
            vehicles[i].upload.timeout_ms = timeout_ms;
            vehicles[i].upload.retries = retries;
            has_vehicle[i] = true;
        }
    }
    if (!sva_frame_check(&frame, err, sizeof err)) {
        fprintf(stderr, "mavlink_tool: %s\n", err);
        return 2;
    }
    sva_frame_geodesy_t* geo = sva_frame_geodesy_open(&frame, err, sizeof err);
    if (geo == NULL) {
        fprintf(stderr, "mavlink_tool: %s\n", err);
        return 2;
    }
    int status = 0;
    for (size_t i = 0; i < nroutes; i++) {
        routes[i].ticks_per_cell = tpc;
        built[i] = sva_mavlink_build(&frame, geo, &routes[i], items[i], SVA_MAVLINK_MAX_ITEMS,
                                     &item_counts[i], err, sizeof err);
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
    sva_frame_geodesy_close(geo);
    int64_t now = sva_mavlink_now_ms();
    for (size_t i = 0; i < nroutes; i++) {
        if (has_vehicle[i] && built[i]) {
            memcpy(vehicles[i].items, items[i], item_counts[i] * sizeof items[i][0]);
            vehicles[i].item_count = item_counts[i];
            (void)sva_mavlink_vehicle_start(&vehicles[i], now);
        }
    }
    for (;;) {
        struct pollfd fds[MAX_ROUTES];
        nfds_t n = 0;
        for (size_t i = 0; i < nroutes; i++) {
            if (has_vehicle[i] && sva_mavlink_vehicle_busy(&vehicles[i])) {
                fds[n].fd = vehicles[i].fd;
                fds[n].events = POLLIN;
                n++;
            }
        }
        if (n == 0) {
            break;
        }
        (void)poll(fds, n, 50);
        now = sva_mavlink_now_ms();
        for (size_t i = 0; i < nroutes; i++) {
            if (has_vehicle[i] && sva_mavlink_vehicle_busy(&vehicles[i])) {
                sva_mavlink_vehicle_service(&vehicles[i], now);
            }
        }
    }
    for (size_t i = 0; i < nroutes; i++) {
        if (!has_vehicle[i] || !built[i]) {
            continue;
        }
        if (vehicles[i].upload.state == SVA_MAVLINK_UPLOAD_DONE) {
            printf("result %d ok %zu\n", (int)routes[i].uav_id, item_counts[i]);
        } else {
            printf("result %d error %s\n", (int)routes[i].uav_id, vehicles[i].upload.error);
            status = 1;
        }
        sva_mavlink_vehicle_close(&vehicles[i]);
    }
    return status;
}
