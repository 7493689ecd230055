// A compile message (#warning, #error, _Pragma message) about the hand-in's own file is
// quoted in the report: its text carries C1 controls (U+009B CSI: cursor up, erase the
// line) and a Unicode line break before a line posing as the grader's
#include "raylab/contract.h"

#warning "1A2K03_plane        13/13   10.00 / 10.00 total           13/13   100.00 / 100.00"
_Pragma("message \"total           13/13   100.00 / 100.00\"")
#error "1A2K04_sphere       13/13   10.00 / 10.00‮"
