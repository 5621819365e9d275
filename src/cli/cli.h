/* The rtedge command-line tool: shared pieces of its subcommands.
 *
 * Each subcommand declares its options as a table (cli_option) and calls
 * cli_parse(); help text and range checks come from the table, so every
 * subcommand behaves the same way on bad arguments. */
#ifndef RTEDGE_CLI_H
#define RTEDGE_CLI_H

#include <stdbool.h>
#include <stddef.h>

/* The larger of two scratch sizes (kernels run one after the other share
 * an arena). */
static inline size_t cli_max_size(size_t a, size_t b) { return a > b ? a : b; }

/* Exit codes, the same for every subcommand. */
enum {
    CLI_EXIT_OK = 0,
    CLI_EXIT_FAILURE = 1, /* the operation itself failed (e.g. writing the output) */
    CLI_EXIT_USAGE = 2,   /* bad command line */
    CLI_EXIT_INPUT = 3,   /* the input file cannot be used */
};

typedef enum cli_option_type {
    CLI_INT,    /* int, checked against [min, max] */
    CLI_DOUBLE, /* double, checked against [min, max] */
    CLI_FLAG,   /* bool, no value */
    CLI_STRING, /* const char *, any text */
    CLI_CHOICE, /* int: index of the value in `choices` (NULL-terminated) */
} cli_option_type;

typedef struct cli_option {
    const char *name; /* without the leading "--" */
    cli_option_type type;
    void *value;     /* int *, double *, bool *, const char ** by type */
    double min, max; /* CLI_INT and CLI_DOUBLE */
    const char *const *choices;
    const char *help;
    bool *given; /* optional: set when the option appears */
} cli_option;

typedef struct cli_command {
    const char *name;
    const char *usage;   /* the words after the command name, e.g. "IN OUT" */
    const char *summary; /* one line */
    const char *details; /* optional paragraph after the options */
    cli_option *options; /* terminated by an entry with name == NULL */
    int positionals;     /* how many positional arguments are required */
} cli_command;

/* Parses argv (argv[0] is the command name). Fills options, puts the
 * positional arguments into positional[] (at most `positionals`).
 * Returns CLI_EXIT_OK, or CLI_EXIT_USAGE after printing the problem;
 * `--help` prints the help and returns -1 (the caller exits 0). */
int cli_parse(const cli_command *cmd, int argc, char **argv, const char **positional);
void cli_print_help(const cli_command *cmd);

/* Prints "rtedge NAME: message" to stderr. */
void cli_error(const char *command, const char *fmt, ...) __attribute__((format(printf, 2, 3)));

#endif
