// sva_mavlink_bridge's command line (bridge.h): every option checked against its range,
// one error line naming the option, the rule and the limit.
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "bridge.h"
#include "sva/sva.h"  // SVA_VERSION_*; SVA_MAX_FUEL: report_t.fuel is [0, SVA_MAX_FUEL]
#include "sva/sva_text.h"

#define PROGRAM "sva_mavlink_bridge"

// Ranges of the numeric options.
#define MAX_SYSTEM         255
#define MAX_TIMEOUT_MS     600000
#define MAX_RETRIES        100
#define MAX_UPLOAD_RETRIES 100
#define MIN_REPORT_MS      10
#define MAX_REPORT_MS      3600000
#define MAX_HB_TIMEOUT_MS  600000
#define MAX_FUEL_CELLS     ((long)SVA_MAX_FUEL)
#define MAX_CRUISE_M_S     100.0

static void usage(FILE* f)
{
    fprintf(f,
            "usage: " PROGRAM " --vehicle UAV_ID=udp:HOST:PORT[:SYSID] [--vehicle ...]\n"
            "                          [--url URL] [--prefix P] [--system N] [--timeout-ms N]\n"
            "                          [--retries N] [--upload-retries N] [--ardupilot]\n"
            "                          [--report-ms N]\n"
            "                          [--heartbeat-timeout-ms N] [--fuel-capacity CELLS]\n"
            "                          [--cruise-speed M_S]\n"
            "       " PROGRAM " --help | --version\n"
            "  --vehicle     UAV_ID=udp:HOST:PORT[:SYSID] or UAV_ID=tcp:HOST:PORT[:SYSID]\n"
            "                (SYSID 1 by default); tcp: connects and reconnects every %d ms\n"
            "  --url         LCM URL (default %s)\n"
            "  --prefix      channel prefix (default %s): <prefix>FLEET, MISSION, PLAN, REPLAN\n"
            "                in, <prefix>REPORT out\n"
            "  --system      this side's MAVLink system id, [1, %d] (default %d)\n"
            "  --timeout-ms  wait per message before resending, [1, %d] (default %d)\n"
            "  --retries     resends of one message before giving up, [0, %d] (default %d)\n"
            "  --upload-retries\n"
            "                a failed upload is tried again this many times, [0, %d]\n"
            "                (default %d), after %d ms, then twice the wait before, at most\n"
            "                %d ms; a newer mission for the vehicle replaces it\n"
            "  --ardupilot   put a home item 0 first (ArduPilot overwrites item 0 with home)\n"
            "  --report-ms   host ms between two reports of a vehicle, [%d, %d] (default %d)\n"
            "  --heartbeat-timeout-ms\n"
            "                a vehicle silent longer than this is reported LOST, [1, %d]\n"
            "                (default %d)\n"
            "  --fuel-capacity\n"
            "                fuel in cells of a full battery, [0, %ld]; report fuel =\n"
            "                floor(CELLS * battery %% / 100); 0 (default): fuel not reported\n"
            "  --cruise-speed\n"
            "                m/s to command, (0, %g], at least the plan's speed: the vehicle\n"
            "                then has room to make up acceleration and turns; default: the\n"
            "                plan's speed\n"
            "  --version     print \"" PROGRAM " VERSION\" (the sva library's)\n",
            SVA_MAVLINK_RECONNECT_MS, BRIDGE_DEFAULT_URL, BRIDGE_DEFAULT_PREFIX, MAX_SYSTEM,
            BRIDGE_DEFAULT_SYSTEM, MAX_TIMEOUT_MS, SVA_MAVLINK_TIMEOUT_MS, MAX_RETRIES,
            SVA_MAVLINK_RETRIES, MAX_UPLOAD_RETRIES, BRIDGE_DEFAULT_UPLOAD_RETRIES,
            BRIDGE_RETRY_FIRST_MS, BRIDGE_RETRY_MAX_MS, MIN_REPORT_MS, MAX_REPORT_MS,
            BRIDGE_DEFAULT_REPORT_MS, MAX_HB_TIMEOUT_MS, BRIDGE_DEFAULT_HEARTBEAT_TIMEOUT_MS,
            MAX_FUEL_CELLS, MAX_CRUISE_M_S);
}

static bool int_arg(const char* name, const char* text, long lo, long hi, long* out)
{
    char err[512];
    if (sva_text_to_long(name, text, lo, hi, out, err, sizeof err) != SVA_OK) {
        fprintf(stderr, PROGRAM ": error: %s\n", err);
        return false;
    }
    return true;
}

static bool add_vehicle(bridge_options_t* o, const char* v)
{
    char err[SVA_MAVLINK_ERROR_SIZE];
    if (o->spec_count == BRIDGE_MAX_VEHICLES) {
        fprintf(stderr, PROGRAM ": error: --vehicle: at most %d vehicles\n", BRIDGE_MAX_VEHICLES);
        return false;
    }
    sva_mavlink_vehicle_spec_t* spec = &o->specs[o->spec_count];
    if (sva_mavlink_parse_vehicle(v, spec, err, sizeof err) != SVA_MAVLINK_OK) {
        fprintf(stderr, PROGRAM ": error: %s\n", err);
        return false;
    }
    for (size_t k = 0; k < o->spec_count; k++) {
        if (o->specs[k].uav_id == spec->uav_id) {
            fprintf(stderr, PROGRAM ": error: --vehicle: UAV %d given twice\n", (int)spec->uav_id);
            return false;
        }
    }
    o->spec_count++;
    return true;
}

