// live_json.c -- live missions as JSON (docs/SPEC.md, live missions): the LIVE.json
// document `sva replan` reads (mission, plan in force, events, now) and the replan it
// prints (the plan with its changes and the live state). The plan in force is checked
// against the mission by plan_check.c before anything starts.
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include <sva/sva_json.h>
#include <sva/sva_text.h>

#include "input.h"
#include "plan_check.h"

// A required or optional integer member of `object` that must fit int32.
static sva_json_status_t member_int(const json_t* object, const char* path, const char* key,
                                    bool optional, int32_t* out, char* err, size_t size)
{
    const json_t* value = json_object_get(object, key);
    if (value == NULL) {
        return optional ? SVA_JSON_OK
                        : sva_json_refuse(err, size, "%s: missing key \"%s\"", path, key);
    }
    if (!json_is_integer(value)) {
        return sva_json_refuse(err, size, "%s.%s: must be an integer, got %s", path, key,
                               sva_json_type_name(value));
    }
    if (json_integer_value(value) < INT32_MIN || json_integer_value(value) > INT32_MAX) {
        return sva_json_refuse(err, size, "%s.%s: must be an integer in [%ld, %ld], got %lld", path,
                               key, (long)INT32_MIN, (long)INT32_MAX,
                               (long long)json_integer_value(value));
    }
    *out = (int32_t)json_integer_value(value);
    return SVA_JSON_OK;
}

// Every key of `object` is one of `keys` (NULL-terminated).
static sva_json_status_t known_keys(const json_t* object, const char* path, const char* const* keys,
                                    char* err, size_t size)
{
    const char* key;
    json_t* value;
    // json_object_foreach needs a non-const object; nothing is modified.
    json_t* mutable_object = (json_t*)object;
    json_object_foreach(mutable_object, key, value)
    {
        bool known = false;
        for (const char* const* k = keys; *k != NULL; ++k) {
            known = known || strcmp(*k, key) == 0;
        }
        if (!known) {
            return sva_json_refuse(err, size, "%s: unknown key \"%s\"", path, key);
        }
    }
    return SVA_JSON_OK;
}

// The target id `id` of the mission, as an index, or -1.
static int32_t target_index(const sva_mission_t* m, json_int_t id)
{
    for (uint16_t t = 0; t < m->target_count; ++t) {
        if (m->targets[t].id == id) {
            return (int32_t)t;
        }
    }
    return -1;
}

