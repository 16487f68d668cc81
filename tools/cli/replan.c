// replan.c -- sva replan: a live mission replayed, its last replan out.
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

#include "cli.h"

// ---------------------------------------------------------------------------------
// sva replan: a live mission replayed as the on-board node flies it (docs/SPEC.md,
// live missions): the events in order, a replan after the last event of each tick,
// then the clock to `now` and a last replan, which is printed.

static sva_live_t g_live;
static sva_json_live_t g_doc;

// One replan of g_live into *result (its wall time into *solve_us).
static sva_status_t timed_replan(sva_algorithm_t algorithm, sva_live_result_t* result,
                                 sva_diag_t* diag, int64_t* solve_us)
{
    struct timespec before;
    struct timespec after;
    clock_gettime(CLOCK_MONOTONIC, &before);
    const sva_status_t status = sva_live_replan(&g_live, &sva_cli_planner, algorithm, result, diag);
    clock_gettime(CLOCK_MONOTONIC, &after);
    *solve_us = sva_cli_elapsed_us(&before, &after);
    return status;
}

static int write_residual(const char* path, const sva_mission_t* residual, const char* name)
{
    json_t* doc = sva_json_mission_framed(residual, name, g_doc.has_frame ? &g_doc.frame : NULL);
    FILE* out = doc != NULL ? fopen(path, "w") : NULL;
    if (out == NULL) {
        json_decref(doc);
        return sva_cli_error(EXIT_FAILED, "%s: cannot open for writing: %s", path, strerror(errno));
    }
    const int written =
        sva_json_write_plan(out, doc);  // any document: indented, newline-terminated
    json_decref(doc);
    if (fclose(out) != 0 || written != 0) {
        return sva_cli_error(EXIT_FAILED, "%s: cannot write the residual mission", path);
    }
    return EXIT_PLANNED;
}

static int replay(const options_t* opt, sva_algorithm_t algorithm)
{
    sva_diag_t diag;
    sva_diag_clear(&diag);
    if (!g_doc.has_plan) {
        const sva_status_t status =
            sva_plan(&sva_cli_planner, &g_doc.mission, algorithm, &g_doc.plan, &diag);
        if (status != SVA_OK) {
            return sva_cli_plan_failed(status, &diag);
        }
    }
    if (sva_live_init(&g_live, &g_doc.mission, &g_doc.plan, &diag) != SVA_OK) {
        // The JSON layer refuses a plan in force that breaks these rules first; a route
        // rule is the plan document's all the same.
        const bool route = diag.field == SVA_FIELD_ROUTES || diag.field == SVA_FIELD_ROUTE_UAV ||
                           diag.field == SVA_FIELD_ROUTE_TARGETS;
        char message[SVA_JSON_ERROR_SIZE];
        (void)sva_diag_format(&diag, message, sizeof message);
        return sva_cli_error(EXIT_BAD_INPUT, "%s%s", route ? "plan." : "", message);
    }
    sva_live_result_t result;
    bool replanned = false;
    int64_t solve_us = 0;
    for (size_t i = 0; i < g_doc.event_count; ++i) {
        if (sva_live_apply(&g_live, &g_doc.events[i], &diag) != SVA_OK) {
            char message[SVA_JSON_ERROR_SIZE];
            (void)sva_diag_format(&diag, message, sizeof message);
            return sva_cli_error(EXIT_BAD_INPUT, "events[%zu]: %s", i, message);
        }
        const bool last_of_tick =
            i + 1 == g_doc.event_count || g_doc.events[i + 1].at_ticks != g_doc.events[i].at_ticks;
        if (last_of_tick) {
            const sva_status_t status = timed_replan(algorithm, &result, &diag, &solve_us);
            if (status != SVA_OK) {
                return sva_cli_plan_failed(status, &diag);
            }
            replanned = true;
        }
    }
    if (!replanned || g_doc.now_ticks > g_live.now_ticks) {
        const sva_event_t clock = {.type = SVA_EVENT_CLOCK, .at_ticks = g_doc.now_ticks};
        if (sva_live_apply(&g_live, &clock, &diag) != SVA_OK) {
            char message[SVA_JSON_ERROR_SIZE];
            (void)sva_diag_format(&diag, message, sizeof message);
            return sva_cli_error(EXIT_BAD_INPUT, "now: %s", message);
        }
        const sva_status_t status = timed_replan(algorithm, &result, &diag, &solve_us);
        if (status != SVA_OK) {
            return sva_cli_plan_failed(status, &diag);
        }
    } else if (g_doc.has_now && g_doc.now_ticks < g_live.now_ticks) {
        return sva_cli_error(EXIT_BAD_INPUT, "now: %ld is before the last event (%ld)",
                             (long)g_doc.now_ticks, (long)g_live.now_ticks);
    }
    if (opt->residual != NULL) {
        const int code = write_residual(opt->residual, result.residual, g_doc.name);
        if (code != EXIT_PLANNED) {
            return code;
        }
    }
    json_t* doc = sva_json_replan(&g_live, &result, g_doc.name, solve_us);
    if (doc != NULL && !sva_cli_echo_frame(doc, g_doc.has_frame ? &g_doc.frame : NULL)) {
        json_decref(doc);
        doc = NULL;
    }
    if (doc == NULL) {
        return sva_cli_error(EXIT_FAILED, "building the plan JSON: out of memory");
    }
    const int written = sva_json_write_plan(stdout, doc);
    json_decref(doc);
    if (written != 0) {
        return sva_cli_error(EXIT_FAILED, "writing the plan: %s", strerror(errno));
    }
    return EXIT_PLANNED;
}

int sva_cli_replan(int argc, char** argv)
{
    options_t opt;
    sva_algorithm_t algorithm;
    int code = sva_cli_parse_planning("replan", REPLAN_OPTIONS, argc, argv, &opt, &algorithm);
    if (code != EXIT_PLANNED || opt.help) {
        return code;
    }
    char err[SVA_JSON_ERROR_SIZE];
    const sva_json_status_t loaded = sva_json_load_live(opt.mission, &g_doc, err, sizeof err);
    if (loaded != SVA_JSON_OK) {
        return sva_cli_error(sva_cli_exit_of_json(loaded), "%s", err);
    }
    if (sva_planner_init(&sva_cli_planner) != SVA_OK) {
        sva_json_live_free(&g_doc);
        return sva_cli_error(EXIT_FAILED, "planner initialisation failed");
    }
    if (opt.flow_work > 0) {
        // an explicit budget is the budget of every replan too
        sva_cli_planner.flow_max_work = (uint32_t)opt.flow_work;
        sva_cli_planner.flow_replan_work = (uint32_t)opt.flow_work;
    }
    code = replay(&opt, algorithm);
    sva_json_live_free(&g_doc);
    return code;
}
