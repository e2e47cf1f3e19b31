# Shared by scripts/demo and scripts/test: install missing Debian packages,
# then configure and build one build tree. Source it; do not run it.
set -euo pipefail

CLOTH_ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
CLOTH_PACKAGES=(cmake ninja-build g++ pkg-config libeigen3-dev libbullet-dev libgtest-dev libbenchmark-dev
                libstb-dev libtinyobjloader-dev libcli11-dev abigail-tools nlohmann-json3-dev gnuplot-nox
                doxygen libxxhash-dev)
# What the checks add (scripts/test, scripts/format-check, scripts/tidy): the
# second compiler, the format and naming checks, MinGW-w64 for the public
# header's _WIN32 branch, and Python with Mono's C# compiler and runtime for
# the C# binding (bindings/csharp). `cloth_install_packages "${CLOTH_CHECK_PACKAGES[@]}"`.
CLOTH_CHECK_PACKAGES=(clang clang-format clang-tidy gcc-mingw-w64-x86-64-win32 python3 mono-mcs mono-runtime)
# What scripts/windows adds: MinGW-w64's C++ compiler (posix threads, for
# std::thread) and binutils (dlltool), gendef (mingw-w64-tools), wine64, and
# GoogleTest's sources to compile for Windows.
CLOTH_WINDOWS_PACKAGES=(g++-mingw-w64-x86-64-posix binutils-mingw-w64-x86-64 mingw-w64-tools wine64 googletest python3)

cloth_install_packages() {
    local missing=()
    for package in "${CLOTH_PACKAGES[@]}" "$@"; do
        dpkg-query -W -f='${Status}' "$package" 2>/dev/null | grep -q "install ok installed" || missing+=("$package")
    done
    [ ${#missing[@]} -eq 0 ] && return 0
    echo "== installing Debian packages: ${missing[*]}"
    local sudo=""
    [ "$(id -u)" -ne 0 ] && sudo="sudo"
    $sudo apt-get update -qq
    DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
}

# The second compiler's tree, build-clang (scripts/test, scripts/tidy).
CLOTH_CLANG_OPTIONS=(-DCMAKE_C_COMPILER=clang -DCMAKE_CXX_COMPILER=clang++)

# cloth_configure BUILD_DIR [cmake options...]: configure a Release tree with
# tests, samples and benchmarks on (so demo and test share one build tree).
cloth_configure() {
    local dir="$1"
    shift
    cmake -S "$CLOTH_ROOT" -B "$dir" -G Ninja -DCMAKE_BUILD_TYPE=Release -DCLOTH_BUILD_TESTS=ON \
        -DCLOTH_BUILD_SAMPLES=ON -DCLOTH_BUILD_BENCHMARKS=ON "$@" >/dev/null
}

# cloth_build BUILD_DIR TARGET [cmake options...]: configure as above and
# build TARGET ("all" for everything; several targets separated by spaces).
cloth_build() {
    local dir="$1" target="$2"
    shift 2
    cloth_configure "$dir" "$@"
    cmake --build "$dir" --target $target --parallel "$(nproc)"
}
