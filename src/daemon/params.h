/* params_t requests from the network (lcmtypes/rtedge_params_t.lcm): a
 * decoder written by hand into fixed memory, and the step from a decoded
 * request to a new configuration.
 *
 * The channel is unauthenticated, so a message is hostile until proven
 * otherwise: its size is bounded before anything is read, every count and
 * string length is bounded before it is used, names must be NUL-terminated
 * 'section.key' text of [a-z0-9_.], each value's kind must be the key's
 * type and its value within the key's range, and one bad value refuses the
 * whole request with the reason. Nothing is allocated: lcm-gen's decoder
 * would malloc what the message's counts ask for. */
#ifndef RTEDGED_PARAMS_H
#define RTEDGED_PARAMS_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "config.h"

/* Values in one request (more than there are runtime keys). */
#define RTED_PARAMS_MAX 32
/* A name's bytes, its NUL included. */
#define RTED_PARAM_NAME_MAX 64
/* A text value's bytes, its NUL included (a text key's capacity). */
#define RTED_PARAM_TEXT_MAX RTED_TEXT
/* The largest valid message: fingerprint, utime, request_id, action,
 * nparams, then per value a name (length, bytes), kind, int_value,
 * real_value and text_value (length, bytes). */
#define RTED_PARAMS_HEAD_BYTES (8 + 8 + 8 + 1 + 4)
#define RTED_PARAMS_MAX_BYTES \
    (RTED_PARAMS_HEAD_BYTES + \
     RTED_PARAMS_MAX * (4 + RTED_PARAM_NAME_MAX + 1 + 8 + 8 + 4 + RTED_PARAM_TEXT_MAX))
#define RTED_PARAMS_MIN_BYTES RTED_PARAMS_HEAD_BYTES

typedef struct rted_param {
    char name[RTED_PARAM_NAME_MAX];
    int8_t kind; /* RTEDGE_PARAM_T_KIND_* */
    int64_t int_value;
    double real_value;
    char text_value[RTED_PARAM_TEXT_MAX];
} rted_param;

typedef struct rted_params_request {
    int64_t utime;
    int64_t request_id;
    bool have_id;  /* request_id was read (for messages about a bad request) */
    int8_t action; /* RTEDGE_PARAMS_T_ACTION_* */
    int32_t count;
    rted_param params[RTED_PARAMS_MAX];
} rted_params_request;

/* Decodes an encoded rtedge.params_t (fingerprint first, as LCM delivers
 * it) into *req. false and *why on anything malformed: a size outside
 * RTED_PARAMS_MIN_BYTES..RTED_PARAMS_MAX_BYTES, another fingerprint, an
 * action other than ACTION_SET (with 1..RTED_PARAMS_MAX values) or
 * ACTION_SAVE (with none), a name length outside 2..RTED_PARAM_NAME_MAX, a
 * name without its NUL or with bytes other than [a-z0-9_.], a text value
 * over RTED_PARAM_TEXT_MAX bytes, without its NUL or with bytes outside
 * printable ASCII, data cut short or bytes left over. */
bool rted_params_decode(const void *data, size_t size, rted_params_request *req, char *why,
                        size_t why_size);

/* Sets every value of req on *next (a copy of *now): the key must exist, be
 * a runtime key, be listed in params.keys (when the list is set), the
 * value's kind must be the key's (KIND_TEXT for text and choice keys,
 * KIND_BOOL: 0 or 1) and the value valid for the key (range, choice, text
 * the file can hold); a key may appear once. false and
 * *why ("value 2 (lane.canny_low): ...") at the first value that fails;
 * *next is then partly changed and must be dropped. Cross-key and
 * frame-size checks are the caller's (rted_daemon_apply). */
bool rted_params_to_config(const rted_params_request *req, const rted_config *now,
                           rted_config *next, char *why, size_t why_size);

#endif
