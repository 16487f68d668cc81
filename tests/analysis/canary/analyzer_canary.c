/* A planted defect: gcc -fanalyzer must reject this file (use after free), so an
 * analyzer that checks nothing cannot pass silently. */
#include <stdlib.h>

int analyzer_canary(void);
int analyzer_canary(void)
{
    int* p = malloc(sizeof *p);
    if (p == NULL) {
        return 0;
    }
    *p = 1;
    free(p);
    return *p;
}
