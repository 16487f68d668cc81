// input.c -- read a whole mission document (see input.h).
#define _POSIX_C_SOURCE 200809L

#include "input.h"

#include <errno.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

static sva_json_result_t read_stream(FILE* in, const char* name, char** text, size_t* len,
                                     char* err, size_t err_size)
{
    size_t cap = 4096;
    size_t used = 0;
    char* buf = malloc(cap);
    if (buf == NULL) {
        snprintf(err, err_size, "%s: out of memory", name);
        return SVA_JSON_IO_ERROR;
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
                return SVA_JSON_IO_ERROR;
            }
            buf = grown;
            cap = next;
        }
        size_t got = fread(buf + used, 1, cap - 1 - used, in);
        used += got;
        if (used > (size_t)SVA_JSON_MAX_INPUT_BYTES) {
            free(buf);
            snprintf(err, err_size, "%s: input exceeds %ld bytes", name, SVA_JSON_MAX_INPUT_BYTES);
            return SVA_JSON_BAD_INPUT;
        }
        if (got == 0) {
            break;
        }
    }
    if (ferror(in)) {
        int saved = errno;
        free(buf);
        snprintf(err, err_size, "%s: cannot read: %s", name, strerror(saved));
        return SVA_JSON_IO_ERROR;
    }
    buf[used] = '\0';
    *text = buf;
    *len = used;
    return SVA_JSON_OK;
}

sva_json_result_t sva_json_read_input(const char* path, char** text, size_t* len, char* err,
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
        return SVA_JSON_BAD_INPUT;
    }
    struct stat st;
    if (fstat(fileno(in), &st) == 0 && S_ISDIR(st.st_mode)) {
        fclose(in);
        snprintf(err, err_size, "%s: cannot open: %s", shown, strerror(EISDIR));
        return SVA_JSON_BAD_INPUT;
    }
    sva_json_result_t result = read_stream(in, shown, text, len, err, err_size);
    fclose(in);
    return result;
}

sva_json_result_t sva_json_refuse(char* err, size_t size, const char* fmt, ...)
{
    va_list args;
    va_start(args, fmt);
    if (size > 0) {
        vsnprintf(err, size, fmt, args);
    }
    va_end(args);
    return SVA_JSON_BAD_INPUT;
}
