// sva_node -- the on-board planner process: fleet state and missions in over LCM,
// plans and a 1 Hz status out; each plan starts a live mission, whose events come in
// and whose replans go out (docs/lcm.md). One thread calls lcm_handle_timeout in a loop (LCM
// requires a single handling thread); SIGINT/SIGTERM end the loop cleanly. With
// --state-dir its inputs are journaled (sva_lcm_journal.h) and a restart resumes the
// live mission where it stood (docs/lcm.md, "Crash safety").
#include <errno.h>
#include <sched.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <time.h>

#include "sva/sva_lcm.h"
#include "sva/sva_lcm_journal.h"
#include "sva/sva_text.h"

#define DEFAULT_URL    "udpm://239.255.76.67:7667?ttl=0&recv_buf_size=4194304"
#define DEFAULT_PREFIX "SVA_"
/// Socket receive buffer requested when a udpm URL does not name one: a burst of 1000
/// mission messages (6 KiB each) is ~ 6 MiB of payload; the kernel caps the request at
/// net.core.rmem_max (docs/lcm.md).
#define RECV_BUF_BYTES 4194304
#define URL_SIZE       512
/// Room for a user-supplied string (an option value, the URL, a channel name, an
/// adapter log line) as the node prints it: escaped with sva_text_escape().
#define SHOWN_SIZE SVA_TEXT_ESCAPED_SIZE(URL_SIZE)
/// Exit status of a journal the node refuses to resume (another version, a header that
/// does not parse, other options): systemd's RestartPreventExitStatus names it, so a
/// refused journal is not retried in a loop.
#define EXIT_STATE_REFUSED 3

static volatile sig_atomic_t stop_requested = 0;

static void on_signal(int sig)
{
    (void)sig;
    stop_requested = 1;
}

static void log_stderr(void* user, const char* line)
{
    (void)user;
    // Adapter lines name channels, which come from --prefix.
    char shown[SHOWN_SIZE];
    fprintf(stderr, "sva_node: %s\n", sva_text_escape(shown, sizeof shown, line));
}

static int64_t realtime_us(void)
{
    struct timespec ts;
    (void)clock_gettime(CLOCK_REALTIME, &ts);
    return ((int64_t)ts.tv_sec * 1000000) + ((int64_t)ts.tv_nsec / 1000);
}

static int64_t monotonic_ms(void)
{
    struct timespec ts;
    (void)clock_gettime(CLOCK_MONOTONIC, &ts);
    return ((int64_t)ts.tv_sec * 1000) + ((int64_t)ts.tv_nsec / 1000000);
}

static void usage(FILE* out)
{
    fprintf(out,
            "usage: sva_node [options]\n"
            "       sva_node --help | --version\n"
            "  -u, --url URL          LCM provider (default " DEFAULT_URL ")\n"
            "                         a udpm URL without recv_buf_size gets %d\n"
            "  -p, --prefix PREFIX    channel prefix (default " DEFAULT_PREFIX "): channels\n"
            "                         PREFIX{FLEET,MISSION,PLAN,STATUS,EVENT,REPLAN}, matched\n"
            "                         exactly\n"
            "  -a, --algo NAME        sva, ga, hga, bfa or flow (default sva); --algorithm\n"
            "                         is the same option\n"
            "  -c, --change-penalty N cells a replan pays per changed visit (default 0,\n"
            "                         at most %ld; SPEC section 12.4)\n"
            "  -k, --takeoff-ticks N  ticks a UAV on the ground (back in service, or home\n"
            "                         with its route done) takes to leave (default 0, at\n"
            "                         most %ld; SPEC section 12.2)\n"
            "  -f, --fleet-reports    while a live mission runs, a fleet message is a report\n"
            "                         checked against the plan in force (a UAV unavailable:\n"
            "                         uav_lost; off its track: a position event; fuel below\n"
            "                         its route's need: a fuel event) instead of a new\n"
            "                         fleet to plan from scratch\n"
            "  -t, --track-tolerance N with --fleet-reports: cells (Manhattan) a reported\n"
            "                         UAV may be from the plan's position before it is off\n"
            "                         its track (default %d, at most %d)\n"
            "  -s, --status-ms MS     status period in milliseconds (default 1000)\n"
            "  -e, --exit-on-eof      stop when the provider ends (file:// logs)\n"
            "  -r, --rt-priority N    run under SCHED_FIFO priority N (1..99), LCM's receive\n"
            "                         thread included (needs CAP_SYS_NICE or RLIMIT_RTPRIO)\n"
            "  -m, --mlock            lock every page in RAM (mlockall current and future)\n"
            "      --state-dir DIR    journal every input in DIR (created if missing) and,\n"
            "                         on start, resume the live mission it holds\n"
            "      --state-reset      with --state-dir: discard the journal and start afresh\n"
            "  -h, --help             this text\n"
            "      --version          print \"sva_node VERSION\" (the sva library's)\n",
            RECV_BUF_BYTES, (long)SVA_MAX_CHANGE_PENALTY, (long)SVA_MAX_TICK,
            SVA_LCM_TRACK_TOLERANCE_DEFAULT, SVA_LCM_TRACK_TOLERANCE_MAX);
}

