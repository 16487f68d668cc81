// bench_core.c -- plans per second and median solve time of each algorithm on the
// paper's sizes (3 and 5 targets with 3 UAVs; 7, 10 and 25 with 5 UAVs), random
// missions on a 20x20 grid (windows 10-20 ticks, need 1, hover 2), and the size of the
// planner structs. A benchmark, not a test: it prints figures.
// Usage: bench_core [missions per size (default 100)] [repeats per mission (default 20)]
#define _POSIX_C_SOURCE 199309L
#include <stdio.h>
#include <stdlib.h>
#include <time.h>

#include "mission_gen.h"
#include "sva/sva.h"

static sva_planner_t planner;
static sva_mission_t missions[100];
static sva_plan_t plan;

static double now_us(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec * 1e6 + (double)ts.tv_nsec / 1e3;
}

static int by_value(const void* a, const void* b)
{
    const double x = *(const double*)a, y = *(const double*)b;
    return (x > y) - (x < y);
}

int main(int argc, char** argv)
{
    int count = argc > 1 ? atoi(argv[1]) : 100;
    const int repeats = argc > 2 ? atoi(argv[2]) : 20;
    if (count < 1 || count > 100 || repeats < 1) {
        fprintf(stderr, "usage: bench_core [missions 1..100] [repeats >= 1]\n");
        return 2;
    }
    if (sva_planner_init(&planner) != SVA_OK) {
        return 1;
    }
    const sva_limits_t limits = sva_limits();
    printf("sizes: sva_planner_t %u B, sva_plan_t %u B, sva_mission_t %u B (SVA_MAX_UAVS %u, "
           "SVA_MAX_TARGETS %u)\n",
           limits.planner_bytes, limits.plan_bytes, limits.mission_bytes, limits.max_uavs,
           limits.max_targets);
    printf("method: %d random missions per size, each planned %d times; per-plan time is the "
           "mean of the repeats (CLOCK_MONOTONIC); median and p95 over missions\n\n",
           count, repeats);
    printf("%-8s %-5s %12s %10s %10s %10s %9s\n", "targets", "algo", "plans/s", "median_us",
           "p95_us", "covered%", "complete%");
    const int sizes[][2] = {{3, 3}, {5, 3}, {7, 5}, {10, 5}, {25, 5}};
    static double per_mission[100];
    for (size_t s = 0; s < sizeof(sizes) / sizeof(sizes[0]); s++) {
        test_rng_t rng;
        test_rng_seed(&rng, 1000 + s);
        const int t = sizes[s][0], u = sizes[s][1];
        for (int i = 0; i < count; i++) {
            // Windows start once any UAV can reach any cell (40 cells away at most).
            const test_gen_params_t p = {
                t, u, 20, 10, 20, 60 * t / u, 1, 40 + 12 * t / u * 3, 60 + 12 * t / u * 3,
                2, 1, 0,  40};
            test_gen_mission(&rng, &p, &missions[i]);
        }
        for (int a = 0; a < (int)SVA_ALGO_COUNT_; a++) {
            if (a == SVA_ALGO_BFA && (t > 10 || u > SVA_BFA_MAX_UAVS)) {
                continue;
            }
            long covered = 0, targets = 0, complete = 0;
            double total = 0.0;
            for (int i = 0; i < count; i++) {
                const double t0 = now_us();
                for (int r = 0; r < repeats; r++) {
                    if (sva_plan(&planner, &missions[i], (sva_algorithm_t)a, &plan, NULL) !=
                        SVA_OK) {
                        fprintf(stderr, "plan failed: size %d algo %s\n", t,
                                sva_algorithm_name((sva_algorithm_t)a));
                        return 1;
                    }
                }
                per_mission[i] = (now_us() - t0) / repeats;
                total += per_mission[i];
                covered += plan.covered;
                targets += missions[i].target_count;
                complete += plan.status == SVA_PLAN_COMPLETE;
            }
            qsort(per_mission, (size_t)count, sizeof(double), by_value);
            printf("%-8d %-5s %12.0f %10.2f %10.2f %9.1f%% %8.1f%%\n", t,
                   sva_algorithm_name((sva_algorithm_t)a), 1e6 * count / total,
                   per_mission[count / 2],
                   per_mission[(count * 95) / 100 < count ? (count * 95) / 100 : count - 1],
                   100.0 * covered / targets, 100.0 * complete / count);
        }
    }
    return 0;
}
