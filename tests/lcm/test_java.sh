#!/bin/sh
# The Java types read an rtedge log through lcm.jar's reader.
#   test_java.sh WRITE_SAMPLE_LOG LCM_JAR RTEDGE_JAR READLOG.java TMPDIR
set -eu
log="$5/java.$$.lcmlog"
"$1" "$log"
java -cp "$2:$3" "$4" "$log"
rm -f "$log"