// One option with its value v. False after the error line.
static bool take(bridge_options_t* o, const char* a, const char* v)
{
    if (strcmp(a, "--url") == 0) {
        o->url = v;
        return true;
    }
    if (strcmp(a, "--prefix") == 0) {
        if (strlen(v) > BRIDGE_CHANNEL_SIZE - BRIDGE_SUFFIX_ROOM) {
            fprintf(stderr, PROGRAM ": error: --prefix: at most %d characters\n",
                    BRIDGE_CHANNEL_SIZE - BRIDGE_SUFFIX_ROOM);
            return false;
        }
        o->prefix = v;
        return true;
    }
    if (strcmp(a, "--system") == 0) {
        return int_arg(a, v, 1, MAX_SYSTEM, &o->own_system);
    }
    if (strcmp(a, "--timeout-ms") == 0) {
        return int_arg(a, v, 1, MAX_TIMEOUT_MS, &o->timeout_ms);
    }
    if (strcmp(a, "--retries") == 0) {
        return int_arg(a, v, 0, MAX_RETRIES, &o->retries);
    }
    if (strcmp(a, "--upload-retries") == 0) {
        return int_arg(a, v, 0, MAX_UPLOAD_RETRIES, &o->upload_retries);
    }
    if (strcmp(a, "--report-ms") == 0) {
        return int_arg(a, v, MIN_REPORT_MS, MAX_REPORT_MS, &o->report_ms);
    }
    if (strcmp(a, "--heartbeat-timeout-ms") == 0) {
        return int_arg(a, v, 1, MAX_HB_TIMEOUT_MS, &o->heartbeat_timeout_ms);
    }
    if (strcmp(a, "--fuel-capacity") == 0) {
        return int_arg(a, v, 0, MAX_FUEL_CELLS, &o->fuel_capacity_cells);
    }
    if (strcmp(a, "--cruise-speed") == 0) {
        char* end = NULL;
        errno = 0;
        const double m_s = strtod(v, &end);
        if (v[0] == '\0' || *end != '\0' || errno != 0 || !(m_s > 0.0) || m_s > MAX_CRUISE_M_S) {
            fprintf(stderr,
                    PROGRAM ": error: --cruise-speed: must be a number in (0, %g], got "
                            "\"%.40s\"\n",
                    MAX_CRUISE_M_S, v);
            return false;
        }
        o->cruise_m_s = (float)m_s;
        return true;
    }
    if (strcmp(a, "--vehicle") == 0) {
        return add_vehicle(o, v);
    }
    fprintf(stderr, PROGRAM ": error: %.40s: unknown option\n", a);
    usage(stderr);
    return false;
}

bridge_parse_t bridge_options_parse(int argc, char** argv, bridge_options_t* o)
{
    memset(o, 0, sizeof *o);
    o->url = BRIDGE_DEFAULT_URL;
    o->prefix = BRIDGE_DEFAULT_PREFIX;
    o->own_system = BRIDGE_DEFAULT_SYSTEM;
    o->timeout_ms = SVA_MAVLINK_TIMEOUT_MS;
    o->retries = SVA_MAVLINK_RETRIES;
    o->upload_retries = BRIDGE_DEFAULT_UPLOAD_RETRIES;
    o->report_ms = BRIDGE_DEFAULT_REPORT_MS;
    o->heartbeat_timeout_ms = BRIDGE_DEFAULT_HEARTBEAT_TIMEOUT_MS;
    for (int i = 1; i < argc; i++) {
        const char* a = argv[i];
        if (strcmp(a, "--help") == 0 || strcmp(a, "-h") == 0) {
            usage(stdout);
            return BRIDGE_HELP;
        }
        if (strcmp(a, "--version") == 0) {
            printf(PROGRAM " %d.%d.%d\n", SVA_VERSION_MAJOR, SVA_VERSION_MINOR, SVA_VERSION_PATCH);
            return BRIDGE_HELP;  // printed: exit 0, as --help
        }
        if (strcmp(a, "--ardupilot") == 0) {
            o->ardupilot = true;
            continue;
        }
        if (i + 1 >= argc) {
            fprintf(stderr, PROGRAM ": error: %.40s: unknown option or missing value\n", a);
            usage(stderr);
            return BRIDGE_BAD;
        }
        if (!take(o, a, argv[++i])) {
            return BRIDGE_BAD;
        }
    }
    if (o->spec_count == 0) {
        fprintf(stderr, PROGRAM ": error: no --vehicle given\n");
        usage(stderr);
        return BRIDGE_BAD;
    }
    return BRIDGE_RUN;
}
