// tests/common/tableau_types.hpp
// The shipped tableaux as GoogleTest type lists, for typed tests that run once per tableau. Takes
// grtrace::AllTableaux (grtrace/tableau/all_tableaux.hpp); gives ::testing::Types of all of them, of those with
// an embedded pair, of those without, and of those with their own dense output, and TableauName, which names
// each typed test after T::name ("EveryTableau/rkf78.Test"): a failing tableau fails alone, under its own name,
// where a for_each_tableau loop inside one TEST failed the whole test. Use:
//   template <class T> class EveryTableau : public ::testing::Test {};
//   TYPED_TEST_SUITE(EveryTableau, tableau_tests::AllTableauTypes, tableau_tests::TableauName);
//   TYPED_TEST(EveryTableau, Something) { using T = TypeParam; ... }
#pragma once

#include "grtrace/tableau/all_tableaux.hpp"

#include <gtest/gtest.h>

#include <set>
#include <string>
#include <type_traits>

namespace grtrace::tableau_tests {

/// Concatenation of two TypeLists (the fold in keep_if needs a binary operator on them).
template <class... A, class... B>
constexpr TypeList<A..., B...> operator+(TypeList<A...>, TypeList<B...>) {
  return {};
}

/// Takes a trait Keep (Keep<T>::value) and a TypeList; returns the TypeList of the T it keeps, in their order.
template <template <class> class Keep, class... T>
constexpr auto keep_if(TypeList<T...>) {
  return (TypeList<>{} + ... + std::conditional_t<Keep<T>::value, TypeList<T>, TypeList<>>{});
}

template <class T>
struct WithEmbeddedPair : std::bool_constant<has_embedded_pair<T>> {};
template <class T>
struct WithoutEmbeddedPair : std::bool_constant<!has_embedded_pair<T>> {};
template <class T>
struct WithDenseOutput : std::bool_constant<TableauWithDenseOutput<T>> {};

template <class List>
struct AsTypes;
template <class... T>
struct AsTypes<TypeList<T...>> {
  using type = ::testing::Types<T...>;
};

/// grtrace::TypeList<T...> as ::testing::Types<T...>.
template <class List>
using Types = typename AsTypes<List>::type;

using AllTableauTypes = Types<AllTableaux>;
using EmbeddedPairTableauTypes = Types<decltype(keep_if<WithEmbeddedPair>(AllTableaux{}))>;
using NoEmbeddedPairTableauTypes = Types<decltype(keep_if<WithoutEmbeddedPair>(AllTableaux{}))>;
using DenseOutputTableauTypes = Types<decltype(keep_if<WithDenseOutput>(AllTableaux{}))>;

/// The name generator of TYPED_TEST_SUITE: a tableau's run-time name, so failures read "rkf78", not "11".
struct TableauName {
  template <class T>
  static std::string GetName(int) {
    return std::string(T::name);
  }
};

/// True the first time it is called with `table` in this program: a table whose rows come from a typed test,
/// one row per tableau, prints its header once (function-local statics in the test bodies would be one per type).
inline bool first_row(const std::string& table) {
  static std::set<std::string> started;
  return started.insert(table).second;
}

}  // namespace grtrace::tableau_tests
