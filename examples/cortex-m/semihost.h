// semihost.h -- a line of text and the exit status over Arm semihosting (semihost.c).
#ifndef SVA_FW_SEMIHOST_H
#define SVA_FW_SEMIHOST_H

#include <stdint.h>

/// Appends to the current line (at most 511 characters; the rest is dropped).
void sh_put_str(const char* s);
void sh_put_int(int64_t v);
/// Ends the line with '\n' and writes it to the host's console (SYS_WRITE0).
void sh_end_line(void);
/// Ends the program with this exit status (SYS_EXIT_EXTENDED); does not return.
void sh_exit(uint32_t status);

#endif
