// Private to sva_mavlink_bridge: what its files share. options.c reads the command
// line; vehicles.c keeps the vehicles' slots and links and prints what they do; plans.c
// turns FLEET, MISSION, PLAN and REPLAN into uploads; reports.c publishes the vehicles'
// telemetry on REPORT; sva_mavlink_bridge.c runs the steps and the loop. Calls go one
// way: main -> options, vehicles, plans, reports; plans -> reports, vehicles;
// reports -> vehicles.
#ifndef SVA_MAVLINK_BRIDGE_H
#define SVA_MAVLINK_BRIDGE_H

#include <lcm/lcm.h>
#include <stdbool.h>
#include <stdint.h>

#include "sva/sva_frame.h"
#include "sva/sva_mavlink.h"

#define BRIDGE_MAX_VEHICLES 64
/// Room for a channel name (LCM's longest is 63 characters).
#define BRIDGE_CHANNEL_SIZE 64
/// The longest suffix after the prefix ("MISSION", "REPORT", ...) and then some.
#define BRIDGE_SUFFIX_ROOM 8

#define BRIDGE_DEFAULT_URL                  "udpm://239.255.76.67:7667?ttl=0"
#define BRIDGE_DEFAULT_PREFIX               "SVA_"
#define BRIDGE_DEFAULT_SYSTEM               250
#define BRIDGE_DEFAULT_REPORT_MS            1000
#define BRIDGE_DEFAULT_HEARTBEAT_TIMEOUT_MS 3000
/// A failed upload is tried again this many times (--upload-retries), the first after
/// BRIDGE_RETRY_FIRST_MS, each next wait twice the one before, at most BRIDGE_RETRY_MAX_MS.
#define BRIDGE_DEFAULT_UPLOAD_RETRIES 5
#define BRIDGE_RETRY_FIRST_MS         2000
#define BRIDGE_RETRY_MAX_MS           60000

/// The command line.
typedef struct bridge_options {
    const char* url;
    const char* prefix;
    long own_system;
    long timeout_ms;
    long retries;
    long upload_retries;        ///< a failed upload is tried again this many times
    bool ardupilot;             ///< a home item 0 first
    long report_ms;             ///< host ms between two reports of a vehicle
    long heartbeat_timeout_ms;  ///< silent longer than this: reported LOST
    long fuel_capacity_cells;   ///< fuel of a full battery; 0: fuel not reported
    float cruise_m_s;           ///< the speed commanded (>= the plan's); 0: the plan's
    sva_mavlink_vehicle_spec_t specs[BRIDGE_MAX_VEHICLES];
    size_t spec_count;
} bridge_options_t;

typedef enum bridge_parse {
    BRIDGE_RUN = 0,   ///< options read: run
    BRIDGE_HELP = 1,  ///< --help printed: exit 0
    BRIDGE_BAD = 2    ///< one error line printed: exit 2
} bridge_parse_t;

/// Reads argv into *o (defaults first). BRIDGE_BAD after one line on stderr
/// "sva_mavlink_bridge: error: OPTION: RULE, got VALUE" (the usage follows for an
/// unknown option or a missing --vehicle).
bridge_parse_t bridge_options_parse(int argc, char** argv, bridge_options_t* o);

/// Why a vehicle is reported LOST whatever its heartbeats say (docs/mavlink.md, "A
/// vehicle that fails an upload or reboots"). A withheld vehicle gets no upload.
typedef enum bridge_withheld {
    BRIDGE_HELD_NO = 0,       ///< reported as its telemetry says
    BRIDGE_HELD_REFUSED = 1,  ///< an upload failed for good: until it is silent past the
                              ///< heartbeat timeout, its link drops or it reboots (then GONE)
    BRIDGE_HELD_GONE = 2      ///< its link dropped, it rebooted, or it was REFUSED and went
                              ///< silent: until a LOST report went out and it is heard again
} bridge_withheld_t;

