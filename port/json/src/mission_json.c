// mission_json.c -- SPEC section 3 mission JSON into sva_mission_t (see sva/sva_json.h).
#include <sva/sva_json.h>

#include <stdarg.h>
#include <stdbool.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <jansson.h>

#include "input.h"

// One key of an object: its name, whether it may be left out, and its SPEC default.
typedef struct {
    const char* name;
    bool optional;
    int32_t fallback;
} key_spec_t;

// SPEC section 3, in SPEC order (missing keys are reported in this order).
static const key_spec_t MISSION_KEYS[] = {
    {"name", false, 0},
    {"depot", false, 0},
    {"ticks_per_cell", true, 1},
    {"hover_fuel", true, 0},
    {"overlap_percent", true, 70},
    {"change_penalty", true, 0},
    {"takeoff_ticks", true, 0},
    {"uavs", false, 0},
    {"targets", false, 0},
    {"frame", true, 0},
    {NULL, false, 0},
};
static const key_spec_t DEPOT_KEYS[] = {{"x", false, 0}, {"y", false, 0}, {NULL, false, 0}};
static const key_spec_t UAV_KEYS[] = {
    {"id", false, 0},   {"x", false, 0},       {"y", false, 0},
    {"fuel", false, 0}, {"ready_at", true, 0}, {NULL, false, 0},
};
static const key_spec_t FRAME_KEYS[] = {
    {"lat", false, 0},    {"lon", false, 0}, {"alt_m", false, 0}, {"cell_m", false, 0},
    {"tick_s", false, 0}, {"t0", false, 0},  {NULL, false, 0},
};
static const key_spec_t TARGET_KEYS[] = {
    {"id", false, 0},  {"x", false, 0},    {"y", false, 0},  {"start", false, 0},
    {"end", false, 0}, {"need", false, 0}, {NULL, false, 0},
};

// Where messages go: the caller's buffer.
typedef struct {
    char* text;
    size_t size;
} sink_t;

#if defined(__GNUC__) || defined(__clang__)
__attribute__((format(printf, 2, 3)))
#endif
static bool
fail(const sink_t* err, const char* fmt, ...)
{
    va_list args;
    va_start(args, fmt);
    if (err->size > 0) {
        // One printable line whatever the input holds (jansson quotes raw input
        // bytes, a path may hold anything).
        char raw[SVA_JSON_ERROR_SIZE];
        vsnprintf(raw, sizeof raw, fmt, args);
        (void)sva_text_escape(err->text, err->size, raw);
    }
    va_end(args);
    return false;
}

const char* sva_json_type_name(const json_t* value)
{
    switch (json_typeof(value)) {
    case JSON_OBJECT:
        return "object";
    case JSON_ARRAY:
        return "array";
    case JSON_STRING:
        return "string";
    case JSON_INTEGER:
        return "integer";
    case JSON_REAL:
        return "real";
    case JSON_TRUE:
    case JSON_FALSE:
        return "boolean";
    case JSON_NULL:
        return "null";
    }
    return "unknown";
}

// "uavs[1]" + "x" -> "uavs[1].x"; the root's fields have no prefix.
static void field_path(char* out, size_t size, const char* prefix, const char* key)
{
    if (prefix[0] == '\0') {
        snprintf(out, size, "%s", key);
    } else {
        snprintf(out, size, "%s.%s", prefix, key);
    }
}

// How an object is named in messages: the root is "mission".
static const char* object_name(const char* prefix)
{
    return prefix[0] == '\0' ? "mission" : prefix;
}

