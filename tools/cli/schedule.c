// schedule.c -- a plan as a readable schedule (see schedule.h).
#include "schedule.h"

#include <stdbool.h>

#include <sva/sva_json.h>
#include <sva/sva_text.h>

static void write_target(FILE* out, const char* lead, const sva_target_t* t)
{
    fprintf(out, "%starget %ld at (%ld, %ld), window [%ld, %ld], need %ld\n", lead, (long)t->id,
            (long)t->x, (long)t->y, (long)t->start_ticks, (long)t->end_ticks, (long)t->need);
}

static void write_route(FILE* out, const sva_mission_t* mission, const sva_uav_t* uav,
                        const sva_route_t* route)
{
    fprintf(out, "UAV %ld from (%ld, %ld), ready at %ld", (long)uav->id, (long)uav->x, (long)uav->y,
            (long)uav->ready_at_ticks);
    if (route->stranded) {
        fprintf(out, ": stranded, fuel %ld cannot bring it home\n", (long)uav->fuel);
        return;
    }
    if (route->target_count == 0) {
        fprintf(out, ": no targets\n");
    } else {
        fprintf(out, ":\n");
        for (uint16_t i = 0; i < route->target_count; ++i) {
            write_target(out, "  ", &mission->targets[route->targets[i]]);
        }
    }
    fprintf(out, "  back to depot (%ld, %ld): distance %lld, fuel %lld/%ld\n",
            (long)mission->depot_x, (long)mission->depot_y, (long long)route->distance_cells,
            (long long)route->fuel_used, (long)uav->fuel);
}

int sva_write_schedule(FILE* out, const sva_mission_t* mission, const char* name,
                       const sva_plan_t* plan)
{
    char shown[SVA_TEXT_ESCAPED_SIZE(SVA_JSON_NAME_MAX)];
    fprintf(out, "mission %s: algorithm %s, %s, covered %u/%u targets, cost %lld\n",
            sva_text_escape(shown, sizeof shown, name), sva_algorithm_name(plan->algorithm),
            plan->status == SVA_PLAN_COMPLETE ? "complete" : "partial", (unsigned)plan->covered,
            (unsigned)mission->target_count, (long long)plan->cost);
    fprintf(out, "depot (%ld, %ld), ticks_per_cell %ld, hover_fuel %ld\n\n", (long)mission->depot_x,
            (long)mission->depot_y, (long)mission->ticks_per_cell, (long)mission->hover_fuel);
    for (uint16_t i = 0; i < plan->route_count; ++i) {
        write_route(out, mission, &mission->uavs[i], &plan->routes[i]);
    }
    fprintf(out, "\nstranded:");
    bool any = false;
    for (uint16_t i = 0; i < plan->route_count; ++i) {
        if (plan->routes[i].stranded) {
            fprintf(out, " UAV %ld", (long)plan->routes[i].uav_id);
            any = true;
        }
    }
    fprintf(out, "%s\n", any ? "" : " none");
    fprintf(out, "uncovered:%s\n", plan->uncovered_count == 0 ? " none" : "");
    for (uint16_t i = 0; i < plan->uncovered_count; ++i) {
        write_target(out, "  ", &mission->targets[plan->uncovered[i]]);
    }
    return (fflush(out) != 0 || ferror(out)) ? -1 : 0;
}
