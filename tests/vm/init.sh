#!/bin/sh
# /init of the camera test VM: loads vivid, runs the V4L2 source tests,
# loads vimc (built out of tree), runs the listing and the libcamera source
# test, then powers off. The host reads the "RTE-VM PASS|FAIL name" lines.
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

# Only vivid's video capture node: node_types bit 0.
vivid_args="n_devs=1 node_types=0x1"
if modprobe vivid $vivid_args; then
    vm_vivid /dev/video0 "rmmod vivid" "modprobe vivid $vivid_args"
else
    echo "RTE-VM FAIL vivid-load: modprobe vivid failed"
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
    else
        echo "RTE-VM FAIL vimc-load: modprobe vimc failed"
    fi
fi

vm_list_cameras > /tmp/list.txt 2>&1
cat /tmp/list.txt
want="driver vivid"
[ -x /bin/vm_libcamera ] && want="$want|^libcamera "
if [ "$(grep -cE "$want" /tmp/list.txt)" -ge "$(echo "$want" | tr '|' '\n' | wc -l)" ]; then
    echo "RTE-VM PASS list-cameras: $(tail -n 1 /tmp/list.txt)"
else
    echo "RTE-VM FAIL list-cameras: expected lines matching '$want'"
fi

echo "RTE-VM end"
poweroff -f
