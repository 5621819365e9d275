/* [realtime]: the memory locked, the CPUs' wake-up latency bounded, the
 * main thread pinned and SCHED_FIFO, then (threads = 2) the grasp path on a
 * second thread, beside the lane path on the main one.
 *
 * A thread that waits for a frame or for the other path sleeps, and its CPU
 * may go idle; waking it then takes the idle state's exit latency (in a
 * KVM guest, a halted virtual CPU: 60-70 us in the median and up to 2 ms,
 * on every hand-over between the two threads). realtime.cpu_dma_latency_us
 * asks the kernel (PM QoS, /dev/cpu_dma_latency: held while the file is
 * open, as cyclictest does) for no idle state slower to leave than that.
 *
 * The thread is made once at start, after the main thread's settings (so
 * that it inherits SCHED_FIFO and mlockall's MCL_FUTURE locks its stack),
 * with a fixed stack, every signal blocked (they are the main thread's),
 * and pinned to the CPU after realtime.cpu. A frame is
 * handed over and back through two semaphores (futexes: no lock, no heap
 * call); between a post and the wait, the job (d->job) is the thread's
 * alone, and the thread touches nothing else of the daemon but the grasp
 * context and the grey and chroma buffers: counters, stage timings and
 * publishing stay on the main thread, which reads the job's result after
 * the wait. Run-time changes (SIGHUP, params_t) are applied between
 * frames, when the thread waits for the next one. */
#define _GNU_SOURCE
#include <errno.h>
#include <fcntl.h>
#include <pthread.h>
#include <sched.h>
#include <signal.h>
#include <string.h>
#include <sys/mman.h>
#include <unistd.h>

#include "daemon_internal.h"
#include "core/clock.h"

/* The grasp thread's stack: room for the grasp path's calls, sanitizer
 * builds included (the sanitizer suite runs the two-thread tests). */
#define RTED_GRASP_STACK (1024 * 1024)

void rted_grasp_job_run(rted_daemon *d, rted_grasp_job *j)
{
    const rte_frame *frame = &j->frame->frame;
    j->ran = j->skipped = false;
    if (j->need_gray && rte_frame_gray_view(frame, &j->gray) != RTE_OK) {
        j->gray = d->gray;
        j->gray.width = frame->width;
        j->gray.height = frame->height;
        rte_frame_to_gray(frame, &j->gray);
    }
    if (!d->grasp)
        return;
    /* The optional stage: only when the budget still holds it. */
    if (d->deadline_ns - (rte_clock_now_ns() - j->frame->capture_ns) < d->grasp_min_ns) {
        j->skipped = true;
        return;
    }
    /* the colour, where the background mode reads it (a grey frame has none) */
    rte_image_u8 cb = d->cb, cr = d->cr;
    cb.width = cr.width = (frame->width + 1) / 2;
    cb.height = cr.height = (frame->height + 1) / 2;
    const bool chroma = d->cfg.grasp_chroma && d->cfg.grasp_binarize == RTE_GRASP_BACKGROUND &&
                        rte_frame_chroma_half(frame, &cb, &cr) == RTE_OK;
    j->status = rte_grasp_process_chroma(d->grasp, &j->gray, chroma ? &cb : NULL,
                                         chroma ? &cr : NULL, &j->result);
    j->ran = true;
}

static void wait_sem(sem_t *s)
{
    while (sem_wait(s) != 0 && errno == EINTR)
        ;
}

/* Writes the first half of the stack once, before the first frame, so that
 * frames find its pages mapped (mlockall maps and locks all of it). */
static void __attribute__((noinline)) touch_stack(void)
{
    volatile char pages[RTED_GRASP_STACK / 2];
    for (size_t i = 0; i < sizeof pages; i += 4096)
        pages[i] = 0;
}

static void *grasp_thread(void *arg)
{
    rted_daemon *d = arg;
    touch_stack();
    for (;;) {
        wait_sem(&d->job_go);
        if (d->job_quit)
            return NULL;
        rted_grasp_job_run(d, &d->job);
        sem_post(&d->job_done);
    }
}

/* The CPU after cpu among those the process may use (wrapping), -1 when
 * there is no other. */
static int next_cpu(const cpu_set_t *allowed, int cpu)
{
    for (int k = 1; k < CPU_SETSIZE; k++) {
        int c = (cpu + k) % CPU_SETSIZE;
        if (CPU_ISSET(c, allowed))
            return c;
    }
    return -1;
}

/* Pins the calling thread to cpu (a warning when it may not). */
static void pin(int cpu)
{
    cpu_set_t set;
    CPU_ZERO(&set);
    CPU_SET(cpu, &set);
    if (sched_setaffinity(0, sizeof set, &set) != 0)
        rted_warn("CPU affinity %d: %s (not pinned)", cpu, strerror(errno));
}

