#!/usr/bin/env bash
# Checks every relative link and image in the Markdown files under DIR: the file (or
# folder) it names must exist. Links to the web (http:, https:, mailto:) and anchors
# within a page (#...) are not followed. scripts/release/ holds templates whose links are
# relative to the release's root: they are checked in the release, where they land; likewise
# bench/doc/ holds the head and tail of docs/benchmarks.md (bench/make-doc.sh).
#
# Usage: scripts/check-links.sh DIR
# Prints one line per broken link (file:line: target) and exits 1 when there is any.
set -euo pipefail
dir=${1:?usage: scripts/check-links.sh DIR}
cd "$dir"
broken=0 checked=0 files=0
markdown() {
    find . \( -name 'build*' -o -path ./scripts/release -o -path ./bench/doc \) -prune -o -name '*.md' -print |
        sed 's|^\./||' | sort
}
while IFS= read -r md; do
    files=$((files + 1))
    # [text](target) and ![alt](target), one per match; the line number from grep -n
    while IFS=: read -r line target; do
        target=${target%%#*}          # drop an anchor
        target=${target%% \"*}        # drop a title: (file "title")
        [[ -z $target || $target =~ ^[a-z]+: ]] && continue
        checked=$((checked + 1))
        if [[ $target == /* ]]; then
            echo "$md:$line: $target: absolute path (use a relative link)"
            broken=$((broken + 1))
        elif [[ ! -e $(dirname "$md")/$target ]]; then
            echo "$md:$line: $target: no such file"
            broken=$((broken + 1))
        fi
    done < <(grep -no '\]([^)]*)' "$md" | sed 's/:\](\(.*\))$/:\1/')
done < <(markdown)
echo "check-links: $checked relative links in $files Markdown files, $broken broken"
((broken == 0))
