// main.c -- the sva command line: plan or validate a SPEC section 3 mission.
//
// Exit codes (docs/cli.md): 0 planned (complete or partial) or valid; 2 bad input
// (mission or usage); 1 anything else (I/O, SVA_ERR_SOLVER, SVA_ERR_LIMIT).
// Every error is exactly one line "sva: error: <message>" on stderr, and nothing is
// printed on stdout for a mission that was rejected or could not be planned.
//
// The commands are a layer down: plan.c (plan, validate), replan.c (replan), each on
// options.c (the options) and messages.c (errors, usage).
#define _POSIX_C_SOURCE 200809L

#include <stdio.h>
#include <string.h>

#include <sva/sva.h>

#include "cli.h"

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

int main(int argc, char** argv)
{
    if (argc < 2) {
        return sva_cli_error(EXIT_BAD_INPUT, "missing command (try 'sva --help')");
    }
    const char* command = argv[1];
    if (strcmp(command, "--help") == 0 || strcmp(command, "-h") == 0 ||
        strcmp(command, "help") == 0) {
        sva_cli_usage(stdout);
        return EXIT_PLANNED;
    }
    if (strcmp(command, "--version") == 0) {
        print_version();
        return EXIT_PLANNED;
    }
    if (strcmp(command, "plan") == 0) {
        return sva_cli_plan(argc - 1, argv + 1);
    }
    if (strcmp(command, "validate") == 0) {
        return sva_cli_validate(argc - 1, argv + 1);
    }
    if (strcmp(command, "replan") == 0) {
        return sva_cli_replan(argc - 1, argv + 1);
    }
    return sva_cli_error(EXIT_BAD_INPUT, "unknown command \"%s\" (try 'sva --help')", command);
}
