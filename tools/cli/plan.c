// plan.c -- sva plan and sva validate: a mission in, its plan (or "ok") out.
#define _POSIX_C_SOURCE 200809L

#include <errno.h>
#include <stdbool.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>
#include <time.h>

#include <jansson.h>
#include <sva/sva.h>
#include <sva/sva_json.h>
#include <sva/sva_text.h>

#include "cli.h"
#include "schedule.h"

// Large working structs live in static storage, as on firmware.
static sva_mission_t g_mission;
static sva_plan_t g_plan;
sva_planner_t sva_cli_planner;

// The loaded mission's frame (docs/flight-stack.md), when it has one.
static sva_frame_t g_frame;
static bool g_has_frame;

static int load(const char* path, char name[SVA_JSON_NAME_MAX + 1])
{
    char err[SVA_JSON_ERROR_SIZE];
    sva_json_status_t result = sva_json_load_mission_frame(path, &g_mission, name, &g_frame,
                                                           &g_has_frame, err, sizeof err);
    if (result != SVA_JSON_OK) {
        return sva_cli_error(sva_cli_exit_of_json(result), "%s", err);
    }
    return EXIT_PLANNED;
}

int sva_cli_validate(int argc, char** argv)
{
    options_t opt;
    int code = sva_cli_parse_options("validate", VALIDATE_OPTIONS, argc, argv, &opt);
    if (code != EXIT_PLANNED || opt.help) {
        if (opt.help) {
            sva_cli_usage(stdout);
        }
        return code;
    }
    char name[SVA_JSON_NAME_MAX + 1];
    code = load(opt.mission, name);
    if (code != EXIT_PLANNED) {
        return code;
    }
    char shown[SVA_TEXT_ESCAPED_SIZE(SVA_JSON_NAME_MAX)];
    printf("ok: %s: %u UAVs, %u targets\n", sva_text_escape(shown, sizeof shown, name),
           (unsigned)g_mission.uav_count, (unsigned)g_mission.target_count);
    if (fflush(stdout) != 0) {
        return sva_cli_error(EXIT_FAILED, "writing to standard output: %s", strerror(errno));
    }
    return EXIT_PLANNED;
}

int64_t sva_cli_elapsed_us(const struct timespec* a, const struct timespec* b)
{
    return (int64_t)(b->tv_sec - a->tv_sec) * 1000000 + (int64_t)(b->tv_nsec - a->tv_nsec) / 1000;
}

// One sva_plan() call into g_plan; *fastest_us becomes its wall time if that is less.
static sva_status_t timed_plan(sva_algorithm_t algorithm, sva_diag_t* diag, int64_t* fastest_us)
{
    struct timespec before;
    struct timespec after;
    clock_gettime(CLOCK_MONOTONIC, &before);
    const sva_status_t status = sva_plan(&sva_cli_planner, &g_mission, algorithm, &g_plan, diag);
    clock_gettime(CLOCK_MONOTONIC, &after);
    const int64_t us = sva_cli_elapsed_us(&before, &after);
    *fastest_us = (us < *fastest_us) ? us : *fastest_us;
    return status;
}

// Maps a failed sva_plan() to its message and exit code.
int sva_cli_plan_failed(sva_status_t status, const sva_diag_t* diag)
{
    char message[SVA_JSON_ERROR_SIZE];
    (void)sva_diag_format(diag, message, sizeof message);
    switch (status) {
    case SVA_ERR_INVALID:
        return sva_cli_error(EXIT_BAD_INPUT, "%s", message);
    case SVA_ERR_LIMIT:
        return sva_cli_error(EXIT_FAILED, "%s", message);
    case SVA_ERR_SOLVER:
        return sva_cli_error(
            EXIT_FAILED,
            "planner failed: simplex pivot budget SVA_MAX_PIVOTS (%ld) exceeded or "
            "non-unit pivot (SVA_ERR_SOLVER)",
            (long)SVA_MAX_PIVOTS);
    case SVA_ERR_ARGUMENT:
    case SVA_OK:
        break;
    }
    return sva_cli_error(EXIT_FAILED, "planner failed with status %d", (int)status);
}

