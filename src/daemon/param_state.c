/* param_state_t (lcmtypes/rtedge_param_state_t.lcm): the runtime keys with
 * their types, ranges, units and values in force, and the last params_t
 * request's outcome, so that a tuning tool can build its controls and see
 * what became of a change. The message is built once at open over the key
 * table's own strings; publishing it refreshes the values in place and
 * allocates nothing. Saving (ACTION_SAVE) writes through a buffer
 * allocated here at open. */
#include <stdlib.h>
#include <string.h>

#include "daemon_internal.h"
#include "core/clock.h"

static int8_t info_type(rted_key_type t)
{
    switch (t) {
    case RTED_KEY_INT: return RTEDGE_PARAM_INFO_T_TYPE_INT;
    case RTED_KEY_REAL: return RTEDGE_PARAM_INFO_T_TYPE_REAL;
    case RTED_KEY_BOOL: return RTEDGE_PARAM_INFO_T_TYPE_BOOL;
    case RTED_KEY_TEXT: return RTEDGE_PARAM_INFO_T_TYPE_TEXT;
    default: return RTEDGE_PARAM_INFO_T_TYPE_CHOICE;
    }
}

bool rted_param_state_init(rted_daemon *d, char *msg, size_t msg_size)
{
    rtedge_param_state_t *m = &d->state_msg;
    d->config_text = malloc(RTED_CONFIG_TEXT_MAX);
    if (!d->config_text) {
        rted_msgf(msg, msg_size, "out of memory");
        return false;
    }
    d->config_text[0] = 0;
    d->state_reason[0] = 0;
    int32_t n = 0;
    /* Upper bound of the encoded size: the message as built, plus every
     * string that can grow at its largest. */
    int64_t extra = RTED_MSG + RTED_CONFIG_TEXT_MAX;
    const rted_key *k;
    for (size_t i = 0; (k = rted_config_key_at(i)); i++) {
        if (!rted_key_is_runtime(k))
            continue;
        if (n == RTED_STATE_MAX_KEYS)
            abort(); /* more runtime keys than RTED_STATE_MAX_KEYS: raise it */
        rtedge_param_info_t *p = &d->state_keys[n];
        rted_key_desc desc;
        rted_key_describe(k, &desc);
        memset(p, 0, sizeof *p);
        rted_key_get_name(k, d->state_names[n], sizeof d->state_names[n]);
        p->name = d->state_names[n];
        p->type = info_type(rted_key_get_type(k));
        p->min = desc.min;
        p->max = desc.max;
        p->has_unset = desc.has_unset;
        p->unset_value = desc.unset;
        /* lcm-gen's structs take char *: the table's strings are only read. */
        p->choices = (char **)desc.choices;
        while (desc.choices && desc.choices[p->nchoices])
            p->nchoices++;
        p->unit = (char *)desc.unit;
        p->help = (char *)desc.help;
        p->text_value = (char *)"";
        d->state_key_of[n++] = k;
        extra += RTED_TEXT;
    }
    m->nkeys = n;
    m->keys = d->state_keys;
    m->params_channel = d->cfg.params_channel;
    m->reason = d->state_reason;
    m->saved_config = (char *)"";
    extra += (int64_t)strlen(d->cfg.params_channel);
    rted_param_state_refresh(d);
    int64_t size = rtedge_param_state_t_encoded_size(m) + extra;
    if (size > INT32_MAX) {
        rted_msgf(msg, msg_size, "param_state_t would be over 2 GiB");
        return false;
    }
    d->state_max_bytes = (int32_t)size;
    return true;
}

void rted_param_state_refresh(rted_daemon *d)
{
    rtedge_param_state_t *m = &d->state_msg;
    const rted_config *c = &d->cfg;
    m->config_hash = (int64_t)d->config_hash;
    m->enabled = c->params_enabled && d->params_sub != NULL;
    m->save_writes_file = c->params_save_path[0] != 0;
    for (int32_t i = 0; i < m->nkeys; i++) {
        rtedge_param_info_t *p = &d->state_keys[i];
        const char *text;
        rted_config_get(c, d->state_key_of[i], &p->int_value, &p->real_value, &text);
        p->text_value = (char *)text;
        p->settable = m->enabled && rted_config_params_allowed(c, p->name);
    }
}

void rted_param_state_outcome(rted_daemon *d, int64_t request_id, int8_t outcome,
                              const char *reason, bool saved)
{
    rtedge_param_state_t *m = &d->state_msg;
    m->request_id = request_id;
    m->outcome = outcome;
    rted_msgf(d->state_reason, sizeof d->state_reason, "%s", reason);
    m->saved_config = saved ? d->config_text : (char *)"";
    rted_param_state_publish(d);
    m->saved_config = (char *)"";
}

void rted_param_state_publish(rted_daemon *d)
{
    if (!d->pub)
        return;
    rted_param_state_refresh(d);
    const int64_t now = rte_clock_now_ns();
    d->state_msg.utime = rte_clock_wall_us(now);
    char why[RTED_MSG];
    if (rte_publish_param_state(d->pub, d->cfg.params_state_channel, &d->state_msg, why,
                                sizeof why) == RTE_OK)
        d->n.states_sent++;
    else
        d->n.publish_errors++;
    d->state_due_ns = now + (int64_t)d->cfg.params_state_period_ms * 1000000;
}

void rted_param_state_close(rted_daemon *d)
{
    free(d->config_text);
    d->config_text = NULL;
}
