#!/usr/bin/env bash
# Installs the build tree into a temporary prefix, then builds and runs a
# consumer through find_package(cloth) and one through pkg-config.
# Usage: check.sh BUILD_DIR SOURCE_DIR
set -euo pipefail
build="$1"
here="$2"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
cmake --install "$build" --prefix "$work/prefix" >/dev/null
cmake -S "$here" -B "$work/consumer" -G Ninja -DCMAKE_PREFIX_PATH="$work/prefix" >/dev/null
cmake --build "$work/consumer" >/dev/null
LD_LIBRARY_PATH="$work/prefix/lib" "$work/consumer/consumer_shared"
"$work/consumer/consumer_static"
libdir="$(find "$work/prefix" -name cloth.pc -printf '%h')"
PKG_CONFIG_PATH="$libdir" cc "$here/consumer.c" -o "$work/consumer_pc" $(PKG_CONFIG_PATH="$libdir" pkg-config --cflags --libs cloth)
LD_LIBRARY_PATH="$work/prefix/lib:$(dirname "$libdir")" "$work/consumer_pc"
echo "find_package(cloth) and pkg-config consumers: ok"
