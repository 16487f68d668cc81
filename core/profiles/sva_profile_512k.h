// 512k profile: the largest that fits a part with 512 KiB of RAM (checked by
// tests/footprint on Cortex-M4F: planner + plan + 4 KiB stack, the mission in flash).
// The default mission bounds (64 UAVs, 256 targets, 24x48 tableau); only flow's graph
// is capped lower, at 28,672 arcs (200 targets x 40 UAVs with need 1 need ~28,500).
// A mission whose graph is larger gets flow's fallback (ga's and sva's plans through
// the repair and local search, no bound).
// flow also keeps 4 labels per target (not 8) in its Lagrangian phase, and searches
// 16 levels deep (not 24). Its route master (the Lagrangian's LP prices) is off: the
// prices come from subgradient steps alone. So is its coverage search (16 KiB). Its
// missions all plan by the small missions' rules (SVA_FLOW_LARGE_FROM at its 256
// targets): the large ones' granular moves would take 11 KiB of RAM, and their code a
// little more stack than its budget leaves.
#ifndef SVA_PROFILE_512K_H
#define SVA_PROFILE_512K_H
#define SVA_FLOW_MAX_ARCS      28672L
#define SVA_FLOW_LABELS        4
#define SVA_FLOW_MAX_DEPTH     16
#define SVA_FLOW_LP_ROWS       1
#define SVA_FLOW_LP_COLS       1
#define SVA_FLOW_COVER_TARGETS 0
#define SVA_FLOW_LARGE_FROM    256
#endif
