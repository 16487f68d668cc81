// Tiny profile for small microcontrollers: 8 UAVs, 16 targets; flow's route master
// (the Lagrangian's LP prices), its standing plan (a live mission's change_penalty
// weighed by flow itself; the replan still weighs it) and its coverage search off, to
// fit 32 KiB of flash.
#ifndef SVA_PROFILE_TINY_H
#define SVA_PROFILE_TINY_H
#define SVA_MAX_UAVS           8
#define SVA_MAX_TARGETS        16
#define SVA_MAX_TP_SOURCES     8
#define SVA_MAX_TP_SINKS       16
#define SVA_BFA_MAX_TARGETS    8
#define SVA_BFA_MAX_UAVS       4
#define SVA_FLOW_LP_ROWS       1
#define SVA_FLOW_LP_COLS       1
#define SVA_FLOW_STANDING      0
#define SVA_FLOW_COVER_TARGETS 0
#endif
