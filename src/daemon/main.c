/* rtedged: the rtedge daemon. Options, signals, then the loop (loop.c). */
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>

#include "config.h"
#include "daemon.h"
#include "log.h"
#include "rte_version.h"
#include "rtedge/v4l2_source.h"

#define MAX_SETS 64

static volatile sig_atomic_t stop_flag, reload_flag;

static void on_stop(int sig)
{
    stop_flag = 1;
    (void)sig;
}
static void on_hup(int sig)
{
    reload_flag = 1;
    (void)sig;
}

static void usage(FILE *f)
{
    fputs("usage: rtedged [--config FILE] [--set section.key=value]... [options]\n"
          "  --config FILE       INI configuration (see rtedged.conf, --help-config)\n"
          "  --set S.K=V         override one key (repeatable; applied after the file)\n"
          "  --source PATH       source.path (a .y4m, image directory/glob, LCM log,\n"
          "                      udpm:// channel URL, /dev/videoN, a V4L2 card or bus\n"
          "                      name with --set source.kind=v4l2, a libcamera camera\n"
          "                      with --set source.kind=libcamera)\n"
          "  --fps N             source.pace=fps at N frames a second\n"
          "  --speed X           source.pace=recorded at X times real time\n"
          "  --fast              source.pace=fast (as fast as possible)\n"
          "  --loop              source.loop=true\n"
          "  --max-frames N      source.max_frames=N\n"
          "  --lcm-url URL       publish.url\n"
          "  --deadline-ms MS    deadline.ms\n"
          "  --record FILE       source.record: every frame into an LCM log of image_t\n"
          "  --list-cameras      list the V4L2 and libcamera cameras with their formats,\n"
          "                      sizes and frame rates; exit 0 if any, 1 if none\n"
          "  --check-config      validate and print the effective configuration, exit 0 or 2\n"
          "  --dump-config FILE  write the effective configuration as a commented\n"
          "                      rtedged.conf to FILE ('-': stdout), exit 0 (1: not\n"
          "                      written, 2: a bad configuration)\n"
          "  --help-config       print every key with its help, range and default\n"
          "  --help-config=json  the same as JSON: type, range, unit, default, help\n"
          "  --version           print the version and the git revision, exit 0\n"
          "  --bench             run, then print latency p50/p99/max, peak RSS and CPU\n"
          "                      time a frame (every thread's, user + system)\n"
          "Signals: SIGINT/SIGTERM finish the frame, publish a final status and exit 0;\n"
          "SIGHUP re-reads the configuration file (runtime keys only).\n"
          "Exit codes: 0 the recording ended (or a signal), 1 cannot start or the source\n"
          "failed, 2 a bad configuration or option, 3 a recording (or a whole pass of a\n"
          "looping one) had no readable frame.\n",
          f);
}

/* What the command line asked for: the file, the overrides in order (each
 * direct flag stands for one or two of them), and what to do. */
typedef struct options {
    const char *config_path;
    char *sets[MAX_SETS];
    char direct[16][RTED_TEXT + 32];
    int n_sets, n_direct;
    bool check, bench;
    const char *dump_path; /* --dump-config */
} options;

/* The options that print and exit: the exit code, or -1 when a is none of them. */
static int print_option(const char *a)
{
    if (!strcmp(a, "--help") || !strcmp(a, "-h")) {
        usage(stdout);
        return 0;
    }
    if (!strcmp(a, "--version")) {
        printf("rtedged %s (git %s)\n", RTE_VERSION, RTE_REVISION);
        return 0;
    }
    if (!strcmp(a, "--help-config")) {
        rted_config_print_help(stdout);
        return 0;
    }
    if (!strcmp(a, "--help-config=json")) {
        rted_config_print_json(stdout);
        return 0;
    }
    if (!strcmp(a, "--list-cameras")) {
        int n = rte_list_cameras(stdout);
        if (!n)
            fprintf(stderr, "rtedged: no camera found\n");
        return n > 0 ? 0 : 1;
    }
    return -1;
}

/* The flags that stand for one key: *key ("section.key", takes a value) or
 * *fixed (a whole assignment); false when a is not one. */
