// sva_mavlink_bridge's vehicles (bridge.h): their slots, their links' work, and the
// lines they print (upload results, TCP link events).
#include <inttypes.h>
#include <stdio.h>
#include <string.h>

#include "bridge.h"

vehicle_slot_t bridge_slots[BRIDGE_MAX_VEHICLES];
size_t bridge_slot_count;

static int32_t upload_retries;  // --upload-retries

void bridge_say(const vehicle_slot_t* s, const char* prefix, const char* text)
{
    const sva_mavlink_vehicle_spec_t* sp = &s->link.spec;
    printf("%s%suav %d (%s:%s:%u): %s\n", prefix, prefix[0] != '\0' ? " " : "", (int)sp->uav_id,
           sva_mavlink_transport_name(sp->transport), sp->host, (unsigned)sp->port, text);
    fflush(stdout);
}

bool bridge_vehicles_open(const bridge_options_t* o)
{
    char err[SVA_MAVLINK_ERROR_SIZE];
    upload_retries = (int32_t)o->upload_retries;
    for (size_t k = 0; k < o->spec_count; k++) {
        vehicle_slot_t* s = &bridge_slots[k];
        if (sva_mavlink_vehicle_open(&s->link, &o->specs[k], (uint8_t)o->own_system, err,
                                     sizeof err) != SVA_MAVLINK_OK) {
            fprintf(stderr, "sva_mavlink_bridge: error: %s\n", err);
            return false;
        }
        s->link.upload.timeout_ms = (int32_t)o->timeout_ms;
        s->link.upload.retries = (int32_t)o->retries;
        s->reported = true;
        s->said_status = SVA_MAVLINK_REPORT_NEVER_HEARD;
        s->said_health = SVA_MAVLINK_HEALTH_OK;
        s->withheld = BRIDGE_HELD_NO;
        s->said_withheld = BRIDGE_HELD_NO;
        bridge_slot_count++;
    }
    return true;
}

static void start(vehicle_slot_t* s, int64_t now_ms)
{
    s->reported = false;
    (void)sva_mavlink_vehicle_start(&s->link, now_ms);
}

void bridge_vehicles_upload(vehicle_slot_t* s, int64_t plan_id)
{
    s->plan_id = plan_id;
    s->retries_done = 0;
    s->retry_pending = false;
    char prefix[32];
    snprintf(prefix, sizeof prefix, "plan %" PRId64 ":", plan_id);
    char text[64];
    snprintf(text, sizeof text, "uploading %zu items", s->link.item_count);
    bridge_say(s, prefix, text);
    start(s, sva_mavlink_now_ms());
}

// The wait before try again number `retry` (1 for the first): BRIDGE_RETRY_FIRST_MS,
// doubled each time, at most BRIDGE_RETRY_MAX_MS.
static int64_t backoff_ms(int32_t retry)
{
    int64_t wait_ms = BRIDGE_RETRY_FIRST_MS;
    for (int32_t k = 1; k < retry && wait_ms < BRIDGE_RETRY_MAX_MS; k++) {
        wait_ms *= 2;
    }
    return wait_ms < BRIDGE_RETRY_MAX_MS ? wait_ms : BRIDGE_RETRY_MAX_MS;
}

// Forgets what the vehicle holds: the next plan that routes it uploads again.
static void forget(vehicle_slot_t* s)
{
    s->flown_count = 0;
    s->flown_target_count = 0;
}

