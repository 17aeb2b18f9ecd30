#!/usr/bin/env bash
# The CMake package end to end: installs the build into a fresh prefix (`cmake --install`),
# configures and builds examples/cpp against it (find_package(ContactLab) through
# CMAKE_PREFIX_PATH) and runs the program on a small procedural scene with the paper's model and
# a baseline, checking the force it prints; an unknown model must fail naming it. The example
# sets no C++ standard, so it builds only if the package's target carries C++20.
# Usage: package_test.sh BUILD_DIR SOURCE_DIR WORKDIR CMAKE CXX_COMPILER
set -uo pipefail
build=$1; source=$2; work=$3; cmake=$4; cxx=$5
rm -rf "$work" && mkdir -p "$work" || exit 1
prefix=$work/prefix
fail() { echo "FAILED: $*"; exit 1; }

# Install, and the package's files where find_package looks.
"$cmake" --install "$build" --prefix "$prefix" > "$work/install.log" 2>&1 || { cat "$work/install.log"; fail "cmake --install"; }
for f in lib/cmake/ContactLab/ContactLabConfig.cmake lib/cmake/ContactLab/ContactLabConfigVersion.cmake \
         lib/cmake/ContactLab/ContactLabTargets.cmake lib/libcontactlab_contact.a \
         include/contactlab/contact/contact_model.h include/contactlab/contact/register_contact_models.h; do
  [ -f "$prefix/$f" ] || fail "the install lacks $f"
done

# The example, against the installed package only (no build tree on any path).
launcher=()
if command -v ccache > /dev/null; then launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache); fi
generator=()
if command -v ninja > /dev/null; then generator=(-G Ninja); fi
start=$(date +%s)
"$cmake" -S "$source/examples/cpp" -B "$work/example" "${generator[@]}" -DCMAKE_BUILD_TYPE=Release \
    -DCMAKE_CXX_COMPILER="$cxx" "${launcher[@]}" -DCMAKE_EXPORT_COMPILE_COMMANDS=ON -DCMAKE_PREFIX_PATH="$prefix" > "$work/configure.log" 2>&1 ||
  { cat "$work/configure.log"; fail "configuring examples/cpp against $prefix"; }
"$cmake" --build "$work/example" --parallel 1 > "$work/build.log" 2>&1 || { cat "$work/build.log"; fail "building examples/cpp"; }
echo "example configured and built in $(( $(date +%s) - start )) s"
[ -f "$work/example/compile_commands.json" ] || fail "no compile_commands.json for the example"
grep -Eq -- "(-I|-isystem )$source(/src)?[ \"]" "$work/example/compile_commands.json" &&
  fail "the example was compiled with the source tree's include folders"
# examples/cpp sets no C++ standard: the one the headers need comes with ContactLab::contactlab
# (the compiler's default, gnu++17 for GCC 12, lacks std::span).
grep -Eq -- "-std=(c|gnu)\+\+(20|2a|23|2b)" "$work/example/compile_commands.json" ||
  fail "the example was not compiled as C++20: the package does not carry the standard its headers need"
grep -Eq "^[^#]*CMAKE_CXX_STANDARD" "$source/examples/cpp/CMakeLists.txt" &&
  fail "examples/cpp sets CMAKE_CXX_STANDARD, so this test cannot see whether the package carries it"

# A ball 0.5 mm into a plate: the force on the plate (field body) points down, -z.
cat > "$work/scene.yaml" <<'YAML'
name: package-test
bodies:
  - name: ball
    mesh: "sphere:0.02,2"
    pose: [0, 0, 0.0195, 1, 0, 0, 0]
    role: pointshell
    pointshell: {points: 256, levels: 2, seed: 3}
  - name: plate
    mesh: "box:0.05,0.05,0.01,1"
    pose: [0, 0, -0.01, 1, 0, 0, 0]
    role: field
    field: {resolution: 16}
model: {k_C: 1000}
models: [pointshell]
YAML
export CONTACTLAB_CACHE=$work/cache
status=0
for model in pointshell fcl; do
  out=$("$work/example/contact_query" "$work/scene.yaml" $( [ $model = pointshell ] || echo $model ) 2> "$work/$model.err")
  echo "$out"
  if ! echo "$out" | grep -Eq "^$model: force on plate = \[[-0-9.e]+, [-0-9.e]+, -[0-9.e]+\] N$"; then
    cat "$work/$model.err"; echo "FAILED: $model: expected a downward force on the plate"; status=1
  fi
done
if "$work/example/contact_query" "$work/scene.yaml" no-such-model > "$work/bad.out" 2>&1; then
  echo "FAILED: an unknown model was accepted"; status=1
elif ! grep -q "no-such-model" "$work/bad.out"; then
  cat "$work/bad.out"; echo "FAILED: the error does not name the unknown model"; status=1
fi
exit $status