static bool key_option(const char *a, const char **key, const char **fixed)
{
    static const struct {
        const char *flag, *key, *fixed;
    } flags[] = {
        {"--loop", NULL, "source.loop=true"}, {"--fast", NULL, "source.pace=fast"},
        {"--source", "source.path", NULL},    {"--fps", "source.fps", NULL},
        {"--speed", "source.speed", NULL},    {"--max-frames", "source.max_frames", NULL},
        {"--lcm-url", "publish.url", NULL},   {"--deadline-ms", "deadline.ms", NULL},
        {"--record", "source.record", NULL},
    };
    for (size_t i = 0; i < sizeof flags / sizeof flags[0]; i++)
        if (!strcmp(a, flags[i].flag)) {
            *key = flags[i].key;
            *fixed = flags[i].fixed;
            return true;
        }
    return false;
}

/* Reads argv into *o: -1 to go on, else the exit code (an option that
 * prints, or a bad command line). */
static int parse_options(options *o, int argc, char **argv)
{
    memset(o, 0, sizeof *o);
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i];
        const char *v = i + 1 < argc ? argv[i + 1] : NULL;
        const char *key = NULL, *fixed = NULL;
        int code = print_option(a);
        if (code >= 0)
            return code;
        if (!strcmp(a, "--check-config")) {
            o->check = true;
            continue;
        }
        if (!strcmp(a, "--bench")) {
            o->bench = true;
            continue;
        }
        if ((!strcmp(a, "--config") || !strcmp(a, "--set") || !strcmp(a, "--dump-config")) && !v)
            goto missing;
        if (!strcmp(a, "--dump-config")) {
            o->dump_path = argv[++i];
            continue;
        }
        if (!strcmp(a, "--config")) {
            o->config_path = argv[++i];
            continue;
        }
        if (!strcmp(a, "--set")) {
            if (o->n_sets == MAX_SETS) {
                fprintf(stderr, "rtedged: more than %d --set options\n", MAX_SETS);
                return RTED_EXIT_CONFIG;
            }
            o->sets[o->n_sets++] = argv[++i];
            continue;
        }
        if (!key_option(a, &key, &fixed)) {
            fprintf(stderr, "rtedged: unknown option '%s'\n", a);
            usage(stderr);
            return RTED_EXIT_CONFIG;
        }
        if (o->n_direct == 16 || o->n_sets + 2 > MAX_SETS) {
            fprintf(stderr, "rtedged: too many options\n");
            return RTED_EXIT_CONFIG;
        }
        if (!key) {
            o->sets[o->n_sets++] = (char *)fixed;
            continue;
        }
        if (!v)
            goto missing;
        snprintf(o->direct[o->n_direct], sizeof o->direct[0], "%s=%s", key, v);
        i++;
        o->sets[o->n_sets++] = o->direct[o->n_direct++];
        if (!strcmp(a, "--fps"))
            o->sets[o->n_sets++] = "source.pace=fps";
        if (!strcmp(a, "--speed"))
            o->sets[o->n_sets++] = "source.pace=recorded";
        continue;
    missing:
        fprintf(stderr, "rtedged: %s needs a value\n", a);
        return RTED_EXIT_CONFIG;
    }
    return -1;
}

/* The defaults, the file, then the overrides, checked together: false
 * (exit 2) with the reason said. */
static bool configure(rted_config *cfg, const options *o)
{
    char msg[RTED_MSG];
    rted_config_defaults(cfg);
    if (o->config_path && !rted_config_load(cfg, o->config_path, msg, sizeof msg)) {
        rted_error("%s", msg);
        return false;
    }
    for (int i = 0; i < o->n_sets; i++)
        if (!rted_config_set(cfg, o->sets[i], "command line", msg, sizeof msg)) {
            rted_error("%s", msg);
            return false;
        }
    if (!rted_config_validate(cfg, msg, sizeof msg)) {
        rted_error("%s%s%s", o->config_path ? o->config_path : "", o->config_path ? ": " : "", msg);
        return false;
    }
    return true;
}

