// The tests' skip policy (TestSupport.h): under FRUGAL_TEST_STRICT=1 a skip for a missing GL backend
// or a missing dependency is a failure, so that CI cannot pass with a regression skipped.
#include <cstdlib>
#include <optional>
#include <string>

#include <gtest/gtest-spi.h>
#include <gtest/gtest.h>

#include "TestSupport.h"

namespace frugal {
namespace {

void skipForGl() { FRUGAL_SKIP_IF_NO_GL("the backend's reason"); }
void skipForDependency() { FRUGAL_SKIP_IF_MISSING("gnuplot (Debian: gnuplot-nox)"); }

// Sets FRUGAL_TEST_STRICT for one scope, then puts back what was there.
class StrictScope {
public:
    explicit StrictScope(const char* value) {
        if (const char* old = std::getenv("FRUGAL_TEST_STRICT")) old_ = old;
        ::setenv("FRUGAL_TEST_STRICT", value, 1);
    }
    ~StrictScope() {
        if (old_)
            ::setenv("FRUGAL_TEST_STRICT", old_->c_str(), 1);
        else
            ::unsetenv("FRUGAL_TEST_STRICT");
    }
    StrictScope(const StrictScope&) = delete;
    StrictScope& operator=(const StrictScope&) = delete;

private:
    std::optional<std::string> old_;
};

TEST(SkipPolicyTest, StrictTurnsEverySkipForGlOrADependencyIntoAFailure) {
    StrictScope strict("1");
    EXPECT_TRUE(test::strictSkips());
    EXPECT_FATAL_FAILURE(skipForGl(), "no GL backend, and FRUGAL_TEST_STRICT=1 forbids skipping: the backend's reason");
    EXPECT_FATAL_FAILURE(skipForDependency(), "not installed, and FRUGAL_TEST_STRICT=1 forbids skipping: gnuplot");
}

TEST(SkipPolicyTest, OnlyTheValueOneIsStrict) {
    for (const char* value : {"0", "", "yes"}) {
        StrictScope strict(value);
        EXPECT_FALSE(test::strictSkips()) << "FRUGAL_TEST_STRICT='" << value << "'";
    }
}

}  // namespace
}  // namespace frugal