// Appends recv_buf_size to a udpm URL that has none (LCM's default is 2 MiB).
static int build_url(const char* in, char* out, size_t size)
{
    int n;
    if ((strncmp(in, "udpm://", 7) == 0) && (strstr(in, "recv_buf_size=") == NULL)) {
        n = snprintf(out, size, "%s%crecv_buf_size=%d", in, (strchr(in, '?') != NULL) ? '&' : '?',
                     RECV_BUF_BYTES);
    } else {
        n = snprintf(out, size, "%s", in);
    }
    return ((n < 0) || ((size_t)n >= size)) ? -1 : 0;
}

static sva_lcm_node_t node;
static sva_lcm_journal_t journal;
static sva_lcm_journal_file_t journal_file;

// Real-time setup, before lcm_create: threads created later (LCM's udpm receive thread)
// inherit the calling thread's policy. Returns 0, or 1 after printing why it failed.
static int realtime_setup(long rt_priority, int lock_memory)
{
    if (rt_priority > 0) {
        struct sched_param sp;
        memset(&sp, 0, sizeof sp);
        sp.sched_priority = (int)rt_priority;
        if (sched_setscheduler(0, SCHED_FIFO, &sp) != 0) {
            fprintf(stderr,
                    "sva_node: error: --rt-priority: sched_setscheduler(SCHED_FIFO, %ld): %s\n",
                    rt_priority, strerror(errno));
            return 1;
        }
    }
    if (lock_memory && (mlockall(MCL_CURRENT | MCL_FUTURE) != 0)) {
        fprintf(stderr, "sva_node: error: --mlock: mlockall: %s\n", strerror(errno));
        return 1;
    }
    return 0;
}

// An integer option's value in [lo, hi] into *out; false (after the error) otherwise.
static bool integer_option(const char* name, const char* text, long lo, long hi, long* out)
{
    char err[SHOWN_SIZE];
    if (sva_text_to_long(name, text, lo, hi, out, err, sizeof err) != SVA_OK) {
        fprintf(stderr, "sva_node: error: %s\n", err);
        return false;
    }
    return true;
}

// The folder of --state-dir, made when missing. Returns 0, or 1 after printing why.
static int state_dir_ready(const char* dir)
{
    struct stat st;
    if ((stat(dir, &st) != 0) && ((errno != ENOENT) || (mkdir(dir, 0700) != 0))) {
        char shown[SHOWN_SIZE];
        fprintf(stderr, "sva_node: error: --state-dir %s: %s\n",
                sva_text_escape(shown, sizeof shown, dir), strerror(errno));
        return 1;
    }
    return 0;
}

