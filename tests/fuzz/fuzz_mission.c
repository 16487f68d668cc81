// Fuzz target: mission JSON (port/json's sva_json reader) -> sva_mission_validate ->
// sva_plan with every algorithm. Properties checked on every input:
//   - the reader either accepts or writes a one-line message naming what is wrong;
//   - an accepted and valid mission gets a plan from every algorithm (bfa and flow may
//     refuse with SVA_ERR_LIMIT naming the limit), and every plan passes the
//     independent SPEC section 1 checker (tests/support/spec_checker.c);
//   - flow's certified lower bound holds against its own cost and bfa's optimum;
//   - a mission the core rejects gets SVA_ERR_INVALID from sva_plan too, an empty
//     plan, and a formatted message.
// Any violation aborts (a finding). Sanitizers: ASan + UBSan in the fuzz build.
#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <sva/sva_json.h>
#include "spec_checker.h"
#include "sva/sva.h"

int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size);

static sva_mission_t mission;
static sva_planner_t planner;
static sva_plan_t plan;

static void fail(const char* what, const char* detail)
{
    fprintf(stderr, "fuzz_mission: %s: %s\n", what, detail);
    abort();
}

int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size)
{
    char name[SVA_JSON_NAME_MAX + 1];
    char err[SVA_JSON_ERROR_SIZE];
    err[0] = '\0';
    sva_mission_init(&mission);
    const sva_json_status_t r =
        sva_json_parse_mission((const char*)data, size, "fuzz", &mission, name, err, sizeof err);
    if (r != SVA_JSON_OK) {
        if (r != SVA_JSON_ERR_INPUT || err[0] == '\0' || strchr(err, '\n') != NULL) {
            fail("reader refused without a one-line message", err);
        }
        return 0;
    }
    if (strlen(name) > SVA_JSON_NAME_MAX) {
        fail("name longer than SVA_JSON_NAME_MAX", name);
    }
    sva_diag_t diag;
    char msg[256];
    const sva_status_t valid = sva_mission_validate(&mission, &diag);
    bool bfa_ok = false;
    int bfa_covered = 0;
    long long bfa_cost = 0;
    if (sva_planner_init(&planner) != SVA_OK) {
        fail("planner init", "");
    }
    for (int a = 0; a < (int)SVA_ALGO_COUNT_; a++) {
        const sva_algorithm_t algo = (sva_algorithm_t)a;
        sva_diag_t pd;
        const sva_status_t st = sva_plan(&planner, &mission, algo, &plan, &pd);
        if (valid != SVA_OK) {
            (void)sva_diag_format(&pd, msg, sizeof msg);
            if (st != SVA_ERR_INVALID || plan.status != SVA_PLAN_NONE || plan.route_count != 0 ||
                pd.field == SVA_FIELD_NONE) {
                fail("rejected mission was planned or badly reported", msg);
            }
            continue;
        }
        if (st == SVA_ERR_LIMIT && (algo == SVA_ALGO_BFA || algo == SVA_ALGO_FLOW)) {
            if (pd.limit_name == NULL || plan.status != SVA_PLAN_NONE) {
                fail("algorithm limit without a named limit or with a plan",
                     sva_algorithm_name(algo));
            }
            continue;
        }
        if (st != SVA_OK) {
            (void)sva_diag_format(&pd, msg, sizeof msg);
            fprintf(stderr, "fuzz_mission: %s returned %d\n", sva_algorithm_name(algo), (int)st);
            fail("valid mission not planned", msg);
        }
        if (spec_check_plan(&mission, &plan, msg, sizeof msg) != 0) {
            fprintf(stderr, "fuzz_mission: algorithm %s\n", sva_algorithm_name(algo));
            fail("plan breaks SPEC section 1", msg);
        }
        if (algo == SVA_ALGO_BFA) {
            bfa_ok = true;
            bfa_covered = plan.covered;
            bfa_cost = plan.cost;
        }
        // flow's certificate (sva.h): no plan covering as many targets costs less than
        // lower_bound, and an "optimal" plan is not beaten by bfa's optimum.
        if (algo == SVA_ALGO_FLOW && plan.stats.has_bound) {
            if (plan.stats.lower_bound > plan.cost ||
                (plan.stats.optimal && plan.stats.lower_bound != plan.cost)) {
                fail("flow's lower bound is above its cost, or optimal without equality", "");
            }
            if (bfa_ok && bfa_covered == plan.covered && bfa_cost < plan.stats.lower_bound) {
                fail("bfa found a plan cheaper than flow's certified lower bound", "");
            }
            if (bfa_ok && plan.stats.optimal &&
                spec_better(bfa_covered, bfa_cost, plan.covered, plan.cost)) {
                fail("flow claims optimality but bfa's plan is better", "");
            }
        }
    }
    return 0;
}
