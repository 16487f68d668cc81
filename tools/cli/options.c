// options.c -- the command line's options, read with getopt_long (one table per command).
#define _POSIX_C_SOURCE 200809L

#include <errno.h>
#include <getopt.h>
#include <stdbool.h>
#include <stdlib.h>
#include <string.h>

#include <sva/sva.h>
#include <sva/sva_text.h>

#include "cli.h"

// An option's value as a decimal integer in [lo, hi] into *out (the programs' parser;
// bad_value words the error); false if it is not one or out of range.
static bool long_in(const char* value, long lo, long hi, long* out)
{
    return sva_text_to_long(NULL, value, lo, hi, out, NULL, 0) == SVA_OK;
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

const struct option PLAN_OPTIONS[] = {
    {"algo", required_argument, NULL, OPT_ALGO},
    {"flow-work", required_argument, NULL, OPT_FLOW_WORK},
    {"repeat", required_argument, NULL, OPT_REPEAT},
    {"schedule", no_argument, NULL, OPT_SCHEDULE},
    {"trace", required_argument, NULL, OPT_TRACE},
    {"help", no_argument, NULL, OPT_HELP},
    {NULL, 0, NULL, 0},
};
const struct option REPLAN_OPTIONS[] = {
    {"algo", required_argument, NULL, OPT_ALGO},
    {"flow-work", required_argument, NULL, OPT_FLOW_WORK},
    {"residual", required_argument, NULL, OPT_RESIDUAL},
    {"help", no_argument, NULL, OPT_HELP},
    {NULL, 0, NULL, 0},
};
const struct option VALIDATE_OPTIONS[] = {
    {"help", no_argument, NULL, OPT_HELP},
    {NULL, 0, NULL, 0},
};

// Error of an option whose value is missing or wrong.
static int bad_value(const char* command, int code)
{
    switch (code) {
    case OPT_ALGO:
        return sva_cli_error(EXIT_BAD_INPUT, "%s: --algo needs a value", command);
    case OPT_TRACE:
        return sva_cli_error(EXIT_BAD_INPUT, "%s: --trace needs a file name", command);
    case OPT_RESIDUAL:
        return sva_cli_error(EXIT_BAD_INPUT, "%s: --residual needs a file name", command);
    case OPT_FLOW_WORK:
        return sva_cli_error(
            EXIT_BAD_INPUT,
            "%s: --flow-work: must be an integer in [1000, %ld] (SVA_FLOW_MAX_WORK)", command,
            (long)SVA_FLOW_MAX_WORK);
    case OPT_REPEAT:
    default:
        return sva_cli_error(EXIT_BAD_INPUT, "%s: --repeat: must be an integer in [1, %d]", command,
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
    return sva_cli_error(EXIT_BAD_INPUT, "%s: unknown option \"%s\" (try 'sva --help')", command,
                         is_long ? argv[optind - 1] : short_form);
}

// Parses the arguments after the command with getopt_long: options and the mission in
// any order, "--" ends the options, long options as "--name VALUE" or "--name=VALUE"
// (or a unique prefix of the name), from the command's table. argv[0] is the command.
int sva_cli_parse_options(const char* command, const struct option* options, int argc, char** argv,
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
                return sva_cli_error(EXIT_BAD_INPUT,
                                     "%s: one mission expected, got \"%s\" and \"%s\"", command,
                                     opt->mission, optarg);
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
            if ((optarg == NULL) || (optarg[0] == '\0')) {
                return bad_value(command, code);
            }
            opt->trace = optarg;
            break;
        case OPT_RESIDUAL:
            if ((optarg == NULL) || (optarg[0] == '\0')) {
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
            return sva_cli_error(EXIT_BAD_INPUT, "%s: one mission expected, got \"%s\" and \"%s\"",
                                 command, opt->mission, argv[optind]);
        }
        opt->mission = argv[optind];
    }
    if (!opt->help && opt->mission == NULL) {
        return sva_cli_error(EXIT_BAD_INPUT, "%s: missing %s (or - for standard input)", command,
                             strcmp(command, "replan") == 0 ? "LIVE.json" : "MISSION.json");
    }
    return EXIT_PLANNED;
}

// The options of a command that plans (plan, replan), and its --algo: EXIT_PLANNED to go
// on (or with opt->help, after printing the usage), or the exit code of a usage error.
int sva_cli_parse_planning(const char* command, const struct option* options, int argc, char** argv,
                           options_t* opt, sva_algorithm_t* algorithm)
{
    const int code = sva_cli_parse_options(command, options, argc, argv, opt);
    if (code != EXIT_PLANNED || opt->help) {
        if (opt->help) {
            sva_cli_usage(stdout);
        }
        return code;
    }
    if (sva_algorithm_from_name(opt->algo, algorithm) != SVA_OK) {
        char algos[128];
        sva_cli_list_algorithms(algos, sizeof algos);
        return sva_cli_error(EXIT_BAD_INPUT, "%s: --algo: unknown algorithm \"%s\" (known: %s)",
                             command, opt->algo, algos);
    }
    return EXIT_PLANNED;
}
