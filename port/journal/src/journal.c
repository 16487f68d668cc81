// journal.c -- records with length and CRC-32 (contract in sva_journal.h); the CRC is
// zlib's crc32.
#include "sva/sva_journal.h"

#include <stdio.h>
#include <string.h>

#include <zlib.h>

#define LENGTH_BYTES 4

bool sva_journal_storage_complete(const sva_journal_storage_t* storage)
{
    return (storage != NULL) && (storage->open != NULL) && (storage->read != NULL) &&
           (storage->append != NULL) && (storage->sync != NULL) && (storage->truncate != NULL) &&
           (storage->replace != NULL);
}

void sva_journal_put_u16(uint8_t* p, uint32_t v)
{
    p[0] = (uint8_t)(v & 0xFFU);
    p[1] = (uint8_t)((v >> 8U) & 0xFFU);
}

void sva_journal_put_u32(uint8_t* p, uint32_t v)
{
    for (unsigned i = 0U; i < 4U; ++i) {
        p[i] = (uint8_t)((v >> (8U * i)) & 0xFFU);
    }
}

void sva_journal_put_u64(uint8_t* p, uint64_t v)
{
    for (unsigned i = 0U; i < 8U; ++i) {
        p[i] = (uint8_t)((v >> (8U * i)) & 0xFFU);
    }
}

uint32_t sva_journal_get_u16(const uint8_t* p)
{
    return (uint32_t)p[0] | ((uint32_t)p[1] << 8U);
}

uint32_t sva_journal_get_u32(const uint8_t* p)
{
    uint32_t v = 0U;
    for (unsigned i = 0U; i < 4U; ++i) {
        v |= (uint32_t)p[i] << (8U * i);
    }
    return v;
}

uint64_t sva_journal_get_u64(const uint8_t* p)
{
    uint64_t v = 0U;
    for (unsigned i = 0U; i < 8U; ++i) {
        v |= (uint64_t)p[i] << (8U * i);
    }
    return v;
}

uint32_t sva_journal_crc(const uint8_t* p, uint32_t n)
{
    return (uint32_t)crc32(0UL, p, (uInt)n);
}

uint32_t sva_journal_put_record(uint8_t* out, uint8_t type, const void* payload, uint32_t len)
{
    sva_journal_put_u32(out, len);
    out[LENGTH_BYTES] = type;
    if (len > 0U) {
        memcpy(out + SVA_JOURNAL_PREFIX_BYTES, payload, len);
    }
    sva_journal_put_u32(out + SVA_JOURNAL_PREFIX_BYTES + len,
                        sva_journal_crc(out, SVA_JOURNAL_PREFIX_BYTES + len));
    return len + SVA_JOURNAL_RECORD_OVERHEAD;
}

sva_journal_record_status_t sva_journal_read_record(const sva_journal_storage_t* storage,
                                                    uint32_t size, uint32_t offset, uint8_t* buf,
                                                    uint32_t max_payload, uint32_t* type,
                                                    uint32_t* len, char* why, size_t why_size)
{
    const uint32_t left = (offset < size) ? (size - offset) : 0U;
    if (left < (uint32_t)SVA_JOURNAL_RECORD_OVERHEAD) {
        (void)snprintf(why, why_size, "short record: %lu bytes, a record has at least %d",
                       (unsigned long)left, SVA_JOURNAL_RECORD_OVERHEAD);
        return SVA_JOURNAL_RECORD_BAD;
    }
    if (storage->read(storage->ctx, offset, buf, SVA_JOURNAL_PREFIX_BYTES) != 0) {
        return SVA_JOURNAL_RECORD_IO;
    }
    *len = sva_journal_get_u32(buf);
    *type = buf[LENGTH_BYTES];
    if (*len > max_payload) {
        (void)snprintf(why, why_size, "bad length %lu (at most %lu)", (unsigned long)*len,
                       (unsigned long)max_payload);
        return SVA_JOURNAL_RECORD_BAD;
    }
    const uint32_t total = *len + (uint32_t)SVA_JOURNAL_RECORD_OVERHEAD;
    if (left < total) {
        (void)snprintf(why, why_size, "short record: %lu of its %lu bytes", (unsigned long)left,
                       (unsigned long)total);
        return SVA_JOURNAL_RECORD_BAD;
    }
    if (storage->read(storage->ctx, offset + SVA_JOURNAL_PREFIX_BYTES,
                      buf + SVA_JOURNAL_PREFIX_BYTES, *len + LENGTH_BYTES) != 0) {
        return SVA_JOURNAL_RECORD_IO;
    }
    const uint32_t want = sva_journal_get_u32(buf + SVA_JOURNAL_PREFIX_BYTES + *len);
    const uint32_t got = sva_journal_crc(buf, SVA_JOURNAL_PREFIX_BYTES + *len);
    if (got != want) {
        (void)snprintf(why, why_size, "bad CRC 0x%08lx, the record says 0x%08lx",
                       (unsigned long)got, (unsigned long)want);
        return SVA_JOURNAL_RECORD_BAD;
    }
    return SVA_JOURNAL_RECORD_GOOD;
}

