# raylab: the same commands as scripts/dev.sh, for those who type `make`.
#   make run                                 viewer (or build/cornell.png without a display)
#   make run ARGS="--reference all"          extra flags for the viewer / raylab-render
#   make test                                what CI runs
#   make check                               the edit loop: strict build, format, unit tests
#   make grade SUBMISSION=~/handin GRADE_OUT=grades/alice
#   make release OUT=/tmp/raylab-student
#   make grade-class DIR=~/handins ARGS="-j 2"
#   make gradescope OUT=autograder.zip
#   make fuzz ARGS=600                       each fuzz target for 600 s
# `make help` lists everything. Variables: ARGS, SUBMISSION, GRADE_OUT, OUT, DIR.

DEV := ./scripts/dev.sh

# Hand the grading variables to scripts/grade.sh when they are given
ifdef SUBMISSION
export SUBMISSION
endif
ifdef GRADE_OUT
export GRADE_OUT
endif

.DEFAULT_GOAL := help
.PHONY: run test check build grade grade-reference grade-class gradescope release bench fuzz \
	format clean help

run test check build grade grade-reference bench fuzz format clean help:
	$(DEV) $@ $(ARGS)

release gradescope:
	$(DEV) $@ $(OUT) $(ARGS)

grade-class:
	$(DEV) grade-class $(DIR) $(ARGS)
