#!/usr/bin/env bash
# same_bits.sh WINDOWS_EXE WINE_RUN... -- LINUX_EXE...: run the Windows build
# of tests/capi/scene_bits.c under wine (the command after WINDOWS_EXE up to
# "--") and each Linux build after "--"; fail unless every output is the
# same, line for line (struct sizes and position hashes), and every run
# exits 0.
set -uo pipefail
windows_exe="$1"
shift
wine_run=()
while [ $# -gt 0 ] && [ "$1" != "--" ]; do
    wine_run+=("$1")
    shift
done
shift
[ $# -gt 0 ] || { echo "same_bits: no Linux build to compare with" >&2; exit 2; }
windows_out="$("${wine_run[@]}" "$windows_exe" | tr -d '\r')" || { echo "same_bits: the Windows build failed" >&2; exit 1; }
echo "$windows_out" | sed 's/^/windows: /'
status=0
for linux_exe in "$@"; do
    linux_out="$("$linux_exe")" || { echo "same_bits: $linux_exe failed" >&2; status=1; continue; }
    if [ "$linux_out" = "$windows_out" ]; then
        echo "same_bits: $linux_exe prints the same $(echo "$linux_out" | wc -l) lines"
    else
        echo "same_bits: $linux_exe and the Windows build differ:" >&2
        diff <(echo "$linux_out") <(echo "$windows_out") | sed 's/^</linux  /; s/^>/windows/' >&2
        status=1
    fi
done
exit $status
