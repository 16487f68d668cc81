// main.c -- plan the mission held in flash once, then idle.
// A real firmware would refill the mission from its fleet state and run sva_plan()
// from a low-priority task; the planner's memory stays where it is.
#include <stdint.h>

#include "sva/sva.h"

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
