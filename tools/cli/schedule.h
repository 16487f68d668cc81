/// schedule.h -- a plan as a readable schedule (sva plan --schedule).
#ifndef SVA_SCHEDULE_H
#define SVA_SCHEDULE_H

#include <stdio.h>

#include <sva/sva.h>

/// Writes the schedule of a successful sva_plan(): a header (mission, algorithm,
/// status, covered/total, cost), one block per UAV in mission order (start position,
/// each target with position, window and need, distance and fuel used/fuel), then the
/// stranded UAVs and the uncovered targets. The name is printed escaped
/// (sva_text_escape()). Returns 0, or -1 when writing fails.
int sva_write_schedule(FILE* out, const sva_mission_t* mission, const char* name,
                       const sva_plan_t* plan);

#endif  // SVA_SCHEDULE_H
