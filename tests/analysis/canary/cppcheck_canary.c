/* A planted defect for cppcheck's own checks, run as the ports and the CLI are checked
 * (no MISRA addon): the test checks that the out-of-bounds write is reported, so a
 * cppcheck that checks nothing in the ports cannot pass silently. */
int cppcheck_canary(void);
int cppcheck_canary(void)
{
    int cells[4] = {0, 0, 0, 0};
    cells[4] = 1;
    return cells[0];
}
