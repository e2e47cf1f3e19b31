#!/usr/bin/env bash
# The C# binding's checks, run by ctest (bindings/csharp/CMakeLists.txt):
#
#   check.sh build   OUT_DIR              generate the binding from cloth.h into OUT_DIR
#                                         (ClothNative.g.cs, and the owners' get/set properties
#                                         in ClothSharp.g.cs) and compile with Mono's mcs
#                                         (C# 7.2, warnings are errors):
#                                         ClothSharp.dll, the tests, the flag sample; the
#                                         CLOTH_NO_SPAN branch; the Unity branches
#                                         (UNITY_5_3_OR_NEWER, and UNITY_IOS) against the
#                                         UnityEngine stub, with the Unity sample and its tests
#   check.sh run     OUT_DIR LIB_DIR EXE  run OUT_DIR/EXE under mono against LIB_DIR/libcloth.so
#   check.sh layouts OUT_DIR              every struct's size and every field's offset in C#
#                                         equal the C compiler's ($CC, default cc); and the
#                                         comparison fails for a header with one field changed
#   check.sh refuse  OUT_DIR              the generator stops on declarations it cannot bind,
#                                         each spliced into a copy of cloth.h (tests/refusals.py)
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
include="$here/../../include"
header="$include/cloth/cloth.h"
mode="$1"
out="$2"
mkdir -p "$out"
MCS=(mcs -langversion:7.2 -unsafe -warn:4 -warnaserror+ -nologo -r:System.Numerics)

case "$mode" in
build)
    python3 "$here/generate.py" --header "$header" --out "$out/ClothNative.g.cs" \
        --properties "$out/ClothSharp.g.cs" --c-layouts "$out/layouts.c"
    binding=("$out/ClothNative.g.cs" "$out/ClothSharp.g.cs" "$here/ClothSharp.cs")
    "${MCS[@]}" -target:library -out:"$out/ClothSharp.dll" "${binding[@]}"
    "${MCS[@]}" -r:"$out/ClothSharp.dll" -out:"$out/ClothTests.exe" "$here/tests/ClothTests.cs"
    "${MCS[@]}" -r:"$out/ClothSharp.dll" -out:"$out/FlagLoop.exe" "$here/samples/FlagBehaviour.cs"
    "${MCS[@]}" -r:"$out/ClothSharp.dll" -out:"$out/MissingLibrary.exe" "$here/tests/MissingLibrary.cs"
    "${MCS[@]}" -r:"$out/ClothSharp.dll" -out:"$out/Layouts.exe" "$here/tests/Layouts.cs"
    # Runtimes without System.Span: the array overloads alone.
    "${MCS[@]}" -define:CLOTH_NO_SPAN -target:library -out:"$out/ClothSharp.NoSpan.dll" "${binding[@]}"
    # Unity: the UnityEngine stub, the binding's Unity branches, the Unity sample and its tests;
    # iOS (the statically linked "__Internal" import) compiled only.
    "${MCS[@]}" -target:library -out:"$out/UnityEngine.dll" "$here/tests/unity/UnityEngineStub.cs"
    unity=(-r:"$out/UnityEngine.dll" -define:UNITY_5_3_OR_NEWER)
    mkdir -p "$out/unity"
    "${MCS[@]}" "${unity[@]}" -target:library -out:"$out/unity/ClothSharp.dll" "${binding[@]}"
    "${MCS[@]}" "${unity[@]}" -define:UNITY_IOS -target:library -out:"$out/ClothSharp.iOS.dll" "${binding[@]}"
    "${MCS[@]}" "${unity[@]}" -r:"$out/unity/ClothSharp.dll" -out:"$out/unity/UnityTests.exe" \
        "$here/tests/unity/UnityTests.cs" "$here/samples/unity/ClothFlag.cs"
    cp "$out/UnityEngine.dll" "$out/unity/"
    echo "check.sh: ClothSharp.dll, its tests and samples, the CLOTH_NO_SPAN and Unity builds in $out"
    ;;
run)
    # mono finds DllImport("cloth") as libcloth.so on the library path.
    LD_LIBRARY_PATH="$3${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}" mono --debug "$out/$4"
    ;;
layouts)
    cc="${CC:-cc}"
    "$cc" -std=c99 -I"$include" "$out/layouts.c" -o "$out/layouts_c"
    "$out/layouts_c" >"$out/layouts_c.txt"
    mono "$out/Layouts.exe" >"$out/layouts_cs.txt"
    if ! diff -u "$out/layouts_c.txt" "$out/layouts_cs.txt"; then
        echo "check.sh: the C# layout differs from the C compiler's (above: - C, + C#)" >&2
        exit 1
    fi
    echo "check.sh: $(grep -c ' size ' "$out/layouts_c.txt") structs, $(grep -c ' offset ' "$out/layouts_c.txt") fields: every size and offset equal in C and C#"
    # The comparison can fail: the collision parameters' thickness made a double in a
    # copy of the header moves the offsets after it, which the C# lines must then miss.
    python3 - "$header" "$out/changed.h" <<'PY'
import sys
text = open(sys.argv[1], encoding="utf-8").read()
marker = "    float thickness;\n    /// Coulomb coefficient, >= 0; default 0.3"
assert text.count(marker) == 1, "check.sh layouts: the field to change is not in cloth.h"
open(sys.argv[2], "w", encoding="utf-8").write(text.replace(marker, marker.replace("float", "double")))
PY
    mkdir -p "$out/changed/cloth"
    mv "$out/changed.h" "$out/changed/cloth/cloth.h"
    python3 "$here/generate.py" --header "$out/changed/cloth/cloth.h" --out "$out/changed/unused.g.cs" \
        --c-layouts "$out/changed/layouts.c" >/dev/null
    "$cc" -std=c99 -I"$out/changed" "$out/changed/layouts.c" -o "$out/changed/layouts_c"
    if "$out/changed/layouts_c" | diff -q - "$out/layouts_cs.txt" >/dev/null; then
        echo "check.sh: a changed field went unnoticed by the layout comparison" >&2
        exit 1
    fi
    echo "check.sh: a header with one field changed is caught"
    ;;
refuse)
    python3 "$here/tests/refusals.py" "$out"
    ;;
*)
    echo "check.sh: unknown mode $mode" >&2
    exit 2
    ;;
esac
