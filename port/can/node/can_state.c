// can_state.c -- sva_can_node's --state-dir (contract in can_state.h).
#define _POSIX_C_SOURCE 200809L

#include "can_state.h"

#include <errno.h>
#include <stdio.h>
#include <string.h>
#include <sys/stat.h>

#include "sva/sva_text.h"

#define SHOWN_SIZE 512

int sva_can_state_open(sva_can_state_t* self, const char* dir, bool reset, sva_can_live_t* live,
                       const sva_mission_t* mission)
{
    char shown[SHOWN_SIZE];
    char said[SHOWN_SIZE];
    sva_journal_storage_t storage;
    struct stat st;
    sva_can_journal_resume_t r;
    sva_can_journal_status_t js;
    memset(self, 0, sizeof *self);
    if (!sva_journal_file_init(&self->file, dir, SVA_CAN_JOURNAL_FILE_NAME,
                               SVA_CAN_JOURNAL_TEMP_NAME, SVA_CAN_JOURNAL_LOCK_NAME, &storage)) {
        fprintf(stderr,
                "sva_can_node: error: --state-dir: must be a folder path of 1 to %d characters\n",
                SVA_JOURNAL_DIR_MAX);
        return 2;
    }
    if ((stat(dir, &st) != 0) && ((errno != ENOENT) || (mkdir(dir, 0700) != 0))) {
        fprintf(stderr, "sva_can_node: error: --state-dir %s: %s\n",
                sva_text_escape(shown, sizeof shown, dir), strerror(errno));
        return 1;
    }
    if (sva_can_journal_init(&self->journal, &storage, live) != SVA_CAN_JOURNAL_OK) {
        fprintf(stderr, "sva_can_node: error: --state-dir: cannot set up the journal\n");
        return 1;
    }
    self->open = true;
    (void)sva_text_escape(shown, sizeof shown, self->file.path);
    js = sva_can_journal_resume(&self->journal, mission, reset, &r);
    // The journal's lines name paths from --state-dir.
    (void)sva_text_escape(said, sizeof said, self->journal.message);
    if (js == SVA_CAN_JOURNAL_ERR_IO) {
        fprintf(stderr, "sva_can_node: error: --state-dir: %s\n", said);
        return 1;
    }
    if (js != SVA_CAN_JOURNAL_OK) {
        fprintf(
            stderr,
            "sva_can_node: error: --state-dir: journal %s refused: %s; start with --state-reset to "
            "discard it\n",
            shown, said);
        return SVA_CAN_EXIT_STATE_REFUSED;
    }
    if (r.fresh) {
        printf("sva_can_node: state: %s journal %s\n",
               r.discarded ? "--state-reset, a new" : "a new", shown);
    } else {
        char cut[64] = "";
        if (r.cut) {
            fprintf(stderr, "sva_can_node: journal %s: %s\n", shown, said);
            (void)snprintf(cut, sizeof cut, ", a torn tail cut at byte %lu",
                           (unsigned long)r.cut_offset);
        }
        printf("sva_can_node: resumed from %s: %lu frames and %lu replans replayed, revision "
               "%lu, now %ld, plan id %u%s\n",
               shown, (unsigned long)r.frames, (unsigned long)r.replans,
               (unsigned long)live->live.revision, (long)live->live.now_ticks,
               (unsigned)live->plan_id, cut);
    }
    (void)fflush(stdout);
    return 0;
}

void sva_can_state_close(sva_can_state_t* self)
{
    if (self->open) {
        sva_can_journal_close(&self->journal);
        self->open = false;
    }
}
