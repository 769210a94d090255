#!/usr/bin/env bash
# The sanitizer builds (README "Hardening"):
#   scripts/run-sanitizers.sh asan [ctest args]       build/asan: AddressSanitizer + UBSan (and
#                                                     LSan), the CI scope below
#   scripts/run-sanitizers.sh asan-full [ctest args]  the same build, every test (nightly.sh)
#   scripts/run-sanitizers.sh tsan [ctest args]       build/tsan: the tests of the background
#                                                     workers under ThreadSanitizer (nightly.sh)
# The CI scope, measured to fit CI's 30 minutes on two cores: every test that needs no display
# (core, fuzz regressions, the UI's files and documents rooms: scene and library files, undo, the
# documents, the library kill test) except the long accuracy sweeps (numerical loops over code the
# other core tests run too: 7 to 250 s each under ASan, 780 s together; the CPU models of the GGX
# lookups, the truth's tolerance sweep and the split sum's published table: 15 to 27 s each), and
# the OpenGL tests that read users' files or run the workers (opening, saving, the library
# command, mesh import, early environments). asan-full runs everything, the 90 OpenGL tests included.
# The options and suppressions are in tests/sanitizers/ and set by the test presets; they are
# exported here too because the build runs the test executables (test discovery).
set -euo pipefail
cd "$(dirname "$0")/.."
kind=${1:?usage: run-sanitizers.sh asan|asan-full|tsan [ctest args]}
shift
sup=$PWD/tests/sanitizers
preset=$kind
case "$kind" in
  asan|asan-full)
    preset=asan
    # Leak checking is on by default; the OpenGL test binary turns it off for itself and the
    # programs it starts (Mesa's unloaded driver: tests/ui/main.cpp).
    export ASAN_OPTIONS="abort_on_error=1"
    export LSAN_OPTIONS="suppressions=$sup/lsan.supp:print_suppressions=0"
    export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1:suppressions=$sup/ubsan.supp" ;;
  tsan)
    export TSAN_OPTIONS="suppressions=$sup/tsan.supp:halt_on_error=1:second_deadlock_stack=1" ;;
  *) echo "run-sanitizers: asan, asan-full or tsan, not '$kind'" >&2; exit 2 ;;
esac
# clang and its sanitizer and libFuzzer runtimes (a recommendation of clang, so named) are not in
# scripts/install-deps.sh's dev set.
scripts/install-clang.sh
source scripts/sanitizer-env.sh
cmake --preset "$preset" >/dev/null
if [ "$kind" = asan ]; then
  # The CI scope's binaries only (and the programs they start, their dependencies): not the
  # OpenGL picture tests, the benchmarks or the window program, which it does not run (about a
  # minute of CI's two cores; asan-headless leaves out the picture tests' NOT_BUILT placeholder).
  cmake --build --preset "$preset" -j"$(nproc)" --target mipgloss_ibl_tests mipgloss_io_tests mipgloss_scene_tests \
    mipgloss_assets_tests mipgloss_app_tests mipgloss_ui_files_tests mipgloss_ui_documents_tests mipgloss_ui_tests \
    mipgloss_app_cli_tests mipgloss_fuzz_regressions mipgloss_sanitizer_tests
else
  cmake --build --preset "$preset" -j"$(nproc)"
fi
export QT_QPA_PLATFORM=xcb
run() { xvfb-run -a -s "-screen 0 1280x1024x24 -noreset" ctest -j"$(nproc)" "$@"; }
if [ "$kind" = asan ]; then
  # The headless part's filter is its preset's (CMakePresets.json says why not -LE here).
  gl_files='^(OpenFiles|LibraryDocument|LibraryCommand|MeshImporter|EnvironmentEarly|Saving)\.|^MainWindow\.Bad|^LookDevWindow\.(MeshesOpened|Exports|Compare|ABroken)'
  ctest --preset asan-headless -j"$(nproc)" "$@"
  run --preset asan -L gl -R "$gl_files" "$@"
else
  run --preset "$preset" "$@"
fi
