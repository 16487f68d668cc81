// plan_json.c -- SPEC section 3 plan JSON (see sva/sva_json.h).
#include <sva/sva_json.h>

#include <stdbool.h>

// json_object_set_new steals the value even on failure; a NULL value fails the set.
static bool put(json_t* object, const char* key, json_t* value)
{
    return json_object_set_new(object, key, value) == 0;
}

static bool put_int(json_t* object, const char* key, int64_t value)
{
    return put(object, key, json_integer((json_int_t)value));
}

static json_t* target_ids(const sva_mission_t* mission, const uint16_t* indices, uint16_t count)
{
    json_t* list = json_array();
    for (uint16_t i = 0; list != NULL && i < count; ++i) {
        if (json_array_append_new(list, json_integer(mission->targets[indices[i]].id)) != 0) {
            json_decref(list);
            list = NULL;
        }
    }
    return list;
}

static json_t* route_json(const sva_mission_t* mission, const sva_route_t* route)
{
    json_t* r = json_object();
    if (r != NULL && put_int(r, "uav", route->uav_id) &&
        put(r, "targets", target_ids(mission, route->targets, route->target_count)) &&
        put_int(r, "distance", route->distance_cells) &&
        put_int(r, "fuel_used", route->fuel_used)) {
        return r;
    }
    json_decref(r);
    return NULL;
}

static json_t* routes_json(const sva_mission_t* mission, const sva_plan_t* plan)
{
    json_t* list = json_array();
    for (uint16_t i = 0; list != NULL && i < plan->route_count; ++i) {
        if (json_array_append_new(list, route_json(mission, &plan->routes[i])) != 0) {
            json_decref(list);
            list = NULL;
        }
    }
    return list;
}

static json_t* stranded_json(const sva_plan_t* plan)
{
    json_t* list = json_array();
    for (uint16_t i = 0; list != NULL && i < plan->route_count; ++i) {
        if (plan->routes[i].stranded &&
            json_array_append_new(list, json_integer(plan->routes[i].uav_id)) != 0) {
            json_decref(list);
            list = NULL;
        }
    }
    return list;
}

// flow's certificate: a lower bound on any plan covering as many targets, whether
// this plan is proven optimal and whether its coverage is proven the most; plus its
// search counters.
static bool flow_stats(json_t* o, const sva_stats_t* s)
{
    return put_int(o, "lower_bound", s->lower_bound) &&
           put(o, "optimal", json_boolean(s->optimal)) &&
           put(o, "coverage_proven", json_boolean(s->coverage_proven)) &&
           put_int(o, "flow_solves", s->flow_solves) &&
           put_int(o, "flow_augmentations", s->flow_augmentations) &&
           put_int(o, "flow_work", (int64_t)s->flow_work) &&
           put_int(o, "flow_graph_arcs", s->flow_graph_arcs) &&
           put_int(o, "flow_max_depth", s->flow_max_depth) &&
           put_int(o, "flow_lagrange_iters", s->flow_lagrange_iters) &&
           put_int(o, "flow_lp_columns", s->flow_lp_columns) &&
           put_int(o, "flow_dive_routes", s->flow_dive_routes) &&
           put_int(o, "flow_cover_dive", s->flow_cover_dive) &&
           put_int(o, "flow_cover_nodes", s->flow_cover_nodes) &&
           put_int(o, "flow_ruin_rounds", s->flow_ruin_rounds) &&
           put_int(o, "flow_incomplete", s->flow_incomplete);
}

static json_t* stats_json(const sva_stats_t* s, int64_t solve_us)
{
    json_t* o = json_object();
    if (o != NULL && put_int(o, "solve_us", solve_us) && put_int(o, "pivots", s->pivots) &&
        put_int(o, "clusters", s->clusters) &&
        put_int(o, "transport_problems", s->transport_problems) &&
        put_int(o, "largest_cluster", s->largest_cluster) &&
        put_int(o, "largest_sources", s->largest_sources) &&
        put_int(o, "largest_sinks", s->largest_sinks) &&
        put_int(o, "largest_tableau_cells", s->largest_tableau_cells) &&
        put_int(o, "max_pivots", s->max_pivots) &&
        put_int(o, "dropped_sources", s->dropped_sources) &&
        put_int(o, "chunked_clusters", s->chunked_clusters) &&
        put_int(o, "search_nodes", (int64_t)s->search_nodes) &&
        put_int(o, "truncated_searches", s->truncated_searches) &&
        (!s->has_bound || flow_stats(o, s))) {
        return o;
    }
    json_decref(o);
    return NULL;
}

json_t* sva_json_plan(const sva_mission_t* mission, const char* name, const sva_plan_t* plan,
                      int64_t solve_us)
{
    json_t* doc = json_object();
    const char* status = plan->status == SVA_PLAN_COMPLETE ? "complete" : "partial";
    if (doc != NULL && put(doc, "mission", json_string(name)) &&
        put(doc, "algorithm", json_string(sva_algorithm_name(plan->algorithm))) &&
        put(doc, "status", json_string(status)) && put_int(doc, "covered", plan->covered) &&
        put(doc, "uncovered", target_ids(mission, plan->uncovered, plan->uncovered_count)) &&
        put_int(doc, "cost", plan->cost) && put(doc, "routes", routes_json(mission, plan)) &&
        put(doc, "stranded", stranded_json(plan)) &&
        put(doc, "stats", stats_json(&plan->stats, solve_us))) {
        return doc;
    }
    json_decref(doc);
    return NULL;
}

sva_json_status_t sva_json_write_plan(FILE* out, const json_t* plan)
{
    if (json_dumpf(plan, out, JSON_INDENT(2) | JSON_PRESERVE_ORDER | JSON_REAL_PRECISION(15)) !=
            0 ||
        fputc('\n', out) == EOF || fflush(out) != 0 || ferror(out)) {
        return SVA_JSON_ERR_IO;
    }
    return SVA_JSON_OK;
}
