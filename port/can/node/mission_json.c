// Strict SPEC section 3 mission reader over jansson (see mission_json.h).
#include "mission_json.h"

#include <jansson.h>
#include <stdio.h>
#include <string.h>

#include "sva/sva_can.h"

typedef struct {
    char* err;
    size_t size;
} errbuf_t;

static int failf(errbuf_t* e, const char* path, const char* what)
{
    snprintf(e->err, e->size, "%s: %s", path, what);
    return -1;
}

static int check_keys(errbuf_t* e, json_t* obj, const char* path, const char* const* allowed)
{
    const char* key;
    json_t* value;
    json_object_foreach(obj, key, value) {
        size_t i;
        int ok = 0;
        (void)value;
        for (i = 0; allowed[i] != NULL; ++i) {
            if (strcmp(key, allowed[i]) == 0) {
                ok = 1;
            }
        }
        if (!ok) {
            char buf[160];
            snprintf(buf, sizeof buf, "unknown key \"%s\"", key);
            return failf(e, path, buf);
        }
    }
    return 0;
}

static int get_int(errbuf_t* e, json_t* obj, const char* key, const char* path, int required, int32_t deflt,
                   int32_t* out)
{
    char where[96];
    json_t* v = json_object_get(obj, key);
    json_int_t n;
    snprintf(where, sizeof where, "%s%s%s", path, (path[0] != '\0') ? "." : "", key);
    if (v == NULL) {
        if (required) {
            return failf(e, where, "missing required key");
        }
        *out = deflt;
        return 0;
    }
    if (!json_is_integer(v)) {
        return failf(e, where, "must be an integer");
    }
    n = json_integer_value(v);
    if ((n < INT32_MIN) || (n > INT32_MAX)) {
        return failf(e, where, "outside the 32-bit integer range");
    }
    *out = (int32_t)n;
    return 0;
}

int sva_can_mission_load(const char* path, sva_mission_t* m, char* name, size_t name_size, char* err,
                         size_t err_size)
{
    static const char* const top_keys[] = {"name", "depot", "ticks_per_cell", "hover_fuel", "overlap_percent",
                                           "uavs", "targets", NULL};
    static const char* const depot_keys[] = {"x", "y", NULL};
    static const char* const uav_keys[] = {"id", "x", "y", "fuel", "ready_at", NULL};
    static const char* const target_keys[] = {"id", "x", "y", "start", "end", "need", NULL};
    errbuf_t e;
    json_error_t jerr;
    json_t* root;
    json_t* v;
    json_t* list;
    size_t i;
    int rc = -1;
    sva_diag_t diag;
    e.err = err;
    e.size = err_size;
    root = json_load_file(path, JSON_REJECT_DUPLICATES, &jerr);
    if (root == NULL) {
        snprintf(err, err_size, "%s:%d: %s", path, jerr.line, jerr.text);
        return -1;
    }
    sva_mission_init(m);
    if (!json_is_object(root)) {
        failf(&e, "mission", "must be an object");
        goto done;
    }
    if (check_keys(&e, root, "mission", top_keys) != 0) {
        goto done;
    }
    v = json_object_get(root, "name");
    if ((v == NULL) || !json_is_string(v)) {
        failf(&e, "name", (v == NULL) ? "missing required key" : "must be a string");
        goto done;
    }
    if (name != NULL && name_size > 0) {
        snprintf(name, name_size, "%s", json_string_value(v));
    }
    v = json_object_get(root, "depot");
    if ((v == NULL) || !json_is_object(v)) {
        failf(&e, "depot", (v == NULL) ? "missing required key" : "must be an object");
        goto done;
    }
    if ((check_keys(&e, v, "depot", depot_keys) != 0) || (get_int(&e, v, "x", "depot", 1, 0, &m->depot_x) != 0) ||
        (get_int(&e, v, "y", "depot", 1, 0, &m->depot_y) != 0) ||
        (get_int(&e, root, "ticks_per_cell", "", 0, 1, &m->ticks_per_cell) != 0) ||
        (get_int(&e, root, "hover_fuel", "", 0, 0, &m->hover_fuel) != 0) ||
        (get_int(&e, root, "overlap_percent", "", 0, 70, &m->overlap_percent) != 0)) {
        goto done;
    }
    list = json_object_get(root, "uavs");
    if ((list == NULL) || !json_is_array(list)) {
        failf(&e, "uavs", (list == NULL) ? "missing required key" : "must be an array");
        goto done;
    }
    if (json_array_size(list) > SVA_MAX_UAVS) {
        snprintf(err, err_size, "uavs: %zu entries exceed SVA_MAX_UAVS (%d)", json_array_size(list), SVA_MAX_UAVS);
        goto done;
    }
    for (i = 0; i < json_array_size(list); ++i) {
        char p[32];
        sva_uav_t* u = &m->uavs[i];
        json_t* o = json_array_get(list, i);
        snprintf(p, sizeof p, "uavs[%zu]", i);
        if (!json_is_object(o)) {
            failf(&e, p, "must be an object");
            goto done;
        }
        if ((check_keys(&e, o, p, uav_keys) != 0) || (get_int(&e, o, "id", p, 1, 0, &u->id) != 0) ||
            (get_int(&e, o, "x", p, 1, 0, &u->x) != 0) || (get_int(&e, o, "y", p, 1, 0, &u->y) != 0) ||
            (get_int(&e, o, "fuel", p, 1, 0, &u->fuel) != 0) ||
            (get_int(&e, o, "ready_at", p, 0, 0, &u->ready_at_ticks) != 0)) {
            goto done;
        }
    }
    m->uav_count = (uint16_t)json_array_size(list);
    list = json_object_get(root, "targets");
    if ((list == NULL) || !json_is_array(list)) {
        failf(&e, "targets", (list == NULL) ? "missing required key" : "must be an array");
        goto done;
    }
    if (json_array_size(list) > SVA_MAX_TARGETS) {
        snprintf(err, err_size, "targets: %zu entries exceed SVA_MAX_TARGETS (%d)", json_array_size(list),
                 SVA_MAX_TARGETS);
        goto done;
    }
    for (i = 0; i < json_array_size(list); ++i) {
        char p[32];
        sva_target_t* t = &m->targets[i];
        json_t* o = json_array_get(list, i);
        snprintf(p, sizeof p, "targets[%zu]", i);
        if (!json_is_object(o)) {
            failf(&e, p, "must be an object");
            goto done;
        }
        if ((check_keys(&e, o, p, target_keys) != 0) || (get_int(&e, o, "id", p, 1, 0, &t->id) != 0) ||
            (get_int(&e, o, "x", p, 1, 0, &t->x) != 0) || (get_int(&e, o, "y", p, 1, 0, &t->y) != 0) ||
            (get_int(&e, o, "start", p, 1, 0, &t->start_ticks) != 0) ||
            (get_int(&e, o, "end", p, 1, 0, &t->end_ticks) != 0) || (get_int(&e, o, "need", p, 1, 0, &t->need) != 0)) {
            goto done;
        }
    }
    m->target_count = (uint16_t)json_array_size(list);
    sva_diag_clear(&diag);
    if (sva_mission_validate(m, &diag) != SVA_OK) {
        (void)sva_diag_format(&diag, err, err_size);
        goto done;
    }
    sva_diag_clear(&diag);
    if (sva_can_mission_check(m, &diag) != SVA_CAN_OK) {
        (void)sva_diag_format(&diag, err, err_size);
        goto done;
    }
    rc = 0;
done:
    json_decref(root);
    return rc;
}
