#include "cli.h"

#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

void cli_error(const char *command, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    fprintf(stderr, "rtedge %s: ", command);
    vfprintf(stderr, fmt, ap);
    fputc('\n', stderr);
    va_end(ap);
}

static void print_choices(FILE *out, const char *const *choices)
{
    for (int i = 0; choices[i]; i++)
        fprintf(out, "%s%s", i ? "|" : "", choices[i]);
}

static void print_default(FILE *out, const cli_option *o)
{
    switch (o->type) {
    case CLI_INT: fprintf(out, " (default %d, %g..%g)", *(int *)o->value, o->min, o->max); break;
    case CLI_DOUBLE:
        fprintf(out, " (default %g, %g..%g)", *(double *)o->value, o->min, o->max);
        break;
    case CLI_CHOICE: fprintf(out, " (default %s)", o->choices[*(int *)o->value]); break;
    case CLI_STRING:
        if (*(const char **)o->value)
            fprintf(out, " (default %s)", *(const char **)o->value);
        break;
    case CLI_FLAG: break;
    }
}

void cli_print_help(const cli_command *cmd)
{
    printf("usage: rtedge %s %s\n\n%s\n", cmd->name, cmd->usage, cmd->summary);
    if (cmd->options && cmd->options[0].name) {
        printf("\noptions:\n");
        for (const cli_option *o = cmd->options; o->name; o++) {
            char left[64];
            int n = snprintf(left, sizeof left, "--%s", o->name);
            if (o->type == CLI_INT)
                snprintf(left + n, sizeof left - (size_t)n, " N");
            else if (o->type == CLI_DOUBLE)
                snprintf(left + n, sizeof left - (size_t)n, " X");
            else if (o->type == CLI_STRING)
                snprintf(left + n, sizeof left - (size_t)n, " TEXT");
            printf("  %-22s ", left);
            if (o->type == CLI_CHOICE) {
                print_choices(stdout, o->choices);
                printf(": ");
            }
            printf("%s", o->help);
            print_default(stdout, o);
            printf("\n");
        }
    }
    printf("  %-22s %s\n", "--help", "this text");
    if (cmd->details)
        printf("\n%s\n", cmd->details);
}

static const cli_option *find_option(const cli_command *cmd, const char *name, size_t len)
{
    for (const cli_option *o = cmd->options; o && o->name; o++)
        if (strlen(o->name) == len && strncmp(o->name, name, len) == 0)
            return o;
    return NULL;
}

static int set_value(const cli_command *cmd, const cli_option *o, const char *text)
{
    char *end;
    errno = 0;
    switch (o->type) {
    case CLI_INT: {
        long v = strtol(text, &end, 10);
        if (errno || end == text || *end || v < o->min || v > o->max) {
            cli_error(cmd->name, "--%s takes a whole number from %g to %g, not '%s'", o->name,
                      o->min, o->max, text);
            return CLI_EXIT_USAGE;
        }
        *(int *)o->value = (int)v;
        break;
    }
    case CLI_DOUBLE: {
        double v = strtod(text, &end);
        if (errno || end == text || *end || !isfinite(v) || v < o->min || v > o->max) {
            cli_error(cmd->name, "--%s takes a number from %g to %g, not '%s'", o->name, o->min,
                      o->max, text);
            return CLI_EXIT_USAGE;
        }
        *(double *)o->value = v;
        break;
    }
    case CLI_STRING: *(const char **)o->value = text; break;
    case CLI_CHOICE:
        for (int i = 0; o->choices[i]; i++) {
            if (strcmp(o->choices[i], text) == 0) {
                *(int *)o->value = i;
                goto done;
            }
        }
        fprintf(stderr, "rtedge %s: --%s takes one of ", cmd->name, o->name);
        print_choices(stderr, o->choices);
        fprintf(stderr, ", not '%s'\n", text);
        return CLI_EXIT_USAGE;
    case CLI_FLAG: *(bool *)o->value = true; break;
    }
done:
    if (o->given)
        *o->given = true;
    return CLI_EXIT_OK;
}

int cli_parse(const cli_command *cmd, int argc, char **argv, const char **positional)
{
    int npos = 0;
    bool options_done = false;
    for (int i = 1; i < argc; i++) {
        const char *arg = argv[i];
        if (!options_done && strcmp(arg, "--") == 0) {
            options_done = true;
            continue;
        }
        if (!options_done && (strcmp(arg, "--help") == 0 || strcmp(arg, "-h") == 0)) {
            cli_print_help(cmd);
            return -1;
        }
        if (!options_done && arg[0] == '-' && arg[1] == '-') {
            const char *name = arg + 2;
            const char *eq = strchr(name, '=');
            size_t len = eq ? (size_t)(eq - name) : strlen(name);
            const cli_option *o = find_option(cmd, name, len);
            if (!o) {
                cli_error(cmd->name, "unknown option '%s' (see rtedge %s --help)", arg, cmd->name);
                return CLI_EXIT_USAGE;
            }
            const char *text = NULL;
            if (o->type == CLI_FLAG) {
                if (eq) {
                    cli_error(cmd->name, "--%s takes no value", o->name);
                    return CLI_EXIT_USAGE;
                }
            } else if (eq) {
                text = eq + 1;
            } else if (i + 1 < argc) {
                text = argv[++i];
            } else {
                cli_error(cmd->name, "--%s needs a value", o->name);
                return CLI_EXIT_USAGE;
            }
            int rc = set_value(cmd, o, text);
            if (rc != CLI_EXIT_OK)
                return rc;
            continue;
        }
        if (npos >= cmd->positionals) {
            cli_error(cmd->name, "unexpected argument '%s' (usage: rtedge %s %s)", arg, cmd->name,
                      cmd->usage);
            return CLI_EXIT_USAGE;
        }
        positional[npos++] = arg;
    }
    if (npos < cmd->positionals) {
        cli_error(cmd->name, "missing arguments (usage: rtedge %s %s)", cmd->name, cmd->usage);
        return CLI_EXIT_USAGE;
    }
    return CLI_EXIT_OK;
}
