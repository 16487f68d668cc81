// live_names.c -- the SPEC names of a live mission's target states and event types
// (SPEC section 12), used on every interface and in diagnostics.
#include "model.h"
#include "sva/sva_live.h"

const char* sva_target_state_name(sva_target_state_t state)
{
    static const char* const names[SVA_TARGET_STATE_COUNT_] = {
        "waiting", "under_way", "done", "expired", "cancelled", "lost",
    };
    return ((unsigned)state < (unsigned)SVA_TARGET_STATE_COUNT_) ? names[state] : "";
}

static const char* const event_names[SVA_EVENT_COUNT_] = {
    "clock",        "uav_lost",         "uav_back",       "fuel",
    "target_added", "target_cancelled", "target_changed", "position",
};

const char* sva_event_type_name(sva_event_type_t type)
{
    return ((unsigned)type < (unsigned)SVA_EVENT_COUNT_) ? event_names[type] : "";
}

sva_status_t sva_event_type_from_name(const char* name, sva_event_type_t* out)
{
    SVA_ASSERT(out != NULL);
    if ((name == NULL) || (out == NULL)) {
        return SVA_ERR_ARGUMENT;
    }
    for (int32_t k = 0; k < (int32_t)SVA_EVENT_COUNT_; k++) {
        if (sva_names_equal(name, event_names[k])) {
            *out = (sva_event_type_t)k;
            return SVA_OK;
        }
    }
    return SVA_ERR_ARGUMENT;
}