// The plan in force: routes in mission order, target ids mapped to indices. Other
// keys of a plan document are allowed and ignored (the figures follow from the routes).
static sva_json_status_t parse_plan(const json_t* doc, const sva_mission_t* m, sva_plan_t* plan,
                                    char* err, size_t size)
{
    static const char* const keys[] = {"mission", "algorithm", "status",   "covered", "uncovered",
                                       "cost",    "routes",    "stranded", "stats",   "frame",
                                       "changes", "live",      NULL};
    if (!json_is_object(doc)) {
        return sva_json_refuse(err, size, "plan: must be an object, got %s",
                               sva_json_type_name(doc));
    }
    if (known_keys(doc, "plan", keys, err, size) != SVA_JSON_OK) {
        return SVA_JSON_ERR_INPUT;
    }
    const json_t* routes = json_object_get(doc, "routes");
    if (routes == NULL) {
        return sva_json_refuse(err, size, "plan: missing key \"routes\"");
    }
    if (!json_is_array(routes)) {
        return sva_json_refuse(err, size, "plan.routes: must be an array, got %s",
                               sva_json_type_name(routes));
    }
    if (json_array_size(routes) > SVA_MAX_UAVS) {
        return sva_json_refuse(err, size, "plan.routes: %zu entries exceed SVA_MAX_UAVS (%ld)",
                               json_array_size(routes), (long)SVA_MAX_UAVS);
    }
    memset(plan, 0, sizeof *plan);
    plan->route_count = (uint16_t)json_array_size(routes);
    for (size_t r = 0; r < json_array_size(routes); ++r) {
        static const char* const route_keys[] = {"uav", "targets", "distance", "fuel_used", NULL};
        const json_t* route = json_array_get(routes, r);
        char path[64];
        snprintf(path, sizeof path, "plan.routes[%zu]", r);
        int32_t uav = 0;
        if (!json_is_object(route)) {
            return sva_json_refuse(err, size, "%s: must be an object, got %s", path,
                                   sva_json_type_name(route));
        }
        if (known_keys(route, path, route_keys, err, size) != SVA_JSON_OK ||
            member_int(route, path, "uav", false, &uav, err, size) != SVA_JSON_OK) {
            return SVA_JSON_ERR_INPUT;
        }
        const json_t* targets = json_object_get(route, "targets");
        if (targets == NULL) {
            return sva_json_refuse(err, size, "%s: missing key \"targets\"", path);
        }
        if (!json_is_array(targets)) {
            return sva_json_refuse(err, size, "%s.targets: must be an array, got %s", path,
                                   sva_json_type_name(targets));
        }
        if (json_array_size(targets) > SVA_MAX_ROUTE_TARGETS) {
            return sva_json_refuse(err, size,
                                   "%s.targets: %zu entries exceed SVA_MAX_ROUTE_TARGETS (%ld)",
                                   path, json_array_size(targets), (long)SVA_MAX_ROUTE_TARGETS);
        }
        plan->routes[r].uav_id = uav;
        plan->routes[r].target_count = (uint16_t)json_array_size(targets);
        for (size_t k = 0; k < json_array_size(targets); ++k) {
            const json_t* id = json_array_get(targets, k);
            if (!json_is_integer(id)) {
                return sva_json_refuse(err, size, "%s.targets[%zu]: must be an integer, got %s",
                                       path, k, sva_json_type_name(id));
            }
            const int32_t t = target_index(m, json_integer_value(id));
            if (t < 0) {
                return sva_json_refuse(err, size,
                                       "%s.targets[%zu]: not a target id of the mission, got %lld",
                                       path, k, (long long)json_integer_value(id));
            }
            plan->routes[r].targets[k] = (uint16_t)t;
        }
    }
    return SVA_JSON_OK;
}

// One event object (docs/SPEC.md: `{"at": T, "type": NAME, ...}`).
static sva_json_status_t parse_event(const json_t* doc, const char* path, sva_event_t* e, char* err,
                                     size_t size)
{
    static const char* const keys[SVA_EVENT_COUNT_][7] = {
        {"at", "type", NULL},
        {"at", "type", "uav", NULL},
        {"at", "type", "uav", "x", "y", "fuel", NULL},
        {"at", "type", "uav", "fuel", NULL},
        {"at", "type", "target", NULL},
        {"at", "type", "target", NULL},
        {"at", "type", "target", NULL},
        {"at", "type", "uav", "x", "y", "fuel", NULL},
    };
    memset(e, 0, sizeof *e);
    if (!json_is_object(doc)) {
        return sva_json_refuse(err, size, "%s: must be an object", path);
    }
    const json_t* type = json_object_get(doc, "type");
    if (!json_is_string(type) ||
        sva_event_type_from_name(json_string_value(type), &e->type) != SVA_OK) {
        return sva_json_refuse(
            err, size,
            "%s.type: must be one of clock, uav_lost, uav_back, fuel, target_added, "
            "target_cancelled, target_changed, position",
            path);
    }
    if (known_keys(doc, path, keys[e->type], err, size) != SVA_JSON_OK ||
        member_int(doc, path, "at", false, &e->at_ticks, err, size) != SVA_JSON_OK) {
        return SVA_JSON_ERR_INPUT;
    }
    // uav_back and position carry a place and a fuel reading.
    const bool back = e->type == SVA_EVENT_UAV_BACK || e->type == SVA_EVENT_POSITION;
    const bool uav = back || e->type == SVA_EVENT_FUEL || e->type == SVA_EVENT_UAV_LOST;
    if ((uav && member_int(doc, path, "uav", false, &e->uav_id, err, size) != SVA_JSON_OK) ||
        (back && member_int(doc, path, "x", false, &e->x, err, size) != SVA_JSON_OK) ||
        (back && member_int(doc, path, "y", false, &e->y, err, size) != SVA_JSON_OK) ||
        ((back || e->type == SVA_EVENT_FUEL) &&
         member_int(doc, path, "fuel", false, &e->fuel, err, size) != SVA_JSON_OK)) {
        return SVA_JSON_ERR_INPUT;
    }
    if (e->type == SVA_EVENT_TARGET_CANCELLED) {
        return member_int(doc, path, "target", false, &e->target.id, err, size);
    }
    if (e->type == SVA_EVENT_TARGET_ADDED || e->type == SVA_EVENT_TARGET_CHANGED) {
        char target_path[80];
        snprintf(target_path, sizeof target_path, "%s.target", path);
        const json_t* target = json_object_get(doc, "target");
        if (target == NULL) {
            return sva_json_refuse(err, size, "%s: missing key \"target\"", path);
        }
        return sva_json_target_from(target, target_path, &e->target, err, size)
                   ? SVA_JSON_OK
                   : SVA_JSON_ERR_INPUT;
    }
    return SVA_JSON_OK;
}