// The end of an upload: one line with its result. A failure with tries again left is
// tried again after the backoff; a failure for good (no tries left, a refusal the same
// mission would get again, or the link gone under it) forgets what the vehicle holds and
// withholds it (REFUSED, unless it is GONE already).
static void say_upload_result(vehicle_slot_t* s, int64_t now_ms)
{
    if (s->reported || sva_mavlink_vehicle_busy(&s->link)) {
        return;
    }
    s->reported = true;
    char prefix[32];
    snprintf(prefix, sizeof prefix, "plan %" PRId64 ":", s->plan_id);
    char text[SVA_MAVLINK_ERROR_SIZE + 64];
    if (s->link.upload.state == SVA_MAVLINK_UPLOAD_DONE) {
        snprintf(text, sizeof text, "uploaded %u items", (unsigned)s->link.upload.count);
    } else if (s->retries_done < upload_retries && s->withheld != BRIDGE_HELD_GONE &&
               !sva_mavlink_upload_refused_for_good(&s->link.upload)) {
        s->retries_done++;
        const int64_t wait_ms = backoff_ms(s->retries_done);
        s->retry_pending = true;
        s->retry_due_ms = now_ms + wait_ms;
        snprintf(text, sizeof text, "retry %d of %d in %" PRId64 " ms: %s", (int)s->retries_done,
                 (int)upload_retries, wait_ms, s->link.upload.error);
    } else {
        snprintf(text, sizeof text, "error: %s", s->link.upload.error);
        forget(s);
        if (s->withheld == BRIDGE_HELD_NO) {
            s->withheld = BRIDGE_HELD_REFUSED;
            s->lost_said = false;
        }
    }
    bridge_say(s, prefix, text);
}

// A dropped link or a reboot (time since boot gone back): the vehicle holds no mission
// the bridge can vouch for. It is GONE until heard again (reports.c), a retry pending is
// dropped, and the next plan that routes it uploads again.
static void note_link_changes(vehicle_slot_t* s, int64_t now_ms)
{
    const sva_mavlink_vehicle_t* v = &s->link;
    if (v->drops == s->seen_drops && v->telemetry.reboots == s->seen_reboots) {
        return;
    }
    s->seen_drops = v->drops;
    s->seen_reboots = v->telemetry.reboots;
    s->withheld = BRIDGE_HELD_GONE;
    s->gone_host_ms = now_ms;
    s->lost_said = false;
    s->retry_pending = false;
    forget(s);
}

// A retry due: the same mission again (a newer one would have dropped the retry).
static void start_due_retry(vehicle_slot_t* s, int64_t now_ms)
{
    if (!s->retry_pending || now_ms < s->retry_due_ms || sva_mavlink_vehicle_busy(&s->link)) {
        return;
    }
    s->retry_pending = false;
    start(s, now_ms);
}

// TCP links: connections made and lost, and the first failed attempt of each outage.
static void say_link_events(vehicle_slot_t* s)
{
    const sva_mavlink_vehicle_t* v = &s->link;
    char text[SVA_MAVLINK_ERROR_SIZE + 64];
    if (v->drops != s->said_drops) {
        s->said_drops = v->drops;
        snprintf(text, sizeof text, "connection lost: %s; reconnecting every %d ms", v->link_error,
                 SVA_MAVLINK_RECONNECT_MS);
        bridge_say(s, "", text);
    }
    if (v->connects != s->said_connects) {
        s->said_connects = v->connects;
        s->said_connect_failure = false;
        bridge_say(s, "", "connected");
    }
    if (v->failed_connects > 0 && !s->said_connect_failure) {
        s->said_connect_failure = true;
        snprintf(text, sizeof text, "cannot connect: %s; retrying every %d ms", v->link_error,
                 SVA_MAVLINK_RECONNECT_MS);
        bridge_say(s, "", text);
    }
}

void bridge_vehicles_service(int64_t now_ms)
{
    for (size_t k = 0; k < bridge_slot_count; k++) {
        vehicle_slot_t* s = &bridge_slots[k];
        sva_mavlink_vehicle_service(&s->link, now_ms);
        say_link_events(s);
        note_link_changes(s, now_ms);
        say_upload_result(s, now_ms);
        start_due_retry(s, now_ms);
    }
}

void bridge_vehicles_close(void)
{
    for (size_t k = 0; k < bridge_slot_count; k++) {
        sva_mavlink_vehicle_close(&bridge_slots[k].link);
    }
}
