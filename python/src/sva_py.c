/// sva_py.c -- the C side of the `sva` Python package: the core and the JSON layer
/// (port/json) behind four plain C functions, loaded with ctypes by sva/_native.py.
/// Each call plans exactly as `sva plan` / `sva replan` do (same parser, same checks,
/// same JSON writer) and returns the plan text or the CLI's error message (without
/// its "sva: error: " prefix). Working memory is allocated per call, so calls from
/// several threads do not share state.
#define _POSIX_C_SOURCE 200809L  // clock_gettime

#include <stdarg.h>
#include <stdbool.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include <jansson.h>
#include <sva/sva_live.h>
#include <sva/sva_json.h>
#include <sva/sva_text.h>

#define SVA_PY_API __attribute__((visibility("default")))

/// Return codes, the CLI's exit codes where there is one.
enum {
    SVA_PY_OK = 0,            ///< planned; *out holds the plan JSON
    SVA_PY_FAILED = 1,        ///< an algorithm limit, a solver failure, out of memory (CLI exit 1)
    SVA_PY_BAD_INPUT = 2,     ///< the mission or live file is wrong (CLI exit 2)
    SVA_PY_BAD_ARGUMENT = 3,  ///< an unknown algorithm or a flow budget out of range
};

typedef struct {
    sva_planner_t planner;
    sva_mission_t mission;
    sva_plan_t plan;
    sva_frame_t frame;
    bool has_frame;
    sva_live_t live;
    sva_json_live_t doc;
} sva_py_work_t;

#if defined(__GNUC__) || defined(__clang__)
__attribute__((format(printf, 4, 5)))
#endif
static int
fail(int code, char* err, size_t err_size, const char* fmt, ...)
{
    char message[SVA_JSON_ERROR_SIZE];
    va_list args;
    va_start(args, fmt);
    vsnprintf(message, sizeof message, fmt, args);
    va_end(args);
    // The CLI prints its messages escaped (one printable line); so do we.
    char shown[SVA_TEXT_ESCAPED_SIZE(sizeof message)];
    snprintf(err, err_size, "%s", sva_text_escape(shown, sizeof shown, message));
    return code;
}

static int64_t elapsed_us(const struct timespec* a, const struct timespec* b)
{
    return (int64_t)(b->tv_sec - a->tv_sec) * 1000000 + (int64_t)(b->tv_nsec - a->tv_nsec) / 1000;
}

// The same words as the CLI's plan_failed().
static int plan_failed(sva_status_t status, const sva_diag_t* diag, char* err, size_t err_size)
{
    char message[SVA_JSON_ERROR_SIZE];
    (void)sva_diag_format(diag, message, sizeof message);
    switch (status) {
    case SVA_ERR_INVALID:
        return fail(SVA_PY_BAD_INPUT, err, err_size, "%s", message);
    case SVA_ERR_LIMIT:
        return fail(SVA_PY_FAILED, err, err_size, "%s", message);
    case SVA_ERR_SOLVER:
        return fail(SVA_PY_FAILED, err, err_size,
                    "planner failed: simplex pivot budget SVA_MAX_PIVOTS (%ld) exceeded or "
                    "non-unit pivot (SVA_ERR_SOLVER)",
                    (long)SVA_MAX_PIVOTS);
    case SVA_ERR_ARGUMENT:
    case SVA_OK:
        break;
    }
    return fail(SVA_PY_FAILED, err, err_size, "planner failed with status %d", (int)status);
}

static int setup(sva_py_work_t** work, const char* algo, long flow_work, sva_algorithm_t* algorithm,
                 char* err, size_t err_size)
{
    if (sva_algorithm_from_name(algo, algorithm) != SVA_OK) {
        char known[128];
        size_t used = 0;
        known[0] = '\0';
        for (int a = 0; a < (int)SVA_ALGO_COUNT_ && used < sizeof known; ++a) {
            int n = snprintf(known + used, sizeof known - used, "%s%s", a == 0 ? "" : ", ",
                             sva_algorithm_name((sva_algorithm_t)a));
            used += n > 0 ? (size_t)n : 0U;
        }
        return fail(SVA_PY_BAD_ARGUMENT, err, err_size,
                    "algo: unknown algorithm \"%s\" (known: %s)", algo, known);
    }
    if (flow_work != 0 && (flow_work < 1000L || flow_work > (long)SVA_FLOW_MAX_WORK)) {
        return fail(SVA_PY_BAD_ARGUMENT, err, err_size,
                    "flow_work: must be an integer in [1000, %ld] (SVA_FLOW_MAX_WORK)",
                    (long)SVA_FLOW_MAX_WORK);
    }
    *work = calloc(1, sizeof **work);
    if (*work == NULL || sva_planner_init(&(*work)->planner) != SVA_OK) {
        free(*work);
        *work = NULL;
        return fail(SVA_PY_FAILED, err, err_size, "planner initialisation failed");
    }
    return SVA_PY_OK;
}

