// can_state.h -- sva_can_node's --state-dir / --state-reset: the POSIX storage of its
// journal (can_journal.h) in a folder, the resume and the lines it prints.
#ifndef SVA_CAN_STATE_H
#define SVA_CAN_STATE_H

#include <stdbool.h>

#include "can_journal.h"
#include "can_live.h"

/// Exit status of a journal the node refuses to resume (another version, options or
/// mission, or a record it does not take again): a supervisor should not restart the node
/// into the same refusal (systemd: RestartPreventExitStatus=3).
#define SVA_CAN_EXIT_STATE_REFUSED 3

/// The journal and its storage. Static (the journal holds a 7.5 KiB buffer).
typedef struct {
    sva_can_journal_t journal;
    sva_journal_file_t file;
    bool open;
} sva_can_state_t;

/// Makes `dir` when missing (one level, mode 0700), opens the journal in it and resumes
/// `live` (started with `mission`) from it, or with `reset` starts a new one. Prints one
/// line on stdout saying what it found ("sva_can_node: resumed from PATH: ..." or
/// "sva_can_node: state: a new journal PATH"), a cut on stderr. Returns 0, 1 (the folder
/// or the storage failed, e.g. the folder is in use), 2 (a bad --state-dir value) or
/// SVA_CAN_EXIT_STATE_REFUSED, after one line on stderr.
int sva_can_state_open(sva_can_state_t* self, const char* dir, bool reset, sva_can_live_t* live,
                       const sva_mission_t* mission);

/// Closes the journal (the live mission's hook removed). Safe to call twice.
void sva_can_state_close(sva_can_state_t* self);

#endif
