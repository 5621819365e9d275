/* params_t from the network: see params.h. */
#include "params.h"

#include <stdio.h>
#include <string.h>

#include "lcm_wire.h"
#include "log.h"
#include "rtedge_param_t.h"
#include "rtedge_params_t.h"

/* The reason into why, and false. */
#define refuse(...) (rted_msgf(__VA_ARGS__), false)

/* A bounds-checked reader of big-endian fields. */
typedef struct reader {
    const uint8_t *p;
    size_t left;
} reader;

static bool take(reader *r, size_t n, const uint8_t **out)
{
    if (r->left < n)
        return false;
    *out = r->p;
    r->p += n;
    r->left -= n;
    return true;
}

static bool get_u32(reader *r, uint32_t *v)
{
    const uint8_t *b;
    if (!take(r, 4, &b))
        return false;
    *v = rte_lcm_get_u32(b);
    return true;
}

static bool get_u64(reader *r, uint64_t *v)
{
    const uint8_t *b;
    if (!take(r, 8, &b))
        return false;
    *v = rte_lcm_get_u64(b);
    return true;
}

static bool get_i64(reader *r, int64_t *v)
{
    uint64_t u;
    if (!get_u64(r, &u))
        return false;
    memcpy(v, &u, sizeof *v); /* two's complement, no implementation-defined cast */
    return true;
}

