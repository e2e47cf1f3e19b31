#!/usr/bin/env bash
# wine-run.sh PREFIX DLL_DIR PROGRAM.exe [ARGS...]: run a Windows program
# under wine64, headless (no display, no Wine debug output), in the Wine
# prefix PREFIX (created on first use), with DLL_DIR (cloth.dll's folder) on
# its DLL search path. Exits with the program's exit status. The tests'
# command of every test in a MinGW-w64 tree (tests/windows/CMakeLists.txt).
set -euo pipefail
prefix="$1" dll_dir="$2"
shift 2
wine=/usr/lib/wine/wine64
export WINEPREFIX="$prefix" WINEDEBUG=-all WINEARCH=win64
# No Mono or Gecko for the prefix (nothing here uses .NET or HTML), so the
# first start makes no installer prompt.
export WINEDLLOVERRIDES="mscoree,mshtml="
unset DISPLAY WAYLAND_DISPLAY
export WINEPATH="Z:${dll_dir//\//\\}"
# Tests run in parallel: one of them creates the prefix, the others wait.
mkdir -p "$(dirname "$prefix")"
if [ ! -f "$prefix/system.reg" ]; then
    flock "$prefix.lock" bash -c '[ -f "$WINEPREFIX/system.reg" ] || "$0" wineboot --init >/dev/null 2>&1' "$wine"
fi
exec "$wine" "$@"
