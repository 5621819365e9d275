/* rtedged: the rtedge daemon. Options, signals, then the loop (loop.c). */
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>

#include "config.h"
#include "daemon.h"
#include "sources/v4l2_source.h"

#define MAX_SETS 64

static volatile sig_atomic_t stop_flag, reload_flag;

static void on_stop(int sig) { stop_flag = 1; (void)sig; }
static void on_hup(int sig) { reload_flag = 1; (void)sig; }

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
          "  --help-config       print every key with its help, range and default\n"
          "  --bench             run, then print latency p50/p99/max and peak RSS\n"
          "Signals: SIGINT/SIGTERM finish the frame, publish a final status and exit 0;\n"
          "SIGHUP re-reads the configuration file (runtime keys only).\n"
          "Exit codes: 0 the recording ended (or a signal), 1 cannot start or the source\n"
          "failed, 2 a bad configuration or option, 3 a recording (or a whole pass of a\n"
          "looping one) had no readable frame.\n",
          f);
}

int main(int argc, char **argv)
{
    const char *config_path = NULL;
    char *sets[MAX_SETS];
    char direct[16][RTED_TEXT + 32];
    int n_sets = 0, n_direct = 0;
    bool check = false, bench = false;
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i];
        const char *v = i + 1 < argc ? argv[i + 1] : NULL;
        const char *key = NULL, *fixed = NULL;
        if (!strcmp(a, "--help") || !strcmp(a, "-h")) {
            usage(stdout);
            return 0;
        } else if (!strcmp(a, "--help-config")) {
            rted_config_print_help(stdout);
            return 0;
        } else if (!strcmp(a, "--list-cameras")) {
            int n = rte_list_cameras(stdout);
            if (!n)
                fprintf(stderr, "rtedged: no camera found\n");
            return n > 0 ? 0 : 1;
        } else if (!strcmp(a, "--check-config")) {
            check = true;
            continue;
        } else if (!strcmp(a, "--bench")) {
            bench = true;
            continue;
        } else if (!strcmp(a, "--loop")) {
            fixed = "source.loop=true";
        } else if (!strcmp(a, "--fast")) {
            fixed = "source.pace=fast";
        } else if (!strcmp(a, "--config")) {
            if (!v)
                goto missing;
            config_path = v;
            i++;
            continue;
        } else if (!strcmp(a, "--set")) {
            if (!v)
                goto missing;
            if (n_sets == MAX_SETS) {
                fprintf(stderr, "rtedged: more than %d --set options\n", MAX_SETS);
                return RTED_EXIT_CONFIG;
            }
            sets[n_sets++] = argv[++i];
            continue;
        } else if (!strcmp(a, "--source")) {
            key = "source.path";
        } else if (!strcmp(a, "--fps")) {
            key = "source.fps";
        } else if (!strcmp(a, "--speed")) {
            key = "source.speed";
        } else if (!strcmp(a, "--max-frames")) {
            key = "source.max_frames";
        } else if (!strcmp(a, "--lcm-url")) {
            key = "publish.url";
        } else if (!strcmp(a, "--deadline-ms")) {
            key = "deadline.ms";
        } else if (!strcmp(a, "--record")) {
            key = "source.record";
        } else {
            fprintf(stderr, "rtedged: unknown option '%s'\n", a);
            usage(stderr);
            return RTED_EXIT_CONFIG;
        }
        if (n_direct == 16 || n_sets + 2 > MAX_SETS) {
            fprintf(stderr, "rtedged: too many options\n");
            return RTED_EXIT_CONFIG;
        }
        if (key) {
            if (!v)
                goto missing;
            snprintf(direct[n_direct], sizeof direct[0], "%s=%s", key, v);
            i++;
            sets[n_sets++] = direct[n_direct++];
            if (!strcmp(a, "--fps"))
                sets[n_sets++] = "source.pace=fps";
            if (!strcmp(a, "--speed"))
                sets[n_sets++] = "source.pace=recorded";
        } else {
            sets[n_sets++] = (char *)fixed;
        }
        continue;
    missing:
        fprintf(stderr, "rtedged: %s needs a value\n", a);
        return RTED_EXIT_CONFIG;
    }

    rted_config cfg;
    char msg[RTED_MSG];
    rted_config_defaults(&cfg);
    if (config_path && !rted_config_load(&cfg, config_path, msg, sizeof msg)) {
        fprintf(stderr, "rtedged: %s\n", msg);
        return RTED_EXIT_CONFIG;
    }
    for (int i = 0; i < n_sets; i++)
        if (!rted_config_set(&cfg, sets[i], "command line", msg, sizeof msg)) {
            fprintf(stderr, "rtedged: %s\n", msg);
            return RTED_EXIT_CONFIG;
        }
    if (!rted_config_validate(&cfg, msg, sizeof msg)) {
        fprintf(stderr, "rtedged: %s%s%s\n", config_path ? config_path : "",
                config_path ? ": " : "", msg);
        return RTED_EXIT_CONFIG;
    }
    if (check) {
        printf("# effective configuration (hash %016llx)\n",
               (unsigned long long)rted_config_hash(&cfg));
        rted_config_print(&cfg, stdout);
        return 0;
    }

    rted_daemon *d;
    if (!rted_daemon_open(&d, &cfg, config_path, msg, sizeof msg)) {
        fprintf(stderr, "rtedged: %s\n", msg);
        return RTED_EXIT_FAILED;
    }
    rted_daemon_set_overrides(d, sets, n_sets);
    struct sigaction sa;
    memset(&sa, 0, sizeof sa);
    sigemptyset(&sa.sa_mask);
    sa.sa_handler = on_stop;
    sigaction(SIGINT, &sa, NULL);
    sigaction(SIGTERM, &sa, NULL);
    sa.sa_handler = on_hup;
    sigaction(SIGHUP, &sa, NULL);
    signal(SIGPIPE, SIG_IGN);

    int code = rted_daemon_run(d, &stop_flag, &reload_flag);
    rted_counters n;
    rted_daemon_get_counters(d, &n);
    if (bench) {
        /* The last status window: run with a long status period to cover the run. */
        int32_t p50, p99, max;
        rted_daemon_latency(d, &p50, &p99, &max);
        struct rusage ru;
        getrusage(RUSAGE_SELF, &ru);
        printf("bench: %llu frames, latency p50 %d us, p99 %d us, max %d us, peak RSS %ld KiB\n",
               (unsigned long long)n.processed, p50, p99, max, ru.ru_maxrss);
    }
    fprintf(stderr,
            "rtedged: %llu frames received, %llu processed, %llu dropped, %llu bad, "
            "%llu deadline misses, %llu stages skipped, %llu messages, %llu publish errors, "
            "%llu reloads, %llu refused, %llu rate-limited, %llu path errors, %llu rewinds\n",
            (unsigned long long)n.received, (unsigned long long)n.processed,
            (unsigned long long)n.dropped, (unsigned long long)n.bad_frames,
            (unsigned long long)n.deadline_misses, (unsigned long long)n.stages_skipped,
            (unsigned long long)n.published, (unsigned long long)n.publish_errors,
            (unsigned long long)n.reloads, (unsigned long long)n.refused,
            (unsigned long long)n.rate_limited, (unsigned long long)n.path_errors,
            (unsigned long long)n.rewinds);
    rted_daemon_close(d);
    return code;
}
