#pragma once
// A piecewise-constant distribution over the cells of a rows × columns grid,
// sampled as a 2D warp: a row from the rows' marginal CDF, then a column from
// that row's conditional CDF, and the remainders of both searches as the
// point's position inside its cell. Each search starts where a guide table
// (interval of u = g / count, g = 0 … count − 1) points and steps on from
// there: a step or two on average, where a binary search was a fifth of
// env-rays' time. The warp is
// monotone in each coordinate, so stratified unit points (a scrambled Sobol
// net) stay stratified over the distribution. env-rays samples the cube map
// (rows: face × t, columns: s) and each BRDF slice (the equal-area grid) with it.
#include <cstddef>
#include <vector>

namespace rsl {

class PiecewiseConstant2D {
public:
    PiecewiseConstant2D() = default;
    // weights[row · columns + column] ≥ 0; an all-zero grid is empty().
    PiecewiseConstant2D(int rows, int columns, const float* weights);

    bool empty() const { return !(total_ > 0.0); }
    int rows() const { return rows_; }
    int columns() const { return columns_; }
    double total_weight() const { return total_; }
    // The probability of the cell, the product of the two searches' interval
    // widths, so that it is exactly what sample() draws the cell with.
    float probability(int row, int column) const { return probability_[size_t(row) * columns_ + column]; }
    float probability(int cell) const { return probability_[size_t(cell)]; }

    struct Cell {
        int row = 0, column = 0;
        // Where in the cell, each in [0, 1): uniform given the cell.
        double row_fraction = 0, column_fraction = 0;
    };
    // u0 picks the row, u1 the column, both in [0, 1). Never a zero-weight
    // cell. The distribution must not be empty.
    Cell sample(double u0, double u1) const;

private:
    int rows_ = 0, columns_ = 0;
    double total_ = 0.0;
    std::vector<double> row_cdf_;     // rows + 1 entries, 0 … 1
    std::vector<double> column_cdf_;  // per row, columns + 1 entries, 0 … 1 (a zero row: 0 … 0)
    std::vector<int> row_guide_;      // rows entries: the interval holding g / rows
    std::vector<int> column_guide_;   // per row, columns entries
    std::vector<float> probability_;  // per cell
};

}  // namespace rsl
