// main.c -- the sva command line: plan or validate a SPEC section 3 mission.
//
// Exit codes (docs/cli.md): 0 planned (complete or partial) or valid; 2 bad input
// (mission or usage); 1 anything else (I/O, SVA_ERR_SOLVER, SVA_ERR_LIMIT).
// Every error is exactly one line "sva: error: <message>" on stderr, and nothing is
// printed on stdout for a mission that was rejected or could not be planned.
#define _POSIX_C_SOURCE 200809L

#include <errno.h>
#include <getopt.h>
#include <stdarg.h>
#include <stdbool.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include <jansson.h>
#include <sva/sva.h>

#include <sva/sva_json.h>
#include <sva/sva_text.h>

#include "schedule.h"

enum { EXIT_PLANNED = 0, EXIT_FAILED = 1, EXIT_BAD_INPUT = 2 };
enum { REPEAT_MAX = 1000 };  // --repeat: runs of one mission in one process

// Large working structs live in static storage, as on firmware.
static sva_mission_t g_mission;
static sva_plan_t g_plan;
static sva_planner_t g_planner;

#if defined(__GNUC__) || defined(__clang__)
__attribute__((format(printf, 2, 3)))
#endif
static int
error_exit(int code, const char* fmt, ...)
{
    char message[SVA_JSON_ERROR_SIZE];
    va_list args;
    va_start(args, fmt);
    vsnprintf(message, sizeof message, fmt, args);
    va_end(args);
    // User-supplied text in the message (arguments, file names) can hold anything:
    // escaped, the message stays one printable line.
    char shown[SVA_TEXT_ESCAPED_SIZE(sizeof message)];
    fprintf(stderr, "sva: error: %s\n", sva_text_escape(shown, sizeof shown, message));
    return code;
}

static void list_algorithms(char* out, size_t size)
{
    size_t used = 0;
    out[0] = '\0';
    for (int a = 0; a < (int)SVA_ALGO_COUNT_; ++a) {
        int n = snprintf(out + used, size - used, "%s%s", a == 0 ? "" : ", ",
                         sva_algorithm_name((sva_algorithm_t)a));
        if (n < 0 || (size_t)n >= size - used) {
            break;
        }
        used += (size_t)n;
    }
}

static void print_usage(FILE* out)
{
    char algos[128];
    list_algorithms(algos, sizeof algos);
    fprintf(out,
            "usage: sva plan [--algo NAME] [--flow-work N] [--repeat N] [--schedule] [--trace "
            "FILE] MISSION.json|-\n"
            "       sva validate MISSION.json|-\n"
            "       sva replan [--algo NAME] [--flow-work N] [--residual FILE] LIVE.json|-\n"
            "       sva --help | --version\n"
            "\n"
            "plan       plan the mission and print the plan JSON (SPEC section 3)\n"
            "  --algo NAME    algorithm: %s (default sva)\n"
            "  --flow-work N  flow's search budget in arc scans, 1000..%lu (default: the most)\n"
            "  --repeat N     plan N times in this process, 1..%d; solve_us is the fastest run\n"
            "  --schedule     print a readable schedule instead of JSON\n"
            "  --trace FILE   write each transportation problem to FILE as JSON Lines\n"
            "validate   check the mission only; prints \"ok: NAME: N UAVs, M targets\"\n"
            "replan     replay a live mission (mission, plan in force, events) and print the\n"
            "           last replan: the plan of the residual mission with its changes\n"
            "  --flow-work N    flow's budget for every replan (default: %lu with a plan in\n"
            "                   force, SVA_FLOW_REPLAN_WORK; the most without one)\n"
            "  --residual FILE  write the residual mission the plan is for to FILE\n"
            "\n"
            "exit status: 0 planned or valid, 2 bad input (mission or usage), 1 other errors\n",
            algos, (unsigned long)SVA_FLOW_MAX_WORK, REPEAT_MAX,
            (unsigned long)SVA_FLOW_REPLAN_WORK);
}

