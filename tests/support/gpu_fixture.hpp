// A Context shared by the tests of one executable (validation on, as everywhere in the suite);
// each test fails if the validation layer said anything during it.
#pragma once

#include <jade/dev/context.hpp>
#include <jade/context.hpp>

#include <gtest/gtest.h>

#include <memory>

namespace jade::test {

class GpuTest : public ::testing::Test {
protected:
    static Context& context()
    {
        static std::unique_ptr<Context> ctx = [] {
            ContextOptions o;
            o.validation = true;
            return std::make_unique<Context>(o);
        }();
        return *ctx;
    }
    void SetUp() override { messages_before_ = dev::validation_messages(context()); }
    void TearDown() override
    {
        EXPECT_EQ(dev::validation_messages(context()), messages_before_) << "Vulkan validation reported messages";
    }

private:
    uint64_t messages_before_ = 0;
};

}  // namespace jade::test