// Unknown keys are errors at every level (SPEC 3); reported in document order,
// before missing keys, since a misspelt key explains the missing one.
static bool check_keys(const json_t* object, const char* prefix, const key_spec_t* keys,
                       const sink_t* err)
{
    const char* key;
    json_t* value;
    // json_object_foreach needs a non-const object; nothing is modified.
    json_t* mutable_object = (json_t*)object;
    json_object_foreach(mutable_object, key, value)
    {
        bool known = false;
        for (const key_spec_t* k = keys; k->name != NULL; ++k) {
            if (strcmp(k->name, key) == 0) {
                known = true;
                break;
            }
        }
        if (!known) {
            // Quote and escape the key so the message stays one printable line.
            json_t* as_string = json_string(key);
            char* quoted = as_string != NULL
                               ? json_dumps(as_string, JSON_ENCODE_ANY | JSON_ENSURE_ASCII)
                               : NULL;
            fail(err, "%s: unknown key %s", object_name(prefix),
                 quoted != NULL ? quoted : "(unprintable)");
            free(quoted);
            json_decref(as_string);
            return false;
        }
    }
    for (const key_spec_t* k = keys; k->name != NULL; ++k) {
        if (!k->optional && json_object_get(object, k->name) == NULL) {
            return fail(err, "%s: missing key \"%s\"", object_name(prefix), k->name);
        }
    }
    return true;
}

static const key_spec_t* find_key(const key_spec_t* keys, const char* name)
{
    while (keys->name != NULL && strcmp(keys->name, name) != 0) {
        ++keys;
    }
    return keys;
}

// Reads an integer that must fit int32; range rules of the SPEC are the core's, so
// in-range violations pass through and the core's message names the SPEC limit.
static bool get_int(const json_t* object, const char* prefix, const key_spec_t* keys,
                    const char* key, int32_t* out, const sink_t* err)
{
    const json_t* value = json_object_get(object, key);
    if (value == NULL) {
        *out = find_key(keys, key)->fallback;  // check_keys has vetted required keys
        return true;
    }
    char path[128];
    field_path(path, sizeof path, prefix, key);
    if (!json_is_integer(value)) {
        return fail(err, "%s: must be an integer, got %s", path, sva_json_type_name(value));
    }
    json_int_t v = json_integer_value(value);
    if (v < INT32_MIN || v > INT32_MAX) {
        return fail(err, "%s: must be an integer in [%ld, %ld], got %lld", path, (long)INT32_MIN,
                    (long)INT32_MAX, (long long)v);
    }
    *out = (int32_t)v;
    return true;
}

static bool get_object(const json_t* parent, const char* prefix, const char* key,
                       const json_t** out, const sink_t* err)
{
    const json_t* value = json_object_get(parent, key);
    if (!json_is_object(value)) {
        char path[128];
        field_path(path, sizeof path, prefix, key);
        return fail(err, "%s: must be an object, got %s", path, sva_json_type_name(value));
    }
    *out = value;
    return true;
}

static bool parse_name(const json_t* root, char name[SVA_JSON_NAME_MAX + 1], const sink_t* err)
{
    const json_t* value = json_object_get(root, "name");
    if (!json_is_string(value)) {
        return fail(err, "name: must be a string, got %s", sva_json_type_name(value));
    }
    size_t len = json_string_length(value);
    if (len == 0 || len > SVA_JSON_NAME_MAX) {
        return fail(err, "name: must be a non-empty string of at most %d bytes, got %zu",
                    SVA_JSON_NAME_MAX, len);
    }
    memcpy(name, json_string_value(value), len);
    name[len] = '\0';
    return true;
}

// The list length is checked against the compiled bound before anything is copied;
// the message is the core's (sva_diag_format), as for every bound.
static bool get_list(const json_t* root, const char* key, sva_field_t field, size_t bound,
                     const char* bound_name, const json_t** out, const sink_t* err)
{
    const json_t* value = json_object_get(root, key);
    if (!json_is_array(value)) {
        return fail(err, "%s: must be an array, got %s", key, sva_json_type_name(value));
    }
    size_t count = json_array_size(value);
    if (count > bound) {
        sva_diag_t diag;
        sva_diag_set(&diag, field, SVA_RULE_COUNT, -1, (int64_t)count, (int64_t)bound, bound_name);
        (void)sva_diag_format(&diag, err->text, err->size);
        return false;
    }
    *out = value;
    return true;
}