// The plan document as `sva plan` writes it: the frame echoed last, indented by 2,
// newline-terminated.
static int write_doc(json_t* doc, const sva_frame_t* frame, char** out, char* err, size_t err_size)
{
    if (doc != NULL && frame != NULL) {
        json_t* f = sva_json_frame(frame);
        if (f == NULL || json_object_set_new(doc, "frame", f) != 0) {
            json_decref(doc);
            doc = NULL;
        }
    }
    if (doc == NULL) {
        return fail(SVA_PY_FAILED, err, err_size, "building the plan JSON: out of memory");
    }
    char* text = json_dumps(doc, JSON_INDENT(2) | JSON_PRESERVE_ORDER | JSON_REAL_PRECISION(15));
    json_decref(doc);
    size_t len = text != NULL ? strlen(text) : 0U;
    char* with_newline = text != NULL ? realloc(text, len + 2U) : NULL;
    if (with_newline == NULL) {
        free(text);
        return fail(SVA_PY_FAILED, err, err_size, "building the plan JSON: out of memory");
    }
    with_newline[len] = '\n';
    with_newline[len + 1U] = '\0';
    *out = with_newline;
    return SVA_PY_OK;
}

// The mission's frame, when it has one (the text parsed already).
static bool read_frame(const char* text, size_t len, sva_frame_t* frame)
{
    json_error_t error;
    json_t* root = json_loadb(text, len, JSON_REJECT_DUPLICATES | JSON_DECODE_ANY, &error);
    bool present = false;
    char err[SVA_JSON_ERROR_SIZE];
    if (root != NULL &&
        sva_json_mission_frame(root, frame, &present, err, sizeof err) != SVA_JSON_OK) {
        present = false;
    }
    json_decref(root);
    return present;
}

/// Plans the mission document `text` (SPEC section 3) with `algo` (a name of SPEC
/// section 2) and, when flow_work is not 0, that flow budget. Returns SVA_PY_OK with
/// *out the plan JSON (free it with sva_py_free), or another code with err the message
/// `sva plan` prints after "sva: error: "; `source` names the document in errors of
/// the document itself.
SVA_PY_API int sva_py_plan(const char* text, size_t len, const char* source, const char* algo,
                           long flow_work, char** out, char* err, size_t err_size);
SVA_PY_API int sva_py_plan(const char* text, size_t len, const char* source, const char* algo,
                           long flow_work, char** out, char* err, size_t err_size)
{
    *out = NULL;
    sva_algorithm_t algorithm;
    sva_py_work_t* work = NULL;
    int code = setup(&work, algo, flow_work, &algorithm, err, err_size);
    if (code != SVA_PY_OK) {
        return code;
    }
    char name[SVA_JSON_NAME_MAX + 1];
    char message[SVA_JSON_ERROR_SIZE];
    sva_json_status_t parsed =
        sva_json_parse_mission(text, len, source, &work->mission, name, message, sizeof message);
    sva_diag_t diag;
    sva_diag_clear(&diag);
    if (parsed == SVA_JSON_OK && sva_mission_validate(&work->mission, &diag) != SVA_OK) {
        (void)sva_diag_format(&diag, message, sizeof message);
        parsed = SVA_JSON_ERR_INPUT;
    }
    if (parsed != SVA_JSON_OK) {
        code = fail(parsed == SVA_JSON_ERR_INPUT ? SVA_PY_BAD_INPUT : SVA_PY_FAILED, err, err_size,
                    "%s", message);
        free(work);
        return code;
    }
    work->has_frame = read_frame(text, len, &work->frame);
    if (flow_work != 0) {
        work->planner.flow_max_work = (uint32_t)flow_work;
    }
    struct timespec before, after;
    clock_gettime(CLOCK_MONOTONIC, &before);
    const sva_status_t status =
        sva_plan(&work->planner, &work->mission, algorithm, &work->plan, &diag);
    clock_gettime(CLOCK_MONOTONIC, &after);
    if (status != SVA_OK) {
        code = plan_failed(status, &diag, err, err_size);
    } else {
        code =
            write_doc(sva_json_plan(&work->mission, name, &work->plan, elapsed_us(&before, &after)),
                      work->has_frame ? &work->frame : NULL, out, err, err_size);
    }
    free(work);
    return code;
}

static sva_status_t timed_replan(sva_py_work_t* work, sva_algorithm_t algorithm,
                                 sva_live_result_t* result, sva_diag_t* diag, int64_t* solve_us)
{
    struct timespec before, after;
    clock_gettime(CLOCK_MONOTONIC, &before);
    const sva_status_t status =
        sva_live_replan(&work->live, &work->planner, algorithm, result, diag);
    clock_gettime(CLOCK_MONOTONIC, &after);
    *solve_us = elapsed_us(&before, &after);
    return status;
}