static void print_version(void)
{
    sva_limits_t limits = sva_limits();
    printf("sva %d.%d.%d (mission/plan schema %d)\n", SVA_VERSION_MAJOR, SVA_VERSION_MINOR,
           SVA_VERSION_PATCH, SVA_SCHEMA_VERSION);
    printf("limits: SVA_MAX_UAVS %lu, SVA_MAX_TARGETS %lu, SVA_BFA_MAX_UAVS %lu, "
           "SVA_BFA_MAX_TARGETS %lu, "
           "SVA_BFA_MAX_NODES %lu\n",
           (unsigned long)limits.max_uavs, (unsigned long)limits.max_targets,
           (unsigned long)limits.bfa_max_uavs, (unsigned long)limits.bfa_max_targets,
           (unsigned long)limits.bfa_max_nodes);
    printf("bfa plans a mission within SVA_BFA_MAX_UAVS and SVA_BFA_MAX_TARGETS unless its search "
           "passes "
           "SVA_BFA_MAX_NODES nodes\n");
}

typedef struct {
    const char* mission;
    const char* algo;
    const char* trace;
    const char* residual;
    long flow_work;  // 0: the planner's default
    long repeat;     // runs of sva_plan(); 1 unless --repeat
    bool schedule;
    bool help;
} options_t;

// An option's value as a decimal integer in [lo, hi] into *out; false if it is not
// one or out of range.
static bool long_in(const char* value, long lo, long hi, long* out)
{
    char* end = NULL;
    errno = 0;
    const long n = strtol(value, &end, 10);
    if (errno != 0 || end == value || *end != '\0' || n < lo || n > hi) {
        return false;
    }
    *out = n;
    return true;
}

// getopt_long codes of the options; -h is the one short option.
enum {
    OPT_MISSION = 1,
    OPT_HELP = 'h',
    OPT_ALGO = 256,
    OPT_FLOW_WORK,
    OPT_REPEAT,
    OPT_SCHEDULE,
    OPT_TRACE,
    OPT_RESIDUAL
};

static const struct option PLAN_OPTIONS[] = {
    {"algo", required_argument, NULL, OPT_ALGO},
    {"flow-work", required_argument, NULL, OPT_FLOW_WORK},
    {"repeat", required_argument, NULL, OPT_REPEAT},
    {"schedule", no_argument, NULL, OPT_SCHEDULE},
    {"trace", required_argument, NULL, OPT_TRACE},
    {"help", no_argument, NULL, OPT_HELP},
    {NULL, 0, NULL, 0},
};
static const struct option REPLAN_OPTIONS[] = {
    {"algo", required_argument, NULL, OPT_ALGO},
    {"flow-work", required_argument, NULL, OPT_FLOW_WORK},
    {"residual", required_argument, NULL, OPT_RESIDUAL},
    {"help", no_argument, NULL, OPT_HELP},
    {NULL, 0, NULL, 0},
};
static const struct option VALIDATE_OPTIONS[] = {
    {"help", no_argument, NULL, OPT_HELP},
    {NULL, 0, NULL, 0},
};

// Error of an option whose value is missing or wrong.
static int bad_value(const char* command, int code)
{
    switch (code) {
    case OPT_ALGO:
        return error_exit(EXIT_BAD_INPUT, "%s: --algo needs a value", command);
    case OPT_TRACE:
        return error_exit(EXIT_BAD_INPUT, "%s: --trace needs a file name", command);
    case OPT_RESIDUAL:
        return error_exit(EXIT_BAD_INPUT, "%s: --residual needs a file name", command);
    case OPT_FLOW_WORK:
        return error_exit(EXIT_BAD_INPUT,
                          "%s: --flow-work: must be an integer in [1000, %ld] (SVA_FLOW_MAX_WORK)",
                          command, (long)SVA_FLOW_MAX_WORK);
    case OPT_REPEAT:
    default:
        return error_exit(EXIT_BAD_INPUT, "%s: --repeat: must be an integer in [1, %d]", command,
                          REPEAT_MAX);
    }
}