static sva_json_status_t parse_live(const json_t* root, sva_json_live_t* live, char* err,
                                    size_t size)
{
    static const char* const keys[] = {"mission", "plan", "events", "now", NULL};
    if (!json_is_object(root)) {
        return sva_json_refuse(err, size, "live mission: must be an object, got %s",
                               sva_json_type_name(root));
    }
    if (known_keys(root, "live mission", keys, err, size) != SVA_JSON_OK) {
        return SVA_JSON_ERR_INPUT;
    }
    const json_t* mission = json_object_get(root, "mission");
    if (mission == NULL) {
        return sva_json_refuse(err, size, "live mission: missing key \"mission\"");
    }
    char inner[SVA_JSON_ERROR_SIZE];
    if (sva_json_mission_from(mission, &live->mission, live->name, inner, sizeof inner) !=
        SVA_JSON_OK) {
        return sva_json_refuse(err, size, "%s%s",
                               strncmp(inner, "mission", 7) == 0 ? "" : "mission.", inner);
    }
    if (sva_json_mission_frame(mission, &live->frame, &live->has_frame, inner, sizeof inner) !=
        SVA_JSON_OK) {
        return sva_json_refuse(err, size, "mission.%s", inner);
    }
    sva_diag_t diag;
    if (sva_mission_validate(&live->mission, &diag) != SVA_OK) {
        (void)sva_diag_format(&diag, inner, sizeof inner);
        return sva_json_refuse(err, size, "mission.%s", inner);
    }
    const json_t* plan = json_object_get(root, "plan");
    live->has_plan = plan != NULL;
    if (live->has_plan &&
        (parse_plan(plan, &live->mission, &live->plan, err, size) != SVA_JSON_OK ||
         sva_json_check_plan(&live->mission, &live->plan, err, size) != SVA_JSON_OK)) {
        return SVA_JSON_ERR_INPUT;
    }
    const json_t* events = json_object_get(root, "events");
    if (events != NULL && !json_is_array(events)) {
        return sva_json_refuse(err, size, "events: must be an array, got %s",
                               sva_json_type_name(events));
    }
    const size_t count = events != NULL ? json_array_size(events) : 0;
    if (count > SVA_JSON_MAX_EVENTS) {
        return sva_json_refuse(err, size, "events: %zu entries exceed SVA_JSON_MAX_EVENTS (%ld)",
                               count, (long)SVA_JSON_MAX_EVENTS);
    }
    live->events = count > 0 ? calloc(count, sizeof *live->events) : NULL;
    if (count > 0 && live->events == NULL) {
        return sva_json_refuse(err, size, "events: out of memory");
    }
    live->event_count = count;
    for (size_t i = 0; i < count; ++i) {
        char path[32];
        snprintf(path, sizeof path, "events[%zu]", i);
        if (parse_event(json_array_get(events, i), path, &live->events[i], err, size) !=
            SVA_JSON_OK) {
            return SVA_JSON_ERR_INPUT;
        }
    }
    live->now_ticks = count > 0 ? live->events[count - 1].at_ticks : 0;
    live->has_now = json_object_get(root, "now") != NULL;
    return member_int(root, "live mission", "now", true, &live->now_ticks, err, size);
}

