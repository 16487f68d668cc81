// messages.c -- what the sva command line says: one-line errors, the usage text.
#define _POSIX_C_SOURCE 200809L

#include <stdarg.h>
#include <stdio.h>

#include <sva/sva.h>
#include <sva/sva_json.h>
#include <sva/sva_text.h>

#include "cli.h"

#if defined(__GNUC__) || defined(__clang__)
__attribute__((format(printf, 2, 3)))
#endif
int
sva_cli_error(int code, const char* fmt, ...)
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

void sva_cli_list_algorithms(char* out, size_t size)
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

void sva_cli_usage(FILE* out)
{
    char algos[128];
    sva_cli_list_algorithms(algos, sizeof algos);
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
