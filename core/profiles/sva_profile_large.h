// Large profile: fleets of up to 128 UAVs over up to 1,024 targets (sized for 100 UAVs
// over 1,000 targets), for a companion computer rather than a microcontroller.
// flow's graph holds every arc of a need-1 mission at these bounds (656,000: the
// complete graph of 128 UAVs and 1,024 copies), so flow keeps its relaxation, its
// rounding and its certified bound there. Every other bound is the default's, so a
// mission within the default bounds gets the default profile's plans.
#ifndef SVA_PROFILE_LARGE_H
#define SVA_PROFILE_LARGE_H
#define SVA_MAX_UAVS      128
#define SVA_MAX_TARGETS   1024
#define SVA_FLOW_MAX_ARCS 656000L
#endif
