/* The configuration's INI reader and the command line's overrides
 * (config.h). Lines are `key = value` under a `[section]`; a line starting
 * with '#' or ';' is a comment, and so is the rest of a line from a '#'
 * after a blank (';' is no inline comment: it separates the items of
 * lane.roi and source.controls). The first error stops the reading and
 * names the file and line. */
#include "config_table.h"

#include <errno.h>
#include <fcntl.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "log.h"

/* The longest line of a configuration file (without its newline). */
#define RTED_LINE_MAX 1022

static char *trim(char *s)
{
    while (*s == ' ' || *s == '\t')
        s++;
    char *e = s + strlen(s);
    while (e > s && (e[-1] == ' ' || e[-1] == '\t' || e[-1] == '\r' || e[-1] == '\n'))
        *--e = 0;
    return s;
}

/* Ends the line at a '#' that follows a blank. */
static void cut_inline_comment(char *s)
{
    for (char *p = s; *p; p++)
        if (*p == '#' && p > s && (p[-1] == ' ' || p[-1] == '\t')) {
            *p = 0;
            return;
        }
}

typedef struct ini_reader {
    rted_config *c;
    const char *path;
    int lineno;
    char section[64];
    bool seen[RTED_CONFIG_MAX_KEYS];
    char *msg;
    size_t msg_size;
} ini_reader;

/* "path:line: message"; always false. */
static bool fail(ini_reader *r, const char *fmt, ...) __attribute__((format(printf, 2, 3)));
static bool fail(ini_reader *r, const char *fmt, ...)
{
    char text[RTED_MSG + 128];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(text, sizeof text, fmt, ap);
    va_end(ap);
    rted_msgf(r->msg, r->msg_size, "%s:%d: %s", r->path, r->lineno, text);
    return false;
}

/* s: a trimmed line starting with '['. */
static bool read_section(ini_reader *r, char *s)
{
    char *e = strchr(s, ']');
    if (!e || e[1] || (size_t)(e - s - 1) >= sizeof r->section)
        return fail(r, "bad section header '%s'", s);
    *e = 0;
    snprintf(r->section, sizeof r->section, "%s", trim(s + 1));
    if (!rted_config_section_exists(r->section))
        return fail(r, "unknown section [%s]", r->section);
    return true;
}

/* s: a trimmed line that is neither a comment nor a section header. */
static bool read_assignment(ini_reader *r, char *s)
{
    char *eq = strchr(s, '=');
    if (!eq)
        return fail(r, "expected 'key = value', not '%s'", s);
    *eq = 0;
    char *key = trim(s), *value = trim(eq + 1);
    if (!r->section[0])
        return fail(r, "key '%s' outside a [section]", key);
    bool known;
    const rted_key *k = rted_config_lookup(r->section, key, &known);
    if (!k)
        return fail(r, "unknown key '%s' in [%s]", key, r->section);
    if (r->seen[rted_key_index(k)])
        return fail(r, "duplicate key %s.%s", r->section, key);
    r->seen[rted_key_index(k)] = true;
    char why[RTED_MSG];
    if (!rted_config_store(r->c, k, value, why, sizeof why))
        return fail(r, "%s.%s: %s", r->section, key, why);
    return true;
}

static bool read_line(ini_reader *r, char *line, size_t len)
{
    if (memchr(line, 0, len))
        return fail(r, "a NUL byte in the line (not a text file?)");
    if (len > RTED_LINE_MAX)
        return fail(r, "line longer than %d characters", RTED_LINE_MAX);
    char *s = trim(line);
    if (!*s || *s == '#' || *s == ';')
        return true;
    cut_inline_comment(s);
    s = trim(s);
    return *s == '[' ? read_section(r, s) : read_assignment(r, s);
}

