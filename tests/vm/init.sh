#!/bin/sh
# /init of the camera test VM: starts rtedged on a camera not there yet,
# loads vivid (the daemon must stream then), runs the V4L2 source tests,
# then rtedged itself on vivid (with faults injected while it runs, and a
# recording), loads vimc (built out of tree), runs the libcamera source test
# and rtedged on the libcamera camera, lists the cameras, then powers off.
# The host reads the "RTE-VM PASS|FAIL name" lines, and the daemon's LCM
# logs, printed gzipped and base64-encoded between "RTE-VM FILE name
# begin|end" lines, which it decodes and checks (check_logs.py).
export PATH=/bin
export LD_LIBRARY_PATH=/usr/lib/x86_64-linux-gnu
export LIBCAMERA_LOG_LEVELS='*:ERROR'
mount -t proc proc /proc
mount -t sysfs sysfs /sys
mount -t devtmpfs devtmpfs /dev
mkdir -p /run /tmp /dev/shm
mount -t tmpfs tmpfs /run
mount -t tmpfs tmpfs /tmp
mount -t tmpfs tmpfs /dev/shm
echo "RTE-VM boot: kernel $(uname -r)"

result() { # PASS|FAIL NAME DETAIL
    echo "RTE-VM $1 $2: $3"
}

# A file for the host: gzipped, base64, between marker lines.
send_file() { # NAME PATH
    echo "RTE-VM FILE $1 begin"
    gzip -c "$2" | base64
    echo "RTE-VM FILE $1 end"
}

ms_sleep() { usleep $(($1 * 1000)); }

# Sets a control on the node the daemon streams from; the failure is one
# of the run's problems.
inject() { # DEVICE CONTROL
    vm_ctl "$1" "$2" 0 2>>/tmp/problems || echo "could not set '$2'" >>/tmp/problems
}

# Waits up to SECONDS for TEXT in FILE (the daemon's stderr).
wait_for() { # TEXT FILE SECONDS
    n=0
    while ! grep -q "$1" "$2"; do
        n=$((n + 1))
        [ $n -gt $(($3 * 10)) ] && { echo "no '$1' within $3 s" >>/tmp/problems; return 1; }
        usleep 100000
    done
}

# rtedged on vivid: lane and grasp paths at 640x480 YUYV, published to a
# file:// log. While it runs: a buffer marked bad, a fatal streaming error
# (EIO), vivid's Disconnect (the node comes back when the daemon lets go of
# it), and the device unbound from its driver for 1.5 s then bound again (a
# camera unplugged and plugged in). The daemon must report each loss and
# stream again without restarting; the host checks the log. Each step
# waits for the daemon to say it is streaming again, then lets frames flow
# for 1.5 s.
daemon_vivid() {
    dev=/dev/video0 err=/tmp/rtedged-vivid.txt
    : >/tmp/problems
    rtedged --source $dev --set source.width=640 --set source.height=480 \
        --set source.format=yuyv --set publish.status_period_ms=500 \
        --lcm-url file:///tmp/vivid.lcm 2>$err &
    pid=$!
    wait_for "v4l2 source:" $err 10 && ms_sleep 3000
    inject $dev "Inject V4L2_BUF_FLAG_ERROR"
    ms_sleep 500
    inject $dev "Inject Fatal Streaming Error"
    wait_for "reconnection 1)" $err 10 && ms_sleep 1500
    inject $dev "Disconnect"
    wait_for "reconnection 2)" $err 10 && ms_sleep 1500
    echo vivid.0 >/sys/bus/platform/drivers/vivid/unbind || echo "unbind failed" >>/tmp/problems
    ms_sleep 1500
    echo vivid.0 >/sys/bus/platform/drivers/vivid/bind || echo "bind failed" >>/tmp/problems
    wait_for "reconnection 3)" $err 10 && ms_sleep 1500
    kill -TERM $pid
    wait $pid
    code=$?
    cat $err
    send_file daemon-vivid /tmp/vivid.lcm
    grep -q " 1 bad," $err || echo "the bad buffer was not counted" >>/tmp/problems
    if [ $code -eq 0 ] && [ ! -s /tmp/problems ]; then
        result PASS daemon-vivid-run "exit 0; $(tail -n 1 $err)"
    else
        result FAIL daemon-vivid-run "exit $code; $(tr '\n' ' ' </tmp/problems)"
    fi
}