/* --dump-config: the configuration into path. */
static int dump_config(const rted_config *cfg, const char *path)
{
    char *buf = malloc(RTED_CONFIG_TEXT_MAX), why[RTED_MSG];
    bool ok = buf && rted_config_save(cfg, path, buf, RTED_CONFIG_TEXT_MAX, why, sizeof why);
    if (!ok)
        fprintf(stderr, "rtedged: --dump-config %s: %s\n", path, buf ? why : "out of memory");
    free(buf);
    return ok ? 0 : RTED_EXIT_FAILED;
}

static void handle_signals(void)
{
    struct sigaction sa;
    memset(&sa, 0, sizeof sa);
    sigemptyset(&sa.sa_mask);
    sa.sa_handler = on_stop;
    sigaction(SIGINT, &sa, NULL);
    sigaction(SIGTERM, &sa, NULL);
    sa.sa_handler = on_hup;
    sigaction(SIGHUP, &sa, NULL);
    signal(SIGPIPE, SIG_IGN);
}

/* CPU time, user + system, of every thread so far (microseconds). */
static int64_t cpu_us(void)
{
    struct rusage ru;
    getrusage(RUSAGE_SELF, &ru);
    return (int64_t)(ru.ru_utime.tv_sec + ru.ru_stime.tv_sec) * 1000000 + ru.ru_utime.tv_usec +
           ru.ru_stime.tv_usec;
}

/* --bench's line on stdout and the counters on stderr, after the run
 * (run_cpu_us: the CPU time the run took). */
static void report(rted_daemon *d, bool bench, int64_t run_cpu_us)
{
    rted_counters n;
    rted_daemon_get_counters(d, &n);
    if (bench) {
        /* the whole run's latencies */
        int32_t p50, p99, max;
        rted_daemon_latency(d, &p50, &p99, &max);
        struct rusage ru;
        getrusage(RUSAGE_SELF, &ru);
        printf("bench: %llu frames, latency p50 %d us, p99 %d us, max %d us, peak RSS %ld KiB, "
               "CPU %lld us a frame\n",
               (unsigned long long)n.processed, p50, p99, max, ru.ru_maxrss,
               (long long)(n.processed ? run_cpu_us / (int64_t)n.processed : 0));
    }
    rted_log("%llu frames received, %llu processed, %llu dropped, %llu bad, "
             "%llu deadline misses, %llu stages skipped, %llu messages, %llu publish errors, "
             "%llu reloads, %llu refused, %llu rate-limited, %llu path errors, %llu rewinds",
             (unsigned long long)n.received, (unsigned long long)n.processed,
             (unsigned long long)n.dropped, (unsigned long long)n.bad_frames,
             (unsigned long long)n.deadline_misses, (unsigned long long)n.stages_skipped,
             (unsigned long long)n.published, (unsigned long long)n.publish_errors,
             (unsigned long long)n.reloads, (unsigned long long)n.refused,
             (unsigned long long)n.rate_limited, (unsigned long long)n.path_errors,
             (unsigned long long)n.rewinds);
}

int main(int argc, char **argv)
{
    options o;
    int code = parse_options(&o, argc, argv);
    if (code >= 0)
        return code;
    rted_config cfg;
    if (!configure(&cfg, &o))
        return RTED_EXIT_CONFIG;
    if (o.check) {
        printf("# effective configuration (hash %016llx)\n",
               (unsigned long long)rted_config_hash(&cfg));
        rted_config_print(&cfg, stdout);
        return 0;
    }
    if (o.dump_path)
        return dump_config(&cfg, o.dump_path);

    rted_daemon *d;
    char msg[RTED_MSG];
    if (!rted_daemon_open(&d, &cfg, o.config_path, msg, sizeof msg)) {
        rted_error("%s", msg);
        return RTED_EXIT_FAILED;
    }
    rted_daemon_set_overrides(d, o.sets, o.n_sets);
    handle_signals();
    const int64_t cpu0 = cpu_us();
    code = rted_daemon_run(d, &stop_flag, &reload_flag);
    report(d, o.bench, cpu_us() - cpu0);
    rted_daemon_close(d);
    return code;
}