// Error of an option getopt_long did not accept: unknown, ambiguous, or given a value
// it does not take. `argv[optind - 1]` is the argument for a long option; a short
// one is named by optopt.
static int unknown_option(const char* command, char** argv)
{
    char short_form[3] = {'-', (char)optopt, '\0'};
    const bool is_long = optopt == 0 || optopt == OPT_HELP || optopt >= OPT_ALGO;
    return error_exit(EXIT_BAD_INPUT, "%s: unknown option \"%s\" (try 'sva --help')", command,
                      is_long ? argv[optind - 1] : short_form);
}

// Parses the arguments after the command with getopt_long: options and the mission in
// any order, "--" ends the options, long options as "--name VALUE" or "--name=VALUE"
// (or a unique prefix of the name), from the command's table. argv[0] is the command.
static int parse_options(const char* command, const struct option* options, int argc, char** argv,
                         options_t* opt)
{
    memset(opt, 0, sizeof *opt);
    opt->algo = "sva";
    opt->repeat = 1;
    opterr = 0;  // the messages are ours, one line each
    optind = 1;
    // "-": non-options come back in order as OPT_MISSION; ":": a missing value is ':'.
    int code;
    while ((code = getopt_long(argc, argv, "-:h", options, NULL)) != -1) {
        switch (code) {
        case OPT_MISSION:
            if (opt->mission != NULL) {
                return error_exit(EXIT_BAD_INPUT, "%s: one mission expected, got \"%s\" and \"%s\"",
                                  command, opt->mission, optarg);
            }
            opt->mission = optarg;
            break;
        case OPT_HELP:
            opt->help = true;
            break;
        case OPT_SCHEDULE:
            opt->schedule = true;
            break;
        case OPT_ALGO:
            opt->algo = optarg;
            break;
        case OPT_FLOW_WORK:
            if (!long_in(optarg, 1000, (long)SVA_FLOW_MAX_WORK, &opt->flow_work)) {
                return bad_value(command, code);
            }
            break;
        case OPT_REPEAT:
            if (!long_in(optarg, 1, REPEAT_MAX, &opt->repeat)) {
                return bad_value(command, code);
            }
            break;
        case OPT_TRACE:
            if (optarg[0] == '\0') {
                return bad_value(command, code);
            }
            opt->trace = optarg;
            break;
        case OPT_RESIDUAL:
            if (optarg[0] == '\0') {
                return bad_value(command, code);
            }
            opt->residual = optarg;
            break;
        case ':':
            return bad_value(command, optopt);
        default:
            return unknown_option(command, argv);
        }
    }
    for (; optind < argc; ++optind) {  // after "--"
        if (opt->mission != NULL) {
            return error_exit(EXIT_BAD_INPUT, "%s: one mission expected, got \"%s\" and \"%s\"",
                              command, opt->mission, argv[optind]);
        }
        opt->mission = argv[optind];
    }
    if (!opt->help && opt->mission == NULL) {
        return error_exit(EXIT_BAD_INPUT, "%s: missing %s (or - for standard input)", command,
                          strcmp(command, "replan") == 0 ? "LIVE.json" : "MISSION.json");
    }
    return EXIT_PLANNED;
}

// The loaded mission's frame (docs/flight-stack.md), when it has one.
static sva_frame_t g_frame;
static bool g_has_frame;

static int load(const char* path, char name[SVA_JSON_NAME_MAX + 1])
{
    char err[SVA_JSON_ERROR_SIZE];
    sva_json_result_t result = sva_json_load_mission_frame(path, &g_mission, name, &g_frame,
                                                           &g_has_frame, err, sizeof err);
    if (result != SVA_JSON_OK) {
        return error_exit(result == SVA_JSON_BAD_INPUT ? EXIT_BAD_INPUT : EXIT_FAILED, "%s", err);
    }
    return EXIT_PLANNED;
}