// The mission's frame, echoed into its plan as the mission wrote it (last key).
bool sva_cli_echo_frame(json_t* doc, const sva_frame_t* frame)
{
    if (frame == NULL) {
        return true;
    }
    json_t* f = sva_json_frame(frame);
    return f != NULL && json_object_set_new(doc, "frame", f) == 0;
}

static int print_plan(const options_t* opt, const char* name, int64_t solve_us)
{
    if (opt->schedule) {
        if (sva_write_schedule(stdout, &g_mission, name, &g_plan) != 0) {
            return sva_cli_error(EXIT_FAILED, "writing the schedule: %s", strerror(errno));
        }
        return EXIT_PLANNED;
    }
    json_t* doc = sva_json_plan(&g_mission, name, &g_plan, solve_us);
    if (doc != NULL && !sva_cli_echo_frame(doc, g_has_frame ? &g_frame : NULL)) {
        json_decref(doc);
        doc = NULL;
    }
    if (doc == NULL) {
        return sva_cli_error(EXIT_FAILED, "building the plan JSON: out of memory");
    }
    int written = sva_json_write_plan(stdout, doc);
    json_decref(doc);
    if (written != 0) {
        return sva_cli_error(EXIT_FAILED, "writing the plan: %s", strerror(errno));
    }
    return EXIT_PLANNED;
}

int sva_cli_plan(int argc, char** argv)
{
    options_t opt;
    sva_algorithm_t algorithm;
    int code = sva_cli_parse_planning("plan", PLAN_OPTIONS, argc, argv, &opt, &algorithm);
    if (code != EXIT_PLANNED || opt.help) {
        return code;
    }
    char name[SVA_JSON_NAME_MAX + 1];
    code = load(opt.mission, name);
    if (code != EXIT_PLANNED) {
        return code;
    }
    if (sva_planner_init(&sva_cli_planner) != SVA_OK) {
        return sva_cli_error(EXIT_FAILED, "planner initialisation failed");
    }
    if (opt.flow_work > 0) {
        sva_cli_planner.flow_max_work = (uint32_t)opt.flow_work;
    }
    // --repeat: the runs before the last, untraced. Planning is deterministic, so each
    // run gives the same plan; solve_us is the fastest (the planner's memory warm, as
    // in a node that plans again and again).
    sva_diag_t diag;
    sva_diag_clear(&diag);
    int64_t fastest = INT64_MAX;
    for (long run = 1; run < opt.repeat; run++) {
        const sva_status_t status = timed_plan(algorithm, &diag, &fastest);
        if (status != SVA_OK) {
            return sva_cli_plan_failed(status, &diag);
        }
    }
    FILE* trace_file = NULL;
    sva_trace_t trace = {NULL, NULL, 0UL, false};  // attached below when --trace is given
    if (opt.trace != NULL) {
        trace_file = fopen(opt.trace, "w");
        if (trace_file == NULL) {
            return sva_cli_error(EXIT_FAILED, "%s: cannot open for writing: %s", opt.trace,
                                 strerror(errno));
        }
        sva_trace_attach(&trace, &sva_cli_planner, trace_file, &g_mission);
    }
    const sva_status_t status = timed_plan(algorithm, &diag, &fastest);
    if (trace_file != NULL) {
        bool trace_ok = !trace.failed && fflush(trace_file) == 0 && !ferror(trace_file);
        if (fclose(trace_file) != 0 || !trace_ok) {
            return sva_cli_error(EXIT_FAILED, "%s: cannot write the trace", opt.trace);
        }
    }
    if (status != SVA_OK) {
        return sva_cli_plan_failed(status, &diag);
    }
    return print_plan(&opt, name, fastest);
}
