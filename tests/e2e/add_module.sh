#!/usr/bin/env bash
# Follows "Adding a module" of docs/instructor-guide.md in a scratch copy of the tree: adds
# the guide's example module 11_fresnel by its numbered steps, then builds and grades it.
#  - The registry lines are the guide's own code block.
#  - The files this script changes must be exactly the files the numbered steps name: a
#    step the guide drops, or a file it forgets, fails here.
#  - Then, in the copy: the graders, raylab-render and the module switch's tests build; the
#    module tables and the handout's graded list match (the ctest checks of the docs); the module
#    switch's tests pass; the reference gets full marks in every module, 11 included; the
#    untouched stubs, 11 included, are "not started"; raylab-render --help names the module.
# Usage: tests/e2e/add_module.sh ROOT WORK   (WORK is emptied; CMAKE_ARGS adds configure options)
set -euo pipefail
root=$(cd "$1" && pwd)
work=$2
# shellcheck source=../../scripts/lib/common.sh
source "$root/scripts/lib/common.sh"
rm -rf "$work" && mkdir -p "$work"
work=$(cd "$work" && pwd)
tree=$work/tree
fail() { die "add-module: $*"; }
guide=$root/docs/instructor-guide.md
id=11_fresnel

step "add-module: a scratch copy of the tree"
mkdir -p "$tree"
(cd "$root" && git ls-files -z | xargs -0 tar -cf - --no-recursion) | tar -xf - -C "$tree"
git -C "$tree" init -q && git -C "$tree" add -A && git -C "$tree" -c user.name=e2e \
    -c user.email=e2e@localhost commit -qm base

step "add-module: the guide's steps for $id"
python3 - "$tree" "$guide" "$id" <<'PY'
import pathlib, re, sys
tree, guide, mid = pathlib.Path(sys.argv[1]), pathlib.Path(sys.argv[2]).read_text(), sys.argv[3]
section = guide.split("## Adding a module", 1)[1].split("\n## ", 1)[0]
def edit(path, old, new, count=1):
    p = tree / path
    text = p.read_text()
    if old not in text:
        sys.exit(f"{path}: '{old[:60]}' not found")
    p.write_text(text.replace(old, new, count))
def write(path, text):
    (tree / path).write_text(text)

# 1. The registry: the guide's code block, after the last module
block = re.search(r"```c\+\+\n(.*?)```", section, re.S).group(1)
if f'"{mid}"' not in block:
    sys.exit(f"the guide's code block does not add {mid}")
edit("framework/include/raylab/modules.def", "\n#undef RAYLAB_MODULE", "\n" + block + "\n#undef RAYLAB_MODULE")

# 2. The declaration
decl = """
// 11_fresnel ---------------------------------------------------------------------------
/// Schlick's approximation of the Fresnel reflectance at normal-incidence reflectance f0:
///   F = f0 + (1 - f0) (1 - cos_theta)^5.
float schlick_fresnel(float cos_theta, float f0);
"""
p = tree / "framework/include/raylab/contract_functions.inc"
p.write_text(p.read_text().rstrip("\n") + "\n" + decl)

# 3. Stub and reference
write(f"exercises/{mid}.cpp", """// Module 11_fresnel: Fresnel reflectance (docs/handouts/11_fresnel.md).
#include "raylab/contract.h"

namespace raylab::student {

/// Schlick's approximation: F = f0 + (1 - f0) (1 - cos_theta)^5.
float schlick_fresnel(float cos_theta, float f0) {
    // TODO(student) 11_fresnel: return f0 + (1 - f0) (1 - cos_theta)^5
    RAYLAB_STUB("11_fresnel");
    (void)cos_theta, (void)f0;
    return 0.0f;
}

}  // namespace raylab::student
""")
write(f"solutions/{mid}.cpp", """// Reference of module 11_fresnel.
#include <cmath>

#include "raylab/contract.h"

namespace raylab::reference {

float schlick_fresnel(float cos_theta, float f0) {
    return f0 + (1.0f - f0) * std::pow(1.0f - cos_theta, 5.0f);
}

}  // namespace raylab::reference
""")

# 5. The graders (step 4's list names these cases)
cases = ["at normal incidence the reflectance is f0",
         "at grazing incidence everything is reflected",
         "at 60 degrees F = f0 + (1 - f0) / 32"]
write(f"tests/grading/test_{mid}.cpp", """// Graders of module 11_fresnel (docs/handouts/11_fresnel.md).
#include "grading.h"

using namespace raylab;
using namespace raylab::grading;

namespace {

void check(float cos_theta, float f0, double want) {
    const float got = under_test::schlick_fresnel(cos_theta, f0);
    RAYLAB_CHECK(close(got, want, 1e-6), "schlick_fresnel(" << cos_theta << ", " << f0
                                          << "): expected " << want << ", got " << got);
}

}  // namespace

TEST_SUITE("11_fresnel") {
    TEST_CASE("%s") { check(1.0f, 0.04f, 0.04); }
    TEST_CASE("%s") { check(0.0f, 0.04f, 1.0); }
    TEST_CASE("%s") { check(0.5f, 0.04f, 0.04 + 0.96 / 32); }
}
""" % tuple(cases))

