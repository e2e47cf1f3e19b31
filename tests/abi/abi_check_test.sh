#!/usr/bin/env bash
# Shows that scripts/abi-check catches ABI changes: a probe library built
# against the real cloth.h is the baseline; the same probe passes, a copy
# of the header with a field inserted into cloth_stats fails (layout
# change), a dropped exported function fails, and the layout change passes
# once the header's version is bumped.
# Usage: abi_check_test.sh SOURCE_DIR C_COMPILER
set -euo pipefail
root="$1"
cc="$2"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
check="$root/scripts/abi-check"

probe() {  # probe OUT HEADER_ROOT [cc flags...]
    local out="$1" include="$2"
    shift 2
    "$cc" -g -O0 -shared -fPIC -I"$include" "$@" "$root/tests/abi/probe.c" -o "$out"
}
expect() {  # expect pass|fail DESCRIPTION command...
    local want="$1" what="$2"
    shift 2
    if "$@" >"$work/out" 2>&1; then got=pass; else got=fail; fi
    if [ "$got" != "$want" ]; then
        cat "$work/out"
        echo "FAIL: $what: abi-check should $want but did $got"
        exit 1
    fi
    echo "ok: $what ($want)"
}

# Baseline from the real header.
probe "$work/base.so" "$root/include"
"$check" --update --lib "$work/base.so" --headers "$root/include/cloth" --baseline "$work/abi" >/dev/null

# A layout change: a field inserted before cloth_stats.last_step_result.
mkdir -p "$work/changed/cloth"
sed 's/^\(    cloth_result last_step_result;\)/    float inserted_field;\n\1/' "$root/include/cloth/cloth.h" \
    >"$work/changed/cloth/cloth.h"
grep -q inserted_field "$work/changed/cloth/cloth.h" || { echo "FAIL: could not edit cloth_stats"; exit 1; }
probe "$work/changed.so" "$work/changed"

# The same change with the minor version bumped.
mkdir -p "$work/bumped/cloth"
minor=$(sed -n 's/^#define CLOTH_VERSION_MINOR \([0-9]*\).*/\1/p' "$root/include/cloth/cloth.h")
sed "s/^#define CLOTH_VERSION_MINOR .*/#define CLOTH_VERSION_MINOR $((minor + 1))/" \
    "$work/changed/cloth/cloth.h" >"$work/bumped/cloth/cloth.h"
probe "$work/bumped.so" "$work/bumped"

# An exported function removed.
probe "$work/dropped.so" "$root/include" -DPROBE_DROP_FUNCTION

run() { "$check" --lib "$1" --headers "$2" --baseline "$work/abi"; }
expect pass "unchanged library" run "$work/base.so" "$root/include/cloth"
expect fail "struct layout changed, same version" run "$work/changed.so" "$work/changed/cloth"
grep -q "inserted_field" "$work/out" || { echo "FAIL: the report does not name the new field"; exit 1; }
expect fail "exported function removed, same version" run "$work/dropped.so" "$root/include/cloth"
expect pass "struct layout changed, minor version bumped" run "$work/bumped.so" "$work/bumped/cloth"
