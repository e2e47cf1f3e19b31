#!/usr/bin/env bash
# The packages scripts/package makes from this build tree, checked as a user
# meets them (ctest cloth_package.*):
#  - the Linux archive holds the header, both libraries, the CMake package,
#    cloth.pc, the API reference, README.md and CHANGELOG.md, and a fresh
#    CMake project and a pkg-config build consume it unpacked
#    (tests/install/check.sh); with a Windows build, the Windows archive
#    holds its install tree (cloth.dll, libcloth.dll.a, libcloth.a, the CMake
#    package, cloth.pc, the header), cloth.lib and cloth.def, the API
#    reference, README.md and CHANGELOG.md;
#  - the Unity tarball unpacks to package/ with package.json (name, the
#    header's ABI version, displayName, unity), a .meta with a unique GUID
#    for every file and folder outside Samples~, the plugin's import settings
#    enabling Linux x86_64, and a plugin that needs only libc, libm and the
#    loader and exports exactly cloth.h's functions;
#  - a fresh Mono console project made of nothing but the unpacked Runtime/
#    (compiled as its .asmdef says) and the plugin next to the program
#    compiles without -unsafe and runs UnityPackageConsumer.cs, which checks
#    the numbers, and its first scene ends in the same position bits as the
#    same scene through cloth.h (package_scene.c);
#  - with a Windows build tree (scripts/windows; ctest cloth_windows.unity_package),
#    the package also holds that tree's cloth.dll, byte for byte, whose
#    import settings enable it for the Windows x86_64 player and editor and
#    for nothing else, as libcloth.so's do for Linux; without one, no cloth.dll.
# Usage: check_packages.sh BUILD_DIR SOURCE_DIR [WINDOWS_BUILD_DIR]
set -euo pipefail
build="$1"
root="$2"
windows="${3:-}"
here="$root/tests/package"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
fail() { echo "check_packages: $*" >&2; exit 1; }

"$root/scripts/package" --no-build "$build" "$work/dist" $windows >/dev/null
header="$root/include/cloth/cloth.h"
part() { sed -n "s/^#define CLOTH_VERSION_$1 \([0-9]*\)$/\1/p" "$header"; }
version="$(part MAJOR).$(part MINOR).$(part PATCH)"

# The Linux archive.
linux="cloth-$version-linux-x86_64"
tar -tzf "$work/dist/$linux.tar.gz" >"$work/linux.txt"
for entry in include/cloth/cloth.h lib/libcloth.so lib/libcloth.a lib/cmake/cloth/clothConfig.cmake \
             lib/cmake/cloth/clothTargets.cmake lib/pkgconfig/cloth.pc doc/html/index.html README.md CHANGELOG.md; do
    grep -qx "$linux/$entry" "$work/linux.txt" || fail "$linux.tar.gz lacks $entry"
done
echo "ok - $linux.tar.gz: header, libraries, CMake package, cloth.pc, API reference, README, CHANGELOG ($(wc -l <"$work/linux.txt") entries)"
# A fresh CMake project (and a pkg-config build) consumes the unpacked archive.
tar -C "$work" -xzf "$work/dist/$linux.tar.gz"
"$root/tests/install/check.sh" --prefix "$work/$linux" "$root/tests/install"

# The Windows archive, with a Windows build: the DLL byte for byte, its
# import libraries for MSVC and MinGW, the header and the documents.
windows_archive="$work/dist/cloth-$version-windows-x86_64.tar.gz"
if [ -n "$windows" ]; then
    win="cloth-$version-windows-x86_64"
    tar -C "$work" -xzf "$windows_archive"
    for entry in include/cloth/cloth.h bin/cloth.dll lib/cloth.lib lib/cloth.def lib/libcloth.dll.a lib/libcloth.a \
                 lib/cmake/cloth/clothConfig.cmake lib/pkgconfig/cloth.pc doc/html/index.html README.md CHANGELOG.md; do
        [ -f "$work/$win/$entry" ] || fail "$win.tar.gz lacks $entry"
    done
    cmp -s "$work/$win/bin/cloth.dll" "$windows/src/cloth.dll" || fail "$win.tar.gz's cloth.dll is not the build's"
    cmp -s "$work/$win/include/cloth/cloth.h" "$header" || fail "$win.tar.gz's cloth.h is not the source's"
    echo "ok - $win.tar.gz: cloth.dll (the build's), cloth.lib, cloth.def, libcloth.dll.a, libcloth.a, CMake package, cloth.pc, header, API reference, README, CHANGELOG"
elif [ -e "$windows_archive" ]; then
    fail "a Windows archive without a Windows build"
fi

