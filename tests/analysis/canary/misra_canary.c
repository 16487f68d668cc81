/* A planted MISRA C 2012 violation: the cppcheck test checks that the addon reports
 * rule 15.5 (more than one return) here, so a broken addon cannot pass silently. */
int misra_canary(int x);
int misra_canary(int x)
{
    if (x > 0) {
        return 1;
    }
    return 0;
}
