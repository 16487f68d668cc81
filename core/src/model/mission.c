// mission.c -- mission defaults (SPEC section 3).
#include "model.h"

#include <string.h>

void sva_mission_init(sva_mission_t* self)
{
    SVA_ASSERT(self != NULL);
    if (self != NULL) {
        (void)memset(self, 0, sizeof(*self));
        self->ticks_per_cell = 1;
        self->hover_fuel = 0;
        self->overlap_percent = 70;
    }
}
