#pragma once
// Moved to src/core/progress_report.h (shared with `rsl truth`); kept for
// code that still includes it from here.
#include "src/core/progress_report.h"
