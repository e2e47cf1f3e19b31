# Shared by scripts/demo and scripts/test: install missing Debian packages,
# then configure and build one build tree. Source it; do not run it.
set -euo pipefail

CLOTH_ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
CLOTH_PACKAGES=(cmake ninja-build g++ pkg-config libeigen3-dev libbullet-dev libgtest-dev libbenchmark-dev
                libstb-dev libtinyobjloader-dev libcli11-dev abigail-tools nlohmann-json3-dev gnuplot-nox
                doxygen libxxhash-dev)

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

# cloth_build BUILD_DIR TARGET [cmake options...]: configure (tests, samples
# and benchmarks on, so demo and test share one build tree) and build TARGET
# ("all" for everything; several targets separated by spaces).
cloth_build() {
    local dir="$1" target="$2"
    shift 2
    cmake -S "$CLOTH_ROOT" -B "$dir" -G Ninja -DCMAKE_BUILD_TYPE=Release -DCLOTH_BUILD_TESTS=ON \
        -DCLOTH_BUILD_SAMPLES=ON -DCLOTH_BUILD_BENCHMARKS=ON "$@" >/dev/null
    cmake --build "$dir" --target $target --parallel "$(nproc)"
}
