#!/usr/bin/env bash
# Install the Debian 12 packages raylab needs, and only those that are missing. The group
# `grade` (what grading needs, nothing graphical) also installs on Ubuntu 22.04, the base
# image of Gradescope's autograders: its package names are the same there (universe).
#
# Usage: scripts/install-deps.sh [--check | --list] [GROUP...]
#   GROUP    build    compiler and build tools: g++ make cmake ninja-build pkg-config
#            libs     libraries: GLM, tinyobjloader, stb, doctest, Dear ImGui, GLFW, GL headers,
#                     nlohmann-json, libseccomp and bubblewrap (the grader's sandbox),
#                     jq, zip and unzip (class tables, the Gradescope package)
#            grade    grading only (scripts/grade.sh, the Gradescope package's setup.sh):
#                     the build tools and the libraries of the graders, bubblewrap, jq
#            gui      running the GUI tests headless: Xvfb, xauth, Mesa, xdotool (alias gui-test)
#            format   clang-format (the style check of `scripts/dev.sh test`)
#            test     python3 (the docs' checks, the class and end-to-end tests of
#                     `scripts/dev.sh test`), ccache (the compiler cache of `test` and
#                     `check`)
#            fuzz     clang 14 and its runtimes: libFuzzer targets, the stress matrix
#            bench    Embree (the peer of the benchmark)
#            all      every group above (grade is part of build and libs)
#            (default: build libs)
#   --check  only report what is missing; exit 1 if anything is
#   --list   print the packages of the groups, one a line, and exit
#
# Idempotent and non-interactive: it asks dpkg what is installed, runs `apt-get update` only
# when something is missing, installs without recommended packages, and waits up to 10 minutes
# for another apt/dpkg to release its lock. Needs root, or sudo when not root.
set -euo pipefail
# shellcheck source=lib/common.sh
source "$(dirname "${BASH_SOURCE[0]}")/lib/common.sh"

# Package groups (Debian 12 names)
group_packages() {
    case $1 in
        build) echo g++ make cmake ninja-build pkg-config ;;
        # libgl-dev/libopengl-dev: the GL headers and libraries FindOpenGL (GLVND) and GLFW use;
        # libseccomp-dev and bubblewrap: the grader's sandbox (docs/instructor-guide.md)
        # jq reads the graders' results.json for the class table; zip/unzip make and test
        # the Gradescope package
        libs) echo libglm-dev libtinyobjloader-dev libstb-dev doctest-dev libimgui-dev \
            libglfw3-dev libgl-dev libopengl-dev nlohmann-json3-dev libseccomp-dev bubblewrap \
            jq zip unzip ;;
        # xauth is only recommended by xvfb, but xvfb-run needs it; Mesa's llvmpipe renders GL
        # The graders build without the viewer (RAYLAB_WITH_GUI=OFF): no GL, GLFW or ImGui
        grade) echo g++ make cmake ninja-build pkg-config libglm-dev libtinyobjloader-dev \
            libstb-dev doctest-dev nlohmann-json3-dev libseccomp-dev bubblewrap jq ;;
        gui | gui-test) echo xvfb xauth libgl1-mesa-dri xdotool ;;
        format) echo clang-format ;;
        test) echo python3 ccache ;;
        fuzz) echo clang libclang-rt-14-dev ;;
        bench) echo libembree-dev ;;
        *) return 1 ;;
    esac
}
ALL_GROUPS=(build libs gui format test fuzz bench)
# grade is a subset of build + libs, so `all` need not name it

usage() { sed -n '2,/^[^#]/{/^#/s/^# \{0,1\}//p}' "$0"; }

# Arguments
mode=install
groups=()
for arg in "$@"; do
    case $arg in
        -h | --help) usage; exit 0 ;;
        --check) mode=check ;;
        --list) mode=list ;;
        all) groups+=("${ALL_GROUPS[@]}") ;;
        -*) usage >&2; die "unknown option: $arg" ;;
        *) group_packages "$arg" >/dev/null ||
            die "unknown group '$arg' (groups: ${ALL_GROUPS[*]} all)"
            groups+=("$arg") ;;
    esac