static bool name_char(uint8_t c)
{
    return (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '_' || c == '.';
}

/* Value `index`'s name: length (its NUL included), bytes, NUL. */
static bool get_name(reader *r, int32_t index, char *name, char *why, size_t why_size)
{
    uint32_t len;
    const uint8_t *b;
    if (!get_u32(r, &len))
        return refuse(why, why_size, "value %d: cut short before its name", index + 1);
    if (len < 2 || len > RTED_PARAM_NAME_MAX)
        return refuse(why, why_size, "value %d: a name of %u bytes (with its NUL; 2..%d allowed)",
                      index + 1, len, RTED_PARAM_NAME_MAX);
    if (!take(r, len, &b))
        return refuse(why, why_size, "value %d: cut short in its name", index + 1);
    if (b[len - 1] != 0)
        return refuse(why, why_size, "value %d: the name does not end with a NUL byte", index + 1);
    for (uint32_t i = 0; i + 1 < len; i++)
        if (!name_char(b[i]))
            return refuse(why, why_size,
                          "value %d: byte %u of the name is 0x%02x (names are "
                          "'section.key' of a-z, 0-9, '_' and '.')",
                          index + 1, i, b[i]);
    memcpy(name, b, len);
    return true;
}

/* Value `index`'s text: length (its NUL included), printable ASCII, NUL. */
static bool get_text(reader *r, rted_param *p, int32_t index, char *why, size_t why_size)
{
    uint32_t len;
    const uint8_t *b;
    if (!get_u32(r, &len))
        return refuse(why, why_size, "value %d (%s): cut short before its text", index + 1,
                      p->name);
    if (len < 1 || len > RTED_PARAM_TEXT_MAX)
        return refuse(why, why_size,
                      "value %d (%s): a text of %u bytes (with its NUL; 1..%d allowed)", index + 1,
                      p->name, len, RTED_PARAM_TEXT_MAX);
    if (!take(r, len, &b))
        return refuse(why, why_size, "value %d (%s): cut short in its text", index + 1, p->name);
    if (b[len - 1] != 0)
        return refuse(why, why_size, "value %d (%s): the text does not end with a NUL byte",
                      index + 1, p->name);
    for (uint32_t i = 0; i + 1 < len; i++)
        if (b[i] < 0x20 || b[i] > 0x7e)
            return refuse(why, why_size,
                          "value %d (%s): byte %u of the text is 0x%02x (printable ASCII only)",
                          index + 1, p->name, i, b[i]);
    memcpy(p->text_value, b, len);
    return true;
}

bool rted_params_decode(const void *data, size_t size, rted_params_request *req, char *why,
                        size_t why_size)
{
    req->count = 0;
    req->have_id = false;
    req->action = RTEDGE_PARAMS_T_ACTION_SET;
    if (size < RTED_PARAMS_MIN_BYTES || size > RTED_PARAMS_MAX_BYTES)
        return refuse(why, why_size, "a message of %zu bytes (a params_t has %d..%d)", size,
                      RTED_PARAMS_MIN_BYTES, RTED_PARAMS_MAX_BYTES);
    /* The size check above guarantees the head's fields. */
    reader r = {data, size};
    int64_t hash = 0;
    uint32_t count = 0;
    const uint8_t *action;
    get_i64(&r, &hash);
    if (hash != __rtedge_params_t_get_hash())
        return refuse(why, why_size, "not a params_t (fingerprint %016llx)",
                      (unsigned long long)hash);
    get_i64(&r, &req->utime);
    get_i64(&r, &req->request_id);
    req->have_id = true;
    take(&r, 1, &action);
    get_u32(&r, &count);
    req->action = (int8_t)action[0];
    if (req->action == RTEDGE_PARAMS_T_ACTION_SAVE) {
        if (count != 0)
            return refuse(why, why_size, "ACTION_SAVE with nparams = %d (0 allowed)",
                          (int32_t)count);
    } else if (req->action != RTEDGE_PARAMS_T_ACTION_SET) {
        return refuse(why, why_size, "action %d is neither ACTION_SET (0) nor ACTION_SAVE (1)",
                      req->action);
    } else if (count < 1 || count > RTED_PARAMS_MAX) {
        return refuse(why, why_size, "nparams = %d (1..%d allowed)", (int32_t)count,
                      RTED_PARAMS_MAX);
    }
    for (int32_t i = 0; i < (int32_t)count; i++) {
        rted_param *p = &req->params[i];
        const uint8_t *kind;
        uint64_t bits;
        if (!get_name(&r, i, p->name, why, why_size))
            return false;
        if (!take(&r, 1, &kind) || !get_i64(&r, &p->int_value) || !get_u64(&r, &bits))
            return refuse(why, why_size, "value %d (%s): cut short", i + 1, p->name);
        p->kind = (int8_t)kind[0];
        memcpy(&p->real_value, &bits, sizeof bits);
        if (!get_text(&r, p, i, why, why_size))
            return false;
    }
    if (r.left)
        return refuse(why, why_size, "%zu bytes after the last value", r.left);
    req->count = (int32_t)count;
    return true;
}

static const char *kind_name(int8_t kind)
{
    switch (kind) {
    case RTEDGE_PARAM_T_KIND_INT: return "KIND_INT";
    case RTEDGE_PARAM_T_KIND_REAL: return "KIND_REAL";
    case RTEDGE_PARAM_T_KIND_BOOL: return "KIND_BOOL";
    case RTEDGE_PARAM_T_KIND_TEXT: return "KIND_TEXT";
    default: return NULL;
    }
}

/* The kind a key of this type takes. */
static int8_t kind_for(rted_key_type t)
{
    return t == RTED_KEY_INT    ? RTEDGE_PARAM_T_KIND_INT
           : t == RTED_KEY_REAL ? RTEDGE_PARAM_T_KIND_REAL
           : t == RTED_KEY_BOOL ? RTEDGE_PARAM_T_KIND_BOOL
                                : RTEDGE_PARAM_T_KIND_TEXT;
}

/* One value onto *next; false and *why (without the "value N" prefix). */
static bool set_one(const rted_param *p, const rted_config *now, rted_config *next, char *why,
                    size_t why_size)
{
    const rted_key *k = rted_config_find_key(p->name);
    if (!k)
        return refuse(why, why_size, "no such key");
    if (!rted_key_is_runtime(k))
        return refuse(why, why_size,
                      "cannot change while running (it fixes sizes or the "
                      "source): restart rtedged");
    rted_key_type t = rted_key_get_type(k);
    if (!rted_config_params_allowed(now, p->name))
        return refuse(why, why_size, "not in params.keys");
    const char *given = kind_name(p->kind);
    if (!given)
        return refuse(why, why_size,
                      "kind %d is none of KIND_INT (1), KIND_REAL (2), "
                      "KIND_BOOL (3), KIND_TEXT (4)",
                      p->kind);
    if (p->kind != kind_for(t))
        return refuse(why, why_size, "takes %s, not %s", kind_name(kind_for(t)), given);
    switch (t) {
    case RTED_KEY_INT: return rted_config_set_int(next, k, p->int_value, why, why_size);
    case RTED_KEY_REAL: return rted_config_set_real(next, k, p->real_value, why, why_size);
    case RTED_KEY_TEXT:
    case RTED_KEY_CHOICE: return rted_config_set_text(next, k, p->text_value, why, why_size);
    default:
        if (p->int_value != 0 && p->int_value != 1)
            return refuse(why, why_size, "a KIND_BOOL value is 0 or 1, not %lld",
                          (long long)p->int_value);
        return rted_config_set_bool(next, k, p->int_value == 1, why, why_size);
    }
}

bool rted_params_to_config(const rted_params_request *req, const rted_config *now,
                           rted_config *next, char *why, size_t why_size)
{
    *next = *now;
    if (req->count < 1 || req->count > RTED_PARAMS_MAX)
        return refuse(why, why_size, "%d values (1..%d allowed)", req->count, RTED_PARAMS_MAX);
    for (int32_t i = 0; i < req->count; i++) {
        const rted_param *p = &req->params[i];
        char reason[RTED_MSG];
        for (int32_t j = 0; j < i; j++)
            if (!strcmp(req->params[j].name, p->name))
                return refuse(why, why_size, "value %d (%s): given twice (values %d and %d)", i + 1,
                              p->name, j + 1, i + 1);
        if (!set_one(p, now, next, reason, sizeof reason))
            return refuse(why, why_size, "value %d (%s): %s", i + 1, p->name, reason);
    }
    return true;
}
