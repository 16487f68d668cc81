// lcm_journal_file.c -- the journal's POSIX storage: the shared one (sva_journal.h: one
// file in a folder, appended and fsync'd; replaced through a temporary file, fsync,
// rename and an fsync of the folder) under sva_node's file names (contract in
// sva_lcm_journal.h).
#include "sva/sva_lcm_journal.h"

sva_lcm_journal_status_t sva_lcm_journal_file_init(sva_lcm_journal_file_t* self, const char* dir,
                                                   sva_lcm_storage_t* storage)
{
    if (!sva_journal_file_init(self, dir, SVA_LCM_JOURNAL_FILE_NAME, SVA_LCM_JOURNAL_TEMP_NAME,
                               SVA_LCM_JOURNAL_LOCK_NAME, storage)) {
        return SVA_LCM_JOURNAL_ERR_ARGUMENT;
    }
    return SVA_LCM_JOURNAL_OK;
}