// Opens the journal of --state-dir and replays it into the node (before it subscribes).
// Says on stdout what it found (one line). Returns 0, 1 (storage) or EXIT_STATE_REFUSED.
static int resume_state(bool reset)
{
    char shown[SHOWN_SIZE];
    char said[SHOWN_SIZE];
    (void)sva_text_escape(shown, sizeof shown, journal_file.path);
    sva_lcm_journal_resume_t r;
    const sva_lcm_journal_status_t st = sva_lcm_journal_resume(&journal, reset, &r);
    // The journal's lines name paths from --state-dir.
    (void)sva_text_escape(said, sizeof said, journal.message);
    if (st == SVA_LCM_JOURNAL_ERR_IO) {
        fprintf(stderr, "sva_node: error: --state-dir: %s\n", said);
        return 1;
    }
    if (st != SVA_LCM_JOURNAL_OK) {
        fprintf(stderr,
                "sva_node: error: --state-dir: journal %s refused: %s; start with --state-reset to "
                "discard it\n",
                shown, said);
        return EXIT_STATE_REFUSED;
    }
    if (r.fresh) {
        printf("sva_node: state: %s journal %s\n", r.discarded ? "--state-reset, a new" : "a new",
               shown);
    } else {
        if (r.cut) {
            fprintf(stderr, "sva_node: journal %s: %s\n", shown, said);  // a warning
        }
        char live[96];
        if (node.priv.live_active) {
            (void)snprintf(live, sizeof live, "revision %lu, now %ld",
                           (unsigned long)node.priv.live.revision, (long)node.priv.live.now_ticks);
        } else {
            (void)snprintf(live, sizeof live, "no live mission");
        }
        char cut[64] = "";
        if (r.cut) {
            (void)snprintf(cut, sizeof cut, ", a torn tail cut at byte %lu",
                           (unsigned long)r.cut_offset);
        }
        printf("sva_node: resumed from %s: %lu records replayed, %s, plan id %lld%s\n", shown,
               (unsigned long)r.records, live, (long long)node.priv.plan_id, cut);
    }
    fflush(stdout);
    return 0;
}

static void send_status(void)
{
    if (sva_lcm_publish_status(&node, realtime_us()) != SVA_OK) {
        // Counted in node.counters.publish_errors; the node keeps running.
        return;
    }
}

// What the command line asks for, and what it makes of it.
typedef struct {
    const char* url_arg;
    const char* prefix;
    const char* algo_name;
    const char* algo_option;  // as the user spelled it, for its error line
    long status_ms;
    long change_penalty;
    long takeoff_ticks;
    int fleet_reports;
    long track_tolerance;
    long rt_priority;
    int lock_memory;
    int exit_on_eof;
    const char* state_dir;
    bool state_reset;
    sva_algorithm_t algorithm;
    char url[URL_SIZE];
} node_options_t;

