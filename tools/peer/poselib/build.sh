# Sourced by the peer scripts: build_against_poselib CHECKOUT SOURCE.cc OUTPUT builds
# PoseLib from the checkout (CMake, Release, PoseLib's own flags; needs cmake and Eigen 3,
# e.g. Debian's cmake and libeigen3-dev) into CHECKOUT/_build and compiles one driver of
# ours against it.
build_against_poselib() {
  local poselib=$1 source=$2 output=$3
  cmake -S "$poselib" -B "$poselib/_build" -DCMAKE_BUILD_TYPE=Release -DWITH_BENCHMARK=OFF \
    -DPYTHON_PACKAGE=OFF >/dev/null
  cmake --build "$poselib/_build" -j "$(nproc)" >/dev/null
  g++ -O3 -std=c++17 -I"$poselib" -I"$poselib/_build/generated_headers" -I/usr/include/eigen3 \
    "$source" -L"$poselib/_build/PoseLib" -lPoseLib -o "$output"
}
