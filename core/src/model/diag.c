// diag.c -- diagnostics: filling and formatting sva_diag_t without stdio.
#include "model.h"
#include "sva/sva_live.h"

void sva_diag_clear(sva_diag_t* self)
{
    SVA_ASSERT(self != NULL);
    if (self != NULL) {
        sva_diag_set(self, SVA_FIELD_NONE, SVA_RULE_NONE, -1, 0, 0, NULL);
    }
}

void sva_diag_set(sva_diag_t* self, sva_field_t field, sva_rule_t rule, int32_t index,
                  int64_t value, int64_t limit, const char* limit_name)
{
    if (self != NULL) {
        self->field = field;
        self->rule = rule;
        self->index = index;
        self->value = value;
        self->limit = limit;
        self->limit_name = limit_name;
    }
}

const char* sva_field_name(sva_field_t field)
{
    static const char* const names[SVA_FIELD_COUNT_] = {
        "",
        "depot.x",
        "depot.y",
        "ticks_per_cell",
        "hover_fuel",
        "overlap_percent",
        "uavs",
        "uavs.id",
        "uavs.x",
        "uavs.y",
        "uavs.fuel",
        "uavs.ready_at",
        "targets",
        "targets.id",
        "targets.x",
        "targets.y",
        "targets.start",
        "targets.end",
        "targets.need",
        "change_penalty",
        "routes",
        "routes.uav",
        "routes.targets",
        "event.type",
        "event.at",
        "event.uav",
        "event.target",
        "event.x",
        "event.y",
        "event.fuel",
        "takeoff_ticks",
    };
    if ((unsigned)field >= (unsigned)SVA_FIELD_COUNT_) {
        return "";
    }
    return names[field];
}

// A bounded writer: counts every byte, stores what fits (snprintf semantics).
typedef struct {
    char* buf;
    size_t size;
    size_t len;
} sva_writer_t;

static void put_char(sva_writer_t* w, char c)
{
    if ((w->size > 0U) && (w->len < (w->size - 1U))) {
        w->buf[w->len] = c;
    }
    w->len++;
}

static void put_str(sva_writer_t* w, const char* s)
{
    for (const char* c = s; *c != '\0'; c++) {
        put_char(w, *c);
    }
}

static void put_int(sva_writer_t* w, int64_t value)
{
    char digits[24];
    size_t n = 0U;
    // Work with the negative magnitude so INT64_MIN needs no special case.
    int64_t v = (value < 0) ? value : -value;
    if (value < 0) {
        put_char(w, '-');
    }
    do {
        digits[n] = (char)('0' - (char)(v % 10));
        n++;
        v /= 10;
    } while (v != 0);
    while (n > 0U) {
        n--;
        put_char(w, digits[n]);
    }
}

// "targets[3].need": the list name, the index, then the member.
static void put_path(sva_writer_t* w, sva_field_t field, int32_t index)
{
    const char* name = sva_field_name(field);
    const char* dot = name;
    while ((*dot != '\0') && (*dot != '.')) {
        dot++;
    }
    if ((*dot == '.') && (index >= 0) && (field != SVA_FIELD_DEPOT_X) &&
        (field != SVA_FIELD_DEPOT_Y)) {
        const char* p = name;
        while (p != dot) {
            put_char(w, *p);
            p++;
        }
        put_char(w, '[');
        put_int(w, index);
        put_char(w, ']');
        put_str(w, dot);
    } else if (*name == '\0') {
        put_str(w, "mission");
    } else {
        put_str(w, name);
    }
}

size_t sva_diag_format(const sva_diag_t* self, char* buf, size_t size)
{
    sva_writer_t w = {buf, size, 0U};
    SVA_ASSERT((self != NULL) && ((buf != NULL) || (size == 0U)));
    if ((self == NULL) || ((buf == NULL) && (size != 0U))) {
        return 0U;
    }
    put_path(&w, self->field, self->index);
    put_str(&w, ": ");
    switch (self->rule) {
    case SVA_RULE_NONE:
        put_str(&w, "ok");
        break;
    case SVA_RULE_MIN:
        put_str(&w, "must be >= ");
        put_int(&w, self->limit);
        put_str(&w, ", got ");
        put_int(&w, self->value);
        break;
    case SVA_RULE_MAX:
        put_str(&w, "must be <= ");
        if (self->limit_name != NULL) {
            put_str(&w, self->limit_name);
            put_str(&w, " (");
            put_int(&w, self->limit);
            put_str(&w, ")");
        } else {
            put_int(&w, self->limit);
        }
        put_str(&w, ", got ");
        put_int(&w, self->value);
        break;
    case SVA_RULE_COUNT:
        put_int(&w, self->value);
        put_str(&w, " entries exceed ");
        put_str(&w, (self->limit_name != NULL) ? self->limit_name : "the limit");
        put_str(&w, " (");
        put_int(&w, self->limit);
        put_str(&w, ")");
        break;
    case SVA_RULE_DUPLICATE:
        put_str(&w, "duplicate id ");
        put_int(&w, self->value);
        put_str(&w, " (first at index ");
        put_int(&w, self->limit);
        put_str(&w, ")");
        break;
    case SVA_RULE_AFTER:
        put_str(&w, "must be > start (");
        put_int(&w, self->limit);
        put_str(&w, "), got ");
        put_int(&w, self->value);
        break;
    case SVA_RULE_ALGO_LIMIT:
        put_int(&w, self->value);
        put_str(&w, (self->field == SVA_FIELD_NONE) ? " search nodes exceed " : " entries exceed ");
        put_str(&w, (self->limit_name != NULL) ? self->limit_name : "the algorithm limit");
        put_str(&w, " (");
        put_int(&w, self->limit);
        put_str(&w, ")");
        break;
    case SVA_RULE_UNKNOWN:
        put_str(&w, "unknown id ");
        put_int(&w, self->value);
        break;
    case SVA_RULE_PAST:
        put_int(&w, self->value);
        put_str(&w, " is before now (");
        put_int(&w, self->limit);
        put_str(&w, ")");
        break;
    case SVA_RULE_STARTED:
        put_str(&w, "its window started at ");
        put_int(&w, self->value);
        put_str(&w, " (now ");
        put_int(&w, self->limit);
        put_str(&w, "): only a target not yet started may change");
        break;
    case SVA_RULE_STATE:
        if (self->field == SVA_FIELD_EVENT_UAV) {
            put_str(&w, (self->value != 0) ? "the UAV is lost" : "the UAV is in service");
        } else {
            put_str(&w, "the target is ");
            put_str(&w, sva_target_state_name((sva_target_state_t)self->value));
        }
        break;
    case SVA_RULE_ROUTE:
        put_str(&w, "must follow the mission's UAVs (");
        put_int(&w, self->limit);
        put_str(&w, "), got ");
        put_int(&w, self->value);
        break;
    case SVA_RULE_COUNT_:
    default:
        put_str(&w, "unknown rule");
        break;
    }
    if (size > 0U) {
        buf[(w.len < size) ? w.len : (size - 1U)] = '\0';
    }
    return w.len;
}
