#include "src/trace/sample_distribution.h"

#include <algorithm>

#include "src/core/error.h"

namespace rsl {

namespace {

// The interval [cdf[k], cdf[k + 1]) of a normalized CDF of `count` intervals
// that holds u ∈ [0, 1), and u's place in it: the first k with cdf[k + 1] >
// u, so zero-width intervals are never found. The guide's interval holds
// g / count ≤ u, so the search steps forward from it.
int find_interval(const double* cdf, const int* guide, int count, double u, double& fraction) {
    int k = guide[std::min(int(u * count), count - 1)];
    while (k > 0 && cdf[k] > u) --k;  // u · count rounded up onto the next g
    while (k < count - 1 && cdf[k + 1] <= u) ++k;
    const double width = cdf[k + 1] - cdf[k];
    fraction = width > 0.0 ? std::clamp((u - cdf[k]) / width, 0.0, 1.0 - 1e-16) : 0.5;
    return k;
}

// Running sums of `count` weights, normalized to end at exactly 1; the total.
double normalized_cdf(const double* weights, int count, double* cdf) {
    cdf[0] = 0.0;
    for (int k = 0; k < count; ++k) cdf[k + 1] = cdf[k] + weights[k];
    const double total = cdf[count];
    if (total > 0.0) {
        for (int k = 1; k < count; ++k) cdf[k] /= total;
        cdf[count] = 1.0;
    }
    return total;
}

// guide[g]: the interval find_interval would give u = g / count.
void fill_guide(const double* cdf, int count, int* guide) {
    int k = 0;
    for (int g = 0; g < count; ++g) {
        const double u = double(g) / count;
        while (k < count - 1 && cdf[k + 1] <= u) ++k;
        guide[g] = k;
    }
}

}  // namespace

PiecewiseConstant2D::PiecewiseConstant2D(int rows, int columns, const float* weights)
    : rows_(rows), columns_(columns) {
    RSL_CHECK_GE(rows, 1);
    RSL_CHECK_GE(columns, 1);
    const size_t cells = size_t(rows) * size_t(columns);
    std::vector<double> row_weights(size_t(rows), 0.0), cell_weights(columns);
    column_cdf_.assign(size_t(rows) * size_t(columns + 1), 0.0);
    for (int r = 0; r < rows; ++r) {
        for (int c = 0; c < columns; ++c) {
            const float w = weights[size_t(r) * columns + c];
            RSL_CHECK_GE(w, 0.0f);
            cell_weights[c] = double(w);
        }
        row_weights[r] = normalized_cdf(cell_weights.data(), columns, column_cdf_.data() + size_t(r) * (columns + 1));
    }
    row_cdf_.resize(size_t(rows) + 1);
    total_ = normalized_cdf(row_weights.data(), rows, row_cdf_.data());
    row_guide_.resize(size_t(rows));
    fill_guide(row_cdf_.data(), rows, row_guide_.data());
    column_guide_.resize(cells);
    for (int r = 0; r < rows; ++r)
        fill_guide(column_cdf_.data() + size_t(r) * (columns + 1), columns, column_guide_.data() + size_t(r) * columns);
    probability_.assign(cells, 0.0f);
    if (empty()) return;
    for (int r = 0; r < rows; ++r) {
        const double row_probability = row_cdf_[r + 1] - row_cdf_[r];
        if (!(row_probability > 0.0)) continue;
        const double* cdf = column_cdf_.data() + size_t(r) * (columns + 1);
        for (int c = 0; c < columns; ++c)
            probability_[size_t(r) * columns + c] = float(row_probability * (cdf[c + 1] - cdf[c]));
    }
}

PiecewiseConstant2D::Cell PiecewiseConstant2D::sample(double u0, double u1) const {
    Cell cell;
    cell.row = find_interval(row_cdf_.data(), row_guide_.data(), rows_, u0, cell.row_fraction);
    cell.column = find_interval(column_cdf_.data() + size_t(cell.row) * (columns_ + 1),
                                column_guide_.data() + size_t(cell.row) * columns_, columns_, u1, cell.column_fraction);
    return cell;
}

}  // namespace rsl
