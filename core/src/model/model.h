// model.h -- private interfaces of the shared model (core/src/model/): validation,
// diagnostics, the SPEC orders and the planning state every algorithm builds its plan
// in. Not installed; never included by ports or tools. Includes nothing of the core
// but the public header: the model is the bottom of the core's parts (DESIGN.md
// section 9).
#ifndef SVA_MODEL_H
#define SVA_MODEL_H

#include "sva/sva.h"

// Asserts guard API misuse and internal invariants only, never untrusted input (bad
// input gets an error, never a crash: SPEC section 4). Default: the C library's
// assert (so NDEBUG turns it off, as anywhere in C); SVA_ENABLE_ASSERT=0 compiles them
// out; firmware may define SVA_ASSERT(x) to its own handler. Disabled, the expression
// is still type-checked.
#ifndef SVA_ASSERT
#    if SVA_ENABLE_ASSERT && !defined(NDEBUG)
#        include <assert.h>
#        define SVA_ASSERT(x) assert(x)
#    else
#        define SVA_ASSERT(x) ((void)sizeof((x) ? 1 : 0))
#    endif
#endif

// C99 static assertion (negative array size on failure).
#define SVA_STATIC_ASSERT(cond, name) typedef char sva_static_assert_##name[(cond) ? 1 : -1]

// Integer headroom (DESIGN.md section 5): the longest leg is 2 * 65535 cells; every
// leg, supply, demand and index fits the types that hold it.
#define SVA_MAX_LEG_CELLS (2L * (SVA_COORD_MAX - SVA_COORD_MIN))
SVA_STATIC_ASSERT(SVA_MAX_LEG_CELLS <= 2147483647L, leg_fits_int32);
SVA_STATIC_ASSERT(SVA_MAX_LEG_CELLS* SVA_MAX_TICKS_PER_CELL + SVA_MAX_TICK <= 2147483647L,
                  arrival_fits_int32);
SVA_STATIC_ASSERT(SVA_MAX_TARGETS <= 65535L && SVA_MAX_UAVS <= 65535L, indices_fit_uint16);

/// Manhattan distance in cells (SPEC section 1); at most SVA_MAX_LEG_CELLS.
static inline int32_t sva_distance(int32_t ax, int32_t ay, int32_t bx, int32_t by)
{
    const int32_t dx = (ax > bx) ? (ax - bx) : (bx - ax);
    const int32_t dy = (ay > by) ? (ay - by) : (by - ay);
    return dx + dy;
}

/// Greatest common divisor (gcd(a, 0) = a), for the needs' lcm (paper/tableau.c,
/// flow/flow_graph.c).
static inline int64_t sva_gcd64(int64_t a, int64_t b)
{
    int64_t x = a;
    int64_t y = b;
    while (y != 0) {
        const int64_t r = x % y;
        x = y;
        y = r;
    }
    return x;
}

// order.c: targets by (start, end, id) into priv->target_order, UAVs by id into
// priv->uav_order (SPEC section 2).
void sva_sort_targets(sva_planner_priv_t* priv, const sva_mission_t* mission);
void sva_sort_uavs(sva_planner_priv_t* priv, const sva_mission_t* mission);

// plan.c: the planning state shared by every algorithm.
void sva_state_reset(sva_planner_priv_t* priv, const sva_mission_t* mission, sva_plan_t* plan);
bool sva_can_serve(const sva_planner_priv_t* priv, const sva_mission_t* mission,
                   const sva_plan_t* plan, uint16_t uav, uint16_t target);
/// Extra route distance if `uav` serves `target` next instead of flying home now.
int64_t sva_insertion_cells(const sva_planner_priv_t* priv, const sva_mission_t* mission,
                            uint16_t uav, uint16_t target);
void sva_commit(sva_planner_priv_t* priv, const sva_mission_t* mission, sva_plan_t* plan,
                uint16_t uav, uint16_t target);
/// Cells flown over targets[0..count-1] from the UAV's mission position, return leg
/// included; sva_route_cells: over a route's targets.
int64_t sva_path_cells(const sva_mission_t* mission, uint16_t uav, const uint16_t* targets,
                       uint16_t count);
int64_t sva_route_cells(const sva_mission_t* mission, uint16_t uav, const sva_route_t* route);
void sva_plan_finish(sva_planner_priv_t* priv, const sva_mission_t* mission, sva_plan_t* plan);

// algorithm.c: name lookups without the C library.
bool sva_names_equal(const char* a, const char* b);

#endif  // SVA_MODEL_H
