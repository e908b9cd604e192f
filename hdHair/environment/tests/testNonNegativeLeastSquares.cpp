#include <gtest/gtest.h>

#include <vector>

#include "hdHair/environment/NonNegativeLeastSquares.h"

using namespace hdhair;

// With a non-negative unconstrained solution, NNLS is plain least squares:
// G = [[2, 1], [1, 2]], h = [4, 5] gives x = G⁻¹h = (1, 2).
TEST(NonNegativeLeastSquares, NonNegativeSolutionsAreTheLeastSquaresOnes) {
    const std::vector<double> x = nonNegativeLeastSquares({2, 1, 1, 2}, {4, 5});
    ASSERT_EQ(x.size(), 2u);
    EXPECT_NEAR(x[0], 1.0, 1e-9);
    EXPECT_NEAR(x[1], 2.0, 1e-9);
}

// G = [[1, 0.9], [0.9, 1]], h = [1, 0.2]: least squares wants
// x = (4.32, −3.68); held at x₂ = 0, x₁ = h₁ / G₁₁ = 1, and the gradient for
// x₂, h₂ − G₂₁ x₁ = −0.7, says x₂ may not grow (Kuhn-Tucker).
TEST(NonNegativeLeastSquares, NegativeComponentsAreHeldAtZero) {
    const std::vector<double> x = nonNegativeLeastSquares({1, 0.9, 0.9, 1}, {1, 0.2});
    EXPECT_NEAR(x[0], 1.0, 1e-9);
    EXPECT_EQ(x[1], 0.0);
    const std::vector<double> none = nonNegativeLeastSquares({1, 0, 0, 1}, {-1, -2});
    EXPECT_EQ(none, (std::vector<double>{0.0, 0.0}));
}

// Two identical columns (a singular G) still give a solution that fits.
TEST(NonNegativeLeastSquares, DuplicateColumnsStillFit) {
    const std::vector<double> x = nonNegativeLeastSquares({1, 1, 1, 1}, {3, 3});
    EXPECT_GE(x[0], 0.0);
    EXPECT_GE(x[1], 0.0);
    EXPECT_NEAR(x[0] + x[1], 3.0, 1e-6);
    EXPECT_THROW(nonNegativeLeastSquares({1, 2, 3}, {1, 2}), std::invalid_argument);
}
