// Replays inputs through a fuzz target without libFuzzer: every file named on the
// command line, and every regular file in every directory named. Used by the ctest
// `fuzz_replay_*` tests (seed corpora and crash reproducers), built with gcc and the
// sanitizers in the main build. Exit 0 when every input ran; the target aborts on a
// finding.
#include <dirent.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size);

static int replay_file(const char* path)
{
    FILE* f = fopen(path, "rb");
    if (f == NULL) {
        fprintf(stderr, "replay: cannot open %s\n", path);
        return 1;
    }
    size_t cap = 4096;
    size_t used = 0;
    uint8_t* buf = malloc(cap);
    for (;;) {
        if (buf == NULL) {
            fclose(f);
            fprintf(stderr, "replay: out of memory\n");
            return 1;
        }
        used += fread(buf + used, 1, cap - used, f);
        if (used < cap) {
            break;
        }
        cap *= 2;
        buf = realloc(buf, cap);
    }
    fclose(f);
    // An exact-size copy so that ASan sees reads past the input's end.
    uint8_t* exact = malloc(used > 0 ? used : 1);
    if (exact == NULL) {
        free(buf);
        return 1;
    }
    memcpy(exact, buf, used);
    free(buf);
    (void)LLVMFuzzerTestOneInput(exact, used);
    free(exact);
    return 0;
}

int main(int argc, char** argv)
{
    int files = 0;
    int errors = 0;
    for (int i = 1; i < argc; i++) {
        struct stat st;
        if (stat(argv[i], &st) != 0) {
            fprintf(stderr, "replay: no such file or directory: %s\n", argv[i]);
            errors++;
            continue;
        }
        if (!S_ISDIR(st.st_mode)) {
            errors += replay_file(argv[i]);
            files++;
            continue;
        }
        DIR* dir = opendir(argv[i]);
        if (dir == NULL) {
            errors++;
            continue;
        }
        struct dirent* e;
        while ((e = readdir(dir)) != NULL) {
            char path[4096];
            snprintf(path, sizeof path, "%s/%s", argv[i], e->d_name);
            if (e->d_name[0] == '.' || stat(path, &st) != 0 || !S_ISREG(st.st_mode) ||
                strcmp(e->d_name, "README.md") == 0) {
                continue;
            }
            errors += replay_file(path);
            files++;
        }
        closedir(dir);
    }
    printf("replayed %d inputs, %d errors\n", files, errors);
    return (errors == 0 && files > 0) ? 0 : 1;
}
