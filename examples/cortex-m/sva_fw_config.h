// sva_fw_config.h -- this firmware's sva configuration (SVA_CONFIG_HEADER points here).
// sva_config.h includes it first, so everything defined here wins over the defaults.
#ifndef SVA_FW_CONFIG_H
#define SVA_FW_CONFIG_H

// Bounds: one of core/profiles (CMake passes the name), or define SVA_MAX_* yourself.
#ifdef SVA_FW_PROFILE_HEADER
#    include SVA_FW_PROFILE_HEADER
#endif

// API-misuse checks stay on, but go to the firmware's fault handler instead of the C
// library's assert(), which would pull in fprintf and with it newlib's heap.
void fw_assert_failed(void);
#define SVA_ASSERT(x) ((x) ? (void)0 : fw_assert_failed())

#endif
