// target.h -- the test images' own parts between target_main.c and target_io.c.
#ifndef SVA_TARGET_H
#define SVA_TARGET_H

#include <stddef.h>

#include "unity_config.h"

/// Bytes of the fixed heap handed out so far (newlib's stdio and malloc), and its size.
size_t sva_target_heap_used(void);
size_t sva_target_heap_size(void);

#endif
