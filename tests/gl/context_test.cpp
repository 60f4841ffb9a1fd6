#include "gl/context.h"

#include <gtest/gtest.h>

#include "core/error.h"
#include "tests/gl/gl_test_util.h"

namespace photovr {
namespace {

TEST(GLContext, OSMesaGivesOpenGL45Core) {
  gl::Context& ctx = testing::osmesaContext();
  EXPECT_EQ(ctx.backend(), gl::Backend::OSMesa);
  EXPECT_NE(ctx.version().find("4.5"), std::string::npos) << ctx.version();
  EXPECT_FALSE(ctx.renderer().empty());
}

TEST(GLContext, BackendNamesRoundTripAndUnknownIsAUsageError) {
  for (auto b : {gl::Backend::OSMesa, gl::Backend::EGL, gl::Backend::GLFW})
    EXPECT_EQ(gl::parseBackend(gl::backendName(b)), b);
  EXPECT_THROW(gl::parseBackend("vulkan"), UsageError);
}

}  // namespace
}  // namespace photovr
