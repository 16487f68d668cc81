// lcm_status.c -- the node's status message (counters, revisions, state).
#include <string.h>

#include "lcm_internal.h"

sva_status_t sva_lcm_publish_status(sva_lcm_node_t* self, int64_t utime)
{
    sva_lcm_node_status_t* s = &self->priv.status_tx;
    memset(s, 0, sizeof(*s));
    self->counters.status_seq += 1U;
    s->version = SVA_LCM_NODE_STATUS_T_VERSION;
    s->utime = utime;
    s->seq = (int64_t)self->counters.status_seq;
    s->state = (self->priv.have_fleet && self->priv.have_mission)
                   ? SVA_LCM_NODE_STATUS_T_STATE_READY
                   : SVA_LCM_NODE_STATUS_T_STATE_WAITING;
    s->algorithm = (int8_t)self->algorithm;
    s->fleet_revision = self->priv.have_fleet ? self->priv.fleet_revision : -1;
    s->mission_revision = self->priv.have_mission ? self->priv.mission_revision : -1;
    s->last_plan_id = (self->priv.plan_id > 0) ? self->priv.plan_id : -1;
    s->fleet_rx = (int64_t)self->counters.fleet_rx;
    s->mission_rx = (int64_t)self->counters.mission_rx;
    s->plans_published = (int64_t)self->counters.plans_published;
    s->unchanged = (int64_t)self->counters.unchanged;
    for (int r = 0; r < (int)SVA_LCM_REJECT_COUNT_; ++r) {
        s->rejected[r] = (self->counters.rejected[r] > (uint32_t)INT32_MAX)
                             ? INT32_MAX
                             : (int32_t)self->counters.rejected[r];
    }
    const int n = sva_lcm_node_status_t_encode(self->priv.status_buf, 0,
                                               (int)sizeof self->priv.status_buf, s);
    if ((n != SVA_LCM_STATUS_BYTES) ||
        (self->publish(self->publish_user, self->channel_status, self->priv.status_buf,
                       (unsigned int)n) != 0)) {
        self->counters.publish_errors += 1U;
        return SVA_ERR_ARGUMENT;
    }
    return SVA_OK;
}
