// Default profile: the sva_config.h defaults (64 UAVs, 256 targets, 24x48 tableau).
#ifndef SVA_PROFILE_DEFAULT_H
#define SVA_PROFILE_DEFAULT_H
#endif
