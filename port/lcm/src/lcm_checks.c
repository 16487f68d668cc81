// lcm_checks.c -- what a refusal is: counted, logged once per reason; the checks every
// message passes before it is taken (size, fingerprint, version, field ranges).
#include <stdio.h>

#include "lcm_internal.h"

static const char* const reject_names[SVA_LCM_REJECT_COUNT_] = {
    "truncated", "trailing", "fingerprint", "count",   "value",
    "invalid",   "planner",  "too_large",   "version",
};

const char* sva_lcm_reject_name(sva_lcm_reject_t reason)
{
    if ((unsigned)reason >= (unsigned)SVA_LCM_REJECT_COUNT_) {
        return "";
    }
    return reject_names[reason];
}

void sva_lcm_log(sva_lcm_node_t* self, const char* line)
{
    if (self->log != NULL) {
        self->log(self->log_user, line);
    }
}

sva_lcm_status_t sva_lcm_reject(sva_lcm_node_t* self, sva_lcm_reject_t reason, const char* what)
{
    self->last_reject = reason;
    self->counters.rejected[reason] += 1U;
    const uint32_t bit = (uint32_t)1U << (uint32_t)reason;
    if ((self->priv.logged & bit) == 0U) {
        self->priv.logged |= bit;
        char line[360];
        (void)snprintf(line, sizeof line,
                       "rejected (%s; further ones only counted in %.63s): %.239s",
                       sva_lcm_reject_name(reason), self->channel_status, what);
        sva_lcm_log(self, line);
    }
    return SVA_LCM_REJECTED;
}

sva_lcm_status_t sva_lcm_reject_diag(sva_lcm_node_t* self, sva_lcm_reject_t reason,
                                     const char* channel)
{
    char msg[160];
    char what[240];
    (void)sva_diag_format(&self->last_diag, msg, sizeof msg);
    (void)snprintf(what, sizeof what, "%.63s: %.159s", channel, msg);
    return sva_lcm_reject(self, reason, what);
}

// Size and fingerprint, before the generated decoder sees the bytes. Returns
// SVA_LCM_ACCEPTED when the bytes may be decoded.
sva_lcm_status_t sva_lcm_check_frame(sva_lcm_node_t* self, const char* channel, const void* data,
                                     size_t size, size_t want, int64_t fingerprint)
{
    char what[160];
    if ((data == NULL) || (size < want)) {
        (void)snprintf(what, sizeof what, "%s: %zu bytes, the type needs exactly %zu", channel,
                       size, want);
        return sva_lcm_reject(self, SVA_LCM_REJECT_TRUNCATED, what);
    }
    if (size > want) {
        (void)snprintf(what, sizeof what, "%s: %zu bytes, the type needs exactly %zu", channel,
                       size, want);
        return sva_lcm_reject(self, SVA_LCM_REJECT_TRAILING, what);
    }
    const uint8_t* b = (const uint8_t*)data;
    uint64_t got = 0;
    for (size_t i = 0; i < 8U; ++i) {
        got = (got << 8U) | (uint64_t)b[i];
    }
    if (got != (uint64_t)fingerprint) {
        (void)snprintf(what, sizeof what, "%s: fingerprint 0x%016llx, expected 0x%016llx", channel,
                       (unsigned long long)got, (unsigned long long)(uint64_t)fingerprint);
        return sva_lcm_reject(self, SVA_LCM_REJECT_FINGERPRINT, what);
    }
    return SVA_LCM_ACCEPTED;
}

// A decoded message's version field against the type's VERSION: a refusal names both.
bool sva_lcm_version_ok(sva_lcm_node_t* self, const char* channel, const char* type, int version,
                        int want, sva_lcm_status_t* verdict)
{
    if (version == want) {
        return true;
    }
    char what[160];
    (void)sva_lcm_version_check(channel, type, version, want, "node", what, sizeof what);
    *verdict = sva_lcm_reject(self, SVA_LCM_REJECT_VERSION, what);
    return false;
}
