#!/usr/bin/env bash
# Installs the build tree into a temporary prefix (or takes an installed
# prefix, an unpacked archive of scripts/package), then builds and runs a
# consumer through find_package(cloth) and one through pkg-config.
# Usage: check.sh BUILD_DIR SOURCE_DIR
#        check.sh --prefix PREFIX SOURCE_DIR
set -euo pipefail
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
if [ "$1" = "--prefix" ]; then
    prefix="$2"
    here="$3"
else
    here="$2"
    prefix="$work/prefix"
    cmake --install "$1" --prefix "$prefix" >/dev/null
fi
cmake -S "$here" -B "$work/consumer" -G Ninja -DCMAKE_PREFIX_PATH="$prefix" >/dev/null
cmake --build "$work/consumer" >/dev/null
LD_LIBRARY_PATH="$prefix/lib" "$work/consumer/consumer_shared"
"$work/consumer/consumer_static"
libdir="$(find "$prefix" -name cloth.pc -printf '%h')"
PKG_CONFIG_PATH="$libdir" cc "$here/consumer.c" -o "$work/consumer_pc" $(PKG_CONFIG_PATH="$libdir" pkg-config --cflags --libs cloth)
LD_LIBRARY_PATH="$prefix/lib:$(dirname "$libdir")" "$work/consumer_pc"
echo "find_package(cloth) and pkg-config consumers: ok"
