// plan_print.c -- a CAN plan as one JSON line on stdout (plan_print.h).
#include "plan_print.h"

#include <stdio.h>

void sva_can_plan_print(const sva_can_plan_t* plan)
{
    uint16_t i;
    printf("{\"plan_id\": %u, \"algorithm\": %u, \"plan_status\": %u, \"route_count\": %u, "
           "\"items\": [",
           plan->plan_id, plan->algorithm, plan->plan_status, plan->route_count);
    for (i = 0; i < plan->item_count; ++i) {
        const sva_can_item_t* it = &plan->items[i];
        printf("%s{\"uav\": %u, \"target\": %u, \"x\": %d, \"y\": %d, \"arrive_by\": %lu, "
               "\"hold_until\": %lu}",
               (i == 0) ? "" : ", ", it->uav_id, it->target_id, it->x, it->y,
               (unsigned long)it->arrive_by_ticks, (unsigned long)it->hold_until_ticks);
    }
    printf("]}\n");
    fflush(stdout);
}
