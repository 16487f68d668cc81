// mission_gen.c -- see mission_gen.h.
#include "mission_gen.h"

#include <stdio.h>
#include <stdlib.h>

void test_rng_seed(test_rng_t* rng, uint64_t seed)
{
    rng->state = seed ? seed : 0x9E3779B97F4A7C15ULL;
}

static uint64_t next(test_rng_t* rng)
{
    uint64_t x = rng->state;
    x ^= x >> 12;
    x ^= x << 25;
    x ^= x >> 27;
    rng->state = x;
    return x * 0x2545F4914F6CDD1DULL;
}

int32_t test_rng_range(test_rng_t* rng, int32_t lo, int32_t hi)
{
    const uint64_t span = (uint64_t)((int64_t)hi - lo + 1);
    return (int32_t)(lo + (int64_t)(next(rng) % span));
}

void test_gen_mission(test_rng_t* rng, const test_gen_params_t* p, sva_mission_t* m)
{
    sva_mission_init(m);
    m->depot_x = test_rng_range(rng, 0, p->grid);
    m->depot_y = test_rng_range(rng, 0, p->grid);
    m->ticks_per_cell = p->ticks_per_cell;
    m->hover_fuel = p->hover_fuel;
    m->overlap_percent = test_rng_range(rng, 0, 4) == 0 ? test_rng_range(rng, 0, 100) : 70;
    m->uav_count = (uint16_t)p->uavs;
    for (int i = 0; i < p->uavs; i++) {
        sva_uav_t* u = &m->uavs[i];
        u->id = (i + 1) * 10 + test_rng_range(rng, 0, 9);  // unique, not always in list order
        u->x = p->scattered ? test_rng_range(rng, 0, p->grid) : m->depot_x;
        u->y = p->scattered ? test_rng_range(rng, 0, p->grid) : m->depot_y;
        u->fuel = test_rng_range(rng, p->fuel_min, p->fuel_max);
        u->ready_at_ticks = p->scattered ? test_rng_range(rng, 0, p->horizon / 4) : 0;
    }
    m->target_count = (uint16_t)p->targets;
    for (int i = 0; i < p->targets; i++) {
        sva_target_t* t = &m->targets[i];
        t->id = 1 + (i * 7) % 97 + 97 * test_rng_range(rng, 0, 3);
        for (int j = 0; j < i; j++) {  // keep ids unique
            if (m->targets[j].id == t->id) {
                t->id += 1000 + i;
                j = -1;
            }
        }
        t->x = test_rng_range(rng, 0, p->grid);
        t->y = test_rng_range(rng, 0, p->grid);
        t->start_ticks = test_rng_range(rng, p->start_min, p->start_min + p->horizon);
        t->end_ticks = t->start_ticks + test_rng_range(rng, p->window_min, p->window_max);
        t->need = test_rng_range(rng, 1, p->need_max);
    }
}

uint64_t test_seed(uint64_t fallback)
{
    const char* env = getenv("SVA_TEST_SEED");
    uint64_t seed = fallback;
    if (env != NULL && *env != '\0') {
        seed = strtoull(env, NULL, 0);
    }
    printf("# seed %llu (replay: SVA_TEST_SEED=%llu)\n", (unsigned long long)seed,
           (unsigned long long)seed);
    return seed;
}
