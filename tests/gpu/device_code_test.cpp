// The GPU backend's device code calls no function through a null pointer: nvcc's silent stand-in for a function it
// cannot compile for the device (tests/gpu/ptx_null_calls.hpp, core/optional.hpp). Runs on any build machine with
// nvcc (no GPU needed): the build writes the kernels' PTX at -O0 (tests/gpu/CMakeLists.txt, gpu_device_code_O0)
// and lists the files in GRTRACE_DEVICE_PTX_LIST.
#include "ptx_null_calls.hpp"

#include <gtest/gtest.h>

#include <fstream>
#include <sstream>
#include <string>
#include <vector>

namespace {

std::vector<std::string> null_calls_in(const std::string& ptx) {
  std::istringstream in(ptx);
  return gpu_test::ptx_null_calls(in);
}

// What cicc -O0 wrote for std::optional<TraceResult>'s in-place constructor before the hot path used
// grtrace::Optional (trimmed): the callee's address is the constant 0.
constexpr const char* kNullCall = R"(
.func _ZNSt22_Optional_payload_baseIN7grtrace11TraceResultEEC1IJS1_EEESt10in_place_tDpOT_(
	.param .b64 _param_0
)
{
	mov.u64 	%rd6, 0;
	{ // callseq 163, 0
	.param .b64 param0;
	st.param.b64 	[param0+0], %rd1;
	prototype_163 : .callprototype ()_ (.param .b64 _);
	call 
	%rd6, 
	(
	param0
	)
	, prototype_163;
	} // callseq 163
	ret;
}
)";

TEST(PtxNullCalls, FindsACallThroughARegisterHoldingZero) {
  const std::vector<std::string> found = null_calls_in(kNullCall);
  ASSERT_EQ(found.size(), 1u);
  EXPECT_EQ(found[0], "_ZNSt22_Optional_payload_baseIN7grtrace11TraceResultEEC1IJS1_EEESt10in_place_tDpOT_");
  // On one line and with a return value, as other nvcc versions write it.
  EXPECT_EQ(null_calls_in(".visible .entry k(\n)\n{\nmov.b64 %rd2, 0;\ncall (retval0), %rd2, (param0), p;\n}\n").size(),
            1u);
}

TEST(PtxNullCalls, IgnoresDirectCallsAndRegistersWrittenAgain) {
  // A function's address called through a register (unoptimised array construction does this), and a direct call.
  const std::string fine = R"(
.func f(
)
{
	mov.u64 	%rd6, 0;
	mov.u64 	%rd6, _ZN5Eigen6MatrixIdLi8ELi1ELi0ELi8ELi1EEC1Ev;
	call 
	%rd6, 
	(
	param0
	)
	, prototype_1;
	call.uni (retval0), 
	_ZSt7forwardIN7grtrace11TraceResultEEOT_RNSt16remove_referenceIS2_E4typeE, 
	(
	param0
	);
}
.func g(
)
{
	call 
	%rd6, 
	(
	param0
	)
	, prototype_2;
}
)";
  EXPECT_TRUE(null_calls_in(fine).empty());  // g's %rd6 is its own register, never set to 0 there
}

TEST(DeviceCode, CallsNoFunctionThroughANullPointer) {
  std::ifstream list(GRTRACE_DEVICE_PTX_LIST);
  ASSERT_TRUE(list) << "no list of PTX files at " << GRTRACE_DEVICE_PTX_LIST;
  int files = 0;
  for (std::string path; std::getline(list, path);) {
    if (path.empty()) continue;
    ++files;
    std::ifstream ptx(path);
    ASSERT_TRUE(ptx) << "cannot read " << path;
    std::stringstream text;
    text << ptx.rdbuf();
    // The backend's own kernels are in it (an empty or host-only file would pass the scan for nothing).
    EXPECT_NE(text.str().find(".entry"), std::string::npos) << path << " holds no kernel";
    for (const std::string& function : null_calls_in(text.str()))
      ADD_FAILURE() << path << ": " << function
                    << " calls through a null pointer (device code reaches a function nvcc could not compile for "
                       "the GPU: use grtrace::Optional instead of std::optional, write Eigen expressions out; see "
                       "core/optional.hpp)";
  }
  EXPECT_GE(files, 2) << "the application layer's two kernel units";
}

}  // namespace