# 4. The handout
write(f"docs/handouts/{mid}.md", """# Module 11: Fresnel reflectance

> Exercise: `exercises/11_fresnel.cpp`

Schlick's approximation of the reflectance of a dielectric: F = f0 + (1 - f0) (1 - cos)^5.

## How you are graded

The suite `TEST_SUITE("11_fresnel")` has these test cases:

""" + "".join(f"- {c}\n" for c in cases))

# 6. Stub detection: the function's probe (the CLI help's names come from the registry)
edit("framework/src/stub_probes.cpp", "\n}  // namespace probe",
     "\n// 11_fresnel\nvoid schlick_fresnel() { (void)student::schlick_fresnel(1.0f, 0.04f); }\n"
     "\n}  // namespace probe")

# 7. The module tables
edit("README.md", "| [10_area_light](docs/handouts/10_area_light.md) |\n",
     "| [10_area_light](docs/handouts/10_area_light.md) |\n"
     f"| 11 | Fresnel reflectance | `exercises/{mid}.cpp` | [{mid}](docs/handouts/{mid}.md) |\n")
edit("docs/instructor-guide.md", "| `light_sample_points`, `sample_area_light` |\n",
     "| `light_sample_points`, `sample_area_light` |\n"
     f"| 11 | `{mid}` | [11](handouts/{mid}.md) | `schlick_fresnel` |\n")
PY

# The files changed against the files the guide's numbered steps name
changed=$(git -C "$tree" status --porcelain --untracked-files=all | cut -c4- | sort)
named=$(python3 - "$guide" "$id" <<'PY'
import re, sys
section = open(sys.argv[1]).read().split("## Adding a module", 1)[1].split("\n## ", 1)[0]
steps = section.split("\n1. ", 1)[1].split("\n\n", 1)[0]  # the numbered list
paths = set()
for token in re.findall(r"`([^`\s]+)`", steps):
    if "/" in token or re.search(r"\.(md|cpp|h|inc|def)$", token):
        paths.add(token)
print("\n".join(sorted(paths)))
PY
)
if [[ $changed != "$named" ]]; then
    echo "files the script changed:"; sed 's/^/    /' <<<"$changed"
    echo "files the guide's steps name:"; sed 's/^/    /' <<<"$named"
    fail "the guide's steps and what adding $id takes differ"
fi
note "the $(wc -l <<<"$changed") files changed are the files the guide's steps name"

step "add-module: build the copy (graders, raylab-render, the module switch's tests)"
extra=()
if [[ -n ${CMAKE_ARGS:-} ]]; then read -r -a extra <<<"$CMAKE_ARGS"; fi
cmake -S "$tree" -B "$tree/build" -G Ninja -DCMAKE_BUILD_TYPE=Release -DRAYLAB_WITH_GUI=OFF \
    "${extra[@]}" >"$work/configure.log" 2>&1 || { cat "$work/configure.log"; fail "configure failed"; }
ninja -C "$tree/build" raylab-grading-tests raylab-grade raylab_worker_main raylab_core \
    raylab-worker-reference raylab-render raylab-module-tests >"$work/build.log" 2>&1 ||
    { tail -n 40 "$work/build.log"; fail "the copy with $id does not build"; }

step "add-module: the copy's checks"
python3 "$tree/tests/handouts/check_module_tables.py" "$tree" | sed 's/^/    /'
python3 "$tree/tests/handouts/check_graded_lists.py" "$tree" \
    "$tree/build/tests/grading/raylab-grading-tests" | grep "$id" | sed 's/^/    /'
"$tree/build/tests/framework/raylab-module-tests" --test-suite=modules --no-colors \
    >"$work/modules.log" 2>&1 || { cat "$work/modules.log"; fail "the module switch's tests fail"; }
note "framework tests of the module switch: $(grep -o 'test cases:.*' "$work/modules.log")"
"$tree/build/framework/raylab-render" --help | grep 'fresnel' >/dev/null || fail "raylab-render --help does not name fresnel"
export GRADE_BUILD_DIR=$tree/build
GRADE_OUT=$work/reference bash "$tree/scripts/grade.sh" --reference --expect full \
    >"$work/reference.log" 2>&1 || { cat "$work/reference.log"; fail "the reference is not given full marks"; }
sed -n "/^ *$id/{s/^/    reference: /;p;q;}" "$work/reference/summary.txt"
GRADE_OUT=$work/stubs bash "$tree/scripts/grade.sh" --expect not-started \
    >"$work/stubs.log" 2>&1 || { cat "$work/stubs.log"; fail "the stubs are not all 'not started'"; }
sed -n "/^ *$id/{s/^/    stubs:     /;p;q;}" "$work/stubs/summary.txt"
step "add-module: $id added by the guide's steps builds and grades"
