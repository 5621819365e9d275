/* What the configuration's reader, printer and checks need of the key table
 * (config_keys.c) beyond config.h. Internal to the daemon's config_*.c. */
#ifndef RTEDGED_CONFIG_TABLE_H
#define RTEDGED_CONFIG_TABLE_H

#include "config.h"

/* One row of the table: everything about a key. */
struct rted_key {
    const char *section, *key;
    rted_key_type type;
    size_t offset, size; /* size: a text key's capacity */
    const char *unit;    /* integer and real keys: "px", "ms", ... ("" none) */
    double min, max;     /* integer and real keys */
    bool has_unset;      /* `unset` is allowed besides min..max ("the default") */
    double unset;
    const char *const *choices; /* choice keys, NULL-terminated */
    bool runtime;               /* may change while running (SIGHUP, params_t) */
    const char *def;
    const char *help;
};

/* At least the number of keys in the table (checked where it is). */
#define RTED_CONFIG_MAX_KEYS 128

/* The key `key` of [section]; NULL when there is none, with
 * *section_known telling whether the section exists. */
const rted_key *rted_config_lookup(const char *section, const char *key, bool *section_known);
bool rted_config_section_exists(const char *section);
/* The key's row in the table, 0 .. RTED_CONFIG_MAX_KEYS - 1. */
size_t rted_key_index(const rted_key *k);
/* Parses `value` (text, as in the file) into the key's field; false and
 * *why when it is not a valid value of the key (c unchanged). */
bool rted_config_store(rted_config *c, const rted_key *k, const char *value, char *why,
                       size_t why_size);

#endif
