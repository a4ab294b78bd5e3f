// Result (frugal/Result.h): a value or an Error; reaching for the value of an error throws
// BadResultAccess in every build, with the error's message, instead of reading no value.
#include <gtest/gtest.h>

#include <string>

#include <frugal/Result.h>
#include <frugal/Scene.h>

namespace frugal {
namespace {

TEST(ResultTest, AValueIsReachedEveryWay) {
    Result<std::string> r(std::string("frame"));
    ASSERT_TRUE(r.ok());
    EXPECT_EQ(r.value(), "frame");
    EXPECT_EQ(*r, "frame");
    EXPECT_EQ(r->size(), 5u);
}

TEST(ResultTest, TheValueOfAnErrorThrowsWithItsMessageInEveryBuild) {
    const Result<std::string> r(Error{"bunny.obj: no such file", ErrorKind::Io});
    ASSERT_FALSE(r.ok());
    EXPECT_EQ(r.error().message, "bunny.obj: no such file");
    EXPECT_EQ(r.error().kind, ErrorKind::Io);
    try {
        (void)r.value();
        FAIL() << "value() of an error returned";
    } catch (const BadResultAccess& e) {
        EXPECT_STREQ(e.what(), "frugal::Result::value() on an error: bunny.obj: no such file");
        EXPECT_EQ(e.error().kind, ErrorKind::Io);
    }
    EXPECT_THROW((void)*r, BadResultAccess);
    EXPECT_THROW((void)r->size(), BadResultAccess);
    EXPECT_THROW((void)r.value(), std::logic_error);
}

// The README's first lines: a scene that fails to load, its value asked for all the same.
TEST(ResultTest, AFailedLoadDoesNotHandOutAScene) {
    Result<Scene> scene = loadScene("/nonexistent/bunny.obj");
    ASSERT_FALSE(scene);
    EXPECT_THROW((void)scene->triangleCount(), BadResultAccess);
}

// A result converts to one of another type with the same error, or the value converted.
TEST(ResultTest, ConversionKeepsTheError) {
    Result<int> failed(Error{"x: why", ErrorKind::BadInput, true});
    const Result<long> converted(std::move(failed));
    EXPECT_EQ(converted.error().message, "x: why");
    EXPECT_TRUE(converted.error().aboutSetting);
    Result<int> value(3);
    const Result<long> widened(std::move(value));
    EXPECT_EQ(*widened, 3L);
}

}  // namespace
}  // namespace frugal
