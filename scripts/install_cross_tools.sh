#!/usr/bin/env bash
# Best effort: the Windows cross compiler and wine64 for the win64 FMU tests (Debian packages
# gcc-mingw-w64-x86-64-win32 and wine64), and valgrind and cmake, when missing and apt-get can install them (root).
# Never fails: a test that needs a missing tool skips, naming the package.
set -u
need=()
command -v x86_64-w64-mingw32-gcc >/dev/null 2>&1 || need+=(gcc-mingw-w64-x86-64-win32)
{ [ -x /usr/lib/wine/wine64 ] || command -v wine64 >/dev/null 2>&1; } || need+=(wine64)
command -v valgrind >/dev/null 2>&1 || need+=(valgrind)
command -v cmake >/dev/null 2>&1 || need+=(cmake)
if [ ${#need[@]} -gt 0 ] && [ "$(id -u)" = 0 ] && command -v apt-get >/dev/null 2>&1; then
  echo "installing ${need[*]} (apt-get)"
  (apt-get update -qq && DEBIAN_FRONTEND=noninteractive apt-get install -y -qq "${need[@]}") >/dev/null 2>&1 \
    || echo "could not install ${need[*]}: the tests that need them skip"
fi
exit 0