// `sva replan`'s replay: the events in order, a replan after the last event of each
// tick, then the clock to `now` and a last replan, which is the answer (SPEC 12.5).
static int replay(sva_py_work_t* work, sva_algorithm_t algorithm, char** out, char* err,
                  size_t err_size)
{
    sva_json_live_t* doc = &work->doc;
    sva_diag_t diag;
    sva_diag_clear(&diag);
    char message[SVA_JSON_ERROR_SIZE];
    if (!doc->has_plan) {
        const sva_status_t status =
            sva_plan(&work->planner, &doc->mission, algorithm, &doc->plan, &diag);
        if (status != SVA_OK) {
            return plan_failed(status, &diag, err, err_size);
        }
    }
    if (sva_live_init(&work->live, &doc->mission, &doc->plan, &diag) != SVA_OK) {
        const bool route = diag.field == SVA_FIELD_ROUTES || diag.field == SVA_FIELD_ROUTE_UAV ||
                           diag.field == SVA_FIELD_ROUTE_TARGETS;
        (void)sva_diag_format(&diag, message, sizeof message);
        return fail(SVA_PY_BAD_INPUT, err, err_size, "%s%s", route ? "plan." : "", message);
    }
    sva_live_result_t result;
    bool replanned = false;
    int64_t solve_us = 0;
    for (size_t i = 0; i < doc->event_count; ++i) {
        if (sva_live_apply(&work->live, &doc->events[i], &diag) != SVA_OK) {
            (void)sva_diag_format(&diag, message, sizeof message);
            return fail(SVA_PY_BAD_INPUT, err, err_size, "events[%zu]: %s", i, message);
        }
        const bool last_of_tick =
            i + 1 == doc->event_count || doc->events[i + 1].at_ticks != doc->events[i].at_ticks;
        if (last_of_tick) {
            const sva_status_t status = timed_replan(work, algorithm, &result, &diag, &solve_us);
            if (status != SVA_OK) {
                return plan_failed(status, &diag, err, err_size);
            }
            replanned = true;
        }
    }
    if (!replanned || doc->now_ticks > work->live.now_ticks) {
        const sva_event_t clock = {.type = SVA_EVENT_CLOCK, .at_ticks = doc->now_ticks};
        if (sva_live_apply(&work->live, &clock, &diag) != SVA_OK) {
            (void)sva_diag_format(&diag, message, sizeof message);
            return fail(SVA_PY_BAD_INPUT, err, err_size, "now: %s", message);
        }
        const sva_status_t status = timed_replan(work, algorithm, &result, &diag, &solve_us);
        if (status != SVA_OK) {
            return plan_failed(status, &diag, err, err_size);
        }
    } else if (doc->has_now && doc->now_ticks < work->live.now_ticks) {
        return fail(SVA_PY_BAD_INPUT, err, err_size, "now: %ld is before the last event (%ld)",
                    (long)doc->now_ticks, (long)work->live.now_ticks);
    }
    return write_doc(sva_json_replan(&work->live, &result, doc->name, solve_us),
                     doc->has_frame ? &doc->frame : NULL, out, err, err_size);
}

/// Replays the live file at `path` (SPEC 12.5) as `sva replan` does and returns its
/// last replan, with the codes and messages of sva_py_plan.
SVA_PY_API int sva_py_replan(const char* path, const char* algo, long flow_work, char** out,
                             char* err, size_t err_size);
SVA_PY_API int sva_py_replan(const char* path, const char* algo, long flow_work, char** out,
                             char* err, size_t err_size)
{
    *out = NULL;
    sva_algorithm_t algorithm;
    sva_py_work_t* work = NULL;
    int code = setup(&work, algo, flow_work, &algorithm, err, err_size);
    if (code != SVA_PY_OK) {
        return code;
    }
    char message[SVA_JSON_ERROR_SIZE];
    const sva_json_status_t loaded = sva_json_load_live(path, &work->doc, message, sizeof message);
    if (loaded != SVA_JSON_OK) {
        code = fail(loaded == SVA_JSON_ERR_INPUT ? SVA_PY_BAD_INPUT : SVA_PY_FAILED, err, err_size,
                    "%s", message);
        free(work);
        return code;
    }
    if (flow_work != 0) {
        work->planner.flow_max_work = (uint32_t)flow_work;
        work->planner.flow_replan_work = (uint32_t)flow_work;
    }
    code = replay(work, algorithm, out, err, err_size);
    sva_json_live_free(&work->doc);
    free(work);
    return code;
}

/// Frees a plan text returned by sva_py_plan or sva_py_replan.
SVA_PY_API void sva_py_free(char* text);
SVA_PY_API void sva_py_free(char* text)
{
    free(text);
}

/// "MAJOR.MINOR.PATCH" of the core this library was built from.
SVA_PY_API const char* sva_py_version(void);
SVA_PY_API const char* sva_py_version(void)
{
    static char version[32];
    snprintf(version, sizeof version, "%d.%d.%d", (int)SVA_VERSION_MAJOR, (int)SVA_VERSION_MINOR,
             (int)SVA_VERSION_PATCH);
    return version;
}