static bool get_element(const json_t* list, const char* key, size_t i, char* prefix,
                        size_t prefix_size, const key_spec_t* keys, const json_t** out,
                        const sink_t* err)
{
    const json_t* element = json_array_get(list, i);
    snprintf(prefix, prefix_size, "%s[%zu]", key, i);
    if (!json_is_object(element)) {
        return fail(err, "%s: must be an object, got %s", prefix, sva_json_type_name(element));
    }
    if (!check_keys(element, prefix, keys, err)) {
        return false;
    }
    *out = element;
    return true;
}

static bool parse_uavs(const json_t* root, sva_mission_t* mission, const sink_t* err)
{
    const json_t* list = NULL;
    if (!get_list(root, "uavs", SVA_FIELD_UAVS, SVA_MAX_UAVS, "SVA_MAX_UAVS", &list, err)) {
        return false;
    }
    for (size_t i = 0; i < json_array_size(list); ++i) {
        char prefix[64];
        const json_t* e = NULL;
        sva_uav_t* u = &mission->uavs[i];
        if (!get_element(list, "uavs", i, prefix, sizeof prefix, UAV_KEYS, &e, err) ||
            !get_int(e, prefix, UAV_KEYS, "id", &u->id, err) ||
            !get_int(e, prefix, UAV_KEYS, "x", &u->x, err) ||
            !get_int(e, prefix, UAV_KEYS, "y", &u->y, err) ||
            !get_int(e, prefix, UAV_KEYS, "fuel", &u->fuel, err) ||
            !get_int(e, prefix, UAV_KEYS, "ready_at", &u->ready_at_ticks, err)) {
            return false;
        }
    }
    mission->uav_count = (uint16_t)json_array_size(list);
    return true;
}

static bool parse_targets(const json_t* root, sva_mission_t* mission, const sink_t* err)
{
    const json_t* list = NULL;
    if (!get_list(root, "targets", SVA_FIELD_TARGETS, SVA_MAX_TARGETS, "SVA_MAX_TARGETS", &list,
                  err)) {
        return false;
    }
    for (size_t i = 0; i < json_array_size(list); ++i) {
        char prefix[64];
        const json_t* e = NULL;
        sva_target_t* t = &mission->targets[i];
        if (!get_element(list, "targets", i, prefix, sizeof prefix, TARGET_KEYS, &e, err) ||
            !get_int(e, prefix, TARGET_KEYS, "id", &t->id, err) ||
            !get_int(e, prefix, TARGET_KEYS, "x", &t->x, err) ||
            !get_int(e, prefix, TARGET_KEYS, "y", &t->y, err) ||
            !get_int(e, prefix, TARGET_KEYS, "start", &t->start_ticks, err) ||
            !get_int(e, prefix, TARGET_KEYS, "end", &t->end_ticks, err) ||
            !get_int(e, prefix, TARGET_KEYS, "need", &t->need, err)) {
            return false;
        }
    }
    mission->target_count = (uint16_t)json_array_size(list);
    return true;
}

// A number of the frame; bit `bit` of *integers set when it is written as an integer.
static bool get_number(const json_t* object, const char* key, double* out, unsigned bit,
                       unsigned* integers, const sink_t* err)
{
    const json_t* value = json_object_get(object, key);
    if (!json_is_number(value)) {
        return fail(err, "frame.%s: must be a number, got %s", key, sva_json_type_name(value));
    }
    *out = json_number_value(value);
    if (json_is_integer(value)) {
        *integers |= 1U << bit;
    }
    return true;
}

