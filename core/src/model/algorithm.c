// algorithm.c -- algorithm names used on every interface (SPEC section 2).
#include "model.h"

static const char* const algorithm_names[SVA_ALGO_COUNT_] = {"sva", "ga", "hga", "bfa", "flow"};

const char* sva_algorithm_name(sva_algorithm_t algorithm)
{
    if ((unsigned)algorithm >= (unsigned)SVA_ALGO_COUNT_) {
        return "";
    }
    return algorithm_names[algorithm];
}

bool sva_names_equal(const char* a, const char* b)
{
    const char* x = a;
    const char* y = b;
    while ((*x != '\0') && (*x == *y)) {
        x++;
        y++;
    }
    return *x == *y;
}

sva_status_t sva_algorithm_from_name(const char* name, sva_algorithm_t* out)
{
    if ((name == NULL) || (out == NULL)) {
        return SVA_ERR_ARGUMENT;
    }
    for (int i = 0; i < (int)SVA_ALGO_COUNT_; i++) {
        if (sva_names_equal(name, algorithm_names[i])) {
            *out = (sva_algorithm_t)i;
            return SVA_OK;
        }
    }
    return SVA_ERR_ARGUMENT;
}
