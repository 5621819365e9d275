/* V4L2 controls by name: at open, at each reopening, and on request (on
 * the streaming source, or on a device another process streams from). */
#include "sources/v4l2_internal.h"

#include <errno.h>
#include <string.h>

#include "source_msg.h"

/* Finds a control by name among all the device's controls. */
static bool find_control(v4l2_source *s, const char *name, struct v4l2_queryctrl *qc)
{
    memset(qc, 0, sizeof(*qc));
    qc->id = V4L2_CTRL_FLAG_NEXT_CTRL;
    while (rte_v4l2_xioctl(s, VIDIOC_QUERYCTRL, qc) == 0) {
        if (qc->type != V4L2_CTRL_TYPE_CTRL_CLASS && !(qc->flags & V4L2_CTRL_FLAG_DISABLED) &&
            rte_v4l2_names_equal(name, (const char *)qc->name))
            return true;
        qc->id |= V4L2_CTRL_FLAG_NEXT_CTRL;
    }
    return false;
}

rte_status rte_v4l2_set_control(v4l2_source *s, const char *name, int32_t value, char *msg,
                                size_t msg_size)
{
    struct v4l2_queryctrl qc;
    if (s->fd < 0) {
        rte_source_msgf(msg, msg_size, "control %s: the device is not open", name);
        return RTE_ERR_DEVICE;
    }
    if (!find_control(s, name, &qc)) {
        rte_source_msgf(msg, msg_size, "%s has no control \"%s\"", s->info.path, name);
        return RTE_ERR_ARGUMENT;
    }
    switch (qc.type) {
    case V4L2_CTRL_TYPE_INTEGER:
    case V4L2_CTRL_TYPE_BOOLEAN:
    case V4L2_CTRL_TYPE_MENU:
    case V4L2_CTRL_TYPE_INTEGER_MENU:
        if (value < qc.minimum || value > qc.maximum) {
            rte_source_msgf(msg, msg_size, "control \"%s\": %d is outside %d..%d", qc.name, value,
                            qc.minimum, qc.maximum);
            return RTE_ERR_ARGUMENT;
        }
        break;
    case V4L2_CTRL_TYPE_BUTTON: value = 0; break;
    default:
        rte_source_msgf(msg, msg_size, "control \"%s\" is not an integer, boolean, menu or button",
                        qc.name);
        return RTE_ERR_UNSUPPORTED;
    }
    if (qc.flags & V4L2_CTRL_FLAG_READ_ONLY) {
        rte_source_msgf(msg, msg_size, "control \"%s\" is read-only", qc.name);
        return RTE_ERR_ARGUMENT;
    }
    struct v4l2_control c = {qc.id, value};
    if (rte_v4l2_xioctl(s, VIDIOC_S_CTRL, &c) < 0) {
        int err = errno;
        rte_source_msgf(msg, msg_size, "control \"%s\" = %d: %s", qc.name, value, strerror(err));
        return err == ENODEV || err == EIO ? RTE_ERR_DEVICE : RTE_ERR_ARGUMENT;
    }
    return RTE_OK;
}

rte_status rte_v4l2_apply_controls(v4l2_source *s, char *msg, size_t msg_size)
{
    for (int32_t i = 0; i < s->cfg.n_controls; i++) {
        const rte_v4l2_control *c = &s->cfg.controls[i];
        rte_status st = rte_v4l2_set_control(s, c->name, c->value, msg, msg_size);
        if (st != RTE_OK)
            return st;
    }
    return RTE_OK;
}

rte_status rte_v4l2_source_set_control(rte_source *source, const char *name, int32_t value,
                                       char *msg, size_t msg_size)
{
    if (!source || source->ops != &rte_v4l2_source_ops || !name) {
        rte_source_msgf(msg, msg_size, "not a V4L2 source");
        return RTE_ERR_ARGUMENT;
    }
    return rte_v4l2_set_control(source->impl, name, value, msg, msg_size);
}

rte_status rte_v4l2_set_device_control(const char *device, const char *name, int32_t value,
                                       const rte_v4l2_ops *ops, char *msg, size_t msg_size)
{
    v4l2_source s;
    memset(&s, 0, sizeof(s));
    if (!device || !name || strlen(device) >= sizeof(s.device)) {
        rte_source_msgf(msg, msg_size, "no device or control name, or a name too long");
        return RTE_ERR_ARGUMENT;
    }
    s.ops = ops ? ops : &rte_v4l2_system_ops;
    s.fd = -1;
    memcpy(s.device, device, strlen(device) + 1);
    s.cfg.device = s.device;
    rte_v4l2_copy_string(s.info.path, sizeof(s.info.path), s.device, sizeof(s.device));
    rte_status st = rte_v4l2_open_node(&s, msg, msg_size);
    if (st != RTE_OK)
        return st;
    st = rte_v4l2_set_control(&s, name, value, msg, msg_size);
    rte_v4l2_close_fd(&s);
    return st;
}