// The optional frame (docs/flight-stack.md): its shape here, its values by
// sva_frame_from_units (rounded to the stored resolution, ranges named).
static bool parse_frame(const json_t* root, sva_frame_t* frame, bool* present, const sink_t* err)
{
    *present = false;
    const json_t* value = json_object_get(root, "frame");
    if (value == NULL) {
        return true;
    }
    if (!json_is_object(value)) {
        return fail(err, "frame: must be an object, got %s", sva_json_type_name(value));
    }
    sva_frame_units_t units;
    memset(&units, 0, sizeof units);
    if (!check_keys(value, "frame", FRAME_KEYS, err) ||
        !get_number(value, "lat", &units.lat, 0, &units.integers, err) ||
        !get_number(value, "lon", &units.lon, 1, &units.integers, err) ||
        !get_number(value, "alt_m", &units.alt_m, 2, &units.integers, err) ||
        !get_number(value, "cell_m", &units.cell_m, 3, &units.integers, err) ||
        !get_number(value, "tick_s", &units.tick_s, 4, &units.integers, err)) {
        return false;
    }
    const json_t* t0 = json_object_get(value, "t0");
    if (!json_is_string(t0)) {
        return fail(err, "frame.t0: must be a string, got %s", sva_json_type_name(t0));
    }
    units.t0 = json_string_value(t0);
    char line[SVA_FRAME_ERROR_SIZE];
    if (sva_frame_from_units(&units, frame, line, sizeof line) != SVA_OK) {
        return fail(err, "%s", line);
    }
    *present = true;
    return true;
}

static bool parse_root(const json_t* root, sva_mission_t* mission, char name[SVA_JSON_NAME_MAX + 1],
                       sva_frame_t* frame, bool* present, const sink_t* err)
{
    const json_t* depot = NULL;
    if (!json_is_object(root)) {
        return fail(err, "mission: must be an object, got %s", sva_json_type_name(root));
    }
    return check_keys(root, "", MISSION_KEYS, err) && parse_name(root, name, err) &&
           get_object(root, "", "depot", &depot, err) &&
           check_keys(depot, "depot", DEPOT_KEYS, err) &&
           get_int(depot, "depot", DEPOT_KEYS, "x", &mission->depot_x, err) &&
           get_int(depot, "depot", DEPOT_KEYS, "y", &mission->depot_y, err) &&
           get_int(root, "", MISSION_KEYS, "ticks_per_cell", &mission->ticks_per_cell, err) &&
           get_int(root, "", MISSION_KEYS, "hover_fuel", &mission->hover_fuel, err) &&
           get_int(root, "", MISSION_KEYS, "overlap_percent", &mission->overlap_percent, err) &&
           get_int(root, "", MISSION_KEYS, "change_penalty", &mission->change_penalty, err) &&
           get_int(root, "", MISSION_KEYS, "takeoff_ticks", &mission->takeoff_ticks, err) &&
           parse_uavs(root, mission, err) && parse_targets(root, mission, err) &&
           parse_frame(root, frame, present, err);
}

static bool is_blank(const char* text, size_t len)
{
    for (size_t i = 0; i < len; ++i) {
        if (text[i] != ' ' && text[i] != '\t' && text[i] != '\n' && text[i] != '\r') {
            return false;
        }
    }
    return true;
}

// sva_json_parse_mission with the frame.
static sva_json_status_t parse_text(const char* text, size_t len, const char* source,
                                    sva_mission_t* mission, char name[SVA_JSON_NAME_MAX + 1],
                                    sva_frame_t* frame, bool* present, char* err, size_t err_size)
{
    const sink_t sink = {err, err_size};
    *present = false;
    sva_mission_init(mission);
    name[0] = '\0';
    if (is_blank(text, len)) {
        fail(&sink, "%s: empty input", source);
        return SVA_JSON_ERR_INPUT;
    }
    // jansson stops at a raw NUL byte and reports "end of file"; name it instead.
    const char* nul = memchr(text, '\0', len);
    if (nul != NULL) {
        int line = 1;
        int column = 1;
        for (const char* c = text; c < nul; ++c) {
            line += *c == '\n';
            column = *c == '\n' ? 1 : column + 1;
        }
        fail(&sink, "%s:%d:%d: invalid JSON: NUL byte in input", source, line, column);
        return SVA_JSON_ERR_INPUT;
    }
    json_error_t error;
    json_t* root = json_loadb(text, len, JSON_REJECT_DUPLICATES | JSON_DECODE_ANY, &error);
    if (root == NULL) {
        fail(&sink, "%s:%d:%d: invalid JSON: %s", source, error.line, error.column, error.text);
        return SVA_JSON_ERR_INPUT;
    }
    const char* other = sva_json_other_kind(root, "mission");
    if (other != NULL) {
        fail(&sink,
             "%s: this is %s; sva plan and sva validate take a mission (name, depot, uavs, "
             "targets; SPEC 3)",
             source, other);
        json_decref(root);
        return SVA_JSON_ERR_INPUT;
    }
    bool ok = parse_root(root, mission, name, frame, present, &sink);
    json_decref(root);
    if (!ok) {
        // All-or-nothing: a rejected document leaves no half-filled mission behind.
        sva_mission_init(mission);
        name[0] = '\0';
        *present = false;
        return SVA_JSON_ERR_INPUT;
    }
    return SVA_JSON_OK;
}

