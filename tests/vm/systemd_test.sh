#!/bin/sh
# The test in the systemd guest (run_systemd_vm.sh), run by
# rte-vm-test.service next to the enabled rtedged.service (the unit as
# installed, with the camera and a file:// log set in its configuration
# file): rtedged must wait for /dev/video0 ("activating", STATUS= "waiting
# for camera"), become active (READY=1) once vivid is loaded, publish, and
# be killed by systemd's watchdog and restarted when its loop is stopped
# (SIGSTOP). Prints "RTE-VM PASS|FAIL name" lines and the unit's journal on
# the console, then powers off.
exec >/dev/console 2>&1
log=/var/log/rtedge/vm.lcm

result() { # PASS|FAIL NAME DETAIL
    echo "RTE-VM $1 $2: $3"
}
prop() { # PROPERTY
    systemctl show -p "$1" --value rtedged.service
}
uptime_s() { cut -d' ' -f1 /proc/uptime; }
lanes() { # lane messages in the log (their channel names)
    grep -ao RTEDGE_LANES "$log" 2>/dev/null | wc -l
}

# Waits up to SECONDS for COMMAND to succeed; says when.
until_ok() { # SECONDS COMMAND...
    n=$(($1 * 5))
    shift
    while ! "$@"; do
        n=$((n - 1))
        [ $n -le 0 ] && return 1
        usleep 200000
    done
    echo "[$(uptime_s) s] $*"
}
waiting() {
    [ "$(prop ActiveState)" = activating ] && prop StatusText | grep -q "waiting for camera"
}
active() { [ "$(prop ActiveState)" = active ]; }
restarted() { # OLD_PID
    [ "$(prop NRestarts)" = 1 ] && active && [ "$(prop MainPID)" != "$1" ]
}

echo "RTE-VM boot: systemd $(systemctl --version | head -n 1), kernel $(uname -r)"

# 1. No camera yet: rtedged waits, "activating", and says so.
if until_ok 60 waiting; then
    sleep 2
    if waiting; then
        result PASS systemd-wait "$(prop ActiveState) ($(prop SubState)), main PID $(prop MainPID), status: $(prop StatusText); videodev loaded at boot: $(grep -c '^videodev ' /proc/modules)"
    else
        result FAIL systemd-wait "did not keep waiting: $(prop ActiveState), $(prop StatusText)"
    fi
else
    result FAIL systemd-wait "not activating and waiting for the camera: $(prop ActiveState) $(prop SubState) $(prop Result), $(prop StatusText)"
fi

# 2. The camera appears: READY=1 (active) with the first frame; udev gave
# the node to group video.
modprobe vivid n_devs=1 node_types=0x1 || echo "modprobe vivid failed"
loaded=$(uptime_s)
if until_ok 60 active; then
    result PASS systemd-ready "active $(echo "$(uptime_s) $loaded" | awk '{printf "%.1f", $1 - $2}') s after modprobe vivid; status: $(prop StatusText); $(ls -l /dev/video0 | awk '{print $1, $3, $4}')"
else
    result FAIL systemd-ready "$(prop ActiveState) $(prop SubState), status: $(prop StatusText); $(ls -l /dev/video0 2>&1)"
fi

# The sandbox as the unit says: a dynamic user in group video, no new
# privileges, a system call filter, CAP_SYS_NICE and CAP_IPC_LOCK only.
pid=$(prop MainPID)
status() { awk -v k="$1:" '$1 == k {$1 = ""; print substr($0, 2)}' /proc/$pid/status; }
uid=$(status Uid | cut -d' ' -f1) caps=$(status CapEff) groups=$(status Groups)
if [ -n "$uid" ] && [ "$uid" -ne 0 ] && echo " $groups " | grep -q " 44 " &&
   [ "$(status NoNewPrivs)" = 1 ] && [ "$(status Seccomp)" = 2 ] && [ "$caps" = 0000000000804000 ]; then
    result PASS systemd-sandbox "uid $uid, groups $groups, CapEff $caps, NoNewPrivs 1, Seccomp 2"
else
    result FAIL systemd-sandbox "uid '$uid', groups '$groups', CapEff $caps, NoNewPrivs $(status NoNewPrivs), Seccomp $(status Seccomp)"
fi
# realtime.priority = 10 and realtime.mlockall = true work inside it: the
# main thread is SCHED_FIFO (policy 1, /proc/PID/stat's 41st field) at 10,
# and its memory is locked.
sched=$(awk '{print $41, $40}' /proc/$pid/stat) locked=$(status VmLck | awk '{print $1}')
if [ "$sched" = "1 10" ] && [ "${locked:-0}" -gt 0 ]; then
    result PASS systemd-realtime "SCHED_FIFO priority 10, VmLck $locked kB"
else
    result FAIL systemd-realtime "policy and priority '$sched' (want '1 10'), VmLck '$locked' kB"
fi

# 3. Messages: lane messages in the LCM log (LogsDirectory), growing.
before=$(lanes)
sleep 2
after=$(lanes)
if [ "$before" -gt 0 ] && [ "$after" -gt "$before" ]; then
    result PASS systemd-messages "$log: $before lane messages, $after 2 s later; status: $(prop StatusText)"
else
    result FAIL systemd-messages "$log: $before lane messages, then $after; $(ls -l $log 2>&1)"
fi

# 4. The loop stalled (SIGSTOP): no WATCHDOG=1 for WatchdogSec, so systemd
# kills rtedged (SIGABRT) and restarts it.
pid=$(prop MainPID)
took=
kill -STOP "$pid"
stopped=$(uptime_s)
echo "[$stopped s] kill -STOP $pid (WatchdogUSec=$(prop WatchdogUSec))"
if until_ok 60 restarted "$pid" &&
   journalctl -b -u rtedged.service -o cat --no-pager | grep -q "Watchdog timeout"; then
    took=$(echo "$(uptime_s) $stopped" | awk '{printf "%.1f", $1 - $2}')
    before=$(lanes)
    sleep 2
fi
if [ -n "$took" ] && [ "$(lanes)" -gt "$before" ]; then
    result PASS systemd-watchdog "active again $took s after SIGSTOP, NRestarts=$(prop NRestarts), main PID $pid -> $(prop MainPID), lane messages $before -> $(lanes) 2 s later; $(journalctl -b -u rtedged.service -o cat --no-pager | grep 'Watchdog timeout')"
else
    result FAIL systemd-watchdog "$(prop ActiveState) $(prop SubState), NRestarts=$(prop NRestarts), MainPID $(prop MainPID) (was $pid), Result=$(prop Result)"
fi

echo "---- journalctl -u rtedged ----"
journalctl -b -u rtedged.service -o short-monotonic --no-pager
echo "---- systemctl status rtedged ----"
systemctl status --no-pager -n 0 rtedged.service
echo "RTE-VM end"
poweroff -f
