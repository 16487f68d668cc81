// Prints a CAN plan (sva_can_plan_t) as one JSON line on stdout: the node's and the
// VM test bridge's report of what went over the bus (docs/can.md).
#ifndef SVA_CAN_PLAN_PRINT_H
#define SVA_CAN_PLAN_PRINT_H

#include "sva/sva_can.h"

/// {"plan_id", "algorithm", "plan_status", "route_count", "items": [{"uav", "target",
/// "x", "y", "arrive_by", "hold_until"}, ...]} and a newline; flushes stdout.
void sva_can_plan_print(const sva_can_plan_t* plan);

#endif
