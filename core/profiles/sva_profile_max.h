// Max profile: the largest fleet and mission the tests exercise (256 UAVs, 1024 targets).
#ifndef SVA_PROFILE_MAX_H
#define SVA_PROFILE_MAX_H
#define SVA_MAX_UAVS       256
#define SVA_MAX_TARGETS    1024
#define SVA_MAX_TP_SOURCES 32
#define SVA_MAX_TP_SINKS   64
#endif
