// input.c -- read a whole mission document; tell our file kinds apart (see input.h).
#define _POSIX_C_SOURCE 200809L

#include "input.h"

#include <errno.h>
#include <stdarg.h>
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

static sva_json_status_t read_stream(FILE* in, const char* name, char** text, size_t* len,
                                     char* err, size_t err_size)
{
    size_t cap = 4096;
    size_t used = 0;
    char* buf = malloc(cap);
    if (buf == NULL) {
        snprintf(err, err_size, "%s: out of memory", name);
        return SVA_JSON_ERR_IO;
    }
    for (;;) {
        if (used + 1 >= cap) {
            // Grow until one byte past the limit, so an oversized input is detected
            // without reading all of it.
            size_t next = cap * 2;
            char* grown = realloc(buf, next);
            if (grown == NULL) {
                free(buf);
                snprintf(err, err_size, "%s: out of memory", name);
                return SVA_JSON_ERR_IO;
            }
            buf = grown;
            cap = next;
        }
        size_t got = fread(buf + used, 1, cap - 1 - used, in);
        used += got;
        if (used > (size_t)SVA_JSON_MAX_INPUT_BYTES) {
            free(buf);
            snprintf(err, err_size, "%s: input exceeds %ld bytes", name, SVA_JSON_MAX_INPUT_BYTES);
            return SVA_JSON_ERR_INPUT;
        }
        if (got == 0) {
            break;
        }
    }
    if (ferror(in)) {
        int saved = errno;
        free(buf);
        snprintf(err, err_size, "%s: cannot read: %s", name, strerror(saved));
        return SVA_JSON_ERR_IO;
    }
    buf[used] = '\0';
    *text = buf;
    *len = used;
    return SVA_JSON_OK;
}

sva_json_status_t sva_json_read_input(const char* path, char** text, size_t* len, char* err,
                                      size_t err_size)
{
    *text = NULL;
    *len = 0;
    if (strcmp(path, "-") == 0) {
        return read_stream(stdin, SVA_JSON_STDIN_NAME, text, len, err, err_size);
    }
    // The path as messages show it: one printable line whatever it holds.
    char shown[SVA_JSON_ERROR_SIZE];
    (void)sva_text_escape(shown, sizeof shown, path);
    FILE* in = fopen(path, "rb");
    if (in == NULL) {
        snprintf(err, err_size, "%s: cannot open: %s", shown, strerror(errno));
        return SVA_JSON_ERR_INPUT;
    }
    struct stat st;
    if (fstat(fileno(in), &st) == 0 && S_ISDIR(st.st_mode)) {
        (void)fclose(in);  // read only: nothing to lose
        snprintf(err, err_size, "%s: cannot open: %s", shown, strerror(EISDIR));
        return SVA_JSON_ERR_INPUT;
    }
    sva_json_status_t result = read_stream(in, shown, text, len, err, err_size);
    (void)fclose(in);  // read only: read_stream has judged every byte
    return result;
}

sva_json_status_t sva_json_refuse(char* err, size_t size, const char* fmt, ...)
{
    va_list args;
    va_start(args, fmt);
    if (size > 0) {
        vsnprintf(err, size, fmt, args);
    }
    va_end(args);
    return SVA_JSON_ERR_INPUT;
}

const char* sva_json_other_kind(const json_t* root, const char* expected)
{
    static const char MISSION[] = "a mission (name, depot, uavs, targets): sva plan takes it";
    static const char PLAN[] =
        "a plan (mission, algorithm, status, routes): sva-tools check MISSION PLAN takes it";
    static const char LIVE[] = "a live mission (mission, plan, events, now): sva replan takes it";
    static const char SCENARIO[] =
        "a scenario (mission, events, change_penalty): sva-tools sim takes it";
    static const char LOG[] = "a flight log (scenario, uavs, targets, replans): sva-tools sim "
                              "writes it, and takes its scenario";
    if (!json_is_object(root)) {
        return NULL;
    }
    const bool live_expected = strcmp(expected, "live mission") == 0;
    const char* kind = NULL;
    if (json_object_get(root, "scenario") != NULL && json_object_get(root, "replans") != NULL) {
        kind = LOG;
    } else if (json_object_get(root, "routes") != NULL) {
        kind = PLAN;
    } else if (json_is_object(json_object_get(root, "mission"))) {
        // {mission, events} is both a scenario and a live mission; change_penalty makes it
        // a scenario, a plan or a clock a live mission.
        const bool live =
            json_object_get(root, "change_penalty") == NULL &&
            (json_object_get(root, "plan") != NULL || json_object_get(root, "now") != NULL ||
             json_object_get(root, "events") == NULL || live_expected);
        kind = live ? LIVE : SCENARIO;
    } else if (json_object_get(root, "mission") == NULL &&
               (json_object_get(root, "depot") != NULL || json_object_get(root, "uavs") != NULL ||
                json_object_get(root, "targets") != NULL)) {
        kind = MISSION;
    }
    if (kind == (live_expected ? LIVE : MISSION)) {
        return NULL;
    }
    return kind;
}
