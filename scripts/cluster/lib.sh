# Shared by the GNU parallel recipes of this folder (sourced, not run).

# usage_unless N ARGS...: unless ARGS has N words or more, print the calling script's
# header comment and exit 2.
usage_unless() {
  local need=$1
  shift
  if [ $# -lt "$need" ]; then
    sed -n '2,/^[^#]/p' "$0" | grep '^#' >&2
    exit 2
  fi
}

require_parallel() {
  command -v parallel >/dev/null || {
    echo "$(basename "$0"): GNU parallel is not installed (scripts/setup.sh installs it)" >&2
    exit 1
  }
}