static int cmd_validate(int argc, char** argv)
{
    options_t opt;
    int code = parse_options("validate", VALIDATE_OPTIONS, argc, argv, &opt);
    if (code != EXIT_PLANNED || opt.help) {
        if (opt.help) {
            print_usage(stdout);
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
        return error_exit(EXIT_FAILED, "writing to standard output: %s", strerror(errno));
    }
    return EXIT_PLANNED;
}

static int64_t elapsed_us(const struct timespec* a, const struct timespec* b)
{
    return (int64_t)(b->tv_sec - a->tv_sec) * 1000000 + (int64_t)(b->tv_nsec - a->tv_nsec) / 1000;
}

// One sva_plan() call into g_plan; *fastest_us becomes its wall time if that is less.
static sva_status_t timed_plan(sva_algorithm_t algorithm, sva_diag_t* diag, int64_t* fastest_us)
{
    struct timespec before;
    struct timespec after;
    clock_gettime(CLOCK_MONOTONIC, &before);
    const sva_status_t status = sva_plan(&g_planner, &g_mission, algorithm, &g_plan, diag);
    clock_gettime(CLOCK_MONOTONIC, &after);
    const int64_t us = elapsed_us(&before, &after);
    *fastest_us = (us < *fastest_us) ? us : *fastest_us;
    return status;
}

// Maps a failed sva_plan() to its message and exit code.
static int plan_failed(sva_status_t status, const sva_diag_t* diag)
{
    char message[SVA_JSON_ERROR_SIZE];
    (void)sva_diag_format(diag, message, sizeof message);
    switch (status) {
    case SVA_ERR_INVALID:
        return error_exit(EXIT_BAD_INPUT, "%s", message);
    case SVA_ERR_LIMIT:
        return error_exit(EXIT_FAILED, "%s", message);
    case SVA_ERR_SOLVER:
        return error_exit(EXIT_FAILED,
                          "planner failed: simplex pivot budget SVA_MAX_PIVOTS (%ld) exceeded or "
                          "non-unit pivot (SVA_ERR_SOLVER)",
                          (long)SVA_MAX_PIVOTS);
    case SVA_ERR_ARGUMENT:
    case SVA_OK:
        break;
    }
    return error_exit(EXIT_FAILED, "planner failed with status %d", (int)status);
}

// The mission's frame, echoed into its plan as the mission wrote it (last key).
static bool echo_frame(json_t* doc, const sva_frame_t* frame)
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
            return error_exit(EXIT_FAILED, "writing the schedule: %s", strerror(errno));
        }
        return EXIT_PLANNED;
    }
    json_t* doc = sva_json_plan(&g_mission, name, &g_plan, solve_us);
    if (doc != NULL && !echo_frame(doc, g_has_frame ? &g_frame : NULL)) {
        json_decref(doc);
        doc = NULL;
    }
    if (doc == NULL) {
        return error_exit(EXIT_FAILED, "building the plan JSON: out of memory");
    }
    int written = sva_json_write_plan(stdout, doc);
    json_decref(doc);
    if (written != 0) {
        return error_exit(EXIT_FAILED, "writing the plan: %s", strerror(errno));
    }
    return EXIT_PLANNED;
}

// The options of a command that plans (plan, replan), and its --algo: EXIT_PLANNED to go
// on (or with opt->help, after printing the usage), or the exit code of a usage error.
static int parse_planning(const char* command, const struct option* options, int argc, char** argv,
                          options_t* opt, sva_algorithm_t* algorithm)
{
    const int code = parse_options(command, options, argc, argv, opt);
    if (code != EXIT_PLANNED || opt->help) {
        if (opt->help) {
            print_usage(stdout);
        }
        return code;
    }
    if (sva_algorithm_from_name(opt->algo, algorithm) != SVA_OK) {
        char algos[128];
        list_algorithms(algos, sizeof algos);
        return error_exit(EXIT_BAD_INPUT, "%s: --algo: unknown algorithm \"%s\" (known: %s)",
                          command, opt->algo, algos);
    }
    return EXIT_PLANNED;
}

