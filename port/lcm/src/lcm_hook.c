// lcm_hook.c -- durable inputs (sva_lcm_input_fn) and the plan id sequence a journal
// restores.
#include "lcm_internal.h"

bool sva_lcm_input_durable(sva_lcm_node_t* self, sva_lcm_input_t kind, bool restarts,
                           const void* data, size_t size)
{
    if (self->input_hook == NULL) {
        return true;
    }
    if (self->input_hook(self->input_hook_user, kind, restarts, data, size) == 0) {
        self->counters.inputs_hooked += 1U;
        return true;
    }
    self->halted = true;
    sva_lcm_log(self, "the input hook failed: halted, no answer is published from now on");
    return false;
}

sva_status_t sva_lcm_node_set_plan_id(sva_lcm_node_t* self, int64_t plan_id)
{
    if ((self == NULL) || (plan_id < 0)) {
        return SVA_ERR_ARGUMENT;
    }
    self->priv.plan_id = plan_id;
    return SVA_OK;
}