sva_json_status_t sva_json_parse_mission(const char* text, size_t len, const char* source,
                                         sva_mission_t* mission, char name[SVA_JSON_NAME_MAX + 1],
                                         char* err, size_t err_size)
{
    sva_frame_t frame;
    bool present;
    return parse_text(text, len, source, mission, name, &frame, &present, err, err_size);
}

sva_json_status_t sva_json_load_mission(const char* path, sva_mission_t* mission,
                                        char name[SVA_JSON_NAME_MAX + 1], char* err,
                                        size_t err_size)
{
    sva_frame_t frame;
    bool present;
    return sva_json_load_mission_frame(path, mission, name, &frame, &present, err, err_size);
}

sva_json_status_t sva_json_load_mission_frame(const char* path, sva_mission_t* mission,
                                              char name[SVA_JSON_NAME_MAX + 1], sva_frame_t* frame,
                                              bool* present, char* err, size_t err_size)
{
    *present = false;
    char* text;
    size_t len;
    sva_json_status_t result = sva_json_read_input(path, &text, &len, err, err_size);
    if (result != SVA_JSON_OK) {
        return result;
    }
    const char* source = strcmp(path, "-") == 0 ? SVA_JSON_STDIN_NAME : path;
    result = parse_text(text, len, source, mission, name, frame, present, err, err_size);
    free(text);
    if (result != SVA_JSON_OK) {
        return result;
    }
    sva_diag_t diag;
    sva_diag_clear(&diag);
    if (sva_mission_validate(mission, &diag) != SVA_OK) {
        // The core's message names a field, a rule and numbers: nothing to escape.
        (void)sva_diag_format(&diag, err, err_size);
        return SVA_JSON_ERR_INPUT;
    }
    return SVA_JSON_OK;
}

sva_json_status_t sva_json_mission_from(const json_t* root, sva_mission_t* mission,
                                        char name[SVA_JSON_NAME_MAX + 1], char* err,
                                        size_t err_size)
{
    const sink_t sink = {err, err_size};
    sva_mission_init(mission);
    name[0] = '\0';
    sva_frame_t frame;
    bool present;
    if (!parse_root(root, mission, name, &frame, &present, &sink)) {
        sva_mission_init(mission);
        name[0] = '\0';
        return SVA_JSON_ERR_INPUT;
    }
    return SVA_JSON_OK;
}

sva_json_status_t sva_json_mission_frame(const json_t* root, sva_frame_t* frame, bool* present,
                                         char* err, size_t err_size)
{
    const sink_t sink = {err, err_size};
    *present = false;
    if (!json_is_object(root)) {
        fail(&sink, "mission: must be an object, got %s", sva_json_type_name(root));
        return SVA_JSON_ERR_INPUT;
    }
    sva_frame_t read;
    if (!parse_frame(root, &read, present, &sink)) {
        *present = false;
        return SVA_JSON_ERR_INPUT;
    }
    if (*present) {
        *frame = read;
    }
    return SVA_JSON_OK;
}

json_t* sva_json_frame(const sva_frame_t* frame)
{
    char t0[SVA_FRAME_UTC_SIZE];
    if (!sva_frame_format_utc(frame->t0_ms, t0, sizeof t0)) {
        return NULL;
    }
    // Each value at its stored resolution; sva_json_write_plan prints 15 significant
    // digits, which gives these decimals back exactly.
    return json_pack("{s:f, s:f, s:f, s:f, s:f, s:s}", "lat", (double)frame->lat_e7 / 1e7, "lon",
                     (double)frame->lon_e7 / 1e7, "alt_m", (double)frame->alt_cm / 100.0, "cell_m",
                     (double)frame->cell_cm / 100.0, "tick_s", (double)frame->tick_ms / 1000.0,
                     "t0", t0);
}

