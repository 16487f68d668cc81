/// trace_json.h -- transportation problems as JSON Lines (sva plan --trace FILE).
///
/// One compact JSON object per problem, in solving order:
///   {"algorithm":"sva","source_uavs":[..],"supply":[..],"sink_targets":[..],
///    "demand":[..],"dropped":[..],"cost":[[..]],"flow":[[..]],
///    "cost_total":N,"covered":K,"pivots":P}
/// source_uavs holds the id of the first (lowest-index) UAV of each source group,
/// sink_targets the target ids; cost and flow are source-major matrices with null
/// for a pair that is no arc (SVA_TP_NO_ARC).
#ifndef SVA_TRACE_JSON_H
#define SVA_TRACE_JSON_H

#include <stdbool.h>
#include <stdio.h>

#include <jansson.h>
#include <sva/sva.h>

#ifdef __cplusplus
extern "C" {
#endif

/// State of one trace: where lines go and the mission that maps indices to ids.
typedef struct {
    FILE* out;
    const sva_mission_t* mission;
    unsigned long problems;  ///< lines written
    bool failed;             ///< a write or an allocation failed; later lines are skipped
} sva_trace_t;

/// The problem as a JSON object (new reference), or NULL when memory runs out.
json_t* sva_json_transport(const sva_mission_t* mission, const sva_tp_view_t* problem);

/// An sva_tp_observer_t: `user` is an sva_trace_t. Writes one line per problem.
void sva_trace_observer(void* user, const sva_tp_view_t* problem);

/// Points planner->on_transport at sva_trace_observer with *trace.
void sva_trace_attach(sva_trace_t* trace, sva_planner_t* planner, FILE* out, const sva_mission_t* mission);

#ifdef __cplusplus
}
#endif

#endif  // SVA_TRACE_JSON_H