// Reads the command line into *o. Returns -1 to go on, else the exit status (0 after
// --help or --version, 2 after a usage error, each with its message).
static int parse_options(int argc, char** argv, node_options_t* o)
{
    memset(o, 0, sizeof *o);
    o->url_arg = DEFAULT_URL;
    o->prefix = DEFAULT_PREFIX;
    o->algo_name = "sva";
    o->algo_option = "--algo";
    o->status_ms = 1000;
    o->track_tolerance = SVA_LCM_TRACK_TOLERANCE_DEFAULT;
    for (int i = 1; i < argc; ++i) {
        const char* a = argv[i];
        const int has_value = (i + 1) < argc;
        if ((strcmp(a, "-h") == 0) || (strcmp(a, "--help") == 0)) {
            usage(stdout);
            return 0;
        }
        if (strcmp(a, "--version") == 0) {
            printf("sva_node %d.%d.%d\n", SVA_VERSION_MAJOR, SVA_VERSION_MINOR, SVA_VERSION_PATCH);
            return 0;
        }
        if (((strcmp(a, "-u") == 0) || (strcmp(a, "--url") == 0)) && has_value) {
            o->url_arg = argv[++i];
        } else if (((strcmp(a, "-p") == 0) || (strcmp(a, "--prefix") == 0)) && has_value) {
            o->prefix = argv[++i];
        } else if (((strcmp(a, "-a") == 0) || (strcmp(a, "--algo") == 0) ||
                    (strcmp(a, "--algorithm") == 0)) &&
                   has_value) {
            o->algo_option = (strcmp(a, "--algorithm") == 0) ? "--algorithm" : "--algo";
            o->algo_name = argv[++i];
        } else if (((strcmp(a, "-s") == 0) || (strcmp(a, "--status-ms") == 0)) && has_value) {
            if (!integer_option("--status-ms", argv[++i], 10, 3600000, &o->status_ms)) {
                return 2;
            }
        } else if (((strcmp(a, "-c") == 0) || (strcmp(a, "--change-penalty") == 0)) && has_value) {
            if (!integer_option("--change-penalty", argv[++i], 0, (long)SVA_MAX_CHANGE_PENALTY,
                                &o->change_penalty)) {
                return 2;
            }
        } else if (((strcmp(a, "-k") == 0) || (strcmp(a, "--takeoff-ticks") == 0)) && has_value) {
            if (!integer_option("--takeoff-ticks", argv[++i], 0, (long)SVA_MAX_TICK,
                                &o->takeoff_ticks)) {
                return 2;
            }
        } else if (((strcmp(a, "-r") == 0) || (strcmp(a, "--rt-priority") == 0)) && has_value) {
            if (!integer_option("--rt-priority", argv[++i], 1, 99, &o->rt_priority)) {
                return 2;
            }
        } else if (((strcmp(a, "-t") == 0) || (strcmp(a, "--track-tolerance") == 0)) && has_value) {
            if (!integer_option("--track-tolerance", argv[++i], 0, SVA_LCM_TRACK_TOLERANCE_MAX,
                                &o->track_tolerance)) {
                return 2;
            }
        } else if ((strcmp(a, "-f") == 0) || (strcmp(a, "--fleet-reports") == 0)) {
            o->fleet_reports = 1;
        } else if ((strcmp(a, "-m") == 0) || (strcmp(a, "--mlock") == 0)) {
            o->lock_memory = 1;
        } else if ((strcmp(a, "-e") == 0) || (strcmp(a, "--exit-on-eof") == 0)) {
            o->exit_on_eof = 1;
        } else if ((strcmp(a, "--state-dir") == 0) && has_value) {
            o->state_dir = argv[++i];
        } else if (strcmp(a, "--state-reset") == 0) {
            o->state_reset = true;
        } else {
            char shown[SHOWN_SIZE];
            fprintf(stderr, "sva_node: error: unknown or incomplete option '%s'\n",
                    sva_text_escape(shown, sizeof shown, a));
            usage(stderr);
            return 2;
        }
    }
    return -1;
}

// Checks the options together: the algorithm's name, the prefix's and URL's lengths,
// the state options (the journal's files named into *storage). Returns -1 to go on, else
// the exit status 2 with its message.
static int check_options(node_options_t* o, sva_lcm_storage_t* storage)
{
    o->algorithm = SVA_ALGO_SVA;
    if (sva_algorithm_from_name(o->algo_name, &o->algorithm) != SVA_OK) {
        char shown[SHOWN_SIZE];
        fprintf(stderr, "sva_node: error: %s: unknown name '%s' (sva, ga, hga, bfa, flow)\n",
                o->algo_option, sva_text_escape(shown, sizeof shown, o->algo_name));
        return 2;
    }
    if (strlen(o->prefix) > SVA_LCM_PREFIX_MAX) {
        fprintf(
            stderr,
            "sva_node: error: --prefix: %zu characters exceed %d (LCM channel names are <= 63)\n",
            strlen(o->prefix), SVA_LCM_PREFIX_MAX);
        return 2;
    }
    if (build_url(o->url_arg, o->url, sizeof o->url) != 0) {
        fprintf(stderr, "sva_node: error: --url: longer than %d characters\n", URL_SIZE - 1);
        return 2;
    }
    if (o->state_reset && (o->state_dir == NULL)) {
        fprintf(stderr, "sva_node: error: --state-reset needs --state-dir\n");
        return 2;
    }
    if ((o->state_dir != NULL) &&
        (sva_lcm_journal_file_init(&journal_file, o->state_dir, storage) != SVA_LCM_JOURNAL_OK)) {
        fprintf(stderr,
                "sva_node: error: --state-dir: must be a folder path of 1 to %d characters\n",
                SVA_LCM_JOURNAL_DIR_MAX);
        return 2;
    }
    return -1;
}

