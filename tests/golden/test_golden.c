// test_golden.c -- golden plans (fixtures/golden/<algo>/<mission>.json).
//
// For every mission in fixtures/missions and every algorithm: plan it through the
// JSON layer (sva::json) and compare with the golden file using json_equal,
// "stats" removed from both. sva, ga and hga must have a golden file for every
// mission; a missing bfa golden file is accepted only when bfa refuses the mission
// with SVA_ERR_LIMIT. A golden file without its mission fails too.
#define _POSIX_C_SOURCE 200809L

#include <dirent.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "sva_unity.h"
#include <jansson.h>
#include <sva/sva.h>

#include <sva/sva_json.h>

#define MAX_MISSIONS 256
#define PATH_SIZE    1024

typedef struct {
    char mission[128];
    sva_algorithm_t algorithm;
} golden_case_t;

static sva_mission_t g_mission;
static sva_plan_t g_plan;
static sva_planner_t g_planner;

static int is_file(const char* path)
{
    struct stat st;
    return stat(path, &st) == 0 && S_ISREG(st.st_mode);
}

// Mission names (file stems) of a directory's *.json files, sorted.
static int cmp_names(const void* a, const void* b)
{
    return strcmp((const char*)a, (const char*)b);
}

static size_t list_json(const char* dir, char names[][128], size_t max)
{
    size_t count = 0;
    DIR* d = opendir(dir);
    if (d == NULL) {
        return 0;
    }
    struct dirent* e;
    while ((e = readdir(d)) != NULL) {
        size_t len = strlen(e->d_name);
        if (len > 5 && len - 5 < 128 && strcmp(e->d_name + len - 5, ".json") == 0 && count < max) {
            memcpy(names[count], e->d_name, len - 5);
            names[count][len - 5] = '\0';
            ++count;
        }
    }
    closedir(d);
    qsort(names, count, sizeof names[0], cmp_names);
    return count;
}

// The case test_golden_plan() checks (main() sets it before each run).
static const golden_case_t* current;

static void test_golden_plan(void)
{
    const golden_case_t* c = current;
    const char* algo = sva_algorithm_name(c->algorithm);
    char mission_path[PATH_SIZE];
    char golden_path[PATH_SIZE];
    snprintf(mission_path, sizeof mission_path, "%s/missions/%s.json", SVA_FIXTURES_DIR,
             c->mission);
    snprintf(golden_path, sizeof golden_path, "%s/golden/%s/%s.json", SVA_FIXTURES_DIR, algo,
             c->mission);

    char name[SVA_JSON_NAME_MAX + 1];
    char err[SVA_JSON_ERROR_SIZE];
    if (sva_json_load_mission(mission_path, &g_mission, name, err, sizeof err) != SVA_JSON_OK) {
        SVA_TEST_FAIL("%s: %s", mission_path, err);
    }
    TEST_ASSERT_EQUAL_INT(SVA_OK, sva_planner_init(&g_planner));
    sva_diag_t diag;
    sva_status_t status = sva_plan(&g_planner, &g_mission, c->algorithm, &g_plan, &diag);

    if (!is_file(golden_path)) {
        if (c->algorithm == SVA_ALGO_BFA && status == SVA_ERR_LIMIT) {
            return;  // bfa refuses the mission: no golden plan expected
        }
        SVA_TEST_FAIL("%s: missing golden plan (run tools/regen-golden.sh), sva_plan status %d",
                      golden_path, (int)status);
    }
    if (status != SVA_OK) {
        SVA_TEST_FAIL("%s with %s: sva_plan status %d, but %s exists", c->mission, algo,
                      (int)status, golden_path);
    }
    json_error_t error;
    json_t* golden = json_load_file(golden_path, JSON_REJECT_DUPLICATES, &error);
    if (golden == NULL) {
        SVA_TEST_FAIL("%s:%d:%d: %s", golden_path, error.line, error.column, error.text);
    }
    json_t* actual = sva_json_plan(&g_mission, name, &g_plan, 0);
    TEST_ASSERT_NOT_NULL(actual);
    json_object_del(golden, "stats");
    json_object_del(actual, "stats");
    if (!json_equal(golden, actual)) {
        char* want = json_dumps(golden, JSON_COMPACT | JSON_PRESERVE_ORDER);
        char* got = json_dumps(actual, JSON_COMPACT | JSON_PRESERVE_ORDER);
        printf("golden %s\n  want %s\n  got  %s\n", golden_path, want, got);
        free(want);
        free(got);
        json_decref(golden);
        json_decref(actual);
        TEST_FAIL();
    }
    json_decref(golden);
    json_decref(actual);
}

// A golden file whose mission no longer exists is stale.
static void test_no_stale_golden_files(void)
{
    static char missions[MAX_MISSIONS][128];
    static char goldens[MAX_MISSIONS][128];
    char dir[PATH_SIZE];
    snprintf(dir, sizeof dir, "%s/missions", SVA_FIXTURES_DIR);
    size_t mission_count = list_json(dir, missions, MAX_MISSIONS);
    TEST_ASSERT_TRUE(mission_count > 0);
    for (int a = 0; a < (int)SVA_ALGO_COUNT_; ++a) {
        snprintf(dir, sizeof dir, "%s/golden/%s", SVA_FIXTURES_DIR,
                 sva_algorithm_name((sva_algorithm_t)a));
        size_t golden_count = list_json(dir, goldens, MAX_MISSIONS);
        for (size_t g = 0; g < golden_count; ++g) {
            if (bsearch(goldens[g], missions, mission_count, sizeof missions[0], cmp_names) ==
                NULL) {
                SVA_TEST_FAIL("%s/%s.json: no mission of that name", dir, goldens[g]);
            }
        }
    }
}

// One Unity test per mission and algorithm, named algorithm/mission, after the stale
// file check (a hand-written runner: the cases come from the fixtures folder).
void setUp(void)
{
}
void tearDown(void)
{
}

int main(void)
{
    static char missions[MAX_MISSIONS][128];
    static golden_case_t cases[MAX_MISSIONS * SVA_ALGO_COUNT_];
    static char names[MAX_MISSIONS * SVA_ALGO_COUNT_][160];
    char dir[PATH_SIZE];
    snprintf(dir, sizeof dir, "%s/missions", SVA_FIXTURES_DIR);
    size_t mission_count = list_json(dir, missions, MAX_MISSIONS);
    UnityBegin("golden");
    RUN_TEST(test_no_stale_golden_files);
    size_t n = 0;
    for (size_t m = 0; m < mission_count; ++m) {
        for (int a = 0; a < (int)SVA_ALGO_COUNT_; ++a) {
            golden_case_t* c = &cases[n];
            snprintf(c->mission, sizeof c->mission, "%.127s", missions[m]);
            c->algorithm = (sva_algorithm_t)a;
            snprintf(names[n], sizeof names[0], "%.8s/%.127s", sva_algorithm_name(c->algorithm),
                     missions[m]);
            current = c;
            UnityDefaultTestRun(test_golden_plan, names[n], __LINE__);
            ++n;
        }
    }
    return UnityEnd();
}
