# Debian packages each command needs, and the function that installs the
# missing ones (apt-get update once, then install). Sourced by tools/test,
# tools/bench and tools/demo.
RTE_BUILD_PACKAGES=(meson ninja-build gcc g++ pkg-config binutils
    libspng-dev libturbojpeg0-dev          # image files
    liblcm-dev liblcm-bin libglib2.0-dev   # LCM: lcm-gen; lcm.pc needs glib
    linux-libc-dev libcamera-dev)          # cameras: V4L2 headers, libcamera
RTE_BENCH_PACKAGES=(valgrind)  # tools/bench --instructions (callgrind)
RTE_TEST_PACKAGES=("${RTE_BUILD_PACKAGES[@]}"
    libcmocka-dev libopencv-dev python3-opencv python3-numpy  # unit and oracle suites
    liblcm-java default-jdk-headless iproute2 util-linux ffmpeg  # LCM: Java types, udpm in a netns, Y4M
    libcamera-tools v4l-utils qemu-system-x86 busybox-static make xz-utils)  # the camera VM suite

rte_install_packages() {
    local missing=() p
    for p in "$@"; do
        dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q 'install ok installed' || missing+=("$p")
    done
    [ ${#missing[@]} -eq 0 ] && return 0
    echo "installing: ${missing[*]}"
    local sudo=
    [ "$(id -u)" -ne 0 ] && sudo=sudo
    export DEBIAN_FRONTEND=noninteractive
    $sudo apt-get update -q >/dev/null || { echo "apt-get update failed"; return 1; }
    $sudo apt-get install -y -q --no-install-recommends "${missing[@]}" >/dev/null ||
        { echo "apt-get install ${missing[*]} failed"; return 1; }
}
