# Sourced by the scripts that run the sanitizer builds (run-sanitizers.sh, run-fuzz.sh): exports
# ASAN_SYMBOLIZER_PATH (read by ASan, LSan, UBSan and TSan alike) for llvm-symbolizer, or stops
# the run saying what to install. The suppressions in tests/sanitizers/ name functions, which only
# a symbolized stack shows: without the symbolizer they would silently match nothing (issue 22).
# scripts/install-clang.sh installs it (Debian package llvm).
find_symbolizer() {
  if [ -n "${ASAN_SYMBOLIZER_PATH:-}" ]; then
    [ -x "$ASAN_SYMBOLIZER_PATH" ] && return 0
    echo "sanitizer-env: ASAN_SYMBOLIZER_PATH=$ASAN_SYMBOLIZER_PATH is not an executable" >&2
    return 1
  fi
  local candidate
  for candidate in "$(command -v llvm-symbolizer || true)" /usr/lib/llvm-14/bin/llvm-symbolizer; do
    if [ -n "$candidate" ] && [ -x "$candidate" ]; then
      export ASAN_SYMBOLIZER_PATH=$candidate
      return 0
    fi
  done
  echo "sanitizer-env: no llvm-symbolizer: the sanitizers' stacks would be bare addresses and the" \
       "suppressions in tests/sanitizers/ would match nothing; install it (apt install llvm," \
       "or scripts/install-clang.sh)" >&2
  return 1
}
find_symbolizer || exit 1
