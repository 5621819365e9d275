# Debian packages each command needs, and the function that installs the
# missing ones (apt-get update once, then install). Sourced by tools/test,
# tools/bench and tools/demo.
RTE_BUILD_PACKAGES=(meson ninja-build gcc g++ pkg-config binutils
    libspng-dev libturbojpeg0-dev libjpeg62-turbo-dev  # image files, the debug stream's JPEG
    liblcm-dev liblcm-bin libglib2.0-dev   # LCM: lcm-gen; lcm.pc needs glib
    linux-libc-dev libcamera-dev)          # cameras: V4L2 headers, libcamera
RTE_BENCH_PACKAGES=(valgrind)  # tools/bench --instructions (callgrind)
RTE_TEST_PACKAGES=("${RTE_BUILD_PACKAGES[@]}"
    libcmocka-dev libopencv-dev python3-opencv python3-numpy  # unit and oracle suites
    clang-format                           # the build suite's format check
    systemd                                # the build suite: systemd-analyze on the unit
    groff-base man-db bash-completion      # the build suite's man page and completion checks
    liblcm-java default-jdk-headless iproute2 util-linux ffmpeg  # LCM: Java types, udpm in a netns, Y4M
    libcamera-tools v4l-utils qemu-system-x86 busybox-static make xz-utils  # the camera VM suite
    python3-aiohttp python3-selenium chromium chromium-driver  # rtedge-web in a real browser
    default-jre libjchart2d-java xvfb x11-utils fonts-dejavu-core)  # tools/rtedge-spy on Xvfb
# The fuzz stage of tools/test and tools/fuzz: Debian's clang and its
# runtime (libFuzzer, ASan, UBSan), and how build/fuzz is configured
# (CC=clang CXX=clang++): every library instrumented, the fuzz targets
# linked with libFuzzer, no other tests.
RTE_FUZZ_PACKAGES=(clang libclang-rt-14-dev)
RTE_FUZZ_SETUP=(-Dfuzz=true -Dtests=false -Doracle=disabled -Dlibcamera=disabled -Dlcm=enabled
    -Dwerror=true --buildtype=debugoptimized -Db_sanitize=address,undefined -Db_lundef=false
    "-Dc_args=-fno-sanitize-recover=all")
# The aarch64 stage of tools/test: Debian's cross compiler, qemu-user, and
# the target's libraries as arm64 multi-arch packages (rte_install_aarch64
# adds the arm64 architecture to dpkg first). LCM has no multi-arch
# package, so the cross build leaves it out.
RTE_AARCH64_PACKAGES=(gcc-aarch64-linux-gnu qemu-user
    libcmocka-dev:arm64 libspng-dev:arm64 libturbojpeg0-dev:arm64 zlib1g-dev:arm64)

# The package stage of tools/test (tests/packages/check_debs.sh): Debian's
# packaging tools, and for the arm64 packages the cross toolchain and the
# target's build dependencies (pkgconf:arm64 gives aarch64-linux-gnu-pkg-config).
RTE_DEB_PACKAGES=(dpkg-dev debhelper dh-python lintian python3 systemd default-jdk-headless
    liblcm-java liblcm-bin liblcm-dev libglib2.0-dev libcamera-dev libspng-dev
    libturbojpeg0-dev libjpeg62-turbo-dev qemu-user)
RTE_DEB_ARM64_PACKAGES=(crossbuild-essential-arm64 pkgconf:arm64 libspng-dev:arm64
    libturbojpeg0-dev:arm64)

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

# rte_install_python_lcm DIR: the `lcm` Python package (on PyPI; Debian has
# none) into DIR, for the Python subscriber (tools/subscribe.py) and its
# tests; they use it through RTE_PYTHON_LCM=DIR. Without network it says so
# and returns 1: the subscriber then receives with its built-in reader.
RTE_PYTHON_LCM_VERSION=1.5.1
rte_install_python_lcm() {
    local dir=$1
    [ -f "$dir/lcm/__init__.py" ] && return 0
    local py
    for py in python3 /usr/bin/python3; do
        if "$py" -m pip --version >/dev/null 2>&1; then
            mkdir -p "$(dirname "$dir")"
            "$py" -m pip install --quiet --disable-pip-version-check --no-warn-script-location \
                --root-user-action=ignore --target "$dir" "lcm==$RTE_PYTHON_LCM_VERSION" \
                >"$dir.log" 2>&1 && return 0
        fi
    done
    echo "note: could not install the lcm Python package (pip, PyPI); its tests will say SKIP"
    return 1
}

# rte_build_daemon DIR: rtedged and lcm-gen's Python types, release, no
# tests (what tools/demo and tools/soak run), with what they need installed.
rte_build_daemon() {
    local dir=$1
    rte_install_packages "${RTE_BUILD_PACKAGES[@]}" python3 iproute2 util-linux || return 1
    if [ ! -f "$dir/build.ninja" ]; then
        meson setup "$dir" --buildtype=release -Dtests=false -Doracle=disabled >/dev/null || return 1
    fi
    ninja -C "$dir" -j2 src/daemon/rtedged src/publish/python >/dev/null
}

rte_install_aarch64() {
    if ! dpkg --print-foreign-architectures | grep -qx arm64; then
        local sudo=
        [ "$(id -u)" -ne 0 ] && sudo=sudo
        echo "adding the arm64 architecture to dpkg"
        $sudo dpkg --add-architecture arm64 || { echo "dpkg --add-architecture arm64 failed"; return 1; }
    fi
    rte_install_packages "${RTE_AARCH64_PACKAGES[@]}"
}
