#!/usr/bin/env bash
# Prints every test of the last ctest run in BUILD_DIR that was skipped, with the reason it
# gave, so that a skip is never silent in `make test`'s output (ctest lists skipped tests
# by name only). Prints nothing when nothing was skipped.
# usage: skipped_tests.sh BUILD_DIR
set -euo pipefail
log="$1/Testing/Temporary/LastTest.log"
[ -f "$log" ] || exit 0
# GoogleTest writes "[ RUN      ] Suite.Name", then "file:line: Skipped" and the reason on
# the lines that follow, up to "[  SKIPPED ] Suite.Name".
awk '
  /^\[ RUN      \] / { name = $4; reason = ""; inSkip = 0; next }
  /: Skipped$/ { inSkip = 1; next }
  /^\[  SKIPPED \] / { if (name != "") printf "skipped: %s: %s\n", name, reason; inSkip = 0; next }
  inSkip && NF { reason = reason (reason == "" ? "" : " ") $0 }
' "$log" | sort -u
