// planner.c -- the public entry points: planner set-up, sva_plan() and sva_replan().
#include "flow/flow.h"
#include "paper/paper.h"

#include <string.h>

sva_status_t sva_planner_init(sva_planner_t* self)
{
    SVA_ASSERT(self != NULL);
    if (self == NULL) {
        return SVA_ERR_ARGUMENT;
    }
    self->on_transport = NULL;
    self->on_transport_user = NULL;
    self->flow_max_work = (uint32_t)SVA_FLOW_MAX_WORK;
    self->flow_replan_work = (uint32_t)SVA_FLOW_REPLAN_WORK;
    self->priv.standing = NULL;
    return SVA_OK;
}

static void plan_clear(sva_plan_t* plan, sva_algorithm_t algorithm)
{
    plan->algorithm = algorithm;
    plan->status = SVA_PLAN_NONE;
    plan->covered = 0U;
    plan->uncovered_count = 0U;
    plan->cost = 0;
    plan->route_count = 0U;
    plan->stranded_count = 0U;
    (void)memset(&plan->stats, 0, sizeof(plan->stats));
}

sva_status_t sva_plan(sva_planner_t* self, const sva_mission_t* mission, sva_algorithm_t algorithm,
                      sva_plan_t* plan, sva_diag_t* diag)
{
    SVA_ASSERT((self != NULL) && (mission != NULL) && (plan != NULL));
    SVA_ASSERT((unsigned)algorithm < (unsigned)SVA_ALGO_COUNT_);
    // Unsigned: enums may be unsigned (short enums on AAPCS), and a negative value wraps high.
    if ((self == NULL) || (mission == NULL) || (plan == NULL) ||
        ((unsigned)algorithm >= (unsigned)SVA_ALGO_COUNT_)) {
        return SVA_ERR_ARGUMENT;
    }
    plan_clear(plan, algorithm);
    sva_status_t st = sva_mission_validate(mission, diag);
    if (st != SVA_OK) {
        return st;
    }
    sva_planner_priv_t* priv = &self->priv;
    sva_state_reset(priv, mission, plan);
    switch (algorithm) {
    case SVA_ALGO_SVA:
    case SVA_ALGO_HGA:
        st = sva_run_pipeline(self, mission, algorithm, plan);
        break;
    case SVA_ALGO_GA:
        sva_run_ga(priv, mission, plan);
        break;
    case SVA_ALGO_BFA:
        st = sva_run_bfa(priv, mission, plan, diag);
        break;
    case SVA_ALGO_FLOW:
        st = sva_run_flow(self, mission, priv->standing, plan);
        break;
    case SVA_ALGO_COUNT_:
    default:
        st = SVA_ERR_ARGUMENT;
        break;
    }
    if (st != SVA_OK) {
        const sva_stats_t stats = plan->stats;  // keep the counters for diagnosis
        plan_clear(plan, algorithm);
        plan->stats = stats;
        return st;
    }
    sva_plan_finish(priv, mission, plan);
    return SVA_OK;
}

// The standing plan reaches the planner through its private state, not as an argument of
// a shared body: sva_plan() stays the one frame on its own call path (the Cortex-M stack
// budget, tests/footprint/budget.txt), and only a replan pays for this one.
sva_status_t sva_replan(sva_planner_t* self, const sva_mission_t* mission,
                        sva_algorithm_t algorithm, const sva_plan_t* standing, sva_plan_t* plan,
                        sva_diag_t* diag)
{
    SVA_ASSERT(self != NULL);
    if (self == NULL) {
        return SVA_ERR_ARGUMENT;
    }
    self->priv.standing = standing;
    const sva_status_t st = sva_plan(self, mission, algorithm, plan, diag);
    self->priv.standing = NULL;
    return st;
}
