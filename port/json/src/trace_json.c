// trace_json.c -- transportation problems as JSON Lines (see sva/sva_json.h).
#include <sva/sva_json.h>

#include <stddef.h>

// json_array_append_new steals the value; a NULL value makes it fail.
static bool append(json_t* list, json_t* value)
{
    return json_array_append_new(list, value) == 0;
}

static json_t* int_list(const int32_t* values, size_t count)
{
    json_t* list = json_array();
    for (size_t i = 0; list != NULL && i < count; ++i) {
        if (!append(list, json_integer(values[i]))) {
            json_decref(list);
            list = NULL;
        }
    }
    return list;
}

// A source-major matrix; null where the pair is no arc, so the flow and the cost
// matrices line up cell for cell.
static json_t* matrix(const sva_tp_view_t* p, const int32_t* cells)
{
    json_t* rows = json_array();
    for (size_t s = 0; rows != NULL && s < p->source_count; ++s) {
        json_t* row = json_array();
        for (size_t k = 0; row != NULL && k < p->sink_count; ++k) {
            size_t at = s * p->sink_count + k;
            json_t* cell = p->cost[at] == SVA_TP_NO_ARC ? json_null() : json_integer(cells[at]);
            if (!append(row, cell)) {
                json_decref(row);
                row = NULL;
            }
        }
        if (!append(rows, row)) {
            json_decref(rows);
            rows = NULL;
        }
    }
    return rows;
}

json_t* sva_json_transport(const sva_mission_t* mission, const sva_tp_view_t* p)
{
    json_t* sources = json_array();
    json_t* sinks = json_array();
    json_t* dropped = json_array();
    bool ok = sources != NULL && sinks != NULL && dropped != NULL;
    for (size_t s = 0; ok && s < p->source_count; ++s) {
        ok = append(sources, json_integer(mission->uavs[p->source_first_uav[s]].id));
    }
    for (size_t k = 0; ok && k < p->sink_count; ++k) {
        ok = append(sinks, json_integer(mission->targets[p->sink_targets[k]].id)) &&
             append(dropped, json_boolean(p->sink_dropped[k]));
    }
    json_t* doc = ok ? json_object() : NULL;
    if (doc != NULL &&
        json_object_set_new(doc, "algorithm", json_string(sva_algorithm_name(p->algorithm))) == 0 &&
        json_object_set_new(doc, "source_uavs", sources) == 0 &&
        json_object_set_new(doc, "supply", int_list(p->supply, p->source_count)) == 0 &&
        json_object_set_new(doc, "sink_targets", sinks) == 0 &&
        json_object_set_new(doc, "demand", int_list(p->demand, p->sink_count)) == 0 &&
        json_object_set_new(doc, "dropped", dropped) == 0 &&
        json_object_set_new(doc, "cost", matrix(p, p->cost)) == 0 &&
        json_object_set_new(doc, "flow", matrix(p, p->flow)) == 0 &&
        json_object_set_new(doc, "cost_total", json_integer(p->cost_total)) == 0 &&
        json_object_set_new(doc, "covered", json_integer(p->covered)) == 0 &&
        json_object_set_new(doc, "pivots", json_integer(p->pivots)) == 0) {
        return doc;
    }
    if (doc == NULL) {
        // Not yet handed to doc: release them here.
        json_decref(sources);
        json_decref(sinks);
        json_decref(dropped);
    }
    json_decref(doc);
    return NULL;
}

void sva_trace_observer(void* user, const sva_tp_view_t* problem)
{
    sva_trace_t* trace = user;
    if (trace->failed) {
        return;
    }
    json_t* doc = sva_json_transport(trace->mission, problem);
    if (doc == NULL || json_dumpf(doc, trace->out, JSON_COMPACT | JSON_PRESERVE_ORDER) != 0 ||
        fputc('\n', trace->out) == EOF) {
        trace->failed = true;
    } else {
        trace->problems += 1;
    }
    json_decref(doc);
}

void sva_trace_attach(sva_trace_t* trace, sva_planner_t* planner, FILE* out,
                      const sva_mission_t* mission)
{
    trace->out = out;
    trace->mission = mission;
    trace->problems = 0;
    trace->failed = false;
    planner->on_transport = sva_trace_observer;
    planner->on_transport_user = trace;
}