// Real-time set-up, the LCM instance (*lcm) and the node with its options. Returns 0,
// or 1 after printing why (nothing left open).
static int open_node(const node_options_t* o, lcm_t** lcm)
{
    if (realtime_setup(o->rt_priority, o->lock_memory) != 0) {
        return 1;
    }
    *lcm = lcm_create(o->url);
    if (*lcm == NULL) {
        char shown[SHOWN_SIZE];
        fprintf(
            stderr,
            "sva_node: error: lcm_create(\"%s\") failed (for udpm: is there a multicast route?)\n",
            sva_text_escape(shown, sizeof shown, o->url));
        return 1;
    }
    if (sva_lcm_node_init(&node, *lcm, o->prefix, o->algorithm) != SVA_OK) {
        fprintf(stderr, "sva_node: error: cannot set up the node\n");
        lcm_destroy(*lcm);
        return 1;
    }
    node.log = log_stderr;
    node.change_penalty = (int32_t)o->change_penalty;
    node.takeoff_ticks = (int32_t)o->takeoff_ticks;
    node.fleet_reports = (o->fleet_reports != 0);
    node.track_tolerance_cells = (int32_t)o->track_tolerance;
    return 0;
}

// With --state-dir: opens the journal and replays it into the node, before it hears
// anything (its options set by open_node are part of the journal's header). Returns 0,
// or the exit status after printing why (the journal closed, lcm destroyed).
static int open_state(const node_options_t* o, sva_lcm_storage_t* storage, lcm_t* lcm)
{
    if (o->state_dir != NULL) {
        int src = state_dir_ready(o->state_dir);
        if ((src == 0) && (sva_lcm_journal_init(&journal, storage, &node) != SVA_LCM_JOURNAL_OK)) {
            src = 1;
        }
        if (src == 0) {
            src = resume_state(o->state_reset);
        }
        if (src != 0) {
            sva_lcm_journal_close(&journal);
            lcm_destroy(lcm);
            return src;
        }
    }
    return 0;
}

// Subscribes the node to its channels and catches SIGINT and SIGTERM. Returns 0, or 1
// after printing why (the journal closed, lcm destroyed).
static int start_listening(lcm_t* lcm)
{
    if (sva_lcm_node_subscribe(&node) != SVA_OK) {
        char shown_fleet[SHOWN_SIZE];
        char shown_mission[SHOWN_SIZE];
        fprintf(stderr, "sva_node: error: cannot subscribe to %s and %s\n",
                sva_text_escape(shown_fleet, sizeof shown_fleet, node.channel_fleet),
                sva_text_escape(shown_mission, sizeof shown_mission, node.channel_mission));
        sva_lcm_journal_close(&journal);
        lcm_destroy(lcm);
        return 1;
    }

    struct sigaction sa;
    memset(&sa, 0, sizeof sa);
    sa.sa_handler = on_signal;
    sigemptyset(&sa.sa_mask);
    (void)sigaction(SIGINT, &sa, NULL);
    (void)sigaction(SIGTERM, &sa, NULL);
    return 0;
}

