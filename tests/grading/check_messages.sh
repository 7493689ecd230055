#!/usr/bin/env bash
# ctest grading/messages-in-words: every failure message of the graders says in words what
# was expected and what came. doctest's own CHECK and REQUIRE print the raw expression
# ("++count[k] == 1 is 2 == 1"), so the graders use RAYLAB_CHECK and RAYLAB_REQUIRE
# (grading.h) with a message instead. Usage: check_messages.sh FILE...
if grep -nE '(^|[^A-Za-z_])(CHECK|REQUIRE|WARN)(_[A-Z]+)?\(' "$@"; then
    echo "the lines above use doctest's assertions, whose failure shows the raw expression:"
    echo "use RAYLAB_CHECK or RAYLAB_REQUIRE with a message saying what was expected and what came"
    exit 1
fi
echo "$# grader files: every check has a message in words"
