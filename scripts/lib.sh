# Shared by scripts/demo and scripts/test: install missing Debian packages,
# then configure and build one build tree. Source it; do not run it.
set -euo pipefail

CLOTH_ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
CLOTH_PACKAGES=(cmake ninja-build g++ pkg-config libeigen3-dev libbullet-dev libgtest-dev libbenchmark-dev
                libstb-dev libtinyobjloader-dev libcli11-dev)

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

# cloth_build BUILD_DIR [cmake options...]
cloth_build() {
    local dir="$1"
    shift
    cmake -S "$CLOTH_ROOT" -B "$dir" -G Ninja -DCMAKE_BUILD_TYPE=Release "$@" >/dev/null
    cmake --build "$dir" --parallel "$(nproc)"
}