sva_json_status_t sva_json_load_live(const char* path, sva_json_live_t* live, char* err,
                                     size_t err_size)
{
    memset(live, 0, sizeof *live);
    char* text;
    size_t len;
    sva_json_status_t result = sva_json_read_input(path, &text, &len, err, err_size);
    if (result != SVA_JSON_OK) {
        return result;
    }
    json_error_t error;
    json_t* root = json_loadb(text, len, JSON_REJECT_DUPLICATES, &error);
    free(text);
    if (root == NULL) {
        return sva_json_refuse(err, err_size, "%s:%d:%d: invalid JSON: %s",
                               strcmp(path, "-") == 0 ? SVA_JSON_STDIN_NAME : path, error.line,
                               error.column, error.text);
    }
    const char* other = sva_json_other_kind(root, "live mission");
    if (other != NULL) {
        char shown[SVA_JSON_ERROR_SIZE];
        (void)sva_text_escape(shown, sizeof shown,
                              strcmp(path, "-") == 0 ? SVA_JSON_STDIN_NAME : path);
        json_decref(root);
        return sva_json_refuse(err, err_size,
                               "%s: this is %s; sva replan takes a live mission (mission, plan, "
                               "events, now; SPEC 12.5)",
                               shown, other);
    }
    result = parse_live(root, live, err, err_size);
    json_decref(root);
    if (result != SVA_JSON_OK) {
        sva_json_live_free(live);
    }
    return result;
}

void sva_json_live_free(sva_json_live_t* live)
{
    free(live->events);
    live->events = NULL;
    live->event_count = 0;
}

// Pairs of `a` that `b` lacks (sva_plan_changes), as [uav id, target id] (residual
// mission ids).
static json_t* pairs_missing(const sva_mission_t* m, const sva_plan_t* a, const sva_plan_t* b)
{
    const uint32_t count = sva_plan_changes(a, b, NULL, 0U);
    sva_visit_t* visits = malloc(sizeof *visits * (count > 0U ? count : 1U));
    json_t* list = json_array();
    if (visits == NULL || list == NULL) {
        free(visits);
        json_decref(list);
        return NULL;
    }
    (void)sva_plan_changes(a, b, visits, count);
    for (uint32_t i = 0; i < count; ++i) {
        if (json_array_append_new(list, json_pack("[i, i]", (json_int_t)m->uavs[visits[i].route].id,
                                                  (json_int_t)m->targets[visits[i].target].id)) !=
            0) {
            json_decref(list);
            list = NULL;
            break;
        }
    }
    free(visits);
    return list;
}

json_t* sva_json_replan(const sva_live_t* live, const sva_live_result_t* r, const char* name,
                        int64_t solve_us)
{
    json_t* doc = sva_json_plan(r->residual, name, r->plan, solve_us);
    json_t* changes = json_pack("{s:o*, s:o*, s:i, s:i}", "dropped",
                                pairs_missing(r->residual, r->previous, r->plan), "added",
                                pairs_missing(r->residual, r->plan, r->previous), "count",
                                (json_int_t)r->dropped + (json_int_t)r->added, "penalty",
                                (json_int_t)live->mission.change_penalty);
    json_t* under_way = json_array();
    json_t* targets = json_array();
    bool ok = doc != NULL && changes != NULL && under_way != NULL && targets != NULL;
    for (uint16_t i = 0; ok && i < live->mission.target_count; ++i) {
        const sva_target_state_t state = (sva_target_state_t)live->target_state[i];
        const json_int_t id = live->mission.targets[i].id;
        ok = json_array_append_new(targets, json_pack("{s:i, s:s}", "id", id, "state",
                                                      sva_target_state_name(state))) == 0 &&
             (state != SVA_TARGET_UNDER_WAY ||
              json_array_append_new(under_way, json_integer(id)) == 0);
    }
    json_t* state =
        ok ? json_pack("{s:i, s:i, s:b, s:i, s:o, s:o}", "now", (json_int_t)r->now_ticks,
                       "revision", (json_int_t)r->revision, "kept", r->kept ? 1 : 0, "covered",
                       (json_int_t)r->covered, "under_way", under_way, "targets", targets)
           : NULL;
    if (state == NULL) {
        if (!ok) {
            json_decref(under_way);
            json_decref(targets);
        }
        json_decref(changes);
        json_decref(doc);
        return NULL;
    }
    if (json_object_set_new(doc, "changes", changes) != 0 ||
        json_object_set_new(doc, "live", state) != 0) {
        json_decref(doc);
        return NULL;
    }
    return doc;
}