done
((${#groups[@]})) || groups=(build libs)

# The packages of the chosen groups, without repeats
packages=()
for g in "${groups[@]}"; do
    for p in $(group_packages "$g"); do
        [[ " ${packages[*]} " == *" $p "* ]] || packages+=("$p")
    done
done
if [[ $mode == list ]]; then
    printf '%s\n' "${packages[@]}"
    exit 0
fi

# Not Debian: say what to install and let CMake report what is really missing
if ! have dpkg-query || ! have apt-get; then
    warn "no dpkg/apt-get here: this script knows Debian 12 (and Ubuntu 22.04 for the group" \
        "grade) only. Install the equivalents of:"
    note "${packages[*]}"
    [[ $mode == check ]] && exit 1
    exit 0
fi

# What is missing? (dpkg's own record, not a guess from the PATH)
missing=()
for p in "${packages[@]}"; do
    status=$(dpkg-query -W -f='${db:Status-Status}' "$p" 2>/dev/null || true)
    [[ $status == installed ]] || missing+=("$p")
done
if ((${#missing[@]} == 0)); then
    step "Dependencies (${groups[*]}): all present"
    exit 0
fi
if [[ $mode == check ]]; then
    step "Dependencies (${groups[*]}): missing ${missing[*]}"
    exit 1
fi

# Root, or sudo; never a prompt in CI or without a terminal
if ((EUID == 0)); then
    as_root=()
elif have sudo; then
    if [[ ${CI:-} == true || ! -t 0 ]]; then
        as_root=(sudo -n)
        sudo -n true 2>/dev/null ||
            die "installing ${missing[*]} needs root: sudo wants a password, and this run cannot
       ask for one (CI=true or no terminal). Run once from a terminal: $0 ${groups[*]}
       or as root: apt-get update && apt-get install --no-install-recommends ${missing[*]}"
    else
        as_root=(sudo)
    fi
else
    die "installing ${missing[*]} needs root, and this is neither root nor has sudo.
       As root, run: apt-get update && apt-get install --no-install-recommends ${missing[*]}"
fi

step "Installing (${groups[*]}): ${missing[*]}"
t0=$SECONDS
apt=(env DEBIAN_FRONTEND=noninteractive apt-get -o DPkg::Lock::Timeout=600)
"${as_root[@]}" "${apt[@]}" -o Acquire::Languages=none -q update ||
    die "apt-get update failed (as ${as_root[*]:-root}); see above"
# A package the sources do not offer: name it (Ubuntu keeps several in universe)
absent=()
for p in "${missing[@]}"; do
    candidate=$(apt-cache policy "$p" 2>/dev/null | sed -n 's/^ *Candidate: //p')
    [[ -n $candidate && $candidate != '(none)' ]] || absent+=("$p")
done
if ((${#absent[@]})); then
    hint=''
    grep -qi '^ID=ubuntu' /etc/os-release 2>/dev/null &&
        hint=" (on Ubuntu they are in the universe component: add-apt-repository universe)"
    die "apt's package sources offer no ${absent[*]}$hint"
fi
# dpkg's per-package lines go to a log; apt's summary, lock waits and errors stay visible
log=$(mktemp "${TMPDIR:-/tmp}/raylab-apt.XXXXXX")
set +e
"${as_root[@]}" "${apt[@]}" -q -y --no-install-recommends install "${missing[@]}" 2>&1 |
    tee "$log" |
    grep -vE '^(Selecting previously|Preparing to unpack|Unpacking|Setting up|Processing triggers|\(Reading database|Get:[0-9]+ |update-alternatives:)'
apt_status=${PIPESTATUS[0]} # grep finding nothing to show is no failure
set -e
if ((apt_status != 0)); then
    tail -n 30 "$log" >&2
    die "apt-get install failed (exit $apt_status) for: ${missing[*]} (full log: $log)"
fi
rm -f "$log"

# Check that dpkg now has every one of them
still=()
for p in "${missing[@]}"; do
    status=$(dpkg-query -W -f='${db:Status-Status}' "$p" 2>/dev/null || true)
    [[ $status == installed ]] || still+=("$p")
done
((${#still[@]} == 0)) || die "still not installed after apt-get: ${still[*]}"
step "Installed ${#missing[@]} packages in $((SECONDS - t0)) s"
