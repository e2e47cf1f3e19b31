#!/usr/bin/env bash
# The C# binding's checks, run by ctest (bindings/csharp/CMakeLists.txt):
#
#   check.sh build  OUT_DIR              generate the binding from cloth.h into OUT_DIR and
#                                        compile ClothSharp.dll, the tests and the flag sample
#                                        with Mono's mcs (C# 7.2, warnings are errors)
#   check.sh run    OUT_DIR LIB_DIR EXE  run OUT_DIR/EXE under mono against LIB_DIR/libcloth.so
#   check.sh refuse OUT_DIR              the generator stops on declarations it cannot bind,
#                                        each spliced into a copy of cloth.h (tests/refusals.py)
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
header="$here/../../include/cloth/cloth.h"
mode="$1"
out="$2"
mkdir -p "$out"
MCS=(mcs -langversion:7.2 -unsafe -warn:4 -warnaserror+ -nologo)

case "$mode" in
build)
    python3 "$here/generate.py" --header "$header" --out "$out/ClothNative.g.cs"
    "${MCS[@]}" -target:library -out:"$out/ClothSharp.dll" "$out/ClothNative.g.cs" "$here/ClothSharp.cs"
    "${MCS[@]}" -r:"$out/ClothSharp.dll" -out:"$out/ClothTests.exe" "$here/tests/ClothTests.cs"
    "${MCS[@]}" -r:"$out/ClothSharp.dll" -out:"$out/FlagLoop.exe" "$here/samples/FlagBehaviour.cs"
    echo "check.sh: ClothSharp.dll, ClothTests.exe and FlagLoop.exe built in $out"
    ;;
run)
    # mono finds DllImport("cloth") as libcloth.so on the library path.
    LD_LIBRARY_PATH="$3${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}" mono --debug "$out/$4"
    ;;
refuse)
    python3 "$here/tests/refusals.py" "$out"
    ;;
*)
    echo "check.sh: unknown mode $mode" >&2
    exit 2
    ;;
esac
