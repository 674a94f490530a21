#!/usr/bin/env bash
# Installs what evoslam needs to build, test and benchmark, from Debian 12 packages only.
# Idempotent and non-interactive: packages already present are not touched.
# Usage: deploy/install-deps.sh [--dev]
#   --dev  also clang-format (the code's style) and clang (deploy/fuzz.sh's libFuzzer targets),
#          which building and testing do not need.
set -euo pipefail

packages=(
  build-essential cmake ninja-build pkg-config git bzip2
  libeigen3-dev libzmq3-dev cppzmq-dev libsodium-dev libprotobuf-dev protobuf-compiler
  libspdlog-dev libfmt-dev libgtest-dev libgmock-dev libbenchmark-dev libcli11-dev
  zlib1g-dev libbz2-dev libpng-dev libsqlite3-dev libpagmo-dev
  libcpp-httplib-dev  # the HTTP server of evoslam-coordinator --metrics
  python3  # docs/gen-configuration.py, and the test that docs/configuration.md is fresh
  iproute2  # ip, for the network namespaces of deploy/netns-test.sh
)
case "${1:-}" in
  "") ;;
  --dev) packages+=(clang-format clang) ;;
  *) echo "install-deps: unknown option '$1' (the only option is --dev)" >&2; exit 2 ;;
esac

missing=()
for p in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done

if ((${#missing[@]} == 0)); then
  echo "install-deps: all ${#packages[@]} packages present"
  exit 0
fi

if [[ $(id -u) -ne 0 ]]; then
  echo "install-deps: missing packages: ${missing[*]}; run this script as root" >&2
  exit 1
fi

echo "install-deps: installing ${missing[*]}"
export DEBIAN_FRONTEND=noninteractive
apt-get update -qq
apt-get install -y -qq --no-install-recommends "${missing[@]}"
