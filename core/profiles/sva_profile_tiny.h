// Tiny profile for small microcontrollers: 8 UAVs, 16 targets.
#ifndef SVA_PROFILE_TINY_H
#define SVA_PROFILE_TINY_H
#define SVA_MAX_UAVS 8
#define SVA_MAX_TARGETS 16
#define SVA_MAX_TP_SOURCES 8
#define SVA_MAX_TP_SINKS 16
#define SVA_BFA_MAX_TARGETS 8
#define SVA_BFA_MAX_UAVS 4
#endif
