/* A planted defect: clang-tidy (with the project's .clang-tidy) must reject this
 * file, so a clang-tidy that checks nothing cannot pass silently. */
#include <string.h>

int tidy_canary(const char* s);
int tidy_canary(const char* s)
{
    char buf[4];
    strcpy(buf, s);          /* unbounded copy: clang-analyzer / cert checks flag it */
    return tidy_canary(buf); /* recursion: misc-no-recursion */
}
