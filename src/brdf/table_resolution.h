#pragma once
// Whether a BRDF table resolves a material's highlight (docs/design/BRDF.md,
// "Table resolution"): a lobe narrower than the table's texels, or one that
// moves by more than its width between two tabulated views, comes out of the
// table blurred, and a small light such as a sun shows it.
#include <string>

#include "src/brdf/brdf_table.h"

namespace rsl {

// The warning threshold on table_peak_error: a highlight under a sun off by
// more than this is beyond the whole error of the shipped scenes' objects
// (2.9–6.8%, docs/RESULTS.md), so the user should hear of it.
inline constexpr float kTablePeakErrorLimit = 0.10f;

struct TablePeakError {
    float relative_error = 0;   // |table − exact| / exact, summed over RGB
    float view_theta_degrees = 0;  // the view where it is worst
};

// Measured on the table itself, against the BRDF: for views at and halfway
// between the tabulated ones (θ_o up to 60°), the table's average of ρ·cos
// over a square a quarter of a texel wide at the mirror direction, against
// the exact average of brdf over that square (8 × 8 points). The worst view.
TablePeakError table_peak_error(const BrdfTable& table, const Brdf& brdf);

// The warning for `material` (built into `table`) when its peak error passes
// kTablePeakErrorLimit: what the table resolves, the error, and the wider
// lobe (or finer table) that would bring it under the limit. "" when fine.
std::string sharp_material_warning(const MaterialDesc& material, const BrdfTable& table, const TablePeakError& error);

}  // namespace rsl
