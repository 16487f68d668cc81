/* Planted defects: clang-tidy must reject this file under the project's .clang-tidy and
 * under port/.clang-tidy (the ports' adjustments), so a clang-tidy that checks nothing,
 * or an adjustment that switches a planted check off, cannot pass silently. */
#include <stdio.h>
#include <string.h>

int tidy_canary(const char* s);
int tidy_canary(const char* s)
{
    char buf[4];
    strcpy(buf, s);          /* unbounded copy: clang-analyzer / cert checks flag it */
    remove(s);               /* result unused: cert-err33-c (still checked in the ports) */
    return tidy_canary(buf); /* recursion: misc-no-recursion */
}