bool sva_json_target_from(const json_t* object, const char* prefix, sva_target_t* target, char* err,
                          size_t err_size)
{
    const sink_t sink = {err, err_size};
    if (!json_is_object(object)) {
        return fail(&sink, "%s: must be an object, got %s", prefix, sva_json_type_name(object));
    }
    return check_keys(object, prefix, TARGET_KEYS, &sink) &&
           get_int(object, prefix, TARGET_KEYS, "id", &target->id, &sink) &&
           get_int(object, prefix, TARGET_KEYS, "x", &target->x, &sink) &&
           get_int(object, prefix, TARGET_KEYS, "y", &target->y, &sink) &&
           get_int(object, prefix, TARGET_KEYS, "start", &target->start_ticks, &sink) &&
           get_int(object, prefix, TARGET_KEYS, "end", &target->end_ticks, &sink) &&
           get_int(object, prefix, TARGET_KEYS, "need", &target->need, &sink);
}

json_t* sva_json_target(const sva_target_t* t)
{
    return json_pack("{s:i, s:i, s:i, s:i, s:i, s:i}", "id", (json_int_t)t->id, "x",
                     (json_int_t)t->x, "y", (json_int_t)t->y, "start", (json_int_t)t->start_ticks,
                     "end", (json_int_t)t->end_ticks, "need", (json_int_t)t->need);
}

json_t* sva_json_mission(const sva_mission_t* m, const char* name)
{
    return sva_json_mission_framed(m, name, NULL);
}

json_t* sva_json_mission_framed(const sva_mission_t* m, const char* name, const sva_frame_t* frame)
{
    json_t* doc = json_pack("{s:s, s:{s:i, s:i}, s:i, s:i, s:i}", "name", name, "depot", "x",
                            (json_int_t)m->depot_x, "y", (json_int_t)m->depot_y, "ticks_per_cell",
                            (json_int_t)m->ticks_per_cell, "hover_fuel", (json_int_t)m->hover_fuel,
                            "overlap_percent", (json_int_t)m->overlap_percent);
    json_t* uavs = json_array();
    json_t* targets = json_array();
    bool ok = doc != NULL && uavs != NULL && targets != NULL;
    // change_penalty and takeoff_ticks only where set, so plain missions read as before.
    if (ok && m->change_penalty != 0) {
        ok = json_object_set_new(doc, "change_penalty", json_integer(m->change_penalty)) == 0;
    }
    if (ok && m->takeoff_ticks != 0) {
        ok = json_object_set_new(doc, "takeoff_ticks", json_integer(m->takeoff_ticks)) == 0;
    }
    for (uint16_t u = 0; ok && u < m->uav_count; ++u) {
        const sva_uav_t* v = &m->uavs[u];
        ok = json_array_append_new(uavs, json_pack("{s:i, s:i, s:i, s:i, s:i}", "id",
                                                   (json_int_t)v->id, "x", (json_int_t)v->x, "y",
                                                   (json_int_t)v->y, "fuel", (json_int_t)v->fuel,
                                                   "ready_at", (json_int_t)v->ready_at_ticks)) == 0;
    }
    for (uint16_t t = 0; ok && t < m->target_count; ++t) {
        ok = json_array_append_new(targets, sva_json_target(&m->targets[t])) == 0;
    }
    if (ok) {
        ok = json_object_set_new(doc, "uavs", uavs) == 0;
        uavs = NULL;
    }
    if (ok) {
        ok = json_object_set_new(doc, "targets", targets) == 0;
        targets = NULL;
    }
    if (ok && frame != NULL) {
        json_t* f = sva_json_frame(frame);
        ok = f != NULL && json_object_set_new(doc, "frame", f) == 0;
    }
    json_decref(uavs);
    json_decref(targets);
    if (!ok) {
        json_decref(doc);
        return NULL;
    }
    return doc;
}
