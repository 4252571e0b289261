// tests/tableau_test.cpp
// Tests of the Butcher tableaux themselves (grtrace/tableau/*): the rooted-tree enumeration, that every
// shipped tableau has exactly its stated orders, that a one-digit transcription error is rejected at compile
// time, and the name-based dispatch. Needs only the tableau headers.
#include "grtrace/tableau/all_tableaux.hpp"

#include "common/tableau_types.hpp"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstddef>
#include <cstdio>
#include <set>
#include <string_view>
#include <vector>

namespace grtrace {
namespace {

// -----------------------------------------------------------------------------------------------------------
// Rooted trees

TEST(RootedTrees, CountsMatchOeisA000081) {
  constexpr std::array<std::size_t, 8> expected = {1, 1, 2, 4, 9, 20, 48, 115};
  static_assert(rooted_tree_count(4) == 4);
  for (int n = 1; n <= tableau_detail::kMaxCheckedOrder; ++n) {
    EXPECT_EQ(rooted_tree_count(n), expected[static_cast<std::size_t>(n - 1)]) << "order " << n;
  }
}

// -----------------------------------------------------------------------------------------------------------
// Helpers

/// |(p+1) sum_i b_i c_i^p - 1|: the bushy tree of order p+1. The tree enumeration stops at kMaxCheckedOrder,
/// so this one condition is what shows that an order-8 method is not of order 9.
template <std::size_t S>
double bushy_tree_residual(const TableauRow<S>& b, const TableauRow<S>& c, int p) {
  double phi = 0.0;
  for (std::size_t i = 0; i < S; ++i) phi += b[i] * std::pow(c[i], p);
  return std::abs((p + 1) * phi - 1.0);
}

/// Residual of the weights b at order `order + 1`, the first order the method should fail.
template <std::size_t S>
double residual_one_above(const TableauMatrix<S>& a, const TableauRow<S>& b, const TableauRow<S>& c, int order) {
  if (order + 1 <= tableau_detail::kMaxCheckedOrder) return order_condition_residual<S>(a, b, order + 1);
  return bushy_tree_residual<S>(b, c, order);
}

/// The dense output y0 + h sum_i b_i(theta) k_i is one step of size theta*h of the method
/// (A/theta, b(theta)/theta),
/// so it has order q at theta exactly when that tableau satisfies the order conditions up to q.
template <TableauWithDenseOutput T>
double dense_output_residual(double theta, int q) {
  constexpr std::size_t S = T::stages;
  TableauMatrix<S> a{};
  TableauRow<S> b{};
  for (std::size_t i = 0; i < S; ++i) {
    for (std::size_t j = 0; j < S; ++j) a[i][j] = T::a[i][j] / theta;
    double bi = 0.0;
    double power = theta;
    for (int d = 0; d < T::dense_degree; ++d) {
      bi += T::dense[i][static_cast<std::size_t>(d)] * power;
      power *= theta;
    }
    b[i] = bi / theta;
  }
  return order_condition_residual<S>(a, b, q);
}

// -----------------------------------------------------------------------------------------------------------
// Every shipped tableau

// Every shipped tableau on its own (EveryTableau/<name>); the rows of one table.
template <class T>
class EveryTableau : public ::testing::Test {};
TYPED_TEST_SUITE(EveryTableau, tableau_tests::AllTableauTypes, tableau_tests::TableauName);

TYPED_TEST(EveryTableau, IsValidAndHasExactlyItsStatedOrders) {
  using T = TypeParam;
  constexpr std::size_t S = T::stages;
  if (tableau_tests::first_row("orders"))
    std::printf("%-9s %6s %12s %12s | %6s %12s %12s\n", "name", "order", "res(p)", "res(p+1)", "emb", "res(q)",
                "res(q+1)");
  EXPECT_TRUE(tableau_is_valid<T>());

  const double at_order = order_condition_residual<S>(T::a, T::b, T::order);
  const double above = residual_one_above<S>(T::a, T::b, T::c, T::order);
  EXPECT_LT(at_order, kOrderTolerance);
  EXPECT_GT(above, 1e-6) << "b satisfies the conditions of order " << T::order + 1;
  // '*': order + 1 is beyond the tree enumeration, so res(p+1) is the bushy-tree condition alone.
  std::printf("%-9.*s %6d %12.3g %12.3g%s", static_cast<int>(T::name.size()), T::name.data(), T::order, at_order,
              above, T::order + 1 > tableau_detail::kMaxCheckedOrder ? "*" : " ");

  if constexpr (has_embedded_pair<T>) {
    const double emb_at = order_condition_residual<S>(T::a, T::b_hat, T::embedded_order);
    const double emb_above = residual_one_above<S>(T::a, T::b_hat, T::c, T::embedded_order);
    EXPECT_LT(emb_at, kOrderTolerance);
    EXPECT_GT(emb_above, 1e-6) << "b_hat satisfies the conditions of order " << T::embedded_order + 1;
    EXPECT_NE(T::order, T::embedded_order);
    std::printf(" | %6d %12.3g %12.3g\n", T::embedded_order, emb_at, emb_above);
  } else {
    for (double v : T::b_hat) EXPECT_EQ(v, 0.0);
    std::printf(" | %6s\n", "-");
  }

  if constexpr (T::fsal) {
    EXPECT_EQ(T::c[S - 1], 1.0);
    for (std::size_t j = 0; j < S; ++j) EXPECT_EQ(T::a[S - 1][j], T::b[j]) << "j = " << j;
  }
  EXPECT_EQ(T::c[0], 0.0);
}

// Every tableau with its own dense output on its own (TableauDenseOutput/<name>).
template <class T>
class TableauDenseOutput : public ::testing::Test {};
TYPED_TEST_SUITE(TableauDenseOutput, tableau_tests::DenseOutputTableauTypes, tableau_tests::TableauName);

TYPED_TEST(TableauDenseOutput, HasOrderOfItsDegreeAcrossTheStep) {
  using T = TypeParam;
  // Dividing A by theta amplifies round-off (tsit5: ~7e-11 at theta = 0.1), so stay at theta >= 1/4.
  for (double theta : {0.25, 0.5, 0.75, 0.9, 1.0}) {
    EXPECT_LT(dense_output_residual<T>(theta, T::dense_degree), 1e-10) << "theta = " << theta;
  }
  // Weights of degree d cannot give order d + 1 in the interior of the step.
  EXPECT_GT(dense_output_residual<T>(0.5, T::dense_degree + 1), 1e-6);
}

TEST(AllTableaux, AtLeastTwoHaveTheirOwnDenseOutput) {
  int checked = 0;
  for_each_tableau([&](auto tag) {
    using T = typename decltype(tag)::type;
    if constexpr (TableauWithDenseOutput<T>) ++checked;
  });
  EXPECT_GE(checked, 2);  // at least dopri5 and tsit5
}

// -----------------------------------------------------------------------------------------------------------
// Deliberately broken copies: a wrong coefficient must not compile into a stepper.

template <std::size_t S>
constexpr TableauRow<S> nudged(TableauRow<S> row, std::size_t i, double delta) {
  row[i] += delta;
  return row;
}
template <std::size_t S>
constexpr TableauMatrix<S> nudged(TableauMatrix<S> m, std::size_t i, std::size_t j, double delta) {
  m[i][j] += delta;
  return m;
}

// RK4 with b_2 off by 1e-6: already the order-1 condition sum b_i = 1 fails.
struct BrokenRK4 : ClassicRK4 {
  static constexpr TableauRow<4> b = nudged(ClassicRK4::b, 1, 1e-6);
};
static_assert(!tableau_is_valid<BrokenRK4>());
static_assert(!has_stated_order<BrokenRK4>());

// DOPRI5 with a_43 off by 1e-8 and c_4 moved with it, so the row sums still match: only the order conditions
// see the mistake.
struct BrokenDP5 : DormandPrince54 {
  static constexpr TableauMatrix<7> a = nudged(DormandPrince54::a, 3, 2, 1e-8);
  static constexpr TableauRow<7> c = nudged(DormandPrince54::c, 3, 1e-8);
};
static_assert(row_sums_match<BrokenDP5>());
static_assert(fsal_is_consistent<BrokenDP5>());
static_assert(!has_stated_order<BrokenDP5>());
static_assert(!tableau_is_valid<BrokenDP5>());

// RKF78 with 1e-9 moved from b_7 to b_8: sum b_i = 1 still holds, the order-2 condition does not.
struct BrokenRKF78 : Fehlberg78 {
  static constexpr TableauRow<13> b = nudged(nudged(Fehlberg78::b, 6, 1e-9), 7, -1e-9);
};
static_assert(row_sums_match<BrokenRKF78>());
static_assert(!has_stated_order<BrokenRKF78>());
static_assert(!tableau_is_valid<BrokenRKF78>());

// Tsit5 whose dense weight b_4(theta) no longer ends on b_4 (one coefficient off by 1e-12).
struct BrokenTsit5Dense : Tsitouras54 {
  static constexpr std::array<std::array<double, 4>, 7> dense = [] {
    auto d = Tsitouras54::dense;
    d[3][2] += 1e-12;
    return d;
  }();
};
static_assert(has_stated_order<BrokenTsit5Dense>());
static_assert(!dense_output_is_consistent<BrokenTsit5Dense>());
static_assert(!tableau_is_valid<BrokenTsit5Dense>());

// BS3 made to propagate its second-order weights (order lowered to match) while the last row of A still holds
// the third-order ones: still a consistent order-2 method, but no longer FSAL.
struct BrokenBS3Fsal : BogackiShampine32 {
  static constexpr int order = 2;
  static constexpr TableauRow<4> b = BogackiShampine32::b_hat;
};
static_assert(has_stated_order<BrokenBS3Fsal>());
static_assert(!fsal_is_consistent<BrokenBS3Fsal>());
static_assert(!tableau_is_valid<BrokenBS3Fsal>());

TEST(BrokenTableaux, AreRejected) {
  EXPECT_FALSE(tableau_is_valid<BrokenRK4>());
  EXPECT_GT(order_condition_residual<4>(BrokenRK4::a, BrokenRK4::b, 4), kOrderTolerance);

  EXPECT_FALSE(tableau_is_valid<BrokenDP5>());
  EXPECT_TRUE(row_sums_match<BrokenDP5>());
  EXPECT_GT(order_condition_residual<7>(BrokenDP5::a, BrokenDP5::b, 5), kOrderTolerance);

  EXPECT_FALSE(tableau_is_valid<BrokenRKF78>());
  EXPECT_LT(order_condition_residual<13>(BrokenRKF78::a, BrokenRKF78::b, 1), kOrderTolerance);
  EXPECT_GT(order_condition_residual<13>(BrokenRKF78::a, BrokenRKF78::b, 8), kOrderTolerance);

  EXPECT_FALSE(tableau_is_valid<BrokenTsit5Dense>());
  EXPECT_FALSE(tableau_is_valid<BrokenBS3Fsal>());
}

// -----------------------------------------------------------------------------------------------------------
// Names and dispatch

TEST(AllTableaux, NamesAreUniqueAndInListOrder) {
  const std::vector<std::string_view> names = tableau_names();
  ASSERT_EQ(names.size(), 12u);
  EXPECT_EQ(std::set<std::string_view>(names.begin(), names.end()).size(), names.size());
  const std::vector<std::string_view> expected = {"euler", "midpoint", "heun",   "rk4",   "rk38",  "bs3",
                                                  "rkf45", "cashkarp", "dopri5", "tsit5", "vern6", "rkf78"};
  EXPECT_EQ(names, expected);

  constexpr int count = [] {
    int n = 0;
    for_each_tableau([&](auto) { ++n; });
    return n;
  }();
  static_assert(count == 12);
}

TEST(AllTableaux, DispatchFindsEveryNameAndRejectsUnknown) {
  for (std::string_view name : tableau_names()) {
    std::string_view got;
    int calls = 0;
    EXPECT_TRUE(dispatch_tableau(name, [&](auto tag) {
      got = decltype(tag)::type::name;
      ++calls;
    }));
    EXPECT_EQ(got, name);
    EXPECT_EQ(calls, 1);
  }
  int calls = 0;
  EXPECT_FALSE(dispatch_tableau("nope", [&](auto) { ++calls; }));
  EXPECT_FALSE(dispatch_tableau("", [&](auto) { ++calls; }));
  EXPECT_EQ(calls, 0);

  std::size_t stages = 0;
  EXPECT_TRUE(dispatch_tableau("rkf78", [&](auto tag) { stages = decltype(tag)::type::stages; }));
  EXPECT_EQ(stages, 13u);
}

}  // namespace
}  // namespace grtrace
