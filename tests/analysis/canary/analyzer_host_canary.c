/* A planted defect in host code: gcc -fanalyzer, with the flags the ports and the CLI
 * are analysed with, must reject this file's stream leak (-Wanalyzer-file-leak), so an
 * analysis of them that checks nothing cannot pass silently. */
#define _POSIX_C_SOURCE 200809L
#include <stdio.h>

int analyzer_host_canary(const char* path);
int analyzer_host_canary(const char* path)
{
    FILE* in = fopen(path, "rb");
    if (in == NULL) {
        return -1;
    }
    const int byte = fgetc(in);
    if (byte == EOF) {
        return -1; /* the stream leaks here */
    }
    return (fclose(in) == 0) ? byte : -1;
}
