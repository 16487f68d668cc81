/// cli.h -- what the sva command line's files share (tools/cli/); not installed.
/// main.c dispatches to the commands (plan.c: plan, validate; replan.c: replan), which
/// stand on options.c (the options) and messages.c (errors, usage); replan.c also uses
/// plan.c's planner and plan helpers. No file calls one above it.
#ifndef SVA_CLI_H
#define SVA_CLI_H

#include <getopt.h>
#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <time.h>

#include <jansson.h>
#include <sva/sva.h>
#include <sva/sva_frame.h>

#include "exit_status.h"

enum { REPEAT_MAX = 1000 };  // --repeat: runs of one mission in one process

/// A command's options (every command's; a command's table says which it takes).
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

// --- messages.c -----------------------------------------------------------------

/// Prints "sva: error: <message>" (escaped: one printable line) on stderr; returns code.
#if defined(__GNUC__) || defined(__clang__)
__attribute__((format(printf, 2, 3)))
#endif
int sva_cli_error(int code, const char* fmt, ...);

/// The algorithms' names, comma-separated, into out.
void sva_cli_list_algorithms(char* out, size_t size);

/// The usage text.
void sva_cli_usage(FILE* out);

// --- options.c ------------------------------------------------------------------

/// The option tables of the commands.
extern const struct option PLAN_OPTIONS[];
extern const struct option REPLAN_OPTIONS[];
extern const struct option VALIDATE_OPTIONS[];

/// Parses the arguments after the command (argv[0]) with the command's table:
/// EXIT_PLANNED, or the exit code of a usage error (its message printed).
int sva_cli_parse_options(const char* command, const struct option* options, int argc, char** argv,
                          options_t* opt);

/// The options of a command that plans (plan, replan), and its --algo: EXIT_PLANNED to go
/// on (or with opt->help, after printing the usage), or the exit code of a usage error.
int sva_cli_parse_planning(const char* command, const struct option* options, int argc, char** argv,
                           options_t* opt, sva_algorithm_t* algorithm);

// --- plan.c ---------------------------------------------------------------------

/// The planner every command plans with (static storage, as on firmware).
extern sva_planner_t sva_cli_planner;

/// Microseconds from *a to *b.
int64_t sva_cli_elapsed_us(const struct timespec* a, const struct timespec* b);

/// Maps a failed sva_plan() to its message and exit code.
int sva_cli_plan_failed(sva_status_t status, const sva_diag_t* diag);

/// The mission's frame (none: NULL), echoed into its plan as the mission wrote it.
bool sva_cli_echo_frame(json_t* doc, const sva_frame_t* frame);

/// sva validate and sva plan: argv[0] is the command; returns the exit code.
int sva_cli_validate(int argc, char** argv);
int sva_cli_plan(int argc, char** argv);

// --- replan.c -------------------------------------------------------------------

/// sva replan: argv[0] is the command; returns the exit code.
int sva_cli_replan(int argc, char** argv);

#endif  // SVA_CLI_H