bool rted_config_load(rted_config *c, const char *path, char *msg, size_t msg_size)
{
    FILE *f = fopen(path, "r");
    if (!f) {
        rted_msgf(msg, msg_size, "%s: %s", path, strerror(errno));
        return false;
    }
    ini_reader r = {.c = c, .path = path, .msg = msg, .msg_size = msg_size};
    char *line = NULL;
    size_t line_capacity = 0;
    ssize_t len;
    bool ok = true;
    while (ok && (len = getline(&line, &line_capacity, f)) >= 0) {
        r.lineno++;
        ok = read_line(&r, line, (size_t)len);
    }
    if (ok && ferror(f)) {
        r.lineno++;
        ok = fail(&r, "%s", strerror(errno));
    }
    free(line);
    fclose(f);
    return ok;
}

bool rted_config_set(rted_config *c, const char *assignment, const char *origin, char *msg,
                     size_t msg_size)
{
    char buf[RTED_TEXT + 128];
    snprintf(buf, sizeof buf, "%s", assignment);
    char *eq = strchr(buf, '=');
    char *dot = strchr(buf, '.');
    if (!eq || !dot || dot > eq) {
        rted_msgf(msg, msg_size, "%s: expected section.key=value, not '%s'", origin, assignment);
        return false;
    }
    *eq = *dot = 0;
    bool known;
    const rted_key *k = rted_config_lookup(trim(buf), trim(dot + 1), &known);
    if (!k) {
        rted_msgf(msg, msg_size, known ? "%s: unknown key '%s.%s'" : "%s: unknown section '%s'%.0s",
                  origin, trim(buf), trim(dot + 1));
        return false;
    }
    char why[RTED_MSG], name[160];
    if (!rted_config_store(c, k, trim(eq + 1), why, sizeof why)) {
        rted_key_get_name(k, name, sizeof name);
        rted_msgf(msg, msg_size, "%s: %s: %s", origin, name, why);
        return false;
    }
    return true;
}

bool rted_config_save(const rted_config *c, const char *path, char *buf, size_t size, char *why,
                      size_t why_size)
{
    char title[RTED_TEXT + 160];
    snprintf(title, sizeof title,
             "rtedged.conf written by rtedged: the configuration in force (hash %016llx)",
             (unsigned long long)rted_config_hash(c));
    size_t n = rted_config_write(c, title, buf, size);
    if (!n) {
        rted_msgf(why, why_size, "the configuration's text is over %zu bytes", size);
        return false;
    }
    if (!path)
        return true;
    if (!strcmp(path, "-")) {
        if (fwrite(buf, 1, n, stdout) != n || fflush(stdout) != 0) {
            rted_msgf(why, why_size, "cannot write to stdout: %s", strerror(errno));
            return false;
        }
        return true;
    }
    /* Written beside the file and renamed over it: a reader sees the old
     * file or the new one, never a part. */
    char tmp[RTED_TEXT + 16];
    if (snprintf(tmp, sizeof tmp, "%s.tmp", path) >= (int)sizeof tmp) {
        rted_msgf(why, why_size, "the path is too long");
        return false;
    }
    int fd = open(tmp, O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
    if (fd < 0) {
        rted_msgf(why, why_size, "cannot create %s: %s", tmp, strerror(errno));
        return false;
    }
    for (size_t done = 0; done < n;) {
        ssize_t w = write(fd, buf + done, n - done);
        if (w < 0 && errno == EINTR)
            continue;
        if (w <= 0) {
            rted_msgf(why, why_size, "cannot write %s: %s", tmp,
                      w < 0 ? strerror(errno) : "no space");
            close(fd);
            unlink(tmp);
            return false;
        }
        done += (size_t)w;
    }
    if (fsync(fd) != 0 || close(fd) != 0) {
        rted_msgf(why, why_size, "cannot write %s: %s", tmp, strerror(errno));
        unlink(tmp);
        return false;
    }
    if (rename(tmp, path) != 0) {
        rted_msgf(why, why_size, "cannot replace %s: %s", path, strerror(errno));
        unlink(tmp);
        return false;
    }
    return true;
}