static int cmd_plan(int argc, char** argv)
{
    options_t opt;
    sva_algorithm_t algorithm;
    int code = parse_planning("plan", PLAN_OPTIONS, argc, argv, &opt, &algorithm);
    if (code != EXIT_PLANNED || opt.help) {
        return code;
    }
    char name[SVA_JSON_NAME_MAX + 1];
    code = load(opt.mission, name);
    if (code != EXIT_PLANNED) {
        return code;
    }
    if (sva_planner_init(&g_planner) != SVA_OK) {
        return error_exit(EXIT_FAILED, "planner initialisation failed");
    }
    if (opt.flow_work > 0) {
        g_planner.flow_max_work = (uint32_t)opt.flow_work;
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
            return plan_failed(status, &diag);
        }
    }
    FILE* trace_file = NULL;
    sva_trace_t trace = {NULL, NULL, 0UL, false};  // attached below when --trace is given
    if (opt.trace != NULL) {
        trace_file = fopen(opt.trace, "w");
        if (trace_file == NULL) {
            return error_exit(EXIT_FAILED, "%s: cannot open for writing: %s", opt.trace,
                              strerror(errno));
        }
        sva_trace_attach(&trace, &g_planner, trace_file, &g_mission);
    }
    const sva_status_t status = timed_plan(algorithm, &diag, &fastest);
    if (trace_file != NULL) {
        bool trace_ok = !trace.failed && fflush(trace_file) == 0 && !ferror(trace_file);
        if (fclose(trace_file) != 0 || !trace_ok) {
            return error_exit(EXIT_FAILED, "%s: cannot write the trace", opt.trace);
        }
    }
    if (status != SVA_OK) {
        return plan_failed(status, &diag);
    }
    return print_plan(&opt, name, fastest);
}

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
    const sva_status_t status = sva_live_replan(&g_live, &g_planner, algorithm, result, diag);
    clock_gettime(CLOCK_MONOTONIC, &after);
    *solve_us = elapsed_us(&before, &after);
    return status;
}

static int write_residual(const char* path, const sva_mission_t* residual, const char* name)
{
    json_t* doc = sva_json_mission_framed(residual, name, g_doc.has_frame ? &g_doc.frame : NULL);
    FILE* out = doc != NULL ? fopen(path, "w") : NULL;
    if (out == NULL) {
        json_decref(doc);
        return error_exit(EXIT_FAILED, "%s: cannot open for writing: %s", path, strerror(errno));
    }
    const int written =
        sva_json_write_plan(out, doc);  // any document: indented, newline-terminated
    json_decref(doc);
    if (fclose(out) != 0 || written != 0) {
        return error_exit(EXIT_FAILED, "%s: cannot write the residual mission", path);
    }
    return EXIT_PLANNED;
}

