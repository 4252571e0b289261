// grtrace-geodesic --metric kerr as a program: the JSON reports E, L_z and Carter's Q, conserved along
// the ray; both charts start from the same Boyer-Lindquist data and report the same constants; an equatorial
// photon's deflection matches the exact Iyer-Hansen value; bad Kerr input exits with code 2.
//
// The binary: <build>/examples/geodesic/grtrace-geodesic beside this test's <build>/tests/render/.
#include "../common/tool_run.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>

namespace fs = std::filesystem;

namespace {

using grtrace::tool_tests::ToolRun;

fs::path geodesic_binary() { return grtrace::tool_tests::tool_path(nullptr, "geodesic", "grtrace-geodesic"); }

/// The number after "key": in the one-line JSON (NaN when absent or null).
double number(const std::string& json, const std::string& key) {
  const auto at = json.find("\"" + key + "\":");
  if (at == std::string::npos) return std::nan("");
  return std::strtod(json.c_str() + at + key.size() + 3, nullptr);
}

class KerrGeodesicCli : public ::testing::Test {
 protected:
  void SetUp() override {
    ASSERT_TRUE(fs::exists(geodesic_binary())) << "build the grtrace-geodesic target first";
  }
  /// Runs the tool with `args` (a shell word list): stdout in out, stderr apart.
  ToolRun run(const std::string& args) const {
    return grtrace::tool_tests::run_separated(grtrace::tool_tests::quoted(geodesic_binary().string()) + " " + args,
                                              scratch_.path());
  }
  grtrace::tool_tests::ScratchDir scratch_{"grtrace_kerr_geodesic_cli"};
};

TEST_F(KerrGeodesicCli, ReportsConservedConstantsInBothCharts) {
  const std::string ray = "--metric kerr --spin 0.9 --position 0,20,1.2,0 --velocity -1,0.012,0.02 "
                          "--rtol 1e-10 --atol 1e-12 --escape-radius 100 ";
  const ToolRun bl = run(ray), ks = run(ray + "--chart ks");
  ASSERT_EQ(bl.status, 0) << bl.out;
  ASSERT_EQ(ks.status, 0) << ks.out;
  std::printf("BL: %s\nKS: %s\n", bl.out.c_str(), ks.out.c_str());
  for (const ToolRun* r : {&bl, &ks}) {
    EXPECT_NE(r->out.find("\"status\":\"escaped\""), std::string::npos) << r->out;
    EXPECT_LT(std::abs(number(r->out, "energy_drift")), 1e-9) << r->out;
    EXPECT_LT(std::abs(number(r->out, "angular_momentum_drift")), 1e-9) << r->out;
    EXPECT_LT(std::abs(number(r->out, "carter_drift")), 1e-9) << r->out;
    EXPECT_GT(number(r->out, "carter_q"), 0.0) << r->out;  // crosses the equator
  }
  // The same Boyer-Lindquist data in both charts: the same constants.
  for (const char* key : {"energy", "angular_momentum", "carter_q"})
    EXPECT_NEAR(number(bl.out, key), number(ks.out, key), 1e-12 * std::abs(number(bl.out, key))) << key;
}

TEST_F(KerrGeodesicCli, EquatorialDeflectionMatchesIyerHansen) {
  for (const char* args : {"--impact 6 --spin 0.9", "--impact 9 --spin -0.9", "--impact 7 --spin 0.5 --chart ks"}) {
    const ToolRun r = run(std::string("--metric kerr --rtol 1e-11 --atol 1e-13 ") + args);
    ASSERT_EQ(r.status, 0) << args << ": " << r.out;
    std::printf("%s: %s\n", args, r.out.c_str());
    EXPECT_GT(number(r.out, "deflection"), 0.3) << args;
    EXPECT_LT(std::abs(number(r.out, "deflection_error")), 1e-7) << args << ": " << r.out;
  }
  // An impact parameter beyond the default escape sphere (1000 M): the photon starts where it can exist (4 |b|),
  // so the deflection is measured, not reported as null from a state that is not null.
  const ToolRun far = run("--metric kerr --spin 0.9 --rtol 1e-11 --atol 1e-13 --impact 2000");
  ASSERT_EQ(far.status, 0) << far.out;
  EXPECT_LT(std::abs(number(far.out, "deflection_error")), 1e-9) << far.out;
  EXPECT_LT(std::abs(number(far.out, "constraint_drift")), 1e-9) << far.out;
}

TEST_F(KerrGeodesicCli, RefusesBadKerrInput) {
  for (const char* args : {"--metric kerr --spin 1 --impact 6", "--metric kerr --spin nan --impact 6",
                           "--metric kerr --spin 0.9 --chart xy --impact 6", "--spin 0.5 --impact 6",
                           "--metric kerr --spin 0.9 --position 0,1.3,1.2,0 --velocity -1,0,0"}) {
    const ToolRun r = run(args);
    EXPECT_EQ(r.status, 2) << args << ": " << r.out;
    EXPECT_TRUE(r.out.empty()) << args;
  }
}

}  // namespace
