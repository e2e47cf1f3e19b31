#!/usr/bin/env python3
"""What a shared build of libcloth needs and what it exports (ctest cloth_library.*).

    check_library.py LIB HEADER --needed NAME[,NAME...] [--expect-failure needed|exports]

  needed   every DT_NEEDED entry of LIB (readelf -d) is one of --needed: the
           library loads on a machine with only those (no tinyobjloader, and
           for the plugin build no C++ runtime).
  exports  the defined dynamic symbols of LIB (nm -D --defined-only) are
           exactly the functions cloth.h declares (CLOTH_API ... CLOTH_CALL
           cloth_x(...)): only the C API leaves the library, all of it does.

Prints the NEEDED entries, the number of exports and the newest GLIBC symbol
version LIB requires. Exits 1 when a check fails. With --expect-failure the
named check must fail (and the test passes): it shows the check can fail.
"""
import argparse
import re
import subprocess
import sys


def needed_entries(lib):
    out = subprocess.run(["readelf", "-d", "-W", lib], check=True, capture_output=True, text=True).stdout
    return re.findall(r"\(NEEDED\)\s+Shared library: \[([^\]]+)\]", out)


def exported_symbols(lib):
    out = subprocess.run(["nm", "-D", "--defined-only", lib], check=True, capture_output=True, text=True).stdout
    symbols = set()
    for line in out.splitlines():
        parts = line.split()
        if len(parts) < 2:
            continue
        kind, name = parts[-2], parts[-1]
        if kind == "A":  # a version definition (CLOTH_1 of cmake/cloth.map), not code or data
            continue
        symbols.add(name.split("@")[0])
    return symbols


def declared_functions(header):
    with open(header, encoding="utf-8") as f:
        text = re.sub(r"/\*.*?\*/|//[^\n]*", " ", f.read(), flags=re.S)
    return set(re.findall(r"\bCLOTH_API\b[^;{}#]*?\bCLOTH_CALL\s+(cloth_\w+)\s*\(", text))


def newest_glibc(lib):
    out = subprocess.run(["objdump", "-T", lib], check=True, capture_output=True, text=True).stdout
    versions = {tuple(int(x) for x in v.split(".")) for v in re.findall(r"\bGLIBC_([0-9.]+)\b", out)}
    return ".".join(str(x) for x in max(versions)) if versions else "none"


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("lib")
    ap.add_argument("header")
    ap.add_argument("--needed", required=True, help="the allowed DT_NEEDED entries, comma-separated")
    ap.add_argument("--expect-failure", choices=["needed", "exports"])
    args = ap.parse_args()
    allowed = set(args.needed.split(","))
    failed = set()

    needed = needed_entries(args.lib)
    print("%s NEEDED: %s" % (args.lib, ", ".join(needed)))
    extra = [n for n in needed if n not in allowed]
    if extra:
        print("FAIL needed: %s beyond the allowed %s" % (", ".join(extra), ", ".join(sorted(allowed))))
        failed.add("needed")

    exported = exported_symbols(args.lib)
    declared = declared_functions(args.header)
    if len(declared) < 50:
        print("FAIL exports: only %d functions found in %s (the header's pattern changed?)" % (len(declared), args.header))
        failed.add("exports")
    foreign = sorted(exported - declared)
    missing = sorted(declared - exported)
    if foreign:
        print("FAIL exports: %d exported symbols cloth.h does not declare, e.g. %s" % (len(foreign), ", ".join(foreign[:5])))
        failed.add("exports")
    if missing:
        print("FAIL exports: %d functions of cloth.h not exported, e.g. %s" % (len(missing), ", ".join(missing[:5])))
        failed.add("exports")
    print("%d exported symbols, %d functions in cloth.h; newest GLIBC symbol version needed: %s"
          % (len(exported), len(declared), newest_glibc(args.lib)))

    if args.expect_failure:
        if args.expect_failure in failed:
            print("ok: the %s check failed, as expected" % args.expect_failure)
            return 0
        print("FAIL: the %s check passed where it should have failed" % args.expect_failure)
        return 1
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
