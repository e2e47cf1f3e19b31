#!/usr/bin/env bash
# The C# binding's checks, run by ctest (bindings/csharp/CMakeLists.txt):
#
#   check.sh build  OUT_DIR              generate the binding from cloth.h into OUT_DIR and
#                                        compile ClothSharp.dll, the tests and the flag sample
#                                        with Mono's mcs (C# 7.2, warnings are errors)
#   check.sh run    OUT_DIR LIB_DIR EXE  run OUT_DIR/EXE under mono against LIB_DIR/libcloth.so
#   check.sh refuse OUT_DIR              the generator stops (status 1) on declarations it
#                                        cannot bind, each spliced into a copy of cloth.h
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
    # Each line: a declaration the binding could not carry exactly, and why.
    cases=(
        'CLOTH_API int CLOTH_CALL cloth_bad(long x);|a C int type instead of a fixed-width one'
        'CLOTH_API cloth_result cloth_bad(uint32_t x);|a function without CLOTH_CALL'
        'typedef struct cloth_bad { uint32_t struct_size; bool flag; } cloth_bad;|a bool field'
        'typedef void cloth_bad_fn(void* user);|a callback type without CLOTH_CALL'
        '#define CLOTH_BAD (CLOTH_MAX_WORLDS * 2)|a macro that is not a number'
        'static inline uint32_t cloth_bad(uint32_t x) { return x; }|an inline function that is not an id equality'
        'typedef struct cloth_bad { uint32_t struct_size; cloth_id ids[4]; } cloth_bad;|an array of structs'
        'typedef struct cloth_bad { uint32_t struct_size; } cloth_bad;|a struct no cloth_struct_kind names'
    )
    for entry in "${cases[@]}"; do
        declaration="${entry%%|*}"
        why="${entry#*|}"
        # Spliced in just before the closing extern "C" block.
        python3 - "$header" "$out/bad.h" "$declaration" <<'PY'
import sys
text = open(sys.argv[1]).read()
marker = "#ifdef __cplusplus\n} /* extern \"C\" */"
assert marker in text
open(sys.argv[2], "w").write(text.replace(marker, sys.argv[3] + "\n\n" + marker))
PY
        set +e
        message="$(python3 "$here/generate.py" --header "$out/bad.h" --out "$out/bad.cs" 2>&1)"
        status=$?
        set -e
        if [ "$status" -ne 1 ]; then
            echo "check.sh: FAIL: the generator accepted $why (status $status): $message" >&2
            exit 1
        fi
        echo "refused, $why: $message"
    done
    ;;
*)
    echo "check.sh: unknown mode $mode" >&2
    exit 2
    ;;
esac
