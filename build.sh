#!/usr/bin/env bash
# gjkdem set-up, build and run. Usage:
#   ./build.sh run     install what is missing, build, run the main job: the built-in default
#                      scene (2,000 polyhedra through a hopper; outputs in ./out, replaced each time)
#   ./build.sh test    install what is missing, build, run every test
#   ./build.sh bench   install the peer libraries too, build, run the benchmarks
# Packages come from Debian's archive (apt-get) and, for the browser viewer's page (web/), from
# the npm registry through web/package-lock.json (npm ci); nothing is downloaded elsewhere.
set -euo pipefail
cd "$(dirname "$0")"

mode="${1:-run}"
base_pkgs=(cmake make g++ pkg-config libgmp-dev libgtest-dev libbenchmark-dev nlohmann-json3-dev libcli11-dev libeigen3-dev libtomlplusplus-dev
           libcpp-httplib-dev
           python3 python3-dev pybind11-dev python3-numpy python3-scipy
           libopenmpi-dev openmpi-bin)  # mpirun -np N gjkdem run (docs/scaling.md)
# VTK's own reader checks the frames in tests/cli_run.sh; pytest runs tests/python; the Python
# example plots with matplotlib.
# Chromium runs the viewer's browser tests (tests/browser), headless. pip, setuptools and venv:
# the offline `pip install .` of the Python module (tests/pip_install.sh). CGAL: the oracle of
# the non-convex overlap (tests/contact/surface_overlap_cgal_test.cpp).
test_pkgs=(python3-vtk9 python3-pytest python3-matplotlib chromium python3-pip python3-setuptools python3-venv
           libcgal-dev)
peer_pkgs=(libccd-dev libfcl-dev libbullet-dev libcgal-dev yade)  # yade: bench/yade_*.py

install_missing() {
  local missing=()
  for p in "$@"; do dpkg -s "$p" >/dev/null 2>&1 || missing+=("$p"); done
  [ ${#missing[@]} -eq 0 ] && return 0
  local sudo=""
  [ "$(id -u)" -ne 0 ] && sudo="sudo"
  echo "build.sh: installing ${missing[*]}"
  $sudo apt-get update -q
  DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -q --no-install-recommends "${missing[@]}"
}

# The viewer's page: three.js (and, for the tests, playwright-core) as web/package-lock.json
# pins them. Node.js and npm come from Debian when the machine has none.
web_packages() {
  command -v npm >/dev/null 2>&1 || install_missing nodejs npm
  if ! cmp -s web/package-lock.json web/node_modules/.gjkdem-lock; then
    (cd web && npm ci --no-audit --no-fund)
    cp web/package-lock.json web/node_modules/.gjkdem-lock
  fi
}

build() {
  cmake -S . -B build -DCMAKE_BUILD_TYPE=Release "$@"
  cmake --build build -j"$(nproc)"
}

case "$mode" in
  run)
    install_missing "${base_pkgs[@]}"
    web_packages
    build
    build/gjkdem run --out out --overwrite
    echo "build.sh: to watch it in a browser: build/gjkdem view out"
    ;;
  test)
    install_missing "${base_pkgs[@]}" "${test_pkgs[@]}"
    web_packages
    build
    ctest --test-dir build --output-on-failure -j"$(nproc)"
    ;;
  bench)
    install_missing "${base_pkgs[@]}" "${peer_pkgs[@]}"
    build -DGJKDEM_BUILD_CGAL_BENCH=ON
    for q in intersect distance penetration contact; do
      build/gjkdem bench --in examples/pairs.jsonl --query "$q" --repeat 20
    done
    build/bench/bench_peers
    build/bench/bench_cgal
    build/bench/bench_queries --benchmark_min_time=0.3
    ;;
  *)
    echo "usage: $0 run|test|bench" >&2
    exit 2
    ;;
esac
