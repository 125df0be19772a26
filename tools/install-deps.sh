#!/usr/bin/env bash
# Installs exactly the Debian packages ubersim needs that are missing; does
# nothing when all are there, so it is safe to run any number of times.
# Usage: tools/install-deps.sh [--print]   (--print: only list what is missing)
set -euo pipefail

packages=(
  # build
  cmake g++ make pkg-config python3
  # LCM (lcm.pc needs glib's development files; lcm-spy needs Java and jchart2d)
  liblcm-dev liblcm-bin liblcm-java libglib2.0-dev default-jdk-headless libjchart2d-java
  # physics and maths
  libode-dev libeigen3-dev
  # logging, command lines, tests, benchmarks
  libspdlog-dev libfmt-dev libcli11-dev libgtest-dev libgmock-dev libbenchmark-dev
  # isolated multicast tests (unshare, ip)
  util-linux iproute2
  libprotobuf-dev protobuf-compiler  # optional SSL protocol bridge
  # optional DDS bridge
  cyclonedds-dev cyclonedds-tools
  # plots for the validation report and the batch runner's figures
  gnuplot-nox
  # batch experiments (tools/ubersim_batch): Python 3; Dask distributed to spread them over machines
  python3 python3-distributed
  # browser viewer: HTTP/WebSocket server and JSON; headless chromium for its end-to-end test
  libwebsocketpp-dev libasio-dev nlohmann-json3-dev chromium
  # fuzz targets (fuzz/, tools/fuzz.sh): clang with libFuzzer and the sanitizers
  clang libclang-rt-14-dev
  # lint tests (tests/lint): the tree stays formatted with .clang-format, and clang-tidy
  # finds nothing with the checks .clang-tidy enables (Debian 12: both version 14)
  clang-format clang-tidy
  # first-minutes test (tests/e2e/test_first_minutes.sh): a real terminal, and the desktop opener
  tmux xdg-utils
  # Python module (python/, docs/python.md): pybind11, Python's headers, numpy, pytest;
  # venv, pip, setuptools and wheel for `pip install --no-build-isolation .`
  pybind11-dev python3-pybind11 python3-dev python3-numpy python3-pytest
  python3-venv python3-pip python3-setuptools python3-wheel
)

missing=()
for package in "${packages[@]}"; do
  status=$(dpkg-query -W -f='${Status}' "$package" 2>/dev/null || true)
  [ "$status" = "install ok installed" ] || missing+=("$package")
done

if [ "${1:-}" = "--print" ]; then
  printf '%s\n' "${missing[@]}"
  exit 0
fi
if [ ${#missing[@]} -eq 0 ]; then
  echo "install-deps: all ${#packages[@]} packages present"
  exit 0
fi

echo "install-deps: installing ${missing[*]}"
sudo=""
[ "$(id -u)" -eq 0 ] || sudo="sudo"
export DEBIAN_FRONTEND=noninteractive
$sudo apt-get update -qq
$sudo apt-get install -y -qq --no-install-recommends "${missing[@]}"