// The start line: channels, algorithm, options.
static void announce(const node_options_t* o)
{
    char started[SHOWN_SIZE];
    (void)snprintf(started, sizeof started,
                   "in %s %s %s, out %s %s %s; algorithm %s; change penalty %ld; take-off %ld "
                   "ticks; %s%s%s",
                   node.channel_fleet, node.channel_mission, node.channel_event, node.channel_plan,
                   node.channel_status, node.channel_replan, sva_algorithm_name(o->algorithm),
                   o->change_penalty, o->takeoff_ticks, o->url,
                   (o->rt_priority > 0) ? "; SCHED_FIFO" : "",
                   o->lock_memory ? "; memory locked" : "");
    log_stderr(NULL, started);  // escapes channel names and URL
}

// Handles messages and publishes the status every status_ms until a signal, the end of
// input (--exit-on-eof), a failure or a halt. Returns the exit status.
static int run_loop(const node_options_t* o, lcm_t* lcm)
{
    send_status();
    int64_t next_status = monotonic_ms() + o->status_ms;
    int rc = 0;
    while (!stop_requested) {
        const int64_t wait = next_status - monotonic_ms();
        const int timeout = (wait < 0) ? 0 : ((wait > 100) ? 100 : (int)wait);
        const int r = lcm_handle_timeout(lcm, timeout);
        if (node.halted) {
            // The journal could not keep an input: nothing was answered for it. Exit as a
            // crash would; a restart resumes from the last record that was kept.
            char said[SHOWN_SIZE];
            fprintf(stderr, "sva_node: error: journal: %s: stopping without an answer\n",
                    sva_text_escape(said, sizeof said, journal.message));
            rc = 1;
            break;
        }
        if (r < 0) {
            // A signal interrupts the wait: that is a request to stop, not a failure.
            if (stop_requested || o->exit_on_eof) {
                break;
            }
            fprintf(stderr, "sva_node: error: lcm_handle_timeout failed\n");
            rc = 1;
            break;
        }
        if (monotonic_ms() >= next_status) {
            send_status();
            next_status += o->status_ms;
            if (next_status < monotonic_ms()) {
                next_status = monotonic_ms() + o->status_ms;
            }
        }
    }
    return rc;
}

// The last status, everything closed, and the exit line with the counters.
static void shut_down(lcm_t* lcm)
{
    send_status();
    sva_lcm_node_unsubscribe(&node);
    sva_lcm_journal_close(&journal);
    lcm_destroy(lcm);

    const sva_lcm_counters_t* c = &node.counters;
    fprintf(stderr,
            "sva_node: exit: fleet %llu, mission %llu, event %llu, unchanged %llu, plans %llu, "
            "replans %llu, rejected",
            (unsigned long long)c->fleet_rx, (unsigned long long)c->mission_rx,
            (unsigned long long)c->event_rx, (unsigned long long)c->unchanged,
            (unsigned long long)c->plans_published, (unsigned long long)c->replans_published);
    for (int r = 0; r < (int)SVA_LCM_REJECT_COUNT_; ++r) {
        fprintf(stderr, " %s=%lu", sva_lcm_reject_name((sva_lcm_reject_t)r),
                (unsigned long)c->rejected[r]);
    }
    fprintf(stderr, "\n");
}

int main(int argc, char** argv)
{
    static node_options_t opt;  // holds the URL: kept off the stack
    sva_lcm_storage_t storage;
    lcm_t* lcm = NULL;
    int rc = parse_options(argc, argv, &opt);
    if (rc < 0) {
        rc = check_options(&opt, &storage);
    }
    if (rc >= 0) {
        return rc;
    }
    rc = open_node(&opt, &lcm);
    if (rc == 0) {
        rc = open_state(&opt, &storage, lcm);
    }
    if (rc == 0) {
        rc = start_listening(lcm);
    }
    if (rc != 0) {
        return rc;
    }
    announce(&opt);
    rc = run_loop(&opt, lcm);
    shut_down(lcm);
    return rc;
}