void sva_journal_say_failed(const sva_journal_storage_t* storage, const char* call, char* message,
                            size_t size)
{
    const char* why = (storage->error != NULL) ? storage->error(storage->ctx) : NULL;
    (void)snprintf(message, size, "storage %s failed: %s", call, (why != NULL) ? why : "no detail");
}

int sva_journal_append(const sva_journal_storage_t* storage, const uint8_t* bytes, uint32_t n,
                       uint32_t* size, uint32_t* records, char* message, size_t message_size)
{
    if (n > (UINT32_MAX - *size)) {
        (void)snprintf(message, message_size, "append: the journal is full (%lu bytes)",
                       (unsigned long)*size);
        return -1;
    }
    if (storage->append(storage->ctx, bytes, n) != 0) {
        sva_journal_say_failed(storage, "append", message, message_size);
        // A record that went half-way is cut back now (a restart would cut it anyway).
        (void)storage->truncate(storage->ctx, *size);
        return -1;
    }
    if (storage->sync(storage->ctx) != 0) {
        sva_journal_say_failed(storage, "sync", message, message_size);
        return -1;
    }
    *size += n;
    *records += 1U;
    return 0;
}

int sva_journal_cut_torn(const sva_journal_storage_t* storage, uint32_t offset, const char* why,
                         uint32_t* size, uint32_t* dropped, char* message, size_t message_size)
{
    *dropped = *size - offset;
    if (storage->truncate(storage->ctx, offset) != 0) {
        sva_journal_say_failed(storage, "truncate", message, message_size);
        return -1;
    }
    (void)snprintf(message, message_size,
                   "torn or corrupt record at byte %lu (%s): cut there, %lu bytes dropped",
                   (unsigned long)offset, why, (unsigned long)*dropped);
    *size = offset;
    return 0;
}

sva_journal_replay_status_t sva_journal_replay(const sva_journal_storage_t* storage,
                                               uint32_t offset, uint32_t* size, uint8_t* buf,
                                               uint32_t max_payload,
                                               sva_journal_on_record_t on_record, void* user,
                                               sva_journal_cut_t* cut, char* message,
                                               size_t message_size)
{
    cut->cut = false;
    cut->offset = 0U;
    cut->bytes = 0U;
    uint32_t off = offset;
    while (off < *size) {
        uint32_t type = 0U;
        uint32_t len = 0U;
        char why[96];
        const sva_journal_record_status_t got = sva_journal_read_record(
            storage, *size, off, buf, max_payload, &type, &len, why, sizeof why);
        if (got == SVA_JOURNAL_RECORD_IO) {
            sva_journal_say_failed(storage, "read", message, message_size);
            return SVA_JOURNAL_REPLAY_IO;
        }
        if (got == SVA_JOURNAL_RECORD_BAD) {
            cut->cut = true;
            cut->offset = off;
            return (sva_journal_cut_torn(storage, off, why, size, &cut->bytes, message,
                                         message_size) == 0)
                       ? SVA_JOURNAL_REPLAY_DONE
                       : SVA_JOURNAL_REPLAY_IO;
        }
        if (on_record(user, off, type, buf + SVA_JOURNAL_PREFIX_BYTES, len) != 0) {
            return SVA_JOURNAL_REPLAY_STOPPED;
        }
        off += len + (uint32_t)SVA_JOURNAL_RECORD_OVERHEAD;
    }
    return SVA_JOURNAL_REPLAY_DONE;
}
