// Fuzz target: the LCM message path of port/lcm (sva_lcm_on_fleet / sva_lcm_on_mission /
// sva_lcm_on_report: size and fingerprint checks, lcm-gen's decoder, the version, count,
// value and frame checks, conversion, sva_plan, plan encoding, the report rule and the
// live replan). The input is a sequence of up to 8 messages:
//   byte  kind: bit 0 = 0 fleet, 1 mission; bit 7 = 1 a vehicle report instead (a
//         refused one must leave the live mission byte for byte as it was); bit 1 = 1
//         "exact": the next bytes are
//         zero-padded or cut to the type's one valid size (so the fuzzer reaches the
//         decoder), 0 "raw": a little-endian 16-bit length follows, then that many
//         bytes (clamped to what is left) are delivered as they are.
// Properties: nothing crashes or reads out of bounds (ASan, UBSan); a refused message
// leaves the node's inputs as they were; every published plan has the wire type's
// exact size and decodes with lcm-gen's decoder; every plan the core made for an
// accepted fleet + mission passes the independent SPEC checker; flow's certificate is
// on the wire exactly when the plan is flow's and has routes, equal to the core's
// (lower_bound <= cost, == cost when optimal), and zero otherwise.
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "spec_checker.h"
#include "sva/sva_lcm.h"

int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size);

static sva_lcm_node_t node;
static sva_lcm_plan_t decoded;
static sva_mission_t before;
static sva_lcm_frame_t frame_before;
static sva_live_t live_before;
static uint8_t message[SVA_LCM_MISSION_BYTES > SVA_LCM_FLEET_BYTES ? SVA_LCM_MISSION_BYTES
                                                                   : SVA_LCM_FLEET_BYTES];
static unsigned published;

static void fail(const char* what)
{
    fprintf(stderr, "fuzz_lcm: %s\n", what);
    abort();
}

static int capture(void* user, const char* channel, const void* bytes, unsigned int n)
{
    (void)user;
    if (strcmp(channel, node.channel_plan) != 0) {
        return 0;
    }
    published++;
    if (n != SVA_LCM_PLAN_BYTES || sva_lcm_plan_t_decode(bytes, 0, (int)n, &decoded) != (int)n) {
        fail("published plan does not decode to its fixed size");
    }
    if (decoded.status == SVA_LCM_PLAN_T_STATUS_COMPLETE ||
        decoded.status == SVA_LCM_PLAN_T_STATUS_PARTIAL) {
        char msg[256];
        if (spec_check_plan(&node.priv.mission, &node.priv.plan, msg, sizeof msg) != 0) {
            fprintf(stderr, "fuzz_lcm: %s\n", msg);
            fail("published plan breaks SPEC section 1");
        }
        if (decoded.route_count != (int16_t)node.priv.mission.uav_count) {
            fail("plan does not have one route per UAV");
        }
        const sva_stats_t* st = &node.priv.plan.stats;
        if (st->has_bound != (node.algorithm == SVA_ALGO_FLOW) ||
            decoded.has_bound != (st->has_bound ? 1 : 0)) {
            fail("has_bound is not set exactly for flow plans");
        }
        if (st->has_bound &&
            (decoded.lower_bound != st->lower_bound || decoded.optimal != (st->optimal ? 1 : 0) ||
             decoded.flow_incomplete != (int8_t)st->flow_incomplete || decoded.lower_bound < 0 ||
             decoded.lower_bound > decoded.cost ||
             (decoded.optimal == 1 && decoded.lower_bound != decoded.cost))) {
            fail("flow's certificate on the wire differs from the core's or contradicts the cost");
        }
    }
    if (decoded.status != SVA_LCM_PLAN_T_STATUS_COMPLETE &&
        decoded.status != SVA_LCM_PLAN_T_STATUS_PARTIAL &&
        (decoded.has_bound != 0 || decoded.lower_bound != 0 || decoded.optimal != 0 ||
         decoded.flow_incomplete != 0)) {
        fail("a plan without routes carries a certificate");
    }
    if (!decoded.has_bound &&
        (decoded.lower_bound != 0 || decoded.optimal != 0 || decoded.flow_incomplete != 0)) {
        fail("certificate fields set without has_bound");
    }
    return 0;
}

int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size)
{
    if (sva_lcm_node_init(&node, NULL, "SVA_", SVA_ALGO_SVA) != SVA_OK) {
        fail("node init");
    }
    node.publish = capture;
    published = 0;
    size_t at = 0;
    for (int m = 0; m < 8 && at < size; m++) {
        const uint8_t kind = data[at++];
        const bool is_report = (kind & 0x80U) != 0U;
        const bool is_mission = !is_report && ((kind & 1U) != 0U);
        const size_t want = is_report    ? SVA_LCM_REPORT_BYTES
                            : is_mission ? SVA_LCM_MISSION_BYTES
                                         : SVA_LCM_FLEET_BYTES;
        size_t n;
        if ((kind & 2U) != 0U) {
            n = want;
            const size_t have = (size - at < want) ? size - at : want;
            memset(message, 0, sizeof message);
            memcpy(message, data + at, have);
            at += have;
        } else {
            if (size - at < 2U) {
                break;
            }
            n = (size_t)data[at] | ((size_t)data[at + 1] << 8U);
            at += 2;
            n = (n > size - at) ? size - at : n;
            n = (n > sizeof message) ? sizeof message : n;
            memcpy(message, data + at, n);
            at += n;
        }
        // The algorithm varies with the kind byte so that every planner sees inputs.
        node.algorithm = (sva_algorithm_t)((kind >> 2U) % (unsigned)SVA_ALGO_COUNT_);
        before = node.priv.mission;
        frame_before = node.priv.frame;
        const bool had_fleet = node.priv.have_fleet;
        const bool had_mission = node.priv.have_mission;
        const unsigned published_before = published;
        if (is_report) {
            memcpy(&live_before, &node.priv.live, sizeof live_before);
            if ((sva_lcm_on_report(&node, message, n) != SVA_LCM_ACCEPTED) &&
                ((memcmp(&live_before, &node.priv.live, sizeof live_before) != 0) ||
                 (published != published_before))) {
                fail("a refused report changed the live mission or published");
            }
            continue;
        }
        const sva_lcm_status_t v = is_mission ? sva_lcm_on_mission(&node, message, n)
                                              : sva_lcm_on_fleet(&node, message, n);
        if (v != SVA_LCM_ACCEPTED) {
            if (memcmp(&before, &node.priv.mission, sizeof before) != 0 ||
                memcmp(&frame_before, &node.priv.frame, sizeof frame_before) != 0 ||
                had_fleet != node.priv.have_fleet || had_mission != node.priv.have_mission ||
                published != published_before) {
                fail("a refused or unchanged message changed the node's inputs");
            }
        } else if (is_mission && (node.priv.frame.present != 0) &&
                   (node.priv.frame.cell_cm < 10 || node.priv.frame.tick_ms < 1)) {
            fail("an accepted mission carries a frame sva_frame_check refuses");
        } else if (node.priv.have_fleet && node.priv.have_mission &&
                   published != published_before + 1U) {
            fail("an accepted change with both inputs present published no plan");
        }
    }
    return 0;
}
