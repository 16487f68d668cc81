// lcm_versions.c -- the wire version check every reader of this port's messages makes:
// the node's adapter (lcm_checks.c) and the MAVLink bridge (contract in sva_lcm.h). It
// stands alone so that a reader links it without the adapter.
#include <stdio.h>

#include "sva/sva_lcm.h"

sva_lcm_status_t sva_lcm_version_check(const char* where, const char* type, int version, int want,
                                       const char* reader, char* err, size_t err_size)
{
    if (version == want) {
        return SVA_LCM_ACCEPTED;
    }
    if ((err != NULL) && (err_size > 0U)) {
        (void)snprintf(err, err_size, "%.63s: %.63s.version is %d, this %.15s speaks version %d",
                       (where != NULL) ? where : "", (type != NULL) ? type : "", version,
                       (reader != NULL) ? reader : "reader", want);
    }
    return SVA_LCM_REJECTED;
}
