#!/usr/bin/env bash
# Installs what evoslam needs to build, test and benchmark, from Debian 12 packages only.
# Idempotent and non-interactive: packages already present are not touched.
set -euo pipefail

packages=(
  build-essential cmake ninja-build pkg-config git bzip2
  libeigen3-dev libzmq3-dev cppzmq-dev libsodium-dev libprotobuf-dev protobuf-compiler
  libspdlog-dev libfmt-dev libgtest-dev libgmock-dev libbenchmark-dev libcli11-dev
  zlib1g-dev libbz2-dev libpng-dev libsqlite3-dev clang-format clang libpagmo-dev
  python3  # docs/gen-configuration.py, and the test that docs/configuration.md is fresh
  iproute2  # ip, for the network namespaces of deploy/netns-test.sh
)

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
