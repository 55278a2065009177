#!/usr/bin/env bash
# One entry point for a fresh Debian 12 machine:
#   tools/dev.sh run [SCENE]   install what is missing, build, start the previewer
#   tools/dev.sh test          install what is missing, build, run the whole test suite
#   tools/dev.sh web           install what is missing, build the web page: build-web/phonglab.html
#   tools/dev.sh serve [PORT]  the web page served cross-origin isolated (on every core) at localhost
#   tools/dev.sh deps|build    the first steps alone
set -euo pipefail
cd "$(dirname "$0")/.."

PACKAGES=(
  build-essential cmake ninja-build pkg-config git
  libglm-dev nlohmann-json3-dev libstb-dev libtinyobjloader-dev
  libgtest-dev libembree-dev
  libglfw3-dev libimgui-dev python3-glad libgl-dev libgl1-mesa-dri
  xvfb xauth xdotool imagemagick fonts-dejavu-core desktop-file-utils man-db dpkg-dev
  clang libclang-rt-14-dev chromium shared-mime-info libxml2-utils emscripten
  libsimde-dev g++-aarch64-linux-gnu qemu-user universal-ctags
)

as_root() { if [ "$(id -u)" -eq 0 ]; then "$@"; else sudo "$@"; fi; }

deps() {
  local missing=()
  for p in "${PACKAGES[@]}"; do
    dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
  done
  if [ ${#missing[@]} -gt 0 ]; then
    echo "== installing: ${missing[*]}"
    as_root apt-get update -qq
    as_root env DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends "${missing[@]}"
  fi
  # npm for the web page's test packages (tests/web); a Node.js from elsewhere brings its own.
  if ! command -v npm >/dev/null; then
    as_root env DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends npm
  fi
}

# The web page, build-web/phonglab.html (Emscripten; apps/web). Emscripten's optimizer needs
# Debian's node modules (acorn) when the `node` on PATH is another one.
# Two modules in the one page: the threaded one (build-web/threads, pthreads) for cross-origin
# isolated pages, carried as text, and the one-thread one for every other page. Unity builds
# (a few files a translation unit) halve Emscripten's build (115 -> 61 s a module on this 2-core
# machine) and give the same page: the same bits, 0.99 of the frame time side by side.
web() {
  export NODE_PATH=/usr/share/nodejs${NODE_PATH:+:$NODE_PATH}
  emcmake cmake -S . -B build-web/threads -G Ninja -DCMAKE_BUILD_TYPE=Release -DCMAKE_UNITY_BUILD=ON \
    -DPHONGLAB_WEB_THREADS=ON >/dev/null
  cmake --build build-web/threads --parallel "$(nproc)"
  emcmake cmake -S . -B build-web -G Ninja -DCMAKE_BUILD_TYPE=Release -DCMAKE_UNITY_BUILD=ON \
    -DPHONGLAB_WEB_THREADS_DIR="$PWD/build-web/threads" >/dev/null
  cmake --build build-web --parallel "$(nproc)"
}

# The page from a local web server that makes it cross-origin isolated: every core renders.
serve() {
  web
  echo "== http://localhost:${1:-8000}/phonglab.html (Ctrl-C stops it)"
  exec /usr/bin/python3 tools/serve_isolated.py build-web "${1:-8000}"
}

# build DIR [cmake args...]
build() {
  local dir=$1; shift
  cmake -S . -B "$dir" -G Ninja -DCMAKE_BUILD_TYPE=Release "$@" >/dev/null
  cmake --build "$dir" --parallel "$(nproc)"
}

run() {
  deps
  build build
  exec build/bin/phonglab "$@"
}

test_all() {
  deps
  local start=$SECONDS
  # The page's build beside the Release build: Emscripten's links and optimiser run on one core,
  # and the other's compiles fill the gaps (its log is printed when it is done).
  echo "== the web page (Emscripten) beside the release build; the page's test packages (puppeteer-core, npm)"
  mkdir -p build-web && (web > build-web/build.log 2>&1) &
  local web_pid=$!
  (cd tests/web && npm ci --no-audit --no-fund --silent)
  # The shipped programs as shipped (a unity build: a few files a translation unit), their numbers'
  # and the command line's unit tests, the previewer under Xvfb, the page in headless Chromium, the
  # bench, the package. The other unit tests run once, in the sanitizer build below.
  build build -DCMAKE_UNITY_BUILD=ON -DPHONGLAB_UNIT_TESTS=shipped -DPHONGLAB_WEB_PAGE="$PWD/build-web/phonglab.html"
  if ! wait "$web_pid"; then cat build-web/build.log; echo "the web page's build failed" >&2; exit 1; fi
  tail -n 3 build-web/build.log
  echo "== release tests (at $((SECONDS - start)) s)"
  (cd build && ctest --output-on-failure --parallel "$(nproc)")

  echo "== aarch64: the core cross-compiled, its NEON packet kernels against its scalar renderer under qemu (at $((SECONDS - start)) s)"
  cmake -S tests/cross -B build-aarch64 -G Ninja -DCMAKE_TOOLCHAIN_FILE="$PWD/tests/cross/aarch64.cmake" >/dev/null
  cmake --build build-aarch64 --parallel "$(nproc)"
  (cd build-aarch64 && ctest --output-on-failure)

  # One clang build serves both the sanitizer run of every unit test and the fuzzers (libFuzzer's
  # coverage instrumentation is the libraries' only, and saves a second full build).
  echo "== AddressSanitizer + UndefinedBehaviorSanitizer build (clang) and every unit test, the soak test (at $((SECONDS - start)) s)"
  # What its tests and the fuzzers run: not the digest (its tests are the Release build's); the bench
  # only because phonglab-cli bench, which test_cli runs, starts it.
  # The sanitizer builds are the test's alone: their libraries and apps compile as unity builds
  # (a few files a translation unit; the test files stay one each), which halves the ThreadSanitizer
  # build (100 -> 54 s on this 2-core machine) and shortens this one.
  CC=clang CXX=clang++ cmake -S . -B build-asan -G Ninja -DPHONGLAB_SANITIZE='address;undefined' -DPHONGLAB_FUZZ=ON \
    -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_UNITY_BUILD=ON >/dev/null
  cmake --build build-asan --parallel "$(nproc)" --target phonglab phonglab-cli phonglab_tests phonglab_shell_tests phonglab_float_loop \
    phonglab_fuzz_scene phonglab_fuzz_obj phonglab_fuzz_lesson phonglab_fuzz_formula phonglab_fuzz_formula_file phonglab_fuzz_image
  (cd build-asan && ASAN_OPTIONS=detect_leaks=1 ctest --output-on-failure --parallel "$(nproc)")

  echo "== ThreadSanitizer: the renderer's threading tests (at $((SECONDS - start)) s)"
  # Only what its tests need: the test binary (not the CLI, the bench, Embree or the digest).
  cmake -S . -B build-tsan -G Ninja -DPHONGLAB_SANITIZE=thread -DPHONGLAB_GUI=OFF -DCMAKE_BUILD_TYPE=RelWithDebInfo \
    -DCMAKE_UNITY_BUILD=ON >/dev/null
  cmake --build build-tsan --parallel "$(nproc)" --target phonglab_tests
  (cd build-tsan && TSAN_OPTIONS=halt_on_error=1 ctest --output-on-failure)

  echo "== fuzzing the scene loader, OBJ + MTL, lesson files, formulas, formula files and images, 15 s side by side (libFuzzer, ASan, UBSan; at $((SECONDS - start)) s)"
  tools/fuzz.sh 15

  echo "== all tests passed in $((SECONDS - start)) s"
}

case "${1:-}" in
  run) shift; run "$@" ;;
  test) test_all ;;
  deps) deps ;;
  build) deps; build build ;;
  web) deps; web ;;
  serve) shift; deps; serve "$@" ;;
  *) echo "usage: tools/dev.sh run [SCENE] | test | web | serve [PORT] | deps | build" >&2; exit 2 ;;
esac
