#!/bin/sh
# Builds the Java classes of the LCM types into one jar:
#   build_java.sh LCM_GEN LCM_JAR WORKDIR OUT.jar TYPE.lcm...
set -eu
lcm_gen=$1 lcm_jar=$2 work=$3 jar=$4
shift 4
rm -rf "$work"
mkdir -p "$work/src" "$work/classes"
"$lcm_gen" -j --jpath "$work/src" "$@"
javac -nowarn -source 8 -target 8 -cp "$lcm_jar" -d "$work/classes" "$work"/src/rtedge/*.java 2>&1 |
    grep -v 'bootstrap class path\|^1 warning\|^warning: \[options\]' || true
[ -f "$work/classes/rtedge/image_t.class" ] || { echo "javac failed" >&2; exit 1; }
jar cf "$jar" -C "$work/classes" .