# The Unity tarball, unpacked as the Package Manager does.
mkdir -p "$work/unpacked"
tar -C "$work/unpacked" -xzf "$work/dist/com.cloth.clothsharp-$version.tgz"
package="$work/unpacked/package"
python3 - "$package" "$version" "$windows" <<'PY'
import filecmp, json, os, sys
package, version, windows = sys.argv[1], sys.argv[2], sys.argv[3]
manifest = json.load(open(os.path.join(package, "package.json")))
assert manifest["name"] == "com.cloth.clothsharp", manifest["name"]
assert manifest["version"] == version, (manifest["version"], version)
assert manifest["displayName"] and manifest["unity"] == "2021.2", manifest
assert all(os.path.isdir(os.path.join(package, s["path"])) for s in manifest["samples"]), manifest["samples"]
guids = {}
for folder, dirs, files in os.walk(package):
    dirs[:] = [d for d in dirs if not d.endswith("~")]  # Unity imports nothing under Samples~
    for name in dirs + [f for f in files if not f.endswith(".meta")]:
        path = os.path.join(folder, name)
        meta = path + ".meta"
        assert os.path.isfile(meta), "no .meta for " + os.path.relpath(path, package)
        lines = open(meta).read().splitlines()
        guid = [l.split(": ")[1] for l in lines if l.startswith("guid: ")][0]
        assert len(guid) == 32 and guid not in guids, (path, guid)
        guids[guid] = path
def enabled(meta, platform):
    return "Standalone: %s\n    second:\n      enabled: 1" % platform in meta
plugins = os.path.join(package, "Runtime/Plugins/x86_64")
plugin_meta = open(os.path.join(plugins, "libcloth.so.meta")).read()
assert enabled(plugin_meta, "Linux64"), "libcloth.so is not enabled for Linux x86_64"
assert "OS: Linux" in plugin_meta and not enabled(plugin_meta, "Win64"), "libcloth.so is enabled off Linux"
dll = os.path.join(plugins, "cloth.dll")
if windows:
    assert filecmp.cmp(dll, os.path.join(windows, "src/cloth.dll"), shallow=False), "cloth.dll is not the Windows build's"
    dll_meta = open(dll + ".meta").read()
    assert enabled(dll_meta, "Win64"), "cloth.dll is not enabled for Windows x86_64"
    assert "OS: Windows" in dll_meta, "cloth.dll is not enabled for the editor on Windows"
    assert not enabled(dll_meta, "Linux64") and not enabled(dll_meta, "Win"), "cloth.dll is enabled off Windows x86_64"
    assert "Windows x86_64" in manifest["description"], manifest["description"]
    print("ok - cloth.dll is the Windows build's, enabled for the Windows x86_64 player and editor only")
else:
    assert not os.path.exists(dll), "a cloth.dll in a package made without a Windows build"
for needed in ["Runtime/ClothNative.g.cs", "Runtime/ClothSharp.g.cs", "Runtime/ClothSharp.cs", "Runtime/ClothSharp.asmdef"]:
    assert os.path.isfile(os.path.join(package, needed)), needed
asmdef = json.load(open(os.path.join(package, "Runtime/ClothSharp.asmdef")))
assert asmdef["allowUnsafeCode"] is True
print("ok - package.json %s %s, %d .meta files with unique GUIDs, the plugin enabled for Linux x86_64" %
      (manifest["name"], manifest["version"], len(guids)))
PY
python3 "$root/tests/library/check_library.py" "$package/Runtime/Plugins/x86_64/libcloth.so" "$header" \
    --needed libc.so.6,libm.so.6,ld-linux-x86-64.so.2

# A fresh console project from the package alone.
project="$work/project"
mkdir -p "$project"
mcs -langversion:7.2 -unsafe -nologo -warnaserror+ -r:System.Numerics -target:library -out:"$project/ClothSharp.dll" \
    "$package"/Runtime/*.cs
mcs -langversion:7.2 -nologo -warnaserror+ -r:System.Numerics -r:"$project/ClothSharp.dll" \
    -out:"$project/Consumer.exe" "$here/UnityPackageConsumer.cs"
cp "$package/Runtime/Plugins/x86_64/libcloth.so" "$project/"
(cd "$project" && env -u LD_LIBRARY_PATH mono Consumer.exe) | tee "$work/consumer.txt"
# The same values as the native library: the C# program's first scene and
# package_scene.c's, through cloth.h, end in the same position bits.
native="$("$build/tests/package/cloth_package_scene")"
grep -qx "$native" "$work/consumer.txt" || fail "the package's scene gives other positions than cloth.h's ($native)"
echo "ok - the package's scene ends in the same position bits as through cloth.h ($native)"
