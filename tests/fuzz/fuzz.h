/* What the libFuzzer targets share (tests/fuzz/fuzz_*.c). Each target
 * defines LLVMFuzzerTestOneInput; it is linked with libFuzzer
 * (-fsanitize=fuzzer, the `fuzz` build: tools/fuzz, the fuzz suite) or with
 * replay_main.c, which runs the seed corpus once (every build's fuzz suite).
 * A target must not leak, and treats an input that the code under test
 * mishandles as a crash (abort), so that libFuzzer keeps it. */
#ifndef RTEDGE_FUZZ_H
#define RTEDGE_FUZZ_H

#define _GNU_SOURCE
#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/mman.h>
#include <unistd.h>

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

/* The input as a file the code under test opens by path: an anonymous
 * memory file (memfd) and its /proc/self/fd path. Returns the fd (close it
 * when done) or aborts. */
static inline int fuzz_file(const uint8_t *data, size_t size, char *path, size_t path_size)
{
    int fd = memfd_create("rtedge-fuzz", MFD_CLOEXEC);
    if (fd < 0) {
        perror("memfd_create");
        abort();
    }
    for (size_t done = 0; done < size;) {
        ssize_t n = write(fd, data + done, size - done);
        if (n <= 0) {
            perror("write");
            abort();
        }
        done += (size_t)n;
    }
    snprintf(path, path_size, "/proc/self/fd/%d", fd);
    return fd;
}

/* A message the code under test wrote: NUL-terminated within its buffer. */
static inline void fuzz_check_message(const char *msg, size_t size)
{
    if (!memchr(msg, 0, size)) {
        fprintf(stderr, "fuzz: a message without its NUL\n");
        abort();
    }
}

/* Fails the input (libFuzzer keeps it as a crash). */
#define FUZZ_ASSERT(cond)                                                    \
    do {                                                                     \
        if (!(cond)) {                                                       \
            fprintf(stderr, "fuzz: %s:%d: %s\n", __FILE__, __LINE__, #cond); \
            abort();                                                         \
        }                                                                    \
    } while (0)

#endif
