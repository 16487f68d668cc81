// main.c -- plan the mission held in flash once, then idle.
// A real firmware would refill the mission from its fleet state and run sva_plan()
// from a low-priority task; the planner's memory stays where it is.
//
// Built with SVA_FW_SEMIHOSTING=1 (CMake option SVA_FW_SEMIHOSTING, for a debugger or
// qemu-system-arm), it instead plans the mission with every algorithm, prints one line
// per plan over semihosting and exits with status 0 if every plan succeeded
// (tests/footprint/qemu_run.py compares the lines with the host's `sva plan`).
#include <stdint.h>

#include "sva/sva.h"
#ifndef SVA_FW_SEMIHOSTING
#    define SVA_FW_SEMIHOSTING 0
#endif
#if SVA_FW_SEMIHOSTING
#    include "semihost.h"
#endif

extern const sva_mission_t fw_mission;  // mission.c: in flash (.rodata)

// All working memory is static: the linker, not a heap, places it (.bss).
static sva_planner_t planner;
static sva_plan_t plan;

// Results for a debugger or a telemetry task to read.
volatile int32_t fw_status = 1;  // 1: not run yet; else an sva_status_t
volatile int64_t fw_cost = -1;
volatile uint32_t fw_covered = 0;

void fw_assert_failed(void)
{
    for (;;) {
        // API misuse (sva_fw_config.h): stop here for the debugger / watchdog.
    }
}

#if SVA_FW_SEMIHOSTING
// One line per plan: "plan algo=<name> status=<sva_status_t> covered=<n> cost=<c>
// lower_bound=<b|-> optimal=<0|1> search_nodes=<n> pivots=<n> flow_work=<n>
// routes=<uav id>:<target id>,...;..." (ids, not indices, as in the JSON plan).
static void report(sva_algorithm_t algorithm, sva_status_t status)
{
    sh_put_str("plan algo=");
    sh_put_str(sva_algorithm_name(algorithm));
    sh_put_str(" status=");
    sh_put_int(status);
    if (status == SVA_OK) {
        sh_put_str(" covered=");
        sh_put_int(plan.covered);
        sh_put_str(" cost=");
        sh_put_int(plan.cost);
        sh_put_str(" lower_bound=");
        if (plan.stats.has_bound) {
            sh_put_int(plan.stats.lower_bound);
        } else {
            sh_put_str("-");
        }
        sh_put_str(" optimal=");
        sh_put_int(plan.stats.optimal ? 1 : 0);
        sh_put_str(" search_nodes=");
        sh_put_int((int64_t)plan.stats.search_nodes);
        sh_put_str(" pivots=");
        sh_put_int(plan.stats.pivots);
        sh_put_str(" flow_work=");
        sh_put_int((int64_t)plan.stats.flow_work);
        sh_put_str(" routes=");
        for (uint16_t u = 0u; u < plan.route_count; u++) {
            const sva_route_t* r = &plan.routes[u];
            sh_put_str((u > 0u) ? ";" : "");
            sh_put_int(r->uav_id);
            sh_put_str(":");
            for (uint16_t k = 0u; k < r->target_count; k++) {
                sh_put_str((k > 0u) ? "," : "");
                sh_put_int(fw_mission.targets[r->targets[k]].id);
            }
        }
    }
    sh_end_line();
}

int main(void)
{
    static const sva_algorithm_t algorithms[] = {SVA_ALGO_SVA, SVA_ALGO_GA, SVA_ALGO_HGA,
                                                 SVA_ALGO_BFA, SVA_ALGO_FLOW};
    sva_diag_t diag;
    uint32_t failures = 0u;
    sva_status_t status = sva_planner_init(&planner);
    for (uint32_t i = 0u; (status == SVA_OK) && (i < sizeof(algorithms) / sizeof(algorithms[0]));
         i++) {
        const sva_status_t st = sva_plan(&planner, &fw_mission, algorithms[i], &plan, &diag);
        report(algorithms[i], st);
        failures += (st == SVA_OK) ? 0u : 1u;
    }
    fw_status = (int32_t)status;
    sh_put_str("done failures=");
    sh_put_int(failures);
    sh_end_line();
    sh_exit(((status == SVA_OK) && (failures == 0u)) ? 0u : 1u);
    return 0;
}
#else
int main(void)
{
    sva_diag_t diag;
    sva_status_t status = sva_planner_init(&planner);
    if (status == SVA_OK) {
        status = sva_plan(&planner, &fw_mission, SVA_ALGO_SVA, &plan, &diag);
    }
    fw_status = (int32_t)status;
    if (status == SVA_OK) {
        fw_cost = plan.cost;
        fw_covered = plan.covered;
        // plan.routes[u].targets[] are indices into fw_mission.targets, in visit order.
    }
    for (;;) {
    }
}
#endif