# rtedged --record: 8 YUYV 320x180 frames (a size vivid's webcam input
# has; the camera opened by its card name, with a control set) into an LCM
# log of image_t, next to the lane messages it published for them; the
# host replays the recording through its own rtedged and must get the same
# lane messages.
daemon_record() {
    rtedged --set source.kind=v4l2 --source vivid --set source.width=320 --set source.height=180 \
        --set source.format=yuyv --set 'source.controls=brightness=140' \
        --max-frames 8 --record /tmp/record.lcm \
        --lcm-url file:///tmp/record-out.lcm 2>/tmp/rtedged-record.txt
    code=$?
    cat /tmp/rtedged-record.txt
    send_file record /tmp/record.lcm
    send_file record-out /tmp/record-out.lcm
    [ $code -eq 0 ] && ok=PASS || ok=FAIL
    result $ok daemon-record-run "exit $code; $(tail -n 1 /tmp/rtedged-record.txt)"
}

# Only vivid's video capture node: node_types bit 0.
vivid_args="n_devs=1 node_types=0x1"

# rtedged started on /dev/video0 before vivid is loaded: it must say it
# waits for the camera and stay up (source.wait), then stream once the
# module is loaded 2.5 s later; the host checks its log (no frames, then
# frames, no reconnection counted). Loads vivid for the tests after it.
daemon_wait() {
    err=/tmp/rtedged-wait.txt
    : >/tmp/problems
    rtedged --source /dev/video0 --set source.width=640 --set source.height=480 \
        --set source.format=yuyv --set publish.status_period_ms=500 \
        --lcm-url file:///tmp/wait.lcm 2>$err &
    pid=$!
    wait_for "waiting for camera: /dev/video0" $err 10
    ms_sleep 2000
    kill -0 $pid 2>/dev/null || echo "rtedged exited while waiting" >>/tmp/problems
    modprobe vivid $vivid_args || echo "modprobe vivid failed" >>/tmp/problems
    wait_for "ready: v4l2:/dev/video0 streaming" $err 20 && ms_sleep 1500
    kill -TERM $pid
    wait $pid
    code=$?
    cat $err
    send_file daemon-wait /tmp/wait.lcm
    if [ $code -eq 0 ] && [ ! -s /tmp/problems ]; then
        result PASS daemon-wait-run "exit 0; $(grep -c 'waiting for camera' $err) waiting lines; $(tail -n 1 $err)"
    else
        result FAIL daemon-wait-run "exit $code; $(tr '\n' ' ' </tmp/problems)"
    fi
    [ -e /sys/bus/platform/drivers/vivid ]
}

if daemon_wait; then
    vm_vivid /dev/video0 "rmmod vivid" "modprobe vivid $vivid_args"
    daemon_vivid
    daemon_record
else
    result FAIL vivid-load "vivid is not loaded"
fi

# libcamera lists only devices udev has initialised: without udev, an
# empty data file per device node stands for that.
udev_data() {
    mkdir -p /run/udev/data
    for dev in /sys/class/video4linux/*/dev /sys/bus/media/devices/*/dev; do
        [ -f "$dev" ] && : > "/run/udev/data/c$(cat "$dev")"
    done
}

if [ -x /bin/vm_libcamera ]; then
    if modprobe vimc; then
        udev_data
        vm_libcamera
        # rtedged on the libcamera camera (vimc adjusts 640 to 636 wide).
        rtedged --set source.kind=libcamera --source 0 --set source.width=640 \
            --set source.height=480 --max-frames 15 --set publish.status_period_ms=500 \
            --lcm-url file:///tmp/libcamera.lcm 2>/tmp/rtedged-libcamera.txt
        code=$?
        cat /tmp/rtedged-libcamera.txt
        send_file daemon-libcamera /tmp/libcamera.lcm
        [ $code -eq 0 ] && ok=PASS || ok=FAIL
        result $ok daemon-libcamera-run "exit $code; $(tail -n 1 /tmp/rtedged-libcamera.txt)"
    else
        result FAIL vimc-load "modprobe vimc failed"
    fi
fi

rtedged --list-cameras > /tmp/list.txt 2>&1
cat /tmp/list.txt
want="driver vivid"
[ -x /bin/vm_libcamera ] && want="$want|^libcamera "
if [ "$(grep -cE "$want" /tmp/list.txt)" -ge "$(echo "$want" | tr '|' '\n' | wc -l)" ]; then
    result PASS list-cameras "$(grep -cE '^(v4l2|libcamera) ' /tmp/list.txt) camera(s)"
else
    result FAIL list-cameras "expected lines matching '$want'"
fi

echo "RTE-VM end"
poweroff -f
