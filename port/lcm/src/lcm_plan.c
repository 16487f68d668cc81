// lcm_plan.c -- planning the fleet and mission in force and publishing the plan.
#include <stdio.h>
#include <string.h>
#include <time.h>

#include "lcm_internal.h"

int64_t sva_lcm_now_us(clockid_t clock)
{
    struct timespec ts;
    if (clock_gettime(clock, &ts) != 0) {
        return 0;
    }
    return ((int64_t)ts.tv_sec * 1000000) + ((int64_t)ts.tv_nsec / 1000);
}

static void publish_plan(sva_lcm_node_t* self)
{
    sva_lcm_plan_t* p = &self->priv.plan_tx;
    p->utime = sva_lcm_now_us(CLOCK_REALTIME);
    const int n = sva_lcm_plan_t_encode(self->priv.plan_buf, 0, (int)sizeof self->priv.plan_buf, p);
    if ((n != SVA_LCM_PLAN_BYTES) || (self->publish(self->publish_user, self->channel_plan,
                                                    self->priv.plan_buf, (unsigned int)n) != 0)) {
        self->counters.publish_errors += 1U;
        return;
    }
    self->counters.plans_published += 1U;
}

void sva_lcm_replan(sva_lcm_node_t* self)
{
    sva_lcm_plan_t* p = &self->priv.plan_tx;
    // Every array is encoded in full: clear what the last plan left behind.
    memset(p, 0, sizeof(*p));
    self->priv.plan_id += 1;
    p->version = SVA_LCM_PLAN_T_VERSION;
    p->plan_id = self->priv.plan_id;
    p->fleet_revision = self->priv.fleet_revision;
    p->mission_revision = self->priv.mission_revision;
    p->algorithm = (int8_t)self->algorithm;

    sva_diag_t diag;
    sva_diag_clear(&diag);
    const int64_t t0 = sva_lcm_now_us(CLOCK_MONOTONIC);
    const sva_status_t st = sva_plan(&self->priv.planner, &self->priv.mission, self->algorithm,
                                     &self->priv.plan, &diag);
    const int64_t dt = sva_lcm_now_us(CLOCK_MONOTONIC) - t0;
    p->solve_us = (dt > (int64_t)INT32_MAX) ? INT32_MAX : (int32_t)dt;

    // The plan published starts the live mission (sva_live_init validates again; a
    // change_penalty or takeoff_ticks out of range fails here and leaves no live mission).
    self->priv.live_active = false;
    if (st == SVA_OK) {
        sva_diag_t live_diag;
        self->priv.mission.change_penalty = self->change_penalty;
        self->priv.mission.takeoff_ticks = self->takeoff_ticks;
        self->priv.live_active = (sva_live_init(&self->priv.live, &self->priv.mission,
                                                &self->priv.plan, &live_diag) == SVA_OK);
        if (!sva_lcm_fill_plan(p, &self->priv.plan, &self->priv.mission)) {
            memset(p->routes, 0, sizeof p->routes);
            memset(p->route_targets, 0, sizeof p->route_targets);
            p->route_count = 0;
            p->item_count = 0;
            p->status = SVA_LCM_PLAN_T_STATUS_TOO_LARGE;
            char what[128];
            (void)snprintf(what, sizeof what,
                           "%s: plan needs more than MAX_ROUTE_ITEMS (%d) route items",
                           self->channel_plan, SVA_LCM_PLAN_T_MAX_ROUTE_ITEMS);
            (void)sva_lcm_reject(self, SVA_LCM_REJECT_TOO_LARGE, what);
        }
    } else {
        self->last_diag = diag;
        sva_lcm_plan_diag(p, &diag);
        p->error_code = (int8_t)st;
        if (st == SVA_ERR_INVALID) {
            p->status = SVA_LCM_PLAN_T_STATUS_REJECTED;
            (void)sva_lcm_reject_diag(self, SVA_LCM_REJECT_INVALID, "fleet+mission");
        } else {
            p->status = SVA_LCM_PLAN_T_STATUS_FAILED;
            (void)sva_lcm_reject_diag(self, SVA_LCM_REJECT_PLANNER, "planner");
        }
    }
    publish_plan(self);
}