/* The PM QoS request of realtime.cpu_dma_latency_us, held open in d (a
 * warning when it cannot be made). */
static void hold_wake_latency(rted_daemon *d, int32_t us)
{
    const int fd = open("/dev/cpu_dma_latency", O_WRONLY | O_CLOEXEC);
    if (fd >= 0 && write(fd, &us, sizeof us) == (ssize_t)sizeof us) {
        d->wake_latency_fd = fd;
        d->wake_latency_held = true;
        return;
    }
    rted_warn("realtime.cpu_dma_latency_us = %d: /dev/cpu_dma_latency: %s (not set)", us,
              strerror(errno));
    if (fd >= 0)
        close(fd);
}

/* The grasp thread, made with every signal blocked and pinned to the CPU
 * after realtime.cpu among those allowed at start. */
static bool start_thread(rted_daemon *d, const cpu_set_t *allowed, char *msg, size_t msg_size)
{
    if (sem_init(&d->job_go, 0, 0) != 0 || sem_init(&d->job_done, 0, 0) != 0) {
        rted_msgf(msg, msg_size, "realtime.threads = 2: %s", strerror(errno));
        return false;
    }
    pthread_attr_t attr;
    pthread_attr_init(&attr);
    pthread_attr_setstacksize(&attr, RTED_GRASP_STACK);
    sigset_t all, old;
    sigfillset(&all);
    pthread_sigmask(SIG_SETMASK, &all, &old);
    int e = pthread_create(&d->job_thread, &attr, grasp_thread, d);
    pthread_sigmask(SIG_SETMASK, &old, NULL);
    pthread_attr_destroy(&attr);
    if (e) {
        sem_destroy(&d->job_go);
        sem_destroy(&d->job_done);
        rted_msgf(msg, msg_size, "realtime.threads = 2: cannot start the grasp thread: %s",
                  strerror(e));
        return false;
    }
    d->threaded = true;
    pthread_setname_np(d->job_thread, "rtedged-grasp");
    if (d->cfg.rt_cpu < 0)
        return true;
    const int cpu = next_cpu(allowed, d->cfg.rt_cpu);
    if (cpu < 0) {
        rted_warn("realtime.threads = 2: no CPU besides %d: the grasp thread shares it",
                  d->cfg.rt_cpu);
        return true;
    }
    cpu_set_t set;
    CPU_ZERO(&set);
    CPU_SET(cpu, &set);
    e = pthread_setaffinity_np(d->job_thread, sizeof set, &set);
    if (e)
        rted_warn("grasp thread's CPU affinity %d: %s (not pinned)", cpu, strerror(e));
    return true;
}

bool rted_realtime_start(rted_daemon *d, char *msg, size_t msg_size)
{
    const rted_config *c = &d->cfg;
    cpu_set_t allowed;
    if (sched_getaffinity(0, sizeof allowed, &allowed) != 0)
        CPU_ZERO(&allowed);
    if (c->rt_mlockall && mlockall(MCL_CURRENT | MCL_FUTURE) != 0)
        rted_warn("mlockall: %s (memory not locked)", strerror(errno));
    if (c->rt_cpu_dma_latency_us >= 0)
        hold_wake_latency(d, c->rt_cpu_dma_latency_us);
    if (c->rt_cpu >= 0)
        pin(c->rt_cpu);
    if (c->rt_priority > 0) {
        struct sched_param sp = {.sched_priority = c->rt_priority};
        if (sched_setscheduler(0, SCHED_FIFO, &sp) != 0)
            rted_warn("SCHED_FIFO priority %d: %s (normal scheduling)", c->rt_priority,
                      strerror(errno));
    }
    /* both paths, or there is nothing to run beside the lane path */
    if (c->rt_threads < 2 || !d->lane || !d->grasp)
        return true;
    return start_thread(d, &allowed, msg, msg_size);
}

void rted_realtime_stop(rted_daemon *d)
{
    if (d->wake_latency_held) {
        close(d->wake_latency_fd);
        d->wake_latency_held = false;
    }
    if (!d->threaded)
        return;
    d->job_quit = true;
    sem_post(&d->job_go);
    pthread_join(d->job_thread, NULL);
    sem_destroy(&d->job_go);
    sem_destroy(&d->job_done);
    d->threaded = false;
}

void rted_grasp_job_post(rted_daemon *d) { sem_post(&d->job_go); }

void rted_grasp_job_wait(rted_daemon *d) { wait_sem(&d->job_done); }
