#!/usr/bin/env python3
"""The generator refuses what it cannot bind: each declaration below, spliced
into a copy of cloth.h before its closing extern "C" block, must stop
generate.py with a BindError (exit status 1 on the command line); the header
itself must bind. One process for every case (ctest: cloth_csharp.generator_refuses)."""
import os
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.dont_write_bytecode = True  # no __pycache__ in the source tree
sys.path.insert(0, os.path.join(HERE, ".."))
import generate  # noqa: E402

CASES = [
    ("CLOTH_API int CLOTH_CALL cloth_bad(long x);", "a C int type instead of a fixed-width one"),
    ("CLOTH_API cloth_result cloth_bad(uint32_t x);", "a function without CLOTH_CALL"),
    ("typedef struct cloth_bad { uint32_t struct_size; bool flag; } cloth_bad;", "a bool field"),
    ("typedef void cloth_bad_fn(void* user);", "a callback type without CLOTH_CALL"),
    ("#define CLOTH_BAD (CLOTH_MAX_WORLDS * 2)", "a macro that is not a number"),
    ("static inline uint32_t cloth_bad(uint32_t x) { return x; }", "an inline function that is not an id equality"),
    ("static inline bool cloth_bad_id_equal(cloth_id a, cloth_id b) { return a.index1 == b.index1; }",
     "an id equality that skips fields"),
    ("typedef struct cloth_bad { uint32_t struct_size; cloth_id ids[4]; } cloth_bad;", "an array of structs"),
    ("typedef struct cloth_bad { uint32_t struct_size; } cloth_bad;", "a struct no cloth_struct_kind names"),
    ("CLOTH_API const float* CLOTH_CALL cloth_bad(void);", "a returned pointer that is not a string"),
    ("CLOTH_API cloth_result CLOTH_CALL cloth_bad(float** out);", "a pointer to a pointer"),
]


def main():
    header = os.path.join(HERE, "..", "..", "..", "include", "cloth", "cloth.h")
    out = sys.argv[1] if len(sys.argv) > 1 else "."
    os.makedirs(out, exist_ok=True)
    text = open(header, encoding="utf-8").read()
    generate.generate(header)  # the header itself binds
    marker = '#ifdef __cplusplus\n} /* extern "C" */'
    if marker not in text:
        print("refusals.py: cloth.h has no closing extern \"C\" block to splice before", file=sys.stderr)
        return 1
    bad = os.path.join(out, "bad.h")
    for declaration, why in CASES:
        with open(bad, "w", encoding="utf-8") as f:
            f.write(text.replace(marker, declaration + "\n\n" + marker))
        try:
            generate.generate(bad)
        except generate.BindError as e:
            print("refused, %s: %s" % (why, e))
            continue
        print("refusals.py: FAIL: the generator accepted %s" % why, file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
