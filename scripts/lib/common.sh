# shellcheck shell=bash
# Shared helpers for raylab's bash scripts (sourced, never run).
# Provides: RAYLAB_ROOT, step, note, warn, die, have.

# The repository root: this file lives in scripts/lib/
# shellcheck disable=SC2034 # used by the scripts that source this file
RAYLAB_ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"

# Colour only on a terminal, never in CI logs
if [[ -t 1 && -z ${NO_COLOR:-} && ${CI:-} != true ]]; then
    _bold=$'\e[1m' _red=$'\e[31m' _yellow=$'\e[33m' _off=$'\e[0m'
else
    _bold='' _red='' _yellow='' _off=''
fi

# A headed step: "==> Building (Release) in build/"
step() { printf '%s==> %s%s\n' "$_bold" "$*" "$_off"; }
# A plain line under a step
note() { printf '    %s\n' "$*"; }
warn() { printf '%swarning:%s %s\n' "$_yellow" "$_off" "$*" >&2; }
# Print an error and stop
die() {
    printf '%serror:%s %s\n' "$_red" "$_off" "$*" >&2
    exit 1
}
# Is a command on the PATH?
have() { command -v "$1" >/dev/null 2>&1; }