static int replay(const options_t* opt, sva_algorithm_t algorithm)
{
    sva_diag_t diag;
    sva_diag_clear(&diag);
    if (!g_doc.has_plan) {
        const sva_status_t status =
            sva_plan(&g_planner, &g_doc.mission, algorithm, &g_doc.plan, &diag);
        if (status != SVA_OK) {
            return plan_failed(status, &diag);
        }
    }
    if (sva_live_init(&g_live, &g_doc.mission, &g_doc.plan, &diag) != SVA_OK) {
        // The JSON layer refuses a plan in force that breaks these rules first; a route
        // rule is the plan document's all the same.
        const bool route = diag.field == SVA_FIELD_ROUTES || diag.field == SVA_FIELD_ROUTE_UAV ||
                           diag.field == SVA_FIELD_ROUTE_TARGETS;
        char message[SVA_JSON_ERROR_SIZE];
        (void)sva_diag_format(&diag, message, sizeof message);
        return error_exit(EXIT_BAD_INPUT, "%s%s", route ? "plan." : "", message);
    }
    sva_live_result_t result;
    bool replanned = false;
    int64_t solve_us = 0;
    for (size_t i = 0; i < g_doc.event_count; ++i) {
        if (sva_live_apply(&g_live, &g_doc.events[i], &diag) != SVA_OK) {
            char message[SVA_JSON_ERROR_SIZE];
            (void)sva_diag_format(&diag, message, sizeof message);
            return error_exit(EXIT_BAD_INPUT, "events[%zu]: %s", i, message);
        }
        const bool last_of_tick =
            i + 1 == g_doc.event_count || g_doc.events[i + 1].at_ticks != g_doc.events[i].at_ticks;
        if (last_of_tick) {
            const sva_status_t status = timed_replan(algorithm, &result, &diag, &solve_us);
            if (status != SVA_OK) {
                return plan_failed(status, &diag);
            }
            replanned = true;
        }
    }
    if (!replanned || g_doc.now_ticks > g_live.now_ticks) {
        const sva_event_t clock = {.type = SVA_EVENT_CLOCK, .at_ticks = g_doc.now_ticks};
        if (sva_live_apply(&g_live, &clock, &diag) != SVA_OK) {
            char message[SVA_JSON_ERROR_SIZE];
            (void)sva_diag_format(&diag, message, sizeof message);
            return error_exit(EXIT_BAD_INPUT, "now: %s", message);
        }
        const sva_status_t status = timed_replan(algorithm, &result, &diag, &solve_us);
        if (status != SVA_OK) {
            return plan_failed(status, &diag);
        }
    } else if (g_doc.has_now && g_doc.now_ticks < g_live.now_ticks) {
        return error_exit(EXIT_BAD_INPUT, "now: %ld is before the last event (%ld)",
                          (long)g_doc.now_ticks, (long)g_live.now_ticks);
    }
    if (opt->residual != NULL) {
        const int code = write_residual(opt->residual, result.residual, g_doc.name);
        if (code != EXIT_PLANNED) {
            return code;
        }
    }
    json_t* doc = sva_json_replan(&g_live, &result, g_doc.name, solve_us);
    if (doc != NULL && !echo_frame(doc, g_doc.has_frame ? &g_doc.frame : NULL)) {
        json_decref(doc);
        doc = NULL;
    }
    if (doc == NULL) {
        return error_exit(EXIT_FAILED, "building the plan JSON: out of memory");
    }
    const int written = sva_json_write_plan(stdout, doc);
    json_decref(doc);
    if (written != 0) {
        return error_exit(EXIT_FAILED, "writing the plan: %s", strerror(errno));
    }
    return EXIT_PLANNED;
}

static int cmd_replan(int argc, char** argv)
{
    options_t opt;
    sva_algorithm_t algorithm;
    int code = parse_planning("replan", REPLAN_OPTIONS, argc, argv, &opt, &algorithm);
    if (code != EXIT_PLANNED || opt.help) {
        return code;
    }
    char err[SVA_JSON_ERROR_SIZE];
    const sva_json_result_t loaded = sva_json_load_live(opt.mission, &g_doc, err, sizeof err);
    if (loaded != SVA_JSON_OK) {
        return error_exit(loaded == SVA_JSON_BAD_INPUT ? EXIT_BAD_INPUT : EXIT_FAILED, "%s", err);
    }
    if (sva_planner_init(&g_planner) != SVA_OK) {
        sva_json_live_free(&g_doc);
        return error_exit(EXIT_FAILED, "planner initialisation failed");
    }
    if (opt.flow_work > 0) {
        // an explicit budget is the budget of every replan too
        g_planner.flow_max_work = (uint32_t)opt.flow_work;
        g_planner.flow_replan_work = (uint32_t)opt.flow_work;
    }
    code = replay(&opt, algorithm);
    sva_json_live_free(&g_doc);
    return code;
}

int main(int argc, char** argv)
{
    if (argc < 2) {
        return error_exit(EXIT_BAD_INPUT, "missing command (try 'sva --help')");
    }
    const char* command = argv[1];
    if (strcmp(command, "--help") == 0 || strcmp(command, "-h") == 0 ||
        strcmp(command, "help") == 0) {
        print_usage(stdout);
        return EXIT_PLANNED;
    }
    if (strcmp(command, "--version") == 0) {
        print_version();
        return EXIT_PLANNED;
    }
    if (strcmp(command, "plan") == 0) {
        return cmd_plan(argc - 1, argv + 1);
    }
    if (strcmp(command, "validate") == 0) {
        return cmd_validate(argc - 1, argv + 1);
    }
    if (strcmp(command, "replan") == 0) {
        return cmd_replan(argc - 1, argv + 1);
    }
    return error_exit(EXIT_BAD_INPUT, "unknown command \"%s\" (try 'sva --help')", command);
}
