// limits.c -- the compiled bounds, reported at run time.
#include "model.h"
#include "sva/sva_live.h"

sva_limits_t sva_limits(void)
{
    sva_limits_t limits;
    limits.max_uavs = (uint32_t)SVA_MAX_UAVS;
    limits.max_targets = (uint32_t)SVA_MAX_TARGETS;
    limits.max_route_targets = (uint32_t)SVA_MAX_ROUTE_TARGETS;
    limits.max_tp_sources = (uint32_t)SVA_MAX_TP_SOURCES;
    limits.max_tp_sinks = (uint32_t)SVA_MAX_TP_SINKS;
    limits.max_pivots = (uint32_t)SVA_MAX_PIVOTS;
    limits.bfa_max_targets = (uint32_t)SVA_BFA_MAX_TARGETS;
    limits.bfa_max_uavs = (uint32_t)SVA_BFA_MAX_UAVS;
    limits.bfa_max_nodes = (uint32_t)SVA_BFA_MAX_NODES;
    limits.hga_max_nodes = (uint32_t)SVA_HGA_MAX_NODES;
    limits.flow_max_copies = (uint32_t)SVA_FLOW_MAX_COPIES;
    limits.flow_max_arcs = (uint32_t)SVA_FLOW_MAX_ARCS;
    limits.flow_max_depth = (uint32_t)SVA_FLOW_MAX_DEPTH;
    limits.flow_max_work = (uint32_t)SVA_FLOW_MAX_WORK;
    limits.mission_bytes = (uint32_t)sizeof(sva_mission_t);
    limits.plan_bytes = (uint32_t)sizeof(sva_plan_t);
    limits.planner_bytes = (uint32_t)sizeof(sva_planner_t);
    limits.live_bytes = (uint32_t)sizeof(sva_live_t);
    return limits;
}