/// One vehicle and what the bridge knows of its missions and of what it said.
typedef struct vehicle_slot {
    sva_mavlink_vehicle_t link;
    sva_mavlink_item_t flown[SVA_MAVLINK_MAX_ITEMS];  ///< the last mission it accepted or got
    size_t flown_count;
    /// The targets of `flown` in visit order: ids and window starts (ticks), to tell a
    /// target left out of a replan because it was served or is under way (its window
    /// has started) from one that is gone (cancelled before its window).
    int32_t flown_target_ids[SVA_MAVLINK_MAX_ROUTE_TARGETS];
    int32_t flown_target_starts[SVA_MAVLINK_MAX_ROUTE_TARGETS];
    size_t flown_target_count;
    int64_t plan_id;       ///< plan of the upload in progress
    int32_t retries_done;  ///< tries again of the mission in link.items so far
    bool retry_pending;    ///< a failed upload is tried again at retry_due_ms
    int64_t retry_due_ms;
    bridge_withheld_t withheld;
    int64_t gone_host_ms;  ///< when it became GONE
    bool lost_said;        ///< a LOST report of it went out since it was withheld
    uint32_t seen_drops;   ///< link.drops and telemetry.reboots already taken
    uint32_t seen_reboots;
    sva_mavlink_report_t last;  ///< the last report published (has_last)
    bool has_last;
    bool reported;           ///< its result was printed
    uint32_t said_connects;  ///< link events printed so far
    uint32_t said_drops;
    bool said_connect_failure;
    sva_mavlink_report_status_t said_status;  ///< the last report status printed
    sva_mavlink_health_t said_health;
    bridge_withheld_t said_withheld;
} vehicle_slot_t;

extern vehicle_slot_t bridge_slots[BRIDGE_MAX_VEHICLES];
extern size_t bridge_slot_count;

/// Prints "PREFIX uav ID (tcp:HOST:PORT): TEXT" on stdout (prefix "plan N:" or empty).
void bridge_say(const vehicle_slot_t* s, const char* prefix, const char* text);

/// Opens a link per --vehicle into bridge_slots. False after one error line on stderr
/// (a host that does not resolve, no socket).
bool bridge_vehicles_open(const bridge_options_t* o);
/// Starts uploading link.items to s for plan_id (a retry pending is dropped: this
/// mission replaces it).
void bridge_vehicles_upload(vehicle_slot_t* s, int64_t plan_id);
/// Services every link at now_ms and prints what happened: an upload's result ("plan
/// N: uav ID (...): uploaded 8 items"; a failure "...: retry 1 of 5 in 2000 ms: ..."
/// while tries again are left, then "...: error: ..."), a retry started when due, a TCP
/// connection made, lost, or its first failed attempt. An upload that fails for good
/// (its tries again used up, or refused by the vehicle for good:
/// sva_mavlink_upload_refused_for_good) makes the vehicle REFUSED; a dropped link or a
/// reboot makes it GONE (a retry pending is dropped); either way what it holds is
/// forgotten.
void bridge_vehicles_service(int64_t now_ms);
void bridge_vehicles_close(void);

/// Subscribes to <prefix>FLEET, MISSION, PLAN and REPLAN. False with a line on stderr.
bool bridge_plans_subscribe(lcm_t* lcm, const bridge_options_t* o);

/// Reports: the options they need (once, before the loop).
void bridge_reports_configure(const bridge_options_t* o);
/// A plan was dispatched in `frame` (checked), answering these revisions: reports go
/// out every report_ms from now on in that frame.
void bridge_reports_hold(const sva_frame_t* frame, int64_t fleet_revision, int64_t mission_revision,
                         int64_t now_ms);
/// No plan is held (e.g. it has no frame): no reports until the next plan.
void bridge_reports_release(void);
/// A fleet or mission message accepted from the ground: when its revision is not the
/// held plan's, a new mission is coming and reports stop until its plan.
void bridge_reports_on_fleet(int64_t revision);
void bridge_reports_on_mission(int64_t revision);
/// Publishes the reports due at now_ms: a withheld vehicle is reported LOST (with its
/// last report's position and tick while it has none of its own) and released once the
/// rule of bridge_withheld_t allows. Returns the ms until the next one is due (-1: none
/// is).
int64_t bridge_reports_service(lcm_t* lcm, int64_t now_ms);

#endif  // SVA_MAVLINK_BRIDGE_H
